"""The containment around the child that runs code bras-kit did not write (docs/security.md).

The child is a ``fork`` of Python (:func:`bras_kit.trust.sandbox.run_limited`): the function to run
and its arguments are already in its memory, so nothing is executed afresh. Before the
learner's code runs, :meth:`Containment.enter` turns that child into a small container made of
what Linux gives any user, without a daemon, root or a helper program:

- a **user namespace** (the child's own uid and gid mapped onto themselves), so the steps
  below need no privilege, and root's powers end at the namespace;
- a **mount namespace** whose root is a fresh read-only tmpfs into which only the granted
  paths are bound, each at its own path: the Python installation, the system libraries, the
  learner's package (read-only) and the run's own folder (read-write). Nothing else exists
  there: not the home folder, not ``~/.ssh``, not ``/tmp``, not ``/proc``, not the sockets of
  ``/run``. The old root is detached (``pivot_root``), as bubblewrap does;
- a **network namespace** with no interface up: no TCP, no UDP, and no abstract Unix socket
  reaches this machine or another, loopback included;
- a **PID namespace**: the code runs as its init (pid 1), sees and can name no process
  outside, so it can neither signal nor trace one; when it ends (or is killed by a limit),
  the kernel kills every process it forked;
- an environment cut down to what a program needs (``PATH``, ``HOME``, the locale, ``ROS_*``...):
  tokens and keys in the others do not reach it;
- its own session and process group (``kill(0, ...)`` would otherwise reach the caller's
  group, and ``TIOCSTI`` the terminal's shell);
- an **unprivileged identity**: the caller's own uid, or for root the overflow user
  (``nobody``), mapped from outside by a helper that stays there, because the kernel never
  counts root in ``RLIMIT_NPROC`` (kernel/fork.c, ``copy_process``: ``real_cred->user !=
  INIT_USER``), whatever its namespace;
- then every capability dropped (the bounding set too) and ``no_new_privs`` set;
  ``RLIMIT_NPROC`` caps the processes it may start, ``RLIMIT_FSIZE`` each file it writes;
- its folder a **bounded tmpfs** (bytes and files) seen only in its mount namespace: what it
  writes there stays in memory and goes with the run, never on this machine's disk;
- a **seccomp filter** (libseccomp, through ``pyseccomp``) that refuses new namespaces
  (``unshare``, ``setns``, ``clone`` with a ``CLONE_NEW*`` flag), mounts (``mount``,
  ``umount2``, ``pivot_root``, the new mount API) and the kernel keyrings, whatever calls them
  (``ctypes`` included).

::

    from ..trust.contain import Containment, available
    status = available()                 # what this machine lacks, and how to get it
    if status.ok:
        run_limited(function, ..., contain=Containment(workdir, readable=(package_root,)))
"""

from __future__ import annotations

import contextlib
import ctypes
import errno
import functools
import mmap
import os
import platform
import select
import signal
import struct
import sys
import sysconfig
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, field
from typing import Any

from ..core.errors import BrasKitError
from ..core.message import M, Message
from . import scratch

CLONE_NEWNS = 0x00020000
CLONE_NEWUTS = 0x04000000
CLONE_NEWIPC = 0x08000000
CLONE_NEWUSER = 0x10000000
CLONE_NEWPID = 0x20000000
CLONE_NEWNET = 0x40000000
NAMESPACES = CLONE_NEWUSER | CLONE_NEWNS | CLONE_NEWNET | CLONE_NEWPID | CLONE_NEWIPC | CLONE_NEWUTS

MS_RDONLY, MS_NOSUID, MS_NODEV, MS_NOEXEC = 1, 2, 4, 8
MS_REMOUNT, MS_BIND, MS_REC, MS_PRIVATE = 32, 4096, 16384, 1 << 18
MS_NOATIME, MS_NODIRATIME, MS_RELATIME = 1024, 2048, 1 << 21
ST_RELATIME = 4096  # statvfs's flag for MS_RELATIME (the other ST_ flags equal the MS_ ones)
MNT_DETACH = 2
PR_SET_PDEATHSIG, PR_SET_KEEPCAPS, PR_CAPBSET_DROP, PR_SET_NO_NEW_PRIVS = 1, 8, 24, 38
CAP_DAC_READ_SEARCH = 2
LINUX_CAPABILITY_VERSION_3 = 0x20080522
PIVOT_ROOT = {"x86_64": 155, "aarch64": 41, "arm64": 41, "riscv64": 41, "ppc64le": 203, "ppc64": 203,
              "s390x": 217, "armv7l": 218, "i686": 217, "i386": 217}
MAX_PROCESSES = 32  # the processes the contained code may start in all (a fork bomb stops there)
MAX_FILE_BYTES = 256 << 20  # the largest file it may write in its folder
MAX_FOLDER_BYTES = 256 << 20  # all it may write in its folder (a tmpfs: kept in memory, never on disk)
MAX_FOLDER_FILES = 4096  # the files and folders it may make there (each inode costs kernel memory)
STAGING = ".bras-kit-root"  # where the new root is built, in the real folder (removed once it is the root)
# clone()'s flags that make a namespace (CLONE_NEWTIME shares its bit with the exit signal there)
CLONE_NEWCGROUP = 0x02000000
NEW_NAMESPACE_FLAGS = (CLONE_NEWNS, CLONE_NEWCGROUP, CLONE_NEWUTS, CLONE_NEWIPC, CLONE_NEWUSER, CLONE_NEWPID,
                       CLONE_NEWNET)
# refused to the contained code (EPERM): namespaces and mounts (a nested user namespace would give
# it every capability there, and a tmpfs it mounts is memory no limit counts), and the kernel's
# keyrings, which are per user and not namespaced (Docker's default profile refuses the same)
REFUSED_CALLS = ("unshare", "setns", "mount", "umount", "umount2", "pivot_root", "chroot", "fsopen", "fsconfig",
                 "fsmount", "fspick", "move_mount", "open_tree", "mount_setattr", "keyctl", "add_key", "request_key")
XCPU_EXIT = 128 + signal.SIGXCPU  # how the init says it ran out of CPU time (see _xcpu)
ROOT_BYTES = 1 << 20  # the tmpfs that holds the mount points (read-only once built)

SYSTEM = ("/usr", "/lib", "/lib64", "/lib32", "/libx32", "/bin", "/sbin")
SYSTEM_FILES = ("/etc/ld.so.cache", "/etc/localtime")
DEVICES_READ = ("/dev/zero", "/dev/urandom", "/dev/random")
DEVICES_WRITE = ("/dev/null", "/dev/full")
# the environment variables the contained code keeps (tokens and keys in the others stay outside)
ENVIRONMENT = frozenset({"PATH", "HOME", "USER", "LOGNAME", "LANG", "LANGUAGE", "TZ", "TERM", "PWD",
                         "PYTHONIOENCODING", "PYTHONUTF8", "NO_COLOR"})
ENVIRONMENT_PREFIXES = ("LC_", "ROS_", "RMW_", "RCUTILS_", "AMENT_", "COLCON_", "BRAS_KIT_")


class ContainmentError(BrasKitError):
    """The containment could not be set up in the child: the code was not run."""


@dataclass(frozen=True)
class Status:
    """What :func:`available` found: ``ok``, else what is ``missing`` and ``how`` to get it."""

    ok: bool
    found: Message
    missing: Message | None = None
    how: Message | None = None


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
        if identity[0] == uid:
            _unshare(NAMESPACES)
            _map_ids(uid, gid)
        else:
            _unshare_mapped_from_outside(identity)
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


def python_paths() -> list[str]:
    """The Python installation (prefixes, stdlib, site-packages), bras-kit itself, and the
    folders on ``sys.path`` that belong to an installation (never the current folder)."""
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))  # bras_kit/
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


# --- the probe -------------------------------------------------------------------------------

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


_AVAILABLE = available  # the cached function itself, whatever later stands for `available`


# --- the trial's record ----------------------------------------------------------------------
# A trial costs each command a throwaway child (namespaces, mounts, pivot_root: 10 ms of CPU, and
# `validate PKG_DIR` waits for it, issue 43). One that passed is noted for the rest of the boot in a
# folder of this user's only, in memory, with what it depended on. Only a pass is ever noted, so the
# record can never let code run without walls: read wrongly, it makes bras-kit try walls that then
# fail, and a child whose walls fail runs nothing (Containment.enter raises before the code runs) and
# removes the record, so the next command tries again. `bras-kit doctor` always tries for real.

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
    the kernel's switches for unprivileged namespaces, the interpreter and this module."""
    parts = [_read("/proc/sys/kernel/random/boot_id"), str(os.getuid()), sys.executable,
             _read("/proc/sys/kernel/unprivileged_userns_clone"), _read("/proc/sys/user/max_user_namespaces"),
             _read("/proc/sys/kernel/apparmor_restrict_unprivileged_userns")]
    for kind in ("user", "mnt", "pid", "net"):
        try:
            parts.append(os.readlink(f"/proc/self/ns/{kind}"))
        except OSError:
            parts.append("")
    try:
        here = os.stat(__file__)
        parts.append(f"{here.st_size}:{here.st_mtime_ns}")
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


def forget_trial() -> None:
    """Drop this boot's record of a passed trial and this process's answer: the next
    :func:`available` tries for real (``bras-kit doctor``; a child whose walls failed)."""
    _AVAILABLE.cache_clear()
    path = _record_path()
    if path is not None:
        with contextlib.suppress(OSError):
            os.remove(path)


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


def _read(path: str) -> str:
    try:
        with open(path) as handle:
            return handle.read().strip()
    except OSError:
        return ""


# --- the steps, in the child -----------------------------------------------------------------

_libc = ctypes.CDLL(None, use_errno=True)


def _check(result: int, step: str) -> None:
    if result != 0:
        code = ctypes.get_errno()
        error = ContainmentError(M("the containment could not be set up: {step} failed ({reason})", step=step,
                                   reason=os.strerror(code)))
        error.errno = code  # type: ignore[attr-defined]
        error.step = step  # type: ignore[attr-defined]
        raise error


def _unshare(flags: int) -> None:
    _check(_libc.unshare(ctypes.c_int(flags)), "unshare")


def _prctl(option: int, value: int) -> None:
    _check(_libc.prctl(ctypes.c_int(option), ctypes.c_ulong(value), ctypes.c_ulong(0), ctypes.c_ulong(0),
                       ctypes.c_ulong(0)), "prctl")


def _mount(source: str | None, target: str, kind: str | None, flags: int, data: str | None = None) -> None:
    def b(text: str | None) -> bytes | None:
        return None if text is None else os.fsencode(text)

    _check(_libc.mount(b(source), b(target), b(kind), ctypes.c_ulong(flags), b(data)), f"mount {target}")


def _write(path: str, text: str) -> None:
    fd = os.open(path, os.O_WRONLY)
    try:
        os.write(fd, text.encode())
    finally:
        os.close(fd)


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


def _environment(workdir: str) -> None:
    """Only the variables a program needs to run and ROS's own are kept; ``tempfile`` and the
    programs it starts make their temporary files in the run's folder."""
    import tempfile

    for name in list(os.environ):
        if name not in ENVIRONMENT and not name.startswith(ENVIRONMENT_PREFIXES):
            del os.environ[name]  # unsetenv() too: gone for the C library and for programs it starts
    os.environ["TMPDIR"] = workdir
    tempfile.tempdir = workdir


def _visible_sys_path() -> None:
    """Folders of ``sys.path`` the walls hide are dropped (the caller's current folder, a test
    runner's folder...): a library that lists every folder of ``sys.path`` (setuptools looking
    for entry points) would otherwise be stopped there, at the learner's line, for nothing
    the learner did."""
    sys.path[:] = [p for p in sys.path if not p or os.path.isdir(p) or os.path.isfile(p)]
    sys.path_importer_cache.clear()


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


# --- who the code runs as -------------------------------------------------------------------

def _identity(uid: int, gid: int) -> tuple[int, int]:
    """The (uid, gid) the contained code runs as: the caller's own, or for root the overflow
    user's (``nobody``): the kernel never counts root's processes against RLIMIT_NPROC."""
    if uid != 0:
        return uid, gid
    return int(_read("/proc/sys/kernel/overflowuid") or 65534), int(_read("/proc/sys/kernel/overflowgid") or 65534)


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


# --- the seccomp filter ---------------------------------------------------------------------

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


class ContainmentUnavailable(ContainmentError):
    """Containment was required and this machine cannot give it."""


CONTAIN_MODES = ("auto", "require", "off")


def containment(mode: str, workdir: str, readable: Iterable[str] = ()) -> Containment | None:
    """The :class:`Containment` for a run in ``workdir`` reading ``readable``, by ``mode``:
    "auto" (contained where :func:`available`, else None), "require" (raises
    :class:`ContainmentUnavailable` where not), "off" (None)."""
    if mode == "off":
        return None
    if mode == "require":
        containment_required()
    if not available().ok:
        return None
    _installation()  # worked out here, once: every child forked to enter this containment has it
    return Containment(workdir, tuple(readable))


def containment_required() -> None:
    """Raise :class:`ContainmentUnavailable` (what is missing, how to get it) where :func:`available` is not ok."""
    status = available()
    if not status.ok:
        raise ContainmentUnavailable(M("code bras-kit did not write cannot be contained on this machine ({found}): "
                                       "it needs {missing}", missing=status.missing, found=status.found),
                                     hint=status.how)


def uncontained_note() -> Message | None:
    """The one line ``run`` and ``launch`` show where the learner's own code runs uncontained
    (None where it is contained)."""
    status = available()
    if status.ok:
        return None
    return M("note: your code runs without walls here (this machine lacks {missing}): it has your rights, "
             "as under ros2 run", missing=status.missing)
