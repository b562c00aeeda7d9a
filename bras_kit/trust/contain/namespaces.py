"""The new namespaces (user, mount, network, PID, IPC, UTS) and who the code runs as in them:
the uid and gid maps, and for root the overflow user mapped from outside."""

from __future__ import annotations

import ctypes
import errno
import os

from ...core.message import M
from .kernel import (
    CAP_DAC_READ_SEARCH,
    PR_SET_KEEPCAPS,
    ContainmentError,
    _check,
    _libc,
    _prctl,
    _read,
    _write,
)

CLONE_NEWNS = 0x00020000
CLONE_NEWUTS = 0x04000000
CLONE_NEWIPC = 0x08000000
CLONE_NEWUSER = 0x10000000
CLONE_NEWPID = 0x20000000
CLONE_NEWNET = 0x40000000
NAMESPACES = CLONE_NEWUSER | CLONE_NEWNS | CLONE_NEWNET | CLONE_NEWPID | CLONE_NEWIPC | CLONE_NEWUTS
# clone()'s flags that make a namespace (CLONE_NEWTIME shares its bit with the exit signal there)
CLONE_NEWCGROUP = 0x02000000


def _unshare(flags: int) -> None:
    _check(_libc.unshare(ctypes.c_int(flags)), "unshare")


def _map_ids(uid: int, gid: int) -> None:
    """The same uid and gid inside as outside: files keep their owners, and nothing else maps."""
    try:
        _write("/proc/self/setgroups", "deny")
        _write("/proc/self/uid_map", f"{uid} {uid} 1\n")
        _write("/proc/self/gid_map", f"{gid} {gid} 1\n")
    except OSError as exc:
        error = ContainmentError(M("the containment could not be set up: {step} failed ({reason})",
                                   step="uid_map", reason=exc.strerror or str(exc)))
        error.errno, error.step = exc.errno, "uid_map"  # type: ignore[attr-defined]
        raise error from None


def _identity(uid: int, gid: int) -> tuple[int, int]:
    """The (uid, gid) the contained code runs as: the caller's own, or for root the overflow
    user's (``nobody``): the kernel never counts root's processes against RLIMIT_NPROC."""
    if uid != 0:
        return uid, gid
    return int(_read("/proc/sys/kernel/overflowuid") or 65534), int(_read("/proc/sys/kernel/overflowgid") or 65534)


def _enter_namespaces(uid: int, gid: int, identity: tuple[int, int]) -> None:
    """The new namespaces, with the caller's own ids mapped onto themselves, or for root (whose
    ``identity`` is another user's) with maps written from outside."""
    if identity[0] == uid:
        _unshare(NAMESPACES)
        _map_ids(uid, gid)
    else:
        _unshare_mapped_from_outside(identity)


def _unshare_mapped_from_outside(identity: tuple[int, int]) -> None:
    """For root: the namespaces made, with a uid and gid map only a process left outside may
    write (it must hold CAP_SETUID over the parent namespace, user_namespaces(7)): root onto
    root for the steps that build the walls, and ``identity`` onto itself for the code."""
    go_read, go_write = os.pipe()
    me = os.getpid()
    helper = os.fork()
    if helper == 0:  # stays outside: writes this process's maps once it has its namespace
        code = 1
        try:
            os.close(go_write)
            if os.read(go_read, 1) == b"1":
                uid, gid = identity
                _write(f"/proc/{me}/uid_map", f"0 0 1\n{uid} {uid} 1\n")
                _write(f"/proc/{me}/gid_map", f"0 0 1\n{gid} {gid} 1\n")
                code = 0
        except BaseException:  # noqa: BLE001 - the waiting process reports the failed step
            pass
        os._exit(code)
    os.close(go_read)
    try:
        _unshare(NAMESPACES)
        os.write(go_write, b"1")
    finally:
        os.close(go_write)
        _, status = os.waitpid(helper, 0)
    if not os.WIFEXITED(status) or os.WEXITSTATUS(status) != 0:
        error = ContainmentError(M("the containment could not be set up: {step} failed ({reason})",
                                   step="uid_map", reason=os.strerror(errno.EPERM)))
        error.errno, error.step = errno.EPERM, "uid_map"  # type: ignore[attr-defined]
        raise error


def _become(identity: tuple[int, int]) -> int:
    """Inside: run as ``identity`` (no supplementary group); returns the capabilities kept.

    For root's code, run as ``nobody``: CAP_DAC_READ_SEARCH in its user namespace, so that it
    still reads what root gave it to read (a package in a folder of mode 700, as root's home
    and ``mkdtemp`` make them); a capability of a user namespace reaches only the files whose
    owner is mapped there (root's, nobody's), its view holds only the granted paths, bound
    read-only, and the kernel checks RLIMIT_NPROC against capabilities of the first namespace
    only (kernel/fork.c), which it has none of. A program it executes loses it (no ambient set)."""
    uid, gid = identity
    if os.getuid() == uid and os.getgid() == gid:
        return 0
    _prctl(PR_SET_KEEPCAPS, 1)
    os.setgroups([])
    os.setresgid(gid, gid, gid)
    os.setresuid(uid, uid, uid)
    return 1 << CAP_DAC_READ_SEARCH
