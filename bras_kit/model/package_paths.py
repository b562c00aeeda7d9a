"""Where ``$(find pkg)`` and ``package://`` look for a package: the folders a caller gives,
``BRAS_KIT_PACKAGE_PATH``, then ``AMENT_PREFIX_PATH`` and ``ROS_PACKAGE_PATH``; and which folder
each package was taken from in this process (for ``--verbose``)."""

from __future__ import annotations

import os
from collections.abc import Iterable

from ..core.errors import XacroError
from ..core.message import M, Message

PACKAGE_PATH_ENV = "BRAS_KIT_PACKAGE_PATH"


def package_roots(extra: Iterable[str] = ()) -> list[str]:
    """Folders to search for packages: the given ones, then BRAS_KIT_PACKAGE_PATH, then AMENT_PREFIX_PATH/share."""
    roots = [os.path.abspath(p) for p in extra]
    for var, suffix in ((PACKAGE_PATH_ENV, ""), ("AMENT_PREFIX_PATH", "share"), ("ROS_PACKAGE_PATH", "")):
        for entry in os.environ.get(var, "").split(os.pathsep):
            if entry:
                roots.append(os.path.join(entry, suffix) if suffix else entry)
    return roots


def find_package(name: str, roots: Iterable[str]) -> str:
    """The folder of package ``name`` under one of ``roots``.

    A folder ``name`` with a ``package.xml`` (or in an install ``share/`` tree) wins; failing
    that, a plain folder named ``name`` is taken, as ``xacro`` does with a package path whose
    packages were copied without their manifest. :func:`packages_used` says which was used.
    """
    searched: list[str] = []
    fallback = None
    for root in roots:
        candidates = [os.path.join(root, name), os.path.join(root, "share", name)]
        if os.path.basename(os.path.normpath(root)) == name:
            candidates.insert(0, root)
        for candidate in candidates:
            searched.append(candidate)
            if not os.path.isdir(candidate):
                continue
            if os.path.isfile(os.path.join(candidate, "package.xml")) \
                    or os.path.basename(os.path.dirname(candidate)) == "share":
                return _remember(name, os.path.abspath(candidate))
            fallback = fallback or os.path.abspath(candidate)
    if fallback is not None:
        return _remember(name, fallback)
    raise XacroError(
        M("$(find {name}): package '{name}' not found", name=name),
        hint=M("pass --package-path DIR (a folder holding {name}/ or an install share/ tree) or set {variable}; "
               "searched: {folders}", name=name, variable=PACKAGE_PATH_ENV, folders=searched) if searched else
        M("pass --package-path DIR (a folder holding {name}/ or an install share/ tree) or set {variable}",
          name=name, variable=PACKAGE_PATH_ENV),
    )


_FOUND: dict[str, str] = {}


def _remember(name: str, folder: str) -> str:
    _FOUND[name] = folder
    return folder


def packages_used() -> dict[str, str]:
    """Every package found so far, name -> folder (``$(find)`` and ``package://``)."""
    return dict(sorted(_FOUND.items()))


def describe_package_folder(name: str, folder: str) -> Message:
    """``name -> folder``, saying when the folder was taken by its name alone (no package.xml)."""
    if os.path.isfile(os.path.join(folder, "package.xml")) or os.path.basename(os.path.dirname(folder)) == "share":
        return M("package '{name}': {folder}", name=name, folder=folder)
    return M("package '{name}': {folder} (no package.xml: found by its folder name)", name=name, folder=folder)
