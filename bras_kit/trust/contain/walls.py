"""The walls put up in the forked child (:class:`Containment`), step by step, and the process left
outside the PID namespace that waits for its init and ends as it ended."""

from __future__ import annotations

import os
import select
import signal
from collections.abc import Sequence
from dataclasses import dataclass, field

from .environment import _environment, _visible_sys_path
from .kernel import PR_SET_PDEATHSIG, ContainmentError, _prctl, _read
from .limits import (
    MAX_FILE_BYTES,
    MAX_PROCESSES,
    _count_processes,
    _drop_bounding_set,
    _drop_privileges,
)
from .namespaces import _become, _enter_namespaces, _identity
from .record import forget_trial
from .seccomp import _refuse_namespaces_and_mounts, _seccomp
from .view import (
    DEVICES_READ,
    DEVICES_WRITE,
    MAX_FOLDER_BYTES,
    STAGING,
    SYSTEM,
    SYSTEM_FILES,
    _build_root,
    _existing,
    _pivot,
    python_paths,
)

XCPU_EXIT = 128 + signal.SIGXCPU  # how the init says it ran out of CPU time (see _xcpu)


@dataclass(frozen=True)
class Containment:
    """What the contained code is granted: ``workdir`` read-write (its working folder),
    ``readable`` read-only (the learner's package), on top of :func:`python_paths` and the
    system libraries. Everything else is absent from its view of the filesystem."""

    workdir: str
    readable: tuple[str, ...] = ()
    max_processes: int = MAX_PROCESSES
    max_file_bytes: int = MAX_FILE_BYTES
    max_folder_bytes: int = MAX_FOLDER_BYTES
    system: tuple[str, ...] = field(default=SYSTEM)
    keep: tuple[int, ...] = ()  # file descriptors the contained code keeps (a pipe its caller reads)

    def granted(self) -> tuple[list[str], list[str]]:
        """(read-only paths, read-write paths): absolute, existing, none inside another."""
        read = _existing([*self.system, *SYSTEM_FILES, *DEVICES_READ, *python_paths(), *self.readable])
        write = _existing([self.workdir, *DEVICES_WRITE])
        return [p for p in read if p not in write], write

    def enter(self, keep: Sequence[int] = ()) -> None:
        """Contain this (freshly forked, single-threaded) process; return in the contained one.

        Closes every file descriptor but 0, 1, 2 and ``keep``. The process that called this
        stays outside the new PID namespace: it forks the namespace's init, which returns from
        here and runs the code, waits for it and ends the way it ended (its exit status or its
        signal), so the caller of :func:`bras_kit.trust.sandbox.run_limited` sees what it always saw.
        Raises :class:`ContainmentError` when a step fails (nothing has run then); this boot's
        record of a passed trial is then dropped (:func:`forget_trial`), as it no longer holds.
        """
        try:
            self._enter(keep)
        except ContainmentError:
            forget_trial()
            raise

    def _enter(self, keep: Sequence[int]) -> None:
        _close_fds_except({0, 1, 2, *keep})
        seccomp = _seccomp()  # loaded before the walls: find_library may ask ldconfig, which is not inside them
        read, write = self.granted()
        uid, gid = os.getuid(), os.getgid()
        identity = _identity(uid, gid)
        last_cap = int(_read("/proc/sys/kernel/cap_last_cap") or 63)
        staging = os.path.join(self.workdir, STAGING)
        os.mkdir(staging, 0o700)
        real_folder = os.open(self.workdir, os.O_RDONLY | os.O_DIRECTORY)  # to remove the staging folder from
        _enter_namespaces(uid, gid, identity)
        _build_root(staging, read, write, self.workdir, self.max_folder_bytes, identity)
        _pivot(staging)
        alive_read, alive_write = os.pipe()  # open at its end while the process outside lives
        pid = os.fork()  # the first child in the new PID namespace is its init
        if pid:
            for fd in (*keep, alive_read):
                os.close(fd)
            try:  # the real folder as its caller made it (the new root lives on, detached from it)
                os.rmdir(STAGING, dir_fd=real_folder)
            except OSError:
                pass
            os.close(real_folder)
            _relay(pid)
        # the namespace's init: dies with the process outside that waits for it
        os.close(alive_write)
        os.close(real_folder)
        _drop_bounding_set(last_cap)
        kept = _become(identity)  # root's own uid is never counted in RLIMIT_NPROC: nobody's is
        _prctl(PR_SET_PDEATHSIG, signal.SIGKILL)  # after _become: a change of uid clears it
        if select.select([alive_read], [], [], 0)[0]:  # it died before the line above
            os._exit(1)
        os.close(alive_read)
        # its own session: kill(0, ...) reaches no process group outside, and the terminal it may
        # share is no longer its controlling one (no TIOCSTI keystrokes pushed into the shell)
        os.setsid()
        # a namespace's init ignores the signals it has no handler for, SIGXCPU included
        signal.signal(signal.SIGXCPU, _xcpu)
        os.chdir(self.workdir)
        _environment(self.workdir)
        _visible_sys_path()
        _drop_privileges(kept, self.max_processes, self.max_file_bytes)
        _refuse_namespaces_and_mounts(seccomp)
        _count_processes(self.max_processes)


def _relay(pid: int) -> None:
    """Outside the PID namespace: wait for its init and end as it ended."""
    for handled in (signal.SIGINT, signal.SIGTERM):
        signal.signal(handled, signal.SIG_DFL)
    status = 1
    try:
        while True:
            try:
                _, status = os.waitpid(pid, 0)
                break
            except InterruptedError:
                continue
        number = 0
        if os.WIFSIGNALED(status):
            number = os.WTERMSIG(status)
        elif os.WIFEXITED(status) and os.WEXITSTATUS(status) == XCPU_EXIT:
            number = signal.SIGXCPU
        if number:
            if number != signal.SIGKILL:
                signal.signal(number, signal.SIG_DFL)
            os.kill(os.getpid(), number)
    except BaseException:  # noqa: BLE001
        os._exit(1)
    os._exit(os.WEXITSTATUS(status) if os.WIFEXITED(status) else 1)


def _xcpu(number: int, frame: object) -> None:
    os._exit(XCPU_EXIT)


def _close_fds_except(keep: set[int]) -> None:
    highest = 0
    try:
        fds = [int(name) for name in os.listdir("/proc/self/fd")]
    except OSError:
        fds = list(range(os.sysconf("SC_OPEN_MAX") if hasattr(os, "sysconf") else 1024))
    for fd in fds:
        highest = max(highest, fd)
        if fd not in keep:
            try:
                os.close(fd)
            except OSError:
                pass
