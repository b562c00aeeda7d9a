"""The package's own nodes live beside the viewer, as ``ros2 launch`` runs them, and the package
watched for saves (``bras-kit launch`` builds and launches again).

Each node runs as :func:`bras_kit.run.run_node` runs it (built, contained, against the stand-in),
on a simulated clock held to the wall clock; every JointState it publishes is handed to
``deliver`` as it is published, and nothing is kept of it, so a node live for an hour stays the
size it was after a second. :meth:`LiveNodes.stop` kills them (a save, Ctrl-C).

::

    nodes = LiveNodes("bras_description", ["animation"], viewer.show_joint_state).start()
    ...
    nodes.stop()
"""

from __future__ import annotations

import os
import sys
import threading
from collections.abc import Callable, Iterable, Sequence
from typing import Any

from ..core.errors import BrasKitError

SKIPPED_FOLDERS = frozenset({"build", "install", "log", "__pycache__"})  # colcon's own output
MAX_STAMPED = 2000


class LiveNodes:
    """``executables`` of the package ``folder`` (with their ``parameters``, by executable) run
    live until :meth:`stop`; ``deliver(names, positions)`` is called with each JointState."""

    def __init__(self, folder: str, executables: Sequence[str], deliver: Callable[[Sequence[str], Sequence[float]], None],
                 parameters: dict[str, dict[str, Any]] | None = None, lang: str | None = None,
                 seconds: float | None = None, beside: Sequence[str] = ()) -> None:
        from .node import MAX_DURATION

        self.folder = folder
        self.executables = list(executables)
        self.deliver = deliver
        self.parameters = parameters or {}
        self.lang = lang
        self.seconds = MAX_DURATION if seconds is None else seconds
        self.beside = tuple(beside)  # the other packages of its workspace, built with it
        self.errors: list[BrasKitError] = []  # why a node ended before it was stopped
        self._stop = threading.Event()
        self._threads: list[threading.Thread] = []

    def start(self) -> LiveNodes:
        # what the threads import, imported here first: a child forked by one thread while another
        # imports a module it needs would wait forever for that module's lock
        from ..trust import contain  # noqa: F401
        from .node import _preload, run_node  # noqa: F401

        _preload()
        contain.available()  # its probe forks a throwaway child: now, not beside a fork of a thread
        for executable in self.executables:
            thread = threading.Thread(target=self._run, args=(executable,), daemon=True,
                                      name=f"bras-kit-live-{executable}")
            thread.start()
            self._threads.append(thread)
        return self

    def _run(self, executable: str) -> None:
        from ..core.i18n import say
        from ..trust.sandbox import Stopped
        from .node import run_node

        try:
            run_node(self.folder, executable, duration=self.seconds, echo=True,
                     parameters=self.parameters.get(executable), live=True, keep=False, stop=self._stop,
                     on_joint_state=lambda state: self.deliver(state.name, state.position), beside=self.beside)
        except Stopped:
            return
        except BrasKitError as exc:
            self.errors.append(exc)
            print(say(exc.message, self.lang), file=sys.stderr, flush=True)

    @property
    def running(self) -> bool:
        return any(thread.is_alive() for thread in self._threads)

    def stop(self, timeout: float = 10.0) -> None:
        self._stop.set()
        for thread in self._threads:
            thread.join(timeout)


# A file modified this recently may be written again within the same tick of the file system's
# clock (a kernel before 6.13 stamps files with a jiffy's resolution, 1 to 10 ms): the same size,
# the same modification time, other bytes. Its content is then part of its stamp (git's "racily
# clean" entries, Documentation/technical/racy-git.adoc, are the same problem).
RACY_NS = 2 * 10**9
RACY_BYTES = 1 << 20  # a larger file (a mesh) is stamped by time and size alone

Stamp = tuple[int, int, "str | None"]


def package_stamps(folder: str, before: dict[str, Stamp] | None = None) -> dict[str, Stamp]:
    """(modification time, size, content digest or None) of every file of the package ``folder``,
    colcon's output folders and hidden ones left out: a save anywhere in it changes the result.
    The digest is taken for a file modified less than RACY_NS ago, and for one ``before`` took it
    for (then :func:`changed_files` compares the two)."""
    import hashlib
    import time

    from ..trust.learner_files import read_bytes

    now = time.time_ns()
    out: dict[str, Stamp] = {}
    for root, dirs, files in os.walk(folder):
        dirs[:] = sorted(d for d in dirs if d not in SKIPPED_FOLDERS and not d.startswith(".")
                         and not d.endswith(".egg-info"))  # what setup.py writes where it may
        for name in sorted(files):
            if name.startswith(".") or name.endswith((".pyc", "~", ".swp")):
                continue
            path = os.path.join(root, name)
            try:
                info = os.stat(path)
            except OSError:
                continue
            digest = None
            earlier = before.get(path) if before is not None else None
            if info.st_size <= RACY_BYTES and (now - info.st_mtime_ns < RACY_NS or
                                               (earlier is not None and earlier[2] is not None)):
                try:  # the one reader: a regular file under the package, never a FIFO or a device
                    digest = hashlib.blake2b(read_bytes(path, (folder,), limit=RACY_BYTES),
                                             digest_size=16).hexdigest()
                except (OSError, ValueError):
                    digest = None
            out[path] = (info.st_mtime_ns, info.st_size, digest)
            if len(out) >= MAX_STAMPED:
                return out
    return out


def changed_files(before: dict[str, Stamp], after: dict[str, Stamp]) -> list[str]:
    """The files saved, made or removed between two :func:`package_stamps`."""
    return sorted(path for path in set(before) | set(after) if _differ(before.get(path), after.get(path)))


def _differ(a: Stamp | None, b: Stamp | None) -> bool:
    if a is None or b is None:
        return a is not b
    return a[:2] != b[:2] or (a[2] is not None and b[2] is not None and a[2] != b[2])


def executables_of(nodes: Iterable[Any], package: str) -> tuple[list[str], dict[str, dict[str, Any]]]:
    """The package's own executables a launch plan starts, and the parameters each is given."""
    names: list[str] = []
    parameters: dict[str, dict[str, Any]] = {}
    for node in nodes:
        if node.package != package or not node.executable or node.executable in names:
            continue
        names.append(node.executable)
        parameters[node.executable] = {k: v for k, v in node.parameters.items()
                                       if isinstance(v, (bool, int, float, str, list))}
    return names, parameters
