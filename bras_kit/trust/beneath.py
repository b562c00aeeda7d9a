"""A path stays under its root: the one test for every name or path a learner's file hands to
bras-kit's own process (``setup()``'s arguments, a launch file's file arguments...).

The model is openat2(2) with ``RESOLVE_BENEATH``: the path is resolved with its symbolic links
followed, and what it resolves to must lie under the root (``pathlib``'s ``is_relative_to``).
``..`` that leaves the root, an absolute path elsewhere, a link that points out, a loop of links,
and a device, pipe or socket where a file or folder is expected are each refused with their own
``kind``, never followed into::

    from bras_kit.trust.beneath import Outside, beneath
    beneath("/ws/src/bras", "urdf/bras.urdf")          # '/ws/src/bras/urdf/bras.urdf'
    beneath("/ws/src/bras", "../../etc/passwd")       # raises Outside(kind="outside")

:func:`beneath` answers with a path, which a later ``open`` resolves again: a folder swapped for a
link in between is followed. What bras-kit reads or writes on a learner's behalf is opened with
:func:`open_beneath` instead, which resolves the path component by component from a descriptor of
the root and gives the descriptor of what it found: nothing is resolved twice. The kernel does it
with openat2(2) and ``RESOLVE_BENEATH | RESOLVE_NO_MAGICLINKS`` where it has the call (Linux 5.6);
otherwise, and for every refusal (so that its ``kind`` is ours, and an absolute link that points
inside the root is followed as :func:`beneath` follows it), each component is opened with
``O_NOFOLLOW`` relative to the folder before it (``os.open(name, flags, dir_fd=fd)``), a link is
read with ``readlinkat`` and its target resolved the same way, and ``..`` goes back to a
descriptor already held, never above the root's::

    fd = open_beneath("/ws/src/bras", "urdf/bras.urdf")   # a descriptor of the regular file
"""

from __future__ import annotations

import contextlib
import ctypes
import errno
import os
import stat
from collections import deque
from pathlib import PurePath

FILE, FOLDER, ANY = "file", "folder", "any"

# why a path is refused (Outside.kind)
KINDS = ("empty", "outside", "link_out", "loop", "missing", "device", "fifo", "socket", "folder", "not_folder",
         "too_deep")

MAX_LINKS = 40  # the kernel's own bound on the links one resolution follows (path_resolution(7))
MAX_DEPTH = 256  # folders deep: a descriptor is held for each, for ``..``
MAX_PATH = 4096  # PATH_MAX


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
    "too_deep": "too deep a path (more than 256 folders, or 4,096 characters)",
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
    resolved = _realpath(joined, text, root)
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


def _realpath(joined: str, text: str, root: str) -> str:
    """os.path.realpath, which raises when a link it met is swapped while it reads it (lstat, then
    readlink): looked at again, then refused as missing. The answer is a check only: what is read
    is opened with :func:`open_beneath`."""
    for _ in range(3):
        try:
            return os.path.realpath(joined)
        except OSError:
            continue
    raise Outside("missing", text, root)


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


# ---------------------------------------------------------------- opening beneath a root, by descriptor

_DIR_FLAGS = os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC | os.O_NOFOLLOW
_FILE_FLAGS = os.O_RDONLY | os.O_NONBLOCK | os.O_NOCTTY | os.O_CLOEXEC | os.O_NOFOLLOW
_RESOLVE_NO_MAGICLINKS, _RESOLVE_BENEATH = 0x02, 0x08
_OPENAT2 = {"x86_64": 437, "aarch64": 437, "armv7l": 437, "riscv64": 437}.get(os.uname().machine)


class _OpenHow(ctypes.Structure):
    _fields_ = [("flags", ctypes.c_uint64), ("mode", ctypes.c_uint64), ("resolve", ctypes.c_uint64)]


_kernel: dict[str, object] = {}


def _openat2(root_fd: int, path: str, flags: int) -> int | None:
    """openat2(2) with RESOLVE_BENEATH: the descriptor, or None (no such call, or any refusal,
    which the walk then states in its own words)."""
    if _OPENAT2 is None or _kernel.get("openat2") is False:
        return None
    libc = _kernel.get("libc")
    if libc is None:
        try:
            libc = _kernel["libc"] = ctypes.CDLL(None, use_errno=True)
        except OSError:
            _kernel["openat2"] = False
            return None
    how = _OpenHow(flags & ~os.O_NOFOLLOW, 0, _RESOLVE_BENEATH | _RESOLVE_NO_MAGICLINKS)
    syscall = libc.syscall  # type: ignore[attr-defined]
    syscall.restype = ctypes.c_long
    fd = int(syscall(ctypes.c_long(_OPENAT2), ctypes.c_int(root_fd), ctypes.c_char_p(os.fsencode(path)),
                     ctypes.byref(how), ctypes.c_size_t(ctypes.sizeof(how))))
    if fd < 0:
        if ctypes.get_errno() in (errno.ENOSYS, errno.EPERM, errno.EINVAL):  # an old kernel, a seccomp filter
            _kernel["openat2"] = False
        return None
    return fd


def _parts(text: str) -> list[str]:
    return [part for part in text.split("/") if part not in ("", ".")]


def _within(root: str, target: str) -> list[str] | None:
    """The components of absolute ``target`` below ``root`` (its text or its real path), or None."""
    for top in dict.fromkeys((os.path.abspath(root), os.path.realpath(root))):
        normal = os.path.normpath(target)
        if _inside(normal, top):
            return _parts(os.path.relpath(normal, top)) if normal != top else []
    return None


def open_root(root: str) -> int:
    """A descriptor of the folder ``root`` (the caller named it: links in it are followed)."""
    try:
        return os.open(root, os.O_RDONLY | os.O_DIRECTORY | os.O_CLOEXEC)
    except OSError as exc:
        raise Outside("loop" if exc.errno == errno.ELOOP else "missing" if exc.errno in (
            errno.ENOENT, errno.ENOTDIR) else "not_folder", root, root) from None


def open_beneath(root: str, path: str, *, want: str = FILE, root_fd: int | None = None) -> int:
    """A descriptor of ``path`` (relative to ``root``, or absolute and inside it) resolved under
    ``root`` without leaving it (see the module's words): a regular file opened for reading
    without blocking (``want=FILE``), a folder (``FOLDER``), or either (``ANY``); else
    :class:`Outside`. ``root_fd``, when given, is a descriptor of ``root`` already open."""
    text = os.fspath(path)
    if not text or "\0" in text:
        raise Outside("empty", text, root)
    if len(text) > MAX_PATH:
        raise Outside("too_deep", text[:200], root)
    own = root_fd is None
    top = open_root(root) if root_fd is None else root_fd
    try:
        if text.startswith("/"):
            parts = _within(root, text)
            if parts is None:
                raise Outside("outside", text, root)
        else:
            parts = _parts(text)
        relative = "/".join(parts) or "."
        flags = _DIR_FLAGS if want == FOLDER else _FILE_FLAGS
        fd = _openat2(top, relative, flags)
        if fd is not None:
            kind = _refused_kind(os.fstat(fd).st_mode, want)
            if not kind:
                return fd
            os.close(fd)
            raise Outside(kind, text, root)
        return _walk(root, top, parts, want, text)
    finally:
        if own:
            os.close(top)


def _walk(root: str, top: int, parts: list[str], want: str, text: str) -> int:
    held = [os.dup(top)]  # the folders walked through, the root first: ``..`` goes back one
    pending = deque(parts)
    links = 0
    try:
        while pending:
            name = pending.popleft()
            if name in ("", "."):
                continue
            if name == "..":
                if len(held) == 1:
                    raise Outside("link_out" if links else "outside", text, root)
                os.close(held.pop())
                continue
            try:
                info = os.stat(name, dir_fd=held[-1], follow_symlinks=False)
            except OSError as exc:
                raise Outside("too_deep" if exc.errno == errno.ENAMETOOLONG else "missing", text, root) from None
            if stat.S_ISLNK(info.st_mode):
                links += 1
                if links > MAX_LINKS:
                    raise Outside("loop", text, root)
                try:
                    target = os.readlink(name, dir_fd=held[-1])
                except OSError:
                    pending.appendleft(name)  # swapped back since the stat: look again
                    continue
                if target.startswith("/"):
                    inner = _within(root, target)
                    if inner is None:
                        raise Outside("link_out", text, root)
                    for fd in held[1:]:
                        os.close(fd)
                    del held[1:]
                    pending.extendleft(reversed(inner))
                else:
                    pending.extendleft(reversed(_parts(target)))
                if len(pending) > MAX_PATH:
                    raise Outside("too_deep", text, root)
                continue
            if pending or want == FOLDER:
                if not stat.S_ISDIR(info.st_mode):
                    raise Outside("not_folder" if not pending else "missing", text, root)
                if len(held) > MAX_DEPTH:
                    raise Outside("too_deep", text, root)
                try:
                    held.append(os.open(name, _DIR_FLAGS, dir_fd=held[-1]))
                except OSError as exc:
                    links = _swapped(exc, name, pending, links, text, root)
                continue
            kind = _refused_kind(info.st_mode, want)
            if kind:
                raise Outside(kind, text, root)
            try:
                fd = os.open(name, _FILE_FLAGS | (os.O_DIRECTORY if stat.S_ISDIR(info.st_mode) else 0),
                             dir_fd=held[-1])
            except OSError as exc:
                links = _swapped(exc, name, pending, links, text, root)
                continue
            kind = _refused_kind(os.fstat(fd).st_mode, want)
            if kind:
                os.close(fd)
                raise Outside(kind, text, root)
            return fd
        kind = _refused_kind(stat.S_IFDIR, want)  # the path ends on a folder: ".", "urdf/..", a link to one
        if kind:
            raise Outside(kind, text, root)
        return held.pop()
    finally:
        for fd in held:
            with contextlib.suppress(OSError):
                os.close(fd)


def open_any_beneath(roots: tuple[str, ...] | list[str], path: str, *, want: str = FILE) -> tuple[int, str]:
    """:func:`open_beneath` for the first of ``roots`` that holds ``path``, with that root; the
    refusal as :func:`beneath_any` chooses it otherwise."""
    text = os.fspath(path)
    refusal = Outside("outside", text)
    for root in roots:
        given = text
        if not os.path.isabs(text) and not os.path.isabs(root) and _inside(os.path.normpath(text), root) \
                and os.path.normpath(root) != ".":
            given = os.path.abspath(text)  # both named from the current folder: "pkg" and "pkg/setup.py"
        try:
            return open_beneath(root, given, want=want), root
        except Outside as exc:
            if exc.kind not in ("outside", "link_out") or refusal.kind in ("outside", "link_out"):
                refusal = exc
    raise refusal


def _swapped(exc: OSError, name: str, pending: deque[str], links: int, text: str, root: str) -> int:
    """A component that changed between its stat and its open (a link now, or gone): walked again,
    counted as a link so that a swap repeated without end is a loop; any other failure is "missing"."""
    if exc.errno not in (errno.ELOOP, errno.ENOTDIR, errno.ENOENT):
        raise Outside("missing", text, root) from None
    if links + 1 > MAX_LINKS:
        raise Outside("loop", text, root) from None
    pending.appendleft(name)
    return links + 1
