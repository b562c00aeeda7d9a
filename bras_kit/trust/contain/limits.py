"""The limits on the contained code: capabilities dropped (bounding set included), no new
privileges, ``RLIMIT_NPROC`` and ``RLIMIT_FSIZE``, and a shared count of the processes it starts."""

from __future__ import annotations

import ctypes
import errno
import mmap
import struct
import sys

from .kernel import PR_CAPBSET_DROP, PR_SET_NO_NEW_PRIVS, _check, _libc, _prctl

LINUX_CAPABILITY_VERSION_3 = 0x20080522
MAX_PROCESSES = 32  # the processes the contained code may start in all (a fork bomb stops there)
MAX_FILE_BYTES = 256 << 20  # the largest file it may write in its folder


class _CapHeader(ctypes.Structure):
    _fields_ = [("version", ctypes.c_uint32), ("pid", ctypes.c_int)]


class _CapData(ctypes.Structure):
    _fields_ = [("effective", ctypes.c_uint32), ("permitted", ctypes.c_uint32), ("inheritable", ctypes.c_uint32)]


def _drop_bounding_set(last_cap: int) -> None:
    """No capability can ever come back (needs CAP_SETPCAP: before :func:`_become`)."""
    for cap in range(last_cap + 1):
        if _libc.prctl(ctypes.c_int(PR_CAPBSET_DROP), ctypes.c_ulong(cap), 0, 0, 0) != 0 and \
                ctypes.get_errno() != errno.EINVAL:
            _check(-1, "PR_CAPBSET_DROP")


def _drop_privileges(kept: int, max_processes: int, max_file_bytes: int) -> None:
    """Every capability dropped but ``kept`` (a mask of the first 32), no new privileges, the limits."""
    import resource

    header = _CapHeader(LINUX_CAPABILITY_VERSION_3, 0)
    data = (_CapData * 2)()
    data[0].effective = data[0].permitted = kept
    _check(_libc.capset(ctypes.byref(header), data), "capset")
    _prctl(PR_SET_NO_NEW_PRIVS, 1)
    resource.setrlimit(resource.RLIMIT_NPROC, (max_processes, max_processes))
    resource.setrlimit(resource.RLIMIT_FSIZE, (max_file_bytes, max_file_bytes))


SPAWNS = frozenset({"os.fork", "os.forkpty", "os.posix_spawn", "os.spawn", "subprocess.Popen", "os.system",
                    "pty.spawn"})


def _count_processes(most: int) -> None:
    """At most ``most`` processes started in all, by any process of the namespace: a counter in
    memory they all share, checked by an audit hook before each fork or spawn, so that Python's
    own calls fail at the learner's line with words of ours. The kernel's ``RLIMIT_NPROC`` (the
    code never runs as root, see :func:`_identity`) is what holds against ``ctypes``."""
    counter = mmap.mmap(-1, 8)

    def hook(event: str, args: tuple[object, ...]) -> None:
        if event in SPAWNS:
            started = struct.unpack_from("<q", counter)[0] + 1
            if started > most:
                raise BlockingIOError(errno.EAGAIN, f"no more processes: {most} were started, the most allowed")
            struct.pack_into("<q", counter, 0, started)

    sys.addaudithook(hook)
