"""The checked form of what a learner's ``setup.py`` handed to ``setup()``: made here, in one
place, and the only form the build (:mod:`.build`) lays an install tree out from.

``setup.py`` runs in the contained child (:mod:`.build`); what comes back is plain data that the
learner chose, so each name and path in it is checked before bras-kit's own process acts on it:

* the package name (``name=``, else package.xml's ``<name>``) by catkin_pkg's rule, which
  colcon-ros applies when it reads package.xml (catkin_pkg/package.py ``Package.validate``:
  ``^[a-zA-Z0-9][a-zA-Z0-9_-]*$``, refused in its words ``Package name "X" does not follow naming
  conventions``); it becomes one folder directly under the install base, nothing else;
* ``data_files``: each target folder relative and below the prefix (setuptools' install_data
  would write an absolute one where it says), each source resolved, links followed, inside the
  package folder (:func:`bras_kit.trust.beneath.beneath`) and a regular file;
* ``packages`` and ``package_dir``: dotted Python names, folders inside the package;
* ``entry_points['console_scripts']``: ``name = module:function`` with a script name that is one
  file name and a module and function that are Python identifiers (they are written into the
  script, so nothing else may be);
* ``scripts``: files inside the package.

A refusal is data (:class:`Refusal`) at the line of ``setup.py`` that said it; the build stops
there, as colcon stops, and acts on nothing.
"""

from __future__ import annotations

import ast
import os
import re
from dataclasses import dataclass, replace
from typing import Any

from ..trust.beneath import FOLDER, Outside, beneath, is_name_component

# catkin_pkg/package.py, Package.validate (read by colcon-ros for every package.xml)
CATKIN_NAME = re.compile(r"^[a-zA-Z0-9][a-zA-Z0-9_-]*$")
# REP 144 (ROS package naming): what catkin_pkg only warns about
REP144_NAME = re.compile(r"^[a-z][a-z0-9_]*$")
# setuptools' script names: one file name (lib/PKG/NAME), nothing that climbs or hides
SCRIPT_NAME = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.+-]*$")
SHOWN = 200  # characters of a refused value shown back


@dataclass(frozen=True)
class Installed:
    """One file of the install tree and the package file it comes from."""

    target: str  # relative to the package's prefix, e.g. share/bras_description/urdf/bras.urdf
    source: str  # relative to the package folder


@dataclass(frozen=True)
class Refusal:
    """What ``setup()`` was given that bras-kit does not act on. ``kind``: "name", "outside"
    (a data_files target), "source" (a path outside the package, a link out, a device...),
    "missing_source" (setuptools' own refusal), "module", "entry_point", "value"; ``why`` the
    :data:`bras_kit.trust.beneath.KINDS` of a refused path; ``line`` in ``file``."""

    kind: str
    value: str
    line: int
    file: str = "setup.py"
    why: str = ""
    target: str = ""
    entry: int = -1  # missing_source: the data_files entry setuptools stopped at
    partial: CheckedSetup | None = None  # missing_source: what setuptools installed before it stopped


@dataclass(frozen=True)
class CheckedSetup:
    """What setup() asked for, every name and path checked: all the build acts on."""

    name: str
    installed: tuple[Installed, ...]  # data_files, in setuptools' order
    modules: tuple[Installed, ...]  # the packages' .py files (target under lib/pythonX.Y/site-packages)
    executables: tuple[Installed, ...]  # ``scripts=`` (target lib/PKG/NAME)
    console_scripts: tuple[tuple[str, str, str], ...]  # (name, module, function)


def name_problem(name: str) -> str | None:
    """catkin_pkg's words when ``name`` is not a package name colcon accepts, else None."""
    if not name:
        return "Package name must not be empty"
    if not CATKIN_NAME.fullmatch(name):  # fullmatch: "$" of re.match would let a final newline in
        return f'Package name "{name}" does not follow naming conventions'
    return None


def follows_rep144(name: str) -> bool:
    """REP 144: lower case letters, digits and single underscores, starting with a letter."""
    return bool(REP144_NAME.fullmatch(name)) and "__" not in name and len(name) >= 2


def _shown(value: Any) -> str:
    text = value if isinstance(value, str) else repr(value)
    return text if len(text) <= SHOWN else text[:SHOWN] + "..."


class _Lines:
    """Where each keyword of the ``setup(...)`` call is written (and each element of a literal
    ``data_files`` list), read from setup.py's syntax tree."""

    def __init__(self, source: str, setup_line: int) -> None:
        self.keywords: dict[str, int] = {}
        self.data_files: list[int] = []
        self.setup_line = setup_line
        self.source_lines = source.splitlines()
        try:
            tree = ast.parse(source)
        except (SyntaxError, ValueError):
            return
        calls = [n for n in ast.walk(tree) if isinstance(n, ast.Call) and _called(n.func).endswith("setup")]
        around = [c for c in calls if c.lineno <= setup_line <= (c.end_lineno or c.lineno)]
        if not calls:
            return
        call = (around or calls)[0]
        self.setup_line = self.setup_line or call.lineno
        for keyword in call.keywords:
            if keyword.arg:
                self.keywords[keyword.arg] = keyword.value.lineno
        value = next((k.value for k in call.keywords if k.arg == "data_files"), None)
        if isinstance(value, ast.List):
            self.data_files = [element.lineno for element in value.elts]

    def of(self, keyword: str) -> int:
        return self.keywords.get(keyword, self.setup_line)

    def of_data(self, index: int, text: str) -> int:
        """The line of data_files' ``index``-th entry: the literal's element, else the line naming ``text``."""
        if index < len(self.data_files):
            return self.data_files[index]
        return self.naming(text, self.of("data_files"))

    def naming(self, text: str, default: int) -> int:
        """The first line of setup.py that holds ``text``, else ``default``."""
        for number, line in enumerate(self.source_lines, 1):
            if text and text in line:
                return number
        return default


def _called(func: ast.expr) -> str:
    if isinstance(func, ast.Name):
        return func.id
    if isinstance(func, ast.Attribute):
        return func.attr
    return ""


def _dotted(name: Any) -> bool:
    return isinstance(name, str) and bool(name) and all(part.isidentifier() for part in name.split("."))


def check_setup(setup: dict[str, Any], root: str, *, manifest_name: str, setup_source: str,
                python_lib: str) -> CheckedSetup | Refusal:
    """The checked record of ``setup`` (what the child recorded), or the first refusal."""
    lines = _Lines(setup_source, int(setup.get("_line") or 0))
    raw_name = setup.get("name")
    if raw_name is not None and raw_name != "":
        name, line, file = raw_name, lines.of("name"), "setup.py"
    else:
        name, line, file = manifest_name, 0, "package.xml"
    if not isinstance(name, str) or name_problem(name) is not None:
        return Refusal("name", _shown(name), line, file)
    installed = _data_files(setup.get("data_files"), root, lines)
    if isinstance(installed, Refusal) and installed.kind != "missing_source":
        return installed
    modules = _modules(setup, root, lines, python_lib)
    if isinstance(modules, Refusal):
        return modules
    executables = _scripts(setup.get("scripts"), root, name, lines)
    if isinstance(executables, Refusal):
        return executables
    console = _console_scripts(setup.get("entry_points"), lines)
    if isinstance(console, Refusal):
        return console
    if isinstance(installed, Refusal):
        # setuptools stops at the missing source: what it installed before is in ``partial`` (the
        # build lays out what came before, in setuptools' order)
        assert installed.partial is not None
        return replace(installed, partial=replace(installed.partial, name=name, modules=tuple(modules),
                                                  executables=tuple(executables), console_scripts=tuple(console)))
    return CheckedSetup(name, tuple(installed), tuple(modules), tuple(executables), tuple(console))


def _relative_target(folder: str) -> str | None:
    """The target folder relative to the prefix, or None when it would leave it."""
    if folder in ("", "."):
        return ""
    normal = os.path.normpath(folder).replace(os.sep, "/")
    if os.path.isabs(folder) or normal == ".." or normal.startswith("../") or "\0" in folder:
        return None
    return "" if normal == "." else normal


def _source(root: str, source: Any, line: int) -> str | Refusal:
    """The source's path relative to the package folder, once resolved inside it."""
    if not isinstance(source, str):
        return Refusal("value", _shown(source), line)
    try:
        resolved = beneath(root, source)
    except Outside as exc:
        if exc.kind in ("missing", "folder"):  # setuptools' own refusal, in its words (build.py)
            return Refusal("missing_source", source, line, why=exc.kind)
        return Refusal("source", _shown(source), line, why=exc.kind)
    return os.path.relpath(resolved, os.path.realpath(root)).replace(os.sep, "/")


def _data_files(entries: Any, root: str, lines: _Lines) -> list[Installed] | Refusal:
    """What setuptools' install_data copies (setuptools/_distutils/command/install_data.py): a
    plain string to the prefix, a (folder, files) pair to prefix/folder/basename."""
    if entries is None:
        return []
    if not isinstance(entries, list):
        return Refusal("value", _shown(entries), lines.of("data_files"))
    out: list[Installed] = []
    for index, entry in enumerate(entries):
        if isinstance(entry, str):
            folder, files = "", [entry]
        elif isinstance(entry, list) and len(entry) == 2 and isinstance(entry[0], str) and isinstance(entry[1], list):
            folder, files = entry[0], entry[1]
        else:
            return Refusal("value", _shown(entry), lines.of_data(index, ""))
        line = lines.of_data(index, folder)
        target_folder = _relative_target(folder)
        if target_folder is None:
            return Refusal("outside", _shown(folder), line)
        for source in files:
            relative = _source(root, source, line)
            if isinstance(relative, Refusal):
                if relative.kind == "missing_source":  # the line naming the file, as a glob's result names none
                    line = lines.naming(os.path.basename(str(source)), line)
                return Refusal(relative.kind, relative.value, line, why=relative.why, target=target_folder,
                               entry=index, partial=CheckedSetup("", tuple(out), (), (), ()))
            base = os.path.basename(str(source))
            if not is_name_component(base):
                return Refusal("source", _shown(source), line, why="outside")
            out.append(Installed(f"{target_folder}/{base}" if target_folder else base, relative))
    return out


def _modules(setup: dict[str, Any], root: str, lines: _Lines, python_lib: str) -> list[Installed] | Refusal:
    """The .py files of ``packages`` (from ``package_dir`` when given), as setuptools' build_py finds them."""
    packages = setup.get("packages") or []
    package_dir = setup.get("package_dir") or {}
    if not isinstance(packages, list):
        return Refusal("value", _shown(packages), lines.of("packages"))
    if not isinstance(package_dir, dict):
        return Refusal("value", _shown(package_dir), lines.of("package_dir"))
    for key, folder in package_dir.items():
        if (key and not _dotted(key)) or not isinstance(folder, str):
            return Refusal("module", _shown(key or folder), lines.of("package_dir"))
        try:
            beneath(root, folder or ".", want=FOLDER, must_exist=False)
        except Outside as exc:
            return Refusal("source", _shown(folder), lines.of("package_dir"), why=exc.kind)
    out = []
    for package in packages:
        if not _dotted(package):
            return Refusal("module", _shown(package), lines.of("packages"))
        parts = package.split(".")
        if package in package_dir:
            folder = package_dir[package]
        else:
            folder = os.path.join(package_dir.get("", ""), *parts)
        try:
            resolved = beneath(root, folder or ".", want=FOLDER)
        except Outside as exc:
            if exc.kind == "missing":
                continue  # setuptools says nothing either until it copies; the static rules name it
            return Refusal("source", _shown(folder), lines.of("packages"), why=exc.kind)
        for name in sorted(os.listdir(resolved)):
            if not name.endswith(".py"):
                continue
            try:
                source = beneath(resolved, name)
            except Outside as exc:
                if exc.kind == "folder":
                    continue
                return Refusal("source", _shown(os.path.join(folder, name)), lines.of("packages"), why=exc.kind)
            if not source.startswith(os.path.realpath(root) + os.sep):
                return Refusal("source", _shown(os.path.join(folder, name)), lines.of("packages"), why="link_out")
            out.append(Installed("/".join([python_lib, *parts, name]),
                                 os.path.relpath(source, os.path.realpath(root)).replace(os.sep, "/")))
    return out


def _scripts(scripts: Any, root: str, package: str, lines: _Lines) -> list[Installed] | Refusal:
    """``scripts=``: colcon's setup.cfg puts them in lib/PKG ([install] install_scripts)."""
    if not scripts:
        return []
    if not isinstance(scripts, list):
        return Refusal("value", _shown(scripts), lines.of("scripts"))
    out = []
    for script in scripts:
        relative = _source(root, script, lines.of("scripts"))
        if isinstance(relative, Refusal):
            return relative
        out.append(Installed(f"lib/{package}/{os.path.basename(relative)}", relative))
    return out


def _console_scripts(entry_points: Any, lines: _Lines) -> list[tuple[str, str, str]] | Refusal:
    """``name = module:function`` (setuptools' EntryPoint pattern, narrowed to what a script can hold)."""
    line = lines.of("entry_points")
    if entry_points is None:
        return []
    if not isinstance(entry_points, dict):
        return Refusal("value", _shown(entry_points), line)
    scripts = entry_points.get("console_scripts", [])
    if isinstance(scripts, str):
        scripts = [s for s in scripts.splitlines() if s.strip()]
    if not isinstance(scripts, list):
        return Refusal("value", _shown(scripts), line)
    out = []
    for text in scripts:
        if not isinstance(text, str) or "=" not in text:
            return Refusal("entry_point", _shown(text), _line_naming(lines, text, line))
        left, _, right = text.partition("=")
        module, _, function = right.strip().partition(":")
        name, module, function = left.strip(), module.strip(), function.strip()
        if not SCRIPT_NAME.fullmatch(name) or not _dotted(module) or not _dotted(function):
            return Refusal("entry_point", _shown(text), _line_naming(lines, text, line))
        out.append((name, module, function))
    return out


def _line_naming(lines: _Lines, text: Any, default: int) -> int:
    head = str(text).partition("=")[0].strip()
    for number, line in enumerate(lines.source_lines, 1):
        if head and head in line and number >= default:
            return number
    return default
