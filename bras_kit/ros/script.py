"""A Python file of the learner's run as a script in the contained child: a ``setup.py`` the way
colcon runs it, a launch file the way ``ros2 launch`` reads it (its module, then one function).

The build and launch features run these files their own way; this is the shared shape, and
what the hostile corpus (tests/data/hostile_code/package/) is checked with::

    ran = run_script("pkg/setup.py", root="pkg", argv=["--name"])
    ran.failure       # NodeFailure (the learner's frames) or None
    ran.blocked       # [Attempt("write", "~/x", "setup.py", 7), ...]: what the walls stopped
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import Any

from ..trust import scratch
from ..trust.contain import containment
from .attempts import Attempt
from .locate import Target
from .recording import NodeFailure


@dataclass
class ScriptRun:
    failure: NodeFailure | None
    blocked: list[Attempt] = field(default_factory=list)
    output: str = ""  # the first and last 64 KiB of what it printed
    contained: bool = False
    dropped: int = 0  # characters printed between the two, not kept


def run_script(path: str, *, root: str | None = None, call: str | None = None, argv: tuple[str, ...] = (),
               contain: str = "require", cpu_seconds: int = 20, memory_bytes: int = 1 << 30,
               wall_seconds: float = 60.0) -> ScriptRun:
    """Run ``path`` as ``__main__`` (``sys.argv`` = the file and ``argv``), then its function
    ``call`` when given, in a limited child contained by ``contain`` (see
    :func:`bras_kit.trust.contain.containment`), with ``root`` (its package, default its folder)
    readable and on ``sys.path``."""
    from ..trust.sandbox import run_limited

    path = os.path.abspath(path)
    root = os.path.abspath(root or os.path.dirname(path))
    target = Target(root, "", call or "", path, os.path.relpath(path, root))
    with scratch.folder("bras-kit-script-") as workdir:
        walls = containment(contain, workdir, (root,))
        ran: ScriptRun = run_limited(_run_here, target, list(argv), workdir, walls, cpu_seconds=cpu_seconds,
                                     memory_bytes=memory_bytes, wall_seconds=wall_seconds, contain=walls,
                                     what=os.path.basename(path))
        return ran


def _run_here(target: Target, argv: list[str], workdir: str, walls: Any) -> ScriptRun:
    import contextlib
    import runpy
    import sys

    from .capture import HeadTail
    from .child import _learner_frames
    from .finder import install

    watcher = None
    if walls is not None:
        from .attempts import Watcher

        read, write = walls.granted()
        watcher = Watcher(target.root, tuple(write), tuple(read))
        watcher.install()
    os.chdir(workdir)
    install()
    sys.path.insert(0, target.root)
    sys.argv = [target.path, *argv]
    output = HeadTail()  # its first and last 64 KiB (bras_kit.ros.capture), never the whole
    failure = None
    try:
        with contextlib.redirect_stdout(output):
            namespace = runpy.run_path(target.path, run_name="__main__")
            if target.function:
                namespace[target.function]()
    except SystemExit as exc:
        if exc.code not in (None, 0):
            failure = NodeFailure("SystemExit", str(exc.code), _learner_frames(exc, target), 0.0)
    except BaseException as exc:  # noqa: BLE001 - the learner's error, reported as data
        failure = NodeFailure(type(exc).__name__, str(exc)[:2000], _learner_frames(exc, target), 0.0)
    blocked = watcher.finish() if watcher is not None else []
    printed = output.kept()
    return ScriptRun(failure, blocked, printed.head + printed.tail, watcher is not None, printed.dropped_chars)
