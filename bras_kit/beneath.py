"""A path stays under its root: the one test for every name or path a learner's file hands to
bras-kit's own process (``setup()``'s arguments, a launch file's file arguments...).

The model is openat2(2) with ``RESOLVE_BENEATH``: the path is resolved with its symbolic links
followed, and what it resolves to must lie under the root (``pathlib``'s ``is_relative_to``).
``..`` that leaves the root, an absolute path elsewhere, a link that points out, a loop of links,
and a device, pipe or socket where a file or folder is expected are each refused with their own
``kind``, never followed into::

    from bras_kit.beneath import Outside, beneath
    beneath("/ws/src/bras", "urdf/bras.urdf")          # '/ws/src/bras/urdf/bras.urdf'
    beneath("/ws/src/bras", "../../etc/passwd")       # raises Outside(kind="outside")
"""

from __future__ import annotations

import errno
import os
import stat
from pathlib import PurePath

FILE, FOLDER, ANY = "file", "folder", "any"

# why a path is refused (Outside.kind)
KINDS = ("empty", "outside", "link_out", "loop", "missing", "device", "fifo", "socket", "folder", "not_folder")


class Outside(OSError):
    """``path`` may not be used under ``root``: ``kind`` says why (one of :data:`KINDS`). The
    text names the path, never what the file holds."""

    def __init__(self, kind: str, path: str, root: str = "") -> None:
        super().__init__(f"{path}: {_WHY.get(kind, kind)}")
        self.kind, self.path, self.root = kind, path, root


_WHY = {
    "empty": "an empty path",
    "outside": "outside the folder it must stay in",
    "link_out": "a symbolic link that leads outside the folder it must stay in",
    "loop": "a loop of symbolic links",
    "missing": "no such file or folder",
    "device": "a device, not a file",
    "fifo": "a named pipe, not a file",
    "socket": "a socket, not a file",
    "folder": "a folder, not a file",
    "not_folder": "not a folder",
}


def _inside(path: str, root: str) -> bool:
    return PurePath(path).is_relative_to(root)


def beneath(root: str, path: str, *, want: str = FILE, must_exist: bool = True) -> str:
    """The absolute, resolved form of ``path`` (relative to ``root``, or absolute) when it stays
    under ``root`` once every symbolic link is followed, and is a ``want`` (a regular file, a
    folder, or either); else :class:`Outside`."""
    text = os.fspath(path)
    if not text or "\0" in text:
        raise Outside("empty", text, root)
    top = os.path.realpath(root)
    joined = os.path.join(top, text)
    resolved = os.path.realpath(joined)
    if not _inside(resolved, top):
        # the words say which trick: the path itself leaves, or a link inside it points out
        raise Outside("outside" if not _inside(os.path.normpath(joined), top) else "link_out", text, root)
    try:
        info = os.stat(resolved)
    except OSError as exc:
        if exc.errno == errno.ELOOP:
            raise Outside("loop", text, root) from None
        if must_exist or exc.errno != errno.ENOENT:
            raise Outside("missing", text, root) from None
        return resolved
    kind = _refused_kind(info.st_mode, want)
    if kind:
        raise Outside(kind, text, root)
    return resolved


def beneath_any(roots: tuple[str, ...] | list[str], path: str, *, want: str = FILE) -> str:
    """:func:`beneath` for the first of ``roots`` that holds ``path`` (an absolute ``path`` is
    judged against each); the refusal of the last root otherwise."""
    refusal = Outside("outside", os.fspath(path))
    for root in roots:
        try:
            return beneath(root, path, want=want)
        except Outside as exc:
            if exc.kind not in ("outside", "link_out") or refusal.kind in ("outside", "link_out"):
                refusal = exc
    raise refusal


def _refused_kind(mode: int, want: str) -> str:
    if stat.S_ISCHR(mode) or stat.S_ISBLK(mode):
        return "device"
    if stat.S_ISFIFO(mode):
        return "fifo"
    if stat.S_ISSOCK(mode):
        return "socket"
    if want == FILE and stat.S_ISDIR(mode):
        return "folder"
    if want == FOLDER and not stat.S_ISDIR(mode):
        return "not_folder"
    if not (stat.S_ISREG(mode) or stat.S_ISDIR(mode)):
        return "device"
    return ""


def is_name_component(name: str) -> bool:
    """One path component that names nothing but itself (no separator, not ``.`` or ``..``)."""
    return bool(name) and name not in (".", "..") and "/" not in name and "\0" not in name and os.sep not in name
