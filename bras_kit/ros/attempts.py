"""What contained code tried beyond its walls, with the learner's file and line.

The kernel enforces the walls (:mod:`.contain`): a write outside the run's folder fails, a
connection finds no network, a signal finds no process. The learner then sees an ``OSError``
somewhere, or nothing at all (a signal to its own group, a process left running that the end
of the run kills). This watcher, a PEP 578 audit hook installed in the contained child before
the learner's module is imported, says what was tried and where, so that a finding can point
at the line. It observes only: it cannot be removed, but it enforces nothing either.

::

    watcher = Watcher(package_root, containment)
    watcher.install()
    ...                                 # the learner's code runs
    attempts = watcher.finish()         # [Attempt("write", "/home/x/bk.txt", "node.py", 7), ...]
"""

from __future__ import annotations

import os
import sys
from dataclasses import dataclass
from typing import Any


@dataclass(frozen=True)
class Attempt:
    """Something the contained node tried that its walls forbid (bras_kit.ros.attempts), and where."""

    kind: str  # "write", "read", "network", "signal", "ctypes", "symlink", "process"
    detail: str  # the path, the address, the signal...
    path: str  # the learner's file (relative to the package folder)
    line: int


MAX_ATTEMPTS = 50
HERE = os.path.dirname(os.path.abspath(__file__)) + os.sep  # bras_kit/ros (the stand-in, this module)
WRITE_FLAGS = os.O_WRONLY | os.O_RDWR | os.O_CREAT | os.O_TRUNC | os.O_APPEND
CHANGES = {"os.remove": 0, "os.rename": 0, "os.mkdir": 0, "os.rmdir": 0, "os.chmod": 0, "os.chown": 0,
           "os.utime": 0, "os.truncate": 0, "os.link": 1, "os.chflags": 0}  # event -> index of the path
READS = ("os.listdir", "os.scandir")
NETWORK = ("socket.connect", "socket.sendto", "socket.bind", "socket.sendmsg")
WATCHED = frozenset({"open", "os.symlink", "os.kill", "os.killpg", "ctypes.dlopen", "os.fork", *CHANGES, *READS,
                     *NETWORK})


def _inside(path: str, folders: tuple[str, ...]) -> bool:
    return any(path == folder or path.startswith(folder.rstrip("/") + "/") for folder in folders)


class Watcher:
    """The audit hook of one contained run: ``root`` is the learner's package (their frames),
    ``writable`` and ``readable`` the folders the containment grants."""

    def __init__(self, root: str, writable: tuple[str, ...], readable: tuple[str, ...]) -> None:
        import sysconfig  # here, in the child: the parent reads Attempt records only

        self.root = os.path.abspath(root) + os.sep
        self.stdlib = os.path.abspath(sysconfig.get_paths()["stdlib"]) + os.sep
        self.writable = tuple(os.path.realpath(p) for p in writable)
        self.readable = self.writable + tuple(os.path.realpath(p) for p in readable)
        self.attempts: list[Attempt] = []
        self.forks: list[tuple[str, int]] = []
        self.active = False

    def install(self) -> None:
        self.active = True
        sys.addaudithook(self._hook)

    def finish(self) -> list[Attempt]:
        """The attempts, with the processes the code forked that still run (killed at the end)."""
        self.active = False
        if _children_running():
            path, line = self.forks[0] if self.forks else ("", 0)
            self._add(Attempt("process", "", path, line))
        return list(self.attempts)

    # --- the hook: called for every audited event of the process, so the first test is cheap
    def _hook(self, event: str, args: tuple[Any, ...]) -> None:
        if event not in WATCHED or not self.active:
            return
        self.active = False  # the checks below may raise events of their own
        try:
            self._judge(event, args)
        except Exception:  # noqa: BLE001 - a watcher never breaks the code it watches
            pass
        finally:
            self.active = True

    def _judge(self, event: str, args: tuple[Any, ...]) -> None:
        found: tuple[str, str] | None = None
        if event == "open":
            path, mode, flags = args
            if isinstance(path, (str, bytes)) and path:
                write = (isinstance(mode, str) and any(c in mode for c in "wax+")) or \
                    (isinstance(flags, int) and flags & WRITE_FLAGS)
                found = self._path("write" if write else "read", path)
        elif event in CHANGES:
            found = self._path("write", args[CHANGES[event]])
        elif event in READS:
            found = self._path("read", args[0] if args and args[0] is not None else ".")
        elif event == "os.symlink":
            source, target = args[0], args[1]
            where = os.path.dirname(os.path.join(os.getcwd(), os.fsdecode(target)))
            pointed = os.path.realpath(os.path.join(where, os.fsdecode(source)))
            if not _inside(pointed, self.readable):
                found = ("symlink", f"{os.fsdecode(target)} -> {os.fsdecode(source)}")
        elif event in NETWORK:
            found = self._address(args[0], args[1])
        elif event in ("os.kill", "os.killpg"):
            pid, number = args[0], args[1]
            if event == "os.killpg" or pid <= 0:
                found = ("signal", f"{'killpg' if event == 'os.killpg' else 'kill'}({pid}, {number})")
        elif event == "ctypes.dlopen":
            found = ("ctypes", str(args[0]))
        elif event == "os.fork":
            place = self._learner_place()
            if place is not None and not self.forks:
                self.forks.append(place)
            return
        if found is not None:
            # a library probing for its own files (setuptools for ~/.pydistutils.cfg) is not the learner
            place = self._learner_place(direct=found[0] == "read")
            if place is not None:
                self._add(Attempt(found[0], found[1][:300], *place))

    def _path(self, kind: str, path: Any) -> tuple[str, str] | None:
        if not isinstance(path, (str, bytes)):
            return None
        text = os.fsdecode(path)
        real = os.path.realpath(os.path.join(os.getcwd(), text))
        if _inside(real, self.writable if kind == "write" else self.readable):
            return None
        return kind, text if real == os.path.abspath(text) else f"{text} ({real})"

    def _address(self, sock: Any, address: Any) -> tuple[str, str] | None:
        import socket  # already loaded: the event comes from it

        family = getattr(sock, "family", None)
        if family == socket.AF_UNIX and isinstance(address, (str, bytes)) and address[:1] not in ("\0", b"\0"):
            return self._path("write", address) and ("network", f"unix:{os.fsdecode(address)}")
        if family == socket.AF_UNIX:
            return "network", f"unix:@{os.fsdecode(address[1:])}"
        return "network", f"{getattr(family, 'name', family)} {address}"

    def _learner_place(self, direct: bool = False) -> tuple[str, int] | None:
        """The learner's innermost frame, unless the import system stands between (it probes
        every folder of sys.path, which is not the learner's doing); ``direct``: unless a
        library other than the standard one stands between."""
        frame: Any = sys._getframe(1)
        while frame is not None:
            name = frame.f_code.co_filename
            if name.startswith("<frozen importlib"):
                return None
            full = os.path.abspath(name)
            if full.startswith(self.root):
                return os.path.relpath(full, self.root).replace(os.sep, "/"), frame.f_lineno
            if direct and not full.startswith(self.stdlib) and not full.startswith(HERE):
                return None
            frame = frame.f_back
        return None

    def _add(self, attempt: Attempt) -> None:
        if len(self.attempts) < MAX_ATTEMPTS and attempt not in self.attempts:
            self.attempts.append(attempt)


def _children_running() -> bool:
    """Whether a process this one forked (or adopted, as its namespace's init) still runs."""
    while True:
        try:
            pid, _ = os.waitpid(-1, os.WNOHANG)  # reaps the ended ones
        except ChildProcessError:
            return False
        if pid == 0:
            return True
