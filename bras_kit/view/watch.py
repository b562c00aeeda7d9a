"""Which files to watch for a robot file: the file, the robot files beside it, and every file it
includes (``<xacro:include>``, ``load_yaml``), followed through ``$(find pkg)`` and relative
paths, wherever they live. Found by reading the text, not by running xacro: the list is only a
watch list, and it must be cheap to rebuild after each save (a new include is then watched too).
"""

from __future__ import annotations

import contextlib
import os
import re
from collections.abc import Iterable, Sequence

ROBOT_SUFFIXES = (".urdf", ".xacro", ".yaml", ".yml")
MAX_WATCHED = 500
MAX_SCANNED_BYTES = 4 << 20

_INCLUDE = re.compile(r"<\s*xacro:include\b[^>]*?\bfilename\s*=\s*(['\"])(.*?)\1", re.S)
_YAML = re.compile(r"load_yaml\(\s*(['\"])(.*?)\1\s*\)")
_FIND = re.compile(r"\$\(\s*find\s+([A-Za-z0-9_\-]+)\s*\)")


def watched_files(path: str, package_paths: Iterable[str] = ()) -> list[str]:
    """Absolute paths of ``path``, its sibling robot files and the files it includes (transitively)."""
    from ..model.package_paths import package_roots

    roots = package_roots(package_paths)
    start = os.path.abspath(path)
    found = {start}
    with contextlib.suppress(OSError):
        from ..trust.learner_files import list_folder

        folder = os.path.dirname(start)  # listed by descriptor: a FIFO or a device beside it is no robot file
        found.update(os.path.join(folder, name) for name, kind in list_folder(folder, (folder,))[:MAX_WATCHED]
                     if name.endswith(ROBOT_SUFFIXES) and kind in ("file", "link"))
    todo, scanned = [start], set()
    while todo and len(found) < MAX_WATCHED:
        current = todo.pop()
        if current in scanned or not current.endswith((".xacro", ".urdf")):
            continue
        scanned.add(current)
        for name in _references(current):
            target = _resolve(name, os.path.dirname(current), roots)
            if target is not None:
                found.add(target)
                todo.append(target)
    return sorted(found)[:MAX_WATCHED]


def _references(path: str) -> list[str]:
    """The names of the files ``path`` includes, read through the one reader (a regular file of
    at most 4 MiB, opened without waiting: an include that is a pipe or a device is skipped,
    never waited on). The user named the robot: its includes may be anywhere, as xacro's."""
    from ..trust.learner_files import read_text

    try:
        text = read_text(os.path.abspath(path), ("/",), limit=MAX_SCANNED_BYTES, errors="replace")
    except OSError:  # Unreadable too, a file past the bound included
        return []
    return [m.group(2) for pattern in (_INCLUDE, _YAML) for m in pattern.finditer(text)]


def _resolve(name: str, folder: str, roots: Sequence[str]) -> str | None:
    """The absolute path ``name`` stands for, or None when it depends on xacro arguments or
    properties (``$(arg ...)``, ``${...}``): those are unknown until xacro runs."""
    from ..core.errors import BrasKitError
    from ..model.package_paths import find_package

    def package(match: re.Match[str]) -> str:
        return find_package(match.group(1), roots)

    try:
        name = _FIND.sub(package, name.strip())
    except BrasKitError:
        return None
    if "$" in name or not name:
        return None
    return os.path.normpath(os.path.join(folder, name))
