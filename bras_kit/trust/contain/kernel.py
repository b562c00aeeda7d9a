"""The C library's calls the containment makes, the error a failed step raises, and
reading a kernel switch under ``/proc``."""

from __future__ import annotations

import ctypes
import os

from ...core.errors import BrasKitError
from ...core.message import M

PR_SET_PDEATHSIG, PR_SET_KEEPCAPS, PR_CAPBSET_DROP, PR_SET_NO_NEW_PRIVS = 1, 8, 24, 38
CAP_DAC_READ_SEARCH = 2


class ContainmentError(BrasKitError):
    """The containment could not be set up in the child: the code was not run."""


def _read(path: str) -> str:
    try:
        with open(path) as handle:
            return handle.read().strip()
    except OSError:
        return ""


_libc = ctypes.CDLL(None, use_errno=True)


def _check(result: int, step: str) -> None:
    if result != 0:
        code = ctypes.get_errno()
        error = ContainmentError(M("the containment could not be set up: {step} failed ({reason})", step=step,
                                   reason=os.strerror(code)))
        error.errno = code  # type: ignore[attr-defined]
        error.step = step  # type: ignore[attr-defined]
        raise error


def _prctl(option: int, value: int) -> None:
    _check(_libc.prctl(ctypes.c_int(option), ctypes.c_ulong(value), ctypes.c_ulong(0), ctypes.c_ulong(0),
                       ctypes.c_ulong(0)), "prctl")


def _write(path: str, text: str) -> None:
    fd = os.open(path, os.O_WRONLY)
    try:
        os.write(fd, text.encode())
    finally:
        os.close(fd)
