"""Which function ``bras-kit run`` calls: the counterpart of ``ros2 run PKG EXE``.

A package folder: the executable is looked up in ``setup.py``'s ``console_scripts``, read
statically with the validator's package reader (``setup.py`` is never run). A ``.py`` file:
its ``main()``.
"""

from __future__ import annotations

import os
from dataclasses import dataclass

from ..core.errors import ParameterError
from ..core.message import M


@dataclass(frozen=True)
class Target:
    """What to run: import ``module`` with ``root`` on the path, call ``function()``."""

    root: str  # the folder put first on sys.path (the package folder, or the file's folder)
    module: str  # dotted name
    function: str
    path: str  # the module's file
    shown: str  # "bras_description animation" or the file as given
    package: str | None = None  # the package folder when one was given


def _names(scripts: list) -> list[str]:
    return [entry.name for entry in scripts]


def locate(where: str, executable: str | None = None) -> Target:
    """The target for ``bras-kit run WHERE [EXECUTABLE]``."""
    if os.path.isfile(where):
        if not where.endswith(".py"):
            raise ParameterError(M("a node is a Python file (.py) or a package folder"), path=where,
                                 hint=M("give the package folder (with setup.py) or the node's .py file"))
        if executable is not None:
            raise ParameterError(M("an executable name goes with a package folder, not with a .py file"),
                                 path=where)
        full = os.path.abspath(where)
        return Target(os.path.dirname(full), os.path.splitext(os.path.basename(full))[0],
                      "main", full, where)
    if not os.path.isdir(where):
        raise ParameterError(M("no such file or folder"), path=where,
                             hint=M("give the package folder (with setup.py) or the node's .py file"))
    return _from_package(where, executable)


def _from_package(where: str, executable: str | None) -> Target:
    from .package import SETUP_PY, Package

    package = Package(where)
    setup = package.setup
    setup_path = package.path(SETUP_PY)
    if setup is None:
        problem = package.problems[0] if package.problems else None
        raise ParameterError(M("cannot read the package's setup.py: {detail}",
                               detail=problem.detail if problem else "missing"),
                             path=setup_path, line=problem.line if problem else None,
                             hint=M("bras-kit run finds the node in setup.py's console_scripts, like ros2 run"))
    if setup.scripts is None:
        raise ParameterError(M("console_scripts in setup.py is not a list of literal strings"),
                             path=setup_path, line=setup.scripts_line,
                             hint=M("write it as 'NAME = PACKAGE.MODULE:main'"))
    scripts = setup.scripts
    if not scripts:
        raise ParameterError(M("setup.py declares no executable (console_scripts is empty)"),
                             path=setup_path, line=setup.scripts_line,
                             hint=M("add 'animation = {package}.animation:main' to console_scripts",
                                    package=package.name))
    if executable is None:
        if len(scripts) > 1:
            raise ParameterError(M("the package declares several executables: {names}", names=_names(scripts)),
                                 path=setup_path, line=setup.scripts_line,
                                 hint=M("name the one to run: bras-kit run {folder} NAME", folder=where))
        entry = scripts[0]
    else:
        found = [e for e in scripts if e.name == executable]
        if not found:
            raise ParameterError(M("no executable '{name}' in console_scripts", name=executable),
                                 path=setup_path, line=setup.scripts_line,
                                 hint=M("the executables are {names}", names=_names(scripts)))
        entry = found[0]
    module_path = os.path.join(package.root, *entry.module.split(".")) + ".py"
    if not entry.module or not entry.function or not package.module_written(entry.module):
        expected = os.path.relpath(module_path, package.root)
        elsewhere = package.misplaced(entry.module) if entry.module else []
        raise ParameterError(M("the entry point '{entry}' names no module file of the package",
                               entry=f"{entry.module}:{entry.function}"),
                             path=setup_path, line=entry.line,
                             hint=M("move {found} to {file}: ros2 run imports the entry's module from there",
                                    found=elsewhere[0], file=expected) if elsewhere
                             else M("expected {file}", file=expected))
    return Target(package.root, entry.module, entry.function, module_path,
                  f"{package.name} {entry.name}", where)
