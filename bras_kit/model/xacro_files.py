"""The gate every file xacro reads goes through: a regular file, outside ``/proc``, ``/sys`` and
``/dev``, of at most :data:`MAX_FILE_BYTES`, read without ever blocking on a pipe."""

from __future__ import annotations

import os
import stat
from collections.abc import Iterable

from ..core.errors import BrasKitError, XacroError
from ..core.message import M
from ..trust.learner_files import refusal

MAX_FILE_BYTES = 8 << 20  # any one file xacro reads
_FORBIDDEN_TREES = ("/proc", "/sys", "/dev")
# the folder in memory where bras-kit builds a package to evaluate it (scratch.IN_MEMORY): its
# regular files are files like any other (a device there is refused below, as anywhere)
_SHARED_MEMORY = "/dev/shm"


def check_readable_file(path: str) -> None:
    """Raise unless ``path`` is a regular file of at most :data:`MAX_FILE_BYTES` outside /proc, /sys,
    /dev (its /dev/shm folder in memory excepted)."""
    real = os.path.realpath(path)
    system = any(real == tree or real.startswith(tree + os.sep) for tree in _FORBIDDEN_TREES)
    if system and not real.startswith(_SHARED_MEMORY + os.sep):
        raise XacroError(M("refused to read {path}: it is a system file, not a robot description", path=path),
                         hint=M("include only files of your robot's packages"))
    try:
        info = os.stat(path)
    except OSError as exc:
        raise BrasKitError(M("cannot read {path}: {reason}", path=path, reason=exc.strerror)) from None
    if stat.S_ISDIR(info.st_mode):
        raise BrasKitError(M("{path} is a folder, not a file", path=path))
    if not stat.S_ISREG(info.st_mode):
        raise XacroError(M("refused to read {path}: it is not a regular file (a device, pipe or socket)", path=path),
                         hint=M("give the path of a .xacro, .urdf or .yaml file"))
    if info.st_size > MAX_FILE_BYTES:
        raise XacroError(M("refused to read {path}: {size} bytes is more than the {limit} MiB a robot "
                           "description file may have", path=path, size=info.st_size, limit=MAX_FILE_BYTES >> 20))


def _read_limited(path: str, roots: tuple[str, ...] | None = None) -> bytes:
    """The bytes of a checked regular file, never blocking on a pipe swapped in meanwhile. With
    ``roots`` (a package's robot, a learner's submission), through the one reader: resolved under
    one of them without following a link out, and read through the descriptor that walk opened."""
    if roots is not None:
        return read_beneath(path, roots, MAX_FILE_BYTES)
    check_readable_file(path)
    fd = os.open(path, os.O_RDONLY | getattr(os, "O_NONBLOCK", 0))
    try:
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            raise XacroError(M("refused to read {path}: it is not a regular file", path=path))
        data = b""
        while len(data) <= MAX_FILE_BYTES:
            chunk = os.read(fd, 1 << 20)
            if not chunk:
                return data
            data += chunk
        raise XacroError(M("refused to read {path}: more than {limit} MiB", path=path, limit=MAX_FILE_BYTES >> 20))
    finally:
        os.close(fd)


def read_beneath(path: str, roots: tuple[str, ...], limit: int) -> bytes:
    """:func:`bras_kit.trust.learner_files.read_bytes`, its refusal worded as xacro's own: the path and
    why, never a byte of the file."""
    from ..trust.learner_files import Unreadable, read_bytes

    try:
        return read_bytes(os.path.abspath(path), roots, limit=limit)  # roots are absolute: so is the path
    except Unreadable as exc:
        if exc.kind == "missing":
            raise BrasKitError(M("no such file: {path}", path=path), hint=M("check the path and spelling")) from None
        if exc.kind == "too_large":
            raise XacroError(M("refused to read {path}: more than {limit} MiB", path=path,
                               limit=limit >> 20)) from None
        raise XacroError(M("refused to read {path}: {reason}", path=path, reason=refusal(exc.kind)),
                         hint=M("keep the robot's files inside its package, or pass the other package with "
                                "--package-path")) from None


def _inside(path: str, folders: Iterable[str]) -> bool:
    real = os.path.realpath(path)
    return any(real == f or real.startswith(f.rstrip(os.sep) + os.sep) for f in folders)
