"""The seccomp filter: libseccomp through ``pyseccomp``, loaded last, refusing new namespaces,
mounts and the kernel keyrings to the contained code and everything it starts."""

from __future__ import annotations

import errno
import functools
import platform
from typing import Any

from ...core.message import M
from .kernel import ContainmentError
from .namespaces import (
    CLONE_NEWCGROUP,
    CLONE_NEWIPC,
    CLONE_NEWNET,
    CLONE_NEWNS,
    CLONE_NEWPID,
    CLONE_NEWUSER,
    CLONE_NEWUTS,
)

NEW_NAMESPACE_FLAGS = (CLONE_NEWNS, CLONE_NEWCGROUP, CLONE_NEWUTS, CLONE_NEWIPC, CLONE_NEWUSER, CLONE_NEWPID,
                       CLONE_NEWNET)
# refused to the contained code (EPERM): namespaces and mounts (a nested user namespace would give
# it every capability there, and a tmpfs it mounts is memory no limit counts), and the kernel's
# keyrings, which are per user and not namespaced (Docker's default profile refuses the same)
REFUSED_CALLS = ("unshare", "setns", "mount", "umount", "umount2", "pivot_root", "chroot", "fsopen", "fsconfig",
                 "fsmount", "fspick", "move_mount", "open_tree", "mount_setattr", "keyctl", "add_key", "request_key")


@functools.lru_cache(maxsize=1)
def _seccomp() -> object:
    """pyseccomp (libseccomp through ctypes), or a :class:`ContainmentError` naming the step."""
    try:
        pyseccomp = _import_pyseccomp()
    except (ImportError, RuntimeError, OSError) as exc:  # RuntimeError: libseccomp.so.2 not found
        error = ContainmentError(M("the containment could not be set up: {step} failed ({reason})",
                                   step="libseccomp", reason=str(exc)))
        error.errno, error.step = errno.ENOENT, "libseccomp"  # type: ignore[attr-defined]
        raise error from None
    return pyseccomp


# the libraries pyseccomp asks ctypes.util.find_library for, by the names the dynamic loader knows
# them by (glibc's C library; libseccomp's one ABI since version 2.0)
SONAMES = {"c": "libc.so.6", "seccomp": "libseccomp.so.2"}


def _import_pyseccomp() -> Any:
    """``import pyseccomp``, whose two libraries are first looked for by their :data:`SONAMES`:
    ``find_library`` runs ``ldconfig -p`` for each (5 ms, on the way to every contained child of
    ``validate PKG_DIR``). Where the loader does not know a soname (another C library, a
    libseccomp of another ABI), ``find_library`` answers as before."""
    import ctypes.util

    looked_up = ctypes.util.find_library

    def find_library(name: str) -> str | None:
        soname = SONAMES.get(name)
        if soname is not None:
            try:
                ctypes.CDLL(soname)
                return soname
            except OSError:
                pass
        return looked_up(name)

    ctypes.util.find_library = find_library
    try:
        import pyseccomp
    finally:
        ctypes.util.find_library = looked_up
    return pyseccomp


def _refuse_namespaces_and_mounts(seccomp: object) -> None:
    """Load the filter of :data:`REFUSED_CALLS` (EPERM) and of ``clone`` with a namespace flag;
    ``clone3``, whose flags sit in memory a filter cannot read, answers ENOSYS, so the C library
    falls back to ``clone`` (glibc's ``__clone_internal``), as Docker's and Chromium's filters do.
    Inherited by every process the code starts; no process can remove it."""
    lib: Any = seccomp
    rules = lib.SyscallFilter(lib.ALLOW)
    refused = lib.ERRNO(errno.EPERM)
    try:
        for name in REFUSED_CALLS:
            if lib.resolve_syscall(lib.Arch.NATIVE, name) >= 0:  # negative: no such call on this processor
                rules.add_rule(refused, name)
        flags_argument = 1 if platform.machine().startswith("s390") else 0  # s390 swaps clone's first two
        for flag in NEW_NAMESPACE_FLAGS:
            rules.add_rule(refused, "clone", lib.Arg(flags_argument, lib.MASKED_EQ, flag, flag))
        if lib.resolve_syscall(lib.Arch.NATIVE, "clone3") >= 0:
            rules.add_rule(lib.ERRNO(errno.ENOSYS), "clone3")
        rules.load()
    except OSError as exc:
        error = ContainmentError(M("the containment could not be set up: {step} failed ({reason})",
                                   step="seccomp", reason=exc.strerror or str(exc)))
        error.errno, error.step = exc.errno, "seccomp"  # type: ignore[attr-defined]
        raise error from None
