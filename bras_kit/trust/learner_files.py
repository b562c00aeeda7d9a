"""The one reader for files bras-kit's own process reads on a learner's behalf: the URDF file
given to robot_state_publisher, RViz's ``-d`` configuration, the package's own sources read by
the static rules, the files ``data_files`` installs.

A path is read only when it stays under one of the folders it belongs to (the package, the
workspace, the install tree), is a regular file (never a device such as ``/dev/zero``, a pipe
or a socket) and holds at most ``limit`` bytes. The path is resolved once, component by
component from a descriptor of the root (:func:`bras_kit.trust.beneath.open_beneath`: no link
followed out of the root, none of its folders resolved twice), and the file is read through
the descriptor that walk opened: a folder swapped for a link between a check and the read
changes nothing, as there is no check apart from the open. Folders are listed through their
descriptor too (:func:`list_folder`, :func:`walk`), and what bras-kit writes for the learner
(:func:`copy_file`'s target, :func:`write_file`) is made under its own root without
following a link there either, and replaces a file atomically (a temporary beside it, then
``os.replace`` in that folder's descriptor). A refusal (:class:`Unreadable`, an ``OSError``) names
the path and why, never a byte of the file::

    from bras_kit.trust.learner_files import read_text
    text = read_text(path, roots=(package_root, install_prefix))
"""

from __future__ import annotations

import contextlib
import errno
import os
import secrets
import stat
from collections.abc import Iterator

from ..core.message import M, Message
from .beneath import ANY, FILE, FOLDER, Outside, open_any_beneath, open_beneath, open_root

MAX_BYTES = 8 << 20  # a launch file, an .rviz, a URDF, a parameter file
MAX_COPY_BYTES = 256 << 20  # a mesh installed by data_files (the mesh reader's own cap)
MAX_LISTED = 100_000  # names in one folder


def refusal(kind: str) -> Message:
    """Why the one reader refused a path (an :class:`Unreadable`'s or :class:`~bras_kit.trust.beneath.Outside`'s
    ``kind``), in the message system: the words a refusal shows, never a byte of the file."""
    return {
        "outside": M("it lies outside the folders it is read from (the package, the submission, the folders given with "
                     "--package-path)"),
        "link_out": M("a symbolic link on the way leads outside the folders it is read from"),
        "loop": M("a loop of symbolic links"),
        "device": M("it is a device, not a file"),
        "fifo": M("it is a named pipe, not a file"),
        "socket": M("it is a socket, not a file"),
        "folder": M("it is a folder, not a file"),
        "too_large": M("it is larger than bras-kit reads"),
        "missing": M("no such file or folder"),
        "not_folder": M("a part of the path is not a folder"),
        "too_deep": M("the path is too deep"),
    }.get(kind, M("it cannot be read"))


class Unreadable(Outside):
    """A file bras-kit does not read for the learner: ``kind`` is a :data:`bras_kit.trust.beneath.KINDS`
    or "too_large"."""


def _open(path: str, roots: tuple[str, ...], limit: int, want: str = FILE) -> tuple[int, int]:
    try:
        fd, _root = open_any_beneath(roots, path, want=want)
    except Outside as exc:
        raise Unreadable(exc.kind, os.fspath(path), exc.root) from None
    info = os.fstat(fd)
    if stat.S_ISREG(info.st_mode) and info.st_size > limit:
        os.close(fd)
        raise Unreadable("too_large", os.fspath(path))
    return fd, info.st_size


def _read_fd(fd: int, path: str, limit: int) -> bytes:
    with os.fdopen(fd, "rb") as handle:
        data = handle.read(limit + 1)  # a file that grows after the open is still cut at the limit
    if len(data) > limit:
        raise Unreadable("too_large", path)
    return data


def read_bytes(path: str, roots: tuple[str, ...] | list[str], *, limit: int = MAX_BYTES) -> bytes:
    """The file's bytes, when bras-kit may read it (see the module's words); else :class:`Unreadable`."""
    fd, _size = _open(os.fspath(path), tuple(roots), limit)
    return _read_fd(fd, os.fspath(path), limit)


def read_text(path: str, roots: tuple[str, ...] | list[str], *, limit: int = MAX_BYTES,
              errors: str = "strict") -> str:
    """:func:`read_bytes` decoded as UTF-8 (``errors`` as for ``bytes.decode``)."""
    return read_bytes(path, roots, limit=limit).decode("utf-8", errors)


def is_file(path: str, roots: tuple[str, ...] | list[str]) -> bool:
    """Whether ``path`` is a regular file bras-kit may read under ``roots`` (opened, then closed)."""
    return _reaches(path, roots, FILE)


def is_folder(path: str, roots: tuple[str, ...] | list[str]) -> bool:
    """Whether ``path`` is a folder under ``roots``, reached without a link out of them."""
    return _reaches(path, roots, FOLDER)


def _reaches(path: str, roots: tuple[str, ...] | list[str], want: str) -> bool:
    try:
        fd, _root = open_any_beneath(tuple(roots), os.fspath(path), want=want)
    except Outside:
        return False
    os.close(fd)
    return True


def list_folder(path: str, roots: tuple[str, ...] | list[str]) -> list[tuple[str, str]]:
    """(name, kind) of each entry of the folder, sorted, listed through its descriptor: kind is
    "file", "folder", "link" (not followed: read it with this module to know where it leads) or
    "other" (a pipe, a socket, a device)."""
    fd, _size = _open(os.fspath(path), tuple(roots), MAX_BYTES, want=FOLDER)
    try:
        return _entries(fd)
    finally:
        os.close(fd)


def _entries(fd: int) -> list[tuple[str, str]]:
    out: list[tuple[str, str]] = []
    with os.scandir(fd) as entries:
        for entry in entries:
            if len(out) >= MAX_LISTED:
                break
            kind = ("link" if entry.is_symlink() else "folder" if entry.is_dir(follow_symlinks=False)
                    else "file" if entry.is_file(follow_symlinks=False) else "other")
            out.append((entry.name, kind))
    return sorted(out)


def walk(path: str, roots: tuple[str, ...] | list[str]) -> Iterator[tuple[str, list[str], list[str]]]:
    """``os.walk`` of the folder under ``roots``, through descriptors (``os.fwalk``): (folder,
    folders, files) with ``folder`` beginning with ``path``; a link to a folder is never walked
    into (it is listed among ``files``, to be read through this module like any file), and a
    caller may prune ``folders`` as with ``os.walk``. Files are regular files and links."""
    text = os.fspath(path)
    fd, _size = _open(text, tuple(roots), MAX_BYTES, want=FOLDER)
    try:
        for place, folders, _files, place_fd in os.fwalk(".", dir_fd=fd, follow_symlinks=False):
            entries = _entries(place_fd)
            real = [name for name, kind in entries if kind == "folder"]
            files = [name for name, kind in entries if kind in ("file", "link")]
            folders[:] = real
            shown = os.path.normpath(os.path.join(text, place))
            yield shown, folders, files
    finally:
        os.close(fd)


def folder_size(path: str, roots: tuple[str, ...] | list[str], *, stop_past: int | None = None) -> int:
    """The bytes of the regular files under the folder (a file: its own size), counted through
    descriptors as :func:`walk` goes: a link is neither followed nor counted, and a folder swapped
    for a link while counting is not entered. Stops once past ``stop_past``."""
    fd, size = _open(os.fspath(path), tuple(roots), 1 << 62, want=ANY)
    if not stat.S_ISDIR(os.fstat(fd).st_mode):
        os.close(fd)
        return size
    total = 0
    try:
        for _place, _folders, files, place_fd in os.fwalk(".", dir_fd=fd, follow_symlinks=False):
            for name in files:
                try:
                    info = os.stat(name, dir_fd=place_fd, follow_symlinks=False)
                except FileNotFoundError:  # removed while counting
                    continue
                if stat.S_ISREG(info.st_mode):
                    total += info.st_size
            if stop_past is not None and total > stop_past:
                break
    finally:
        os.close(fd)
    return total


# ---------------------------------------------------------------- writing under a root, by descriptor


def _parent_fd(root: str, relative: str, *, make: bool) -> tuple[int, str]:
    """A descriptor of the folder that holds ``relative`` under ``root`` (made when ``make``,
    folder by folder with ``mkdirat``), and the file's own name. No link is followed out."""
    folder, name = os.path.split(os.path.normpath(relative))
    if not name or name in (".", "..") or relative.startswith("/"):
        raise Outside("outside", relative, root)
    parts = [p for p in folder.split("/") if p not in ("", ".")]
    top = open_root(root)
    try:
        fd = os.dup(top)
        for index, part in enumerate(parts):
            try:  # each folder resolved from the root, so that a link inside the root is followed as a read follows it
                inner = open_beneath(root, "/".join(parts[:index + 1]), want=FOLDER, root_fd=top)
            except Outside as exc:
                if exc.kind != "missing" or not make:
                    os.close(fd)
                    raise
                try:
                    with contextlib.suppress(FileExistsError):
                        os.mkdir(part, 0o777, dir_fd=fd)
                    inner = os.open(part, os.O_RDONLY | os.O_DIRECTORY | os.O_NOFOLLOW | os.O_CLOEXEC, dir_fd=fd)
                except OSError:
                    os.close(fd)
                    raise
            os.close(fd)
            fd = inner
        return fd, name
    finally:
        os.close(top)


def make_folder(root: str, relative: str) -> None:
    """The folder ``relative`` under ``root``, made folder by folder as :func:`write_file` makes a
    file's parents (setuptools' install_data makes a data_files folder that receives no file)."""
    fd, name = _parent_fd(root, relative, make=True)
    try:
        with contextlib.suppress(FileExistsError):
            os.mkdir(name, 0o777, dir_fd=fd)
    finally:
        os.close(fd)


def make_link(root: str, relative: str, points_to: str) -> None:
    """A symbolic link ``relative`` under ``root`` whose text is ``points_to`` (``colcon build
    --symlink-install``), its folders made as :func:`write_file` makes them; an entry already
    there is replaced only when it is a link or a file, never followed."""
    fd, name = _parent_fd(root, relative, make=True)
    try:
        try:
            info = os.lstat(name, dir_fd=fd)
        except FileNotFoundError:
            info = None
        if info is not None:
            if stat.S_ISDIR(info.st_mode):
                raise IsADirectoryError(errno.EISDIR, "a folder is in the way", os.path.join(root, relative))
            os.unlink(name, dir_fd=fd)
        os.symlink(points_to, name, dir_fd=fd)
    finally:
        os.close(fd)


def _write_new(fd: int, name: str, chunks: Iterator[bytes], mode: int | None) -> None:
    """A new file (never an existing one, never through a link); ``mode`` exactly, or 0o666 less the umask."""
    out = os.open(name, os.O_WRONLY | os.O_CREAT | os.O_EXCL | os.O_NOFOLLOW | os.O_CLOEXEC, 0o666 if mode is None
                  else mode & 0o700, dir_fd=fd)
    try:
        if mode is not None:
            os.fchmod(out, mode)
        with os.fdopen(out, "wb", closefd=False) as sink:
            for chunk in chunks:
                sink.write(chunk)
    finally:
        os.close(out)


def write_file(root: str, relative: str, data: bytes, *, mode: int | None = None, replace: bool = True) -> str:
    """``data`` as the file ``relative`` under ``root``, its folders made on the way, without
    following a link out of ``root``: written whole to a new temporary beside it (``O_EXCL |
    O_NOFOLLOW``: a link planted under that name is never written through) then moved over the
    old file with ``os.replace`` in the folder's descriptor (a link in its place is replaced,
    never followed). ``replace=False`` refuses an existing entry (FileExistsError). ``mode``:
    the file's mode exactly (default: 0o666 less the umask). The path written."""
    fd, name = _parent_fd(root, relative, make=True)
    try:
        if not replace:
            _write_new(fd, name, iter((data,)), mode)
            return os.path.join(root, relative)
        temporary = f".{name}.{secrets.token_hex(6)}.tmp"
        _write_new(fd, temporary, iter((data,)), mode)
        try:
            os.replace(temporary, name, src_dir_fd=fd, dst_dir_fd=fd)
        except OSError:
            with contextlib.suppress(OSError):
                os.unlink(temporary, dir_fd=fd)
            raise
        return os.path.join(root, relative)
    finally:
        os.close(fd)


def copy_file(path: str, roots: tuple[str, ...] | list[str], target: str, *, limit: int = MAX_COPY_BYTES,
              target_root: str | None = None, replace: bool = False, mode: int | None = None) -> None:
    """Copy the file to ``target`` when bras-kit may read it, reading from the descriptor the
    walk opened. The target is made under ``target_root`` (default: the folder holding it) with
    no link followed there either: a new file (``O_EXCL``), or, with ``replace``, a temporary
    moved over the old one."""
    source_fd, _size = _open(os.fspath(path), tuple(roots), limit)
    base = target_root if target_root is not None else os.path.dirname(os.path.abspath(target))
    relative = os.path.relpath(os.path.abspath(target), os.path.abspath(base))
    try:
        with os.fdopen(source_fd, "rb") as source:
            fd, name = _parent_fd(base, relative, make=target_root is not None)
            try:
                written = f".{name}.{secrets.token_hex(6)}.tmp" if replace else name
                _write_new(fd, written, _chunks(source, os.fspath(path), limit), mode)
                if replace:
                    os.replace(written, name, src_dir_fd=fd, dst_dir_fd=fd)
            except BaseException:
                if replace:
                    with contextlib.suppress(OSError):
                        os.unlink(written, dir_fd=fd)
                raise
            finally:
                os.close(fd)
    except Outside as exc:
        if isinstance(exc, Unreadable):
            raise
        raise OSError(errno.ELOOP, f"{target}: {exc.strerror or exc}", target) from None


def _chunks(source, path: str, limit: int) -> Iterator[bytes]:
    copied = 0
    while True:
        chunk = source.read(1 << 20)
        if not chunk:
            return
        copied += len(chunk)
        if copied > limit:
            raise Unreadable("too_large", path)
        yield chunk


__all__ = ["ANY", "FILE", "FOLDER", "MAX_BYTES", "MAX_COPY_BYTES", "Unreadable", "copy_file", "is_file", "make_folder", "make_link",
           "refusal",
           "is_folder", "list_folder", "read_bytes", "read_text", "walk", "write_file"]
