"""Whether this machine can contain a child (:func:`available`): a trial in a throwaway child, begun
early where a command can use the time, and the words for what is missing and how to get it."""

from __future__ import annotations

import contextlib
import functools
import os
import platform
import sys
from dataclasses import dataclass

from ...core.message import M, Message
from .. import scratch
from .kernel import ContainmentError, _read
from .record import ANSWERS, _note_passed, _passed_before
from .seccomp import _seccomp
from .view import PIVOT_ROOT, _installation
from .walls import Containment


@dataclass(frozen=True)
class Status:
    """What :func:`available` found: ``ok``, else what is ``missing`` and ``how`` to get it."""

    ok: bool
    found: Message
    missing: Message | None = None
    how: Message | None = None


@functools.lru_cache(maxsize=1)
def available() -> Status:
    """Whether this machine can contain a child, found by trying it in a throwaway child (or
    read from this boot's record of a trial that passed, :func:`_passed_before`)."""
    try:
        _seccomp()  # imported here, once: every child forked from this process has it
    except ContainmentError:
        pass  # the trial below says so
    if sys.platform != "linux":
        return Status(False, M("{system} has no Linux namespaces", system=platform.system() or sys.platform),
                      M("Linux user, mount, network and PID namespaces"),
                      M("run bras-kit on Linux (a virtual machine, or WSL 2 on Windows)"))
    if platform.machine() not in PIVOT_ROOT:
        return Status(False, M("{machine} is not a processor bras-kit knows the system calls of",
                               machine=platform.machine()),
                      M("the pivot_root system call number"), M("report it to bras-kit's maintainers"))
    if _begun is None and "pyseccomp" in sys.modules and _passed_before():
        return Status(True, M("user, mount, network and PID namespaces"))
    step, code = _trial()
    if not step:
        _note_passed()
        return Status(True, M("user, mount, network and PID namespaces"))
    if step == "libseccomp":
        return Status(False, M("libseccomp was not found"), M("libseccomp (the seccomp filter library)"),
                      M("install it: sudo apt install libseccomp2 (Debian, Ubuntu) or sudo dnf install libseccomp"))
    if step == "unshare":
        return Status(False, M("the kernel refuses new namespaces to this user ({reason})",
                               reason=os.strerror(code) if code else "?"),
                      M("unprivileged user namespaces"), _how_to_enable())
    return Status(False, M("the containment could not be set up: {step} failed ({reason})", step=step,
                           reason=os.strerror(code) if code else "?"),
                  M("mounts inside a user namespace"), _how_to_enable())


# the cached function itself (whatever later stands for `available`): forget_trial clears it
ANSWERS.append(available.cache_clear)


_begun: tuple[int, int, str] | None = None  # the trial's child at work (begin_trial)


def begin_trial() -> bool:
    """Fork the throwaway child of :func:`available`'s trial now and go on: its answer is read when
    :func:`available` is first asked, so the trial can run on another core while this process
    imports (the worker of ``validate PKG_DIR``, :mod:`bras_kit.ros.ahead`, imports the launch
    children's installer meanwhile). False when no trial was begun (one is under way, the answer
    is known, or this boot's record says a trial passed)."""
    global _begun
    if _begun is None and available.cache_info().currsize == 0 and sys.platform == "linux" \
            and platform.machine() in PIVOT_ROOT:
        with contextlib.suppress(ContainmentError):
            _seccomp()  # imported once, before the fork: the trial's child and this process both need it
        if "pyseccomp" in sys.modules and _passed_before():
            return False  # passed earlier in this boot: available() reads the record
        _begun = _trial_start()
        return True
    return False


def _trial() -> tuple[str, int]:
    """The whole containment tried once in a throwaway child: ("", 0), or the step that failed and its errno."""
    global _begun
    begun, _begun = _begun, None
    return _trial_finish(*(begun or _trial_start()))


def _trial_start() -> tuple[int, int, str]:
    import json

    workdir = scratch.mkdtemp("bras-kit-contain-")
    _installation()  # worked out once, here: the trial's child and every child forked later have it
    read, write = os.pipe()
    sys.stdout.flush()
    sys.stderr.flush()
    pid = os.fork()
    if pid == 0:
        answer = {"step": "", "errno": 0}
        try:
            os.close(read)
            Containment(workdir).enter(keep=(write,))
        except ContainmentError as exc:
            answer = {"step": getattr(exc, "step", "?"), "errno": getattr(exc, "errno", 0)}
        except BaseException as exc:  # noqa: BLE001
            answer = {"step": type(exc).__name__, "errno": getattr(exc, "errno", 0) or 0}
        try:
            os.write(write, json.dumps(answer).encode())
        finally:
            os._exit(0)
    os.close(write)
    return pid, read, workdir


def _trial_finish(pid: int, read: int, workdir: str) -> tuple[str, int]:
    import json

    try:
        chunks = []
        while chunk := os.read(read, 4096):
            chunks.append(chunk)
        os.waitpid(pid, 0)
        answer = json.loads(b"".join(chunks) or b'{"step": "?", "errno": 0}')
        return str(answer["step"]), int(answer["errno"] or 0)
    finally:
        os.close(read)
        import shutil

        shutil.rmtree(workdir, ignore_errors=True)


def _how_to_enable() -> Message:
    if os.path.exists("/proc/sys/kernel/apparmor_restrict_unprivileged_userns") and \
            _read("/proc/sys/kernel/apparmor_restrict_unprivileged_userns") == "1":
        return M("Ubuntu's AppArmor forbids them: sudo sysctl -w kernel.apparmor_restrict_unprivileged_userns=0 "
                 "(or an AppArmor profile granting 'userns' to this Python)")
    if _read("/proc/sys/kernel/unprivileged_userns_clone") == "0":
        return M("enable them: sudo sysctl -w kernel.unprivileged_userns_clone=1")
    if _read("/proc/sys/user/max_user_namespaces") == "0":
        return M("enable them: sudo sysctl -w user.max_user_namespaces=15000")
    return M("inside a container, run it with user namespaces allowed (e.g. docker run --security-opt "
             "seccomp=unconfined), or run bras-kit on the host")
