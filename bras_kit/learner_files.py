"""The one reader for files bras-kit's own process reads on a learner's behalf: the URDF file
given to robot_state_publisher, RViz's ``-d`` configuration, the package's own sources read by
the static rules, the files ``data_files`` installs.

A path is read only when it stays under one of the folders it belongs to (the package, the
workspace, the install tree: :func:`bras_kit.beneath.beneath`), is a regular file (never a
device such as ``/dev/zero``, a pipe or a socket: the file is opened without blocking and
checked again once open, so a file swapped for a link or a pipe after the check is refused
too) and holds at most ``limit`` bytes. A refusal (:class:`Unreadable`, an ``OSError``) names
the path and why, never a byte of the file::

    from bras_kit.learner_files import read_text
    text = read_text(path, roots=(package_root, install_prefix))
"""

from __future__ import annotations

import os
import stat

from .beneath import FILE, Outside, beneath_any

MAX_BYTES = 8 << 20  # a launch file, an .rviz, a URDF, a parameter file
MAX_COPY_BYTES = 256 << 20  # a mesh installed by data_files (the mesh reader's own cap)


class Unreadable(Outside):
    """A file bras-kit does not read for the learner: ``kind`` is a :data:`bras_kit.beneath.KINDS`
    or "too_large"."""


def _open(path: str, roots: tuple[str, ...], limit: int) -> tuple[int, int]:
    try:
        resolved = beneath_any(roots, path, want=FILE)
    except Outside as exc:
        raise Unreadable(exc.kind, os.fspath(path), exc.root) from None
    flags = os.O_RDONLY | os.O_NONBLOCK | getattr(os, "O_NOFOLLOW", 0) | getattr(os, "O_CLOEXEC", 0)
    try:
        fd = os.open(resolved, flags)
    except OSError:
        raise Unreadable("missing", os.fspath(path)) from None
    info = os.fstat(fd)
    if not stat.S_ISREG(info.st_mode) or info.st_size > limit:
        os.close(fd)
        raise Unreadable("device" if not stat.S_ISREG(info.st_mode) else "too_large", os.fspath(path))
    return fd, info.st_size


def read_bytes(path: str, roots: tuple[str, ...] | list[str], *, limit: int = MAX_BYTES) -> bytes:
    """The file's bytes, when bras-kit may read it (see the module's words); else :class:`Unreadable`."""
    fd, _size = _open(os.fspath(path), tuple(roots), limit)
    with os.fdopen(fd, "rb") as handle:
        data = handle.read(limit + 1)  # a file that grows after the check is still cut at the limit
    if len(data) > limit:
        raise Unreadable("too_large", os.fspath(path))
    return data


def read_text(path: str, roots: tuple[str, ...] | list[str], *, limit: int = MAX_BYTES,
              errors: str = "strict") -> str:
    """:func:`read_bytes` decoded as UTF-8 (``errors`` as for ``bytes.decode``)."""
    return read_bytes(path, roots, limit=limit).decode("utf-8", errors)


def copy_file(path: str, roots: tuple[str, ...] | list[str], target: str, *, limit: int = MAX_COPY_BYTES) -> None:
    """Copy the file to ``target`` (a new file, written by bras-kit) when bras-kit may read it."""
    fd, _size = _open(os.fspath(path), tuple(roots), limit)
    with os.fdopen(fd, "rb") as source, open(target, "xb") as sink:
        copied = 0
        while True:
            chunk = source.read(1 << 20)
            if not chunk:
                break
            copied += len(chunk)
            if copied > limit:
                raise Unreadable("too_large", os.fspath(path))
            sink.write(chunk)
