"""The contained code's view of the filesystem: the granted paths, bound at their own place
in a fresh read-only root, its folder a bounded tmpfs, and the old root detached."""

from __future__ import annotations

import ctypes
import functools
import os
import platform
import sys
import sysconfig
from collections.abc import Iterable

from .kernel import _check, _libc

MS_RDONLY, MS_NOSUID, MS_NODEV, MS_NOEXEC = 1, 2, 4, 8
MS_REMOUNT, MS_BIND, MS_REC, MS_PRIVATE = 32, 4096, 16384, 1 << 18
MS_NOATIME, MS_NODIRATIME, MS_RELATIME = 1024, 2048, 1 << 21
ST_RELATIME = 4096  # statvfs's flag for MS_RELATIME (the other ST_ flags equal the MS_ ones)
MNT_DETACH = 2
PIVOT_ROOT = {"x86_64": 155, "aarch64": 41, "arm64": 41, "riscv64": 41, "ppc64le": 203, "ppc64": 203,
              "s390x": 217, "armv7l": 218, "i686": 217, "i386": 217}
MAX_FOLDER_BYTES = 256 << 20  # all it may write in its folder (a tmpfs: kept in memory, never on disk)
MAX_FOLDER_FILES = 4096  # the files and folders it may make there (each inode costs kernel memory)
STAGING = ".bras-kit-root"  # where the new root is built, in the real folder (removed once it is the root)
ROOT_BYTES = 1 << 20  # the tmpfs that holds the mount points (read-only once built)
SYSTEM = ("/usr", "/lib", "/lib64", "/lib32", "/libx32", "/bin", "/sbin")
SYSTEM_FILES = ("/etc/ld.so.cache", "/etc/localtime")
DEVICES_READ = ("/dev/zero", "/dev/urandom", "/dev/random")
DEVICES_WRITE = ("/dev/null", "/dev/full")


def python_paths() -> list[str]:
    """The Python installation (prefixes, stdlib, site-packages), bras-kit itself, and the
    folders on ``sys.path`` that belong to an installation (never the current folder)."""
    here = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))  # bras_kit/
    paths = {sys.prefix, sys.base_prefix, sys.exec_prefix, sys.base_exec_prefix, here, *_installation()}
    paths.update(p for p in sys.path if p and ("site-packages" in p or "dist-packages" in p))
    home = os.path.abspath(os.path.expanduser("~"))
    # never "/" nor the home folder (a Python installed as ~ itself): its own folders are granted instead
    return sorted(p for p in {os.path.abspath(p) for p in paths if p}
                  if p != "/" and not (home + "/").startswith(p.rstrip("/") + "/"))


@functools.lru_cache(maxsize=1)
def _installation() -> tuple[str, ...]:
    """The interpreter's stdlib and site-packages folders (sysconfig takes 2 ms to work them out:
    once per process, and a child forked after the first containment has them)."""
    return tuple(v for k, v in sysconfig.get_paths().items() if k in ("stdlib", "platstdlib", "purelib", "platlib"))


def _existing(paths: Iterable[str]) -> list[str]:
    out: list[str] = []
    for path in paths:
        real = os.path.abspath(path)
        if os.path.exists(real) and real not in out:
            out.append(real)
    # a path inside another granted one is already there (and would be bound twice)
    return [p for p in out if not any(p != q and p.startswith(q.rstrip("/") + "/") for q in out)
            or p in DEVICES_WRITE]


def _mount(source: str | None, target: str, kind: str | None, flags: int, data: str | None = None) -> None:
    def b(text: str | None) -> bytes | None:
        return None if text is None else os.fsencode(text)

    _check(_libc.mount(b(source), b(target), b(kind), ctypes.c_ulong(flags), b(data)), f"mount {target}")


def _locked_flags(path: str) -> int:
    """The flags a bind mount of ``path`` must keep (a user namespace may not clear them)."""
    flags = os.statvfs(path).f_flag
    out = flags & (MS_NOSUID | MS_NODEV | MS_NOEXEC | MS_NOATIME | MS_NODIRATIME)
    if flags & ST_RELATIME:
        out |= MS_RELATIME
    return out


def _bind(path: str, staging: str, writable: bool) -> None:
    target = staging + path
    if os.path.isdir(path):
        os.makedirs(target, exist_ok=True)
    else:
        os.makedirs(os.path.dirname(target), exist_ok=True)
        if not os.path.exists(target):
            os.close(os.open(target, os.O_CREAT | os.O_WRONLY, 0o600))
    _mount(path, target, None, MS_BIND)
    _mount(None, target, None, MS_REMOUNT | MS_BIND | _locked_flags(path) | (0 if writable else MS_RDONLY))


def _build_root(staging: str, read: list[str], write: list[str], workdir: str, folder_bytes: int,
                owner: tuple[int, int]) -> None:
    """The new root, built at ``staging``: ``read`` bound read-only, ``write`` read-write but
    ``workdir``, a bounded tmpfs (:func:`_bounded_folder`)."""
    _mount(None, "/", None, MS_REC | MS_PRIVATE)  # nothing below propagates back to this machine
    _mount("tmpfs", staging, "tmpfs", MS_NOSUID | MS_NODEV, f"size={ROOT_BYTES},mode=0755")
    previous = os.umask(0o022)  # the folders on the way to a granted path: open to the identity the code runs as
    try:
        for path in SYSTEM:  # a merged /usr: /lib -> usr/lib stays a symbolic link
            if os.path.islink(path):
                os.symlink(os.readlink(path), staging + path)
        for path in read:
            if not os.path.lexists(staging + path):
                _bind(path, staging, writable=False)
        for path in write:
            if path == os.path.abspath(workdir):
                _bounded_folder(path, staging, folder_bytes, owner)
            else:
                _bind(path, staging, writable=True)
    finally:
        os.umask(previous)


def _bounded_folder(workdir: str, staging: str, most: int, owner: tuple[int, int]) -> None:
    """The code's folder: a tmpfs of ``most`` bytes and :data:`MAX_FOLDER_FILES` files, owned
    by the identity it runs as, holding what the caller put in ``workdir`` (its files and
    folders bound read-only, its empty folders as empty folders of its own, to write in). A
    node filling it gets ENOSPC at its line; nothing it writes reaches this machine's disk
    (every caller's folder is a temporary one, removed after the run)."""
    target = staging + workdir
    os.makedirs(target, exist_ok=True)
    names = sorted(n for n in os.listdir(workdir) if n != STAGING)
    _mount("tmpfs", target, "tmpfs", MS_NOSUID | MS_NODEV,
           f"size={most},nr_inodes={MAX_FOLDER_FILES},mode=0700,uid={owner[0]},gid={owner[1]}")
    for name in names:
        path = os.path.join(workdir, name)
        if os.path.isdir(path) and not os.path.islink(path) and not os.listdir(path):
            os.mkdir(os.path.join(target, name), 0o755)
            os.chown(os.path.join(target, name), *owner)
        elif os.path.islink(path):
            os.symlink(os.readlink(path), os.path.join(target, name))
            os.lchown(os.path.join(target, name), *owner)
        else:
            _bind(path, staging, writable=False)


def _pivot(staging: str) -> None:
    os.chdir(staging)
    number = PIVOT_ROOT[platform.machine()]
    _check(_libc.syscall(ctypes.c_long(number), b".", b"."), "pivot_root")
    _check(_libc.umount2(b".", ctypes.c_int(MNT_DETACH)), "umount")  # the old root, now stacked on the new
    os.chdir("/")
    _mount(None, "/", None, MS_REMOUNT | MS_RDONLY | MS_NOSUID | MS_NODEV)
