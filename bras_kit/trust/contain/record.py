"""This boot's record of a trial that passed: where it is kept (a folder of this user's only, in
memory) and what the trial's outcome depends on.

A trial costs every command a throwaway child (namespaces, mounts, pivot_root: about 10 ms of CPU,
which ``validate PKG_DIR`` waits for, issue 43). A pass is therefore noted for the rest of the boot,
keyed by what it depended on. Nothing but a pass is ever noted, so the record cannot make code run
without walls: a record read wrongly only makes bras-kit try walls that then fail, and a child whose
walls fail runs nothing (:meth:`~bras_kit.trust.contain.walls.Containment.enter` raises first) and
drops the record, so the next command tries again. ``bras-kit doctor`` always tries for real."""

from __future__ import annotations

import contextlib
import os
import sys
from collections.abc import Callable

from .. import scratch
from .kernel import _read

_RECORD = "containment-trial-passed"
SHARED_MEMORY = "/dev/shm"  # the record's folder where the login manager made no runtime folder


def _record_path(make: bool = False) -> str | None:
    """The record's file: in ``$XDG_RUNTIME_DIR/bras-kit`` (the login manager's folder of this
    user's, a tmpfs emptied at logout), else in ``SHARED_MEMORY/bras-kit-UID``, the first whose
    base :func:`bras_kit.trust.scratch.usable` takes (a folder this user writes and no one else may empty);
    None where the record's folder is not this user's only (``make``: made, 0700, when missing)."""
    import stat

    uid = os.getuid()
    runtime = os.environ.get("XDG_RUNTIME_DIR", "")
    for base, name in ((runtime, "bras-kit"), (SHARED_MEMORY, f"bras-kit-{uid}")):
        if not os.path.isabs(base) or not scratch.usable(base, min_free=0):
            continue
        folder = os.path.join(base, name)
        if make:
            with contextlib.suppress(FileExistsError, OSError):
                os.mkdir(folder, 0o700)
        try:
            own = os.lstat(folder)
        except OSError:
            return None
        if stat.S_ISDIR(own.st_mode) and own.st_uid == uid and not own.st_mode & 0o077:
            return os.path.join(folder, _RECORD)
        return None  # made by someone else, or opened to others: no record at all
    return None


def _trial_key() -> str:
    """What a trial's outcome depends on: the boot, the user, the namespaces this process is in,
    the kernel's switches for unprivileged namespaces, the interpreter and the modules of this package."""
    parts = [_read("/proc/sys/kernel/random/boot_id"), str(os.getuid()), sys.executable,
             _read("/proc/sys/kernel/unprivileged_userns_clone"), _read("/proc/sys/user/max_user_namespaces"),
             _read("/proc/sys/kernel/apparmor_restrict_unprivileged_userns")]
    for kind in ("user", "mnt", "pid", "net"):
        try:
            parts.append(os.readlink(f"/proc/self/ns/{kind}"))
        except OSError:
            parts.append("")
    folder = os.path.dirname(os.path.abspath(__file__))  # the containment's code, one module per concern
    try:
        names = sorted(name for name in os.listdir(folder) if name.endswith(".py"))
    except OSError:
        names = []
    for name in names:
        try:
            here = os.stat(os.path.join(folder, name))
            parts.append(f"{name}:{here.st_size}:{here.st_mtime_ns}")
        except OSError:
            parts.append("")
    return "\n".join(parts) + "\n"


def _passed_before() -> bool:
    path = _record_path()
    return path is not None and _read(path) + "\n" == _trial_key()


def _note_passed() -> None:
    path = _record_path(make=True)
    if path is None:
        return
    try:
        partial = f"{path}.{os.getpid()}"
        with open(partial, "w") as handle:
            handle.write(_trial_key())
        os.replace(partial, path)
    except OSError:
        pass  # no record: the next command tries again


# this process's cached answers (:func:`bras_kit.trust.contain.probe.available` adds its own), cleared with the record
ANSWERS: list[Callable[[], None]] = []


def forget_trial() -> None:
    """Drop this boot's record of a passed trial and this process's answer: the next
    :func:`~bras_kit.trust.contain.probe.available` tries for real (``bras-kit doctor``; a child
    whose walls failed)."""
    for clear in ANSWERS:
        clear()
    path = _record_path()
    if path is not None:
        with contextlib.suppress(OSError):
            os.remove(path)
