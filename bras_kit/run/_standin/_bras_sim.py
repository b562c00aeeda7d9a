"""The simulation behind bras-kit's stand-in for rclpy: one virtual clock, one recording.

This folder is put in front of the import system *only* in the child process that runs a
learner's node (``bras_kit.run.child``); it never shadows a real ROS 2 install elsewhere.
Time is simulated: timers fire on the virtual clock and ``time.sleep`` moves it forward, so
ten seconds of node time take a fraction of a second, the same way on every run.
"""

from __future__ import annotations

import math
from typing import Any

START_NS = 1_767_225_600 * 10**9  # the simulated wall clock starts at 2026-01-01 00:00:00 UTC
MAX_MESSAGES = 200_000  # messages kept in the recording; more are counted, not kept
STORM = 10_000  # messages published without simulated time passing: a loop without sleep


class NotSimulated(Exception):
    """Something real rclpy has that the stand-in does not simulate."""

    def __init__(self, what: str) -> None:
        super().__init__(what)
        self.what = what


class DurationReached(KeyboardInterrupt):
    """The run's simulated duration is over: raised like the Ctrl-C that stops ``ros2 run``."""


class RunStopped(BaseException):
    """The node kept going after the end of the run was signalled (it caught KeyboardInterrupt)."""


class PublishStorm(BaseException):
    """The node published thousands of messages while no simulated time passed."""


class State:
    def __init__(self) -> None:
        self.now_ns = 0  # simulated time since the start
        self.end_ns = 10 * 10**9
        self.stops = 0
        self.messages: list[tuple[int, str, str, str, dict]] = []  # (t_ns, node, topic, type, fields)
        self.dropped = 0
        self.logs: list[tuple[int, str, str, str]] = []  # (t_ns, level, node, text)
        self.echo = True
        self.nodes: list = []
        self.publishers: list[tuple[str, str, str, str, int]] = []  # (node, topic, type, file, line)
        self.subscriptions: list[tuple[str, str, str, str, int]] = []
        self.timers: list[tuple[str, float, str, int]] = []  # (node, period in s, file, line)
        self.rate_sleeps = 0  # Rate.sleep() calls with no executor spinning in another thread
        self.same_time_count = 0
        self.same_time_ns = -1
        self.sleeps = 0
        self.parameters: dict = {}  # --ros-args -p NAME:=VALUE, for every node
        self.background: list = []  # executors spinning "in another thread" (threading.Thread(target=rclpy.spin))
        self.in_background = False
        self.on_advance = None  # called with the new time (the parent watches it through shared memory)


STATE = State()


def now_ns() -> int:
    return STATE.now_ns


def stop() -> None:
    """Signal the end of the run (again, more firmly, if the node ignored it)."""
    STATE.stops += 1
    if STATE.stops > 3:
        raise RunStopped()
    raise DurationReached()


def set_now(t_ns: int) -> None:
    if t_ns > STATE.now_ns:
        STATE.now_ns = t_ns
        if STATE.on_advance is not None:
            STATE.on_advance(t_ns)


def advance_to(t_ns: int) -> None:
    """Move the clock forward to ``t_ns`` (never back); past the end of the run, the node stops.

    Executors spun "in another thread" run their callbacks due on the way, in time order,
    as a real spinning thread would while the main thread sleeps."""
    if STATE.background and not STATE.in_background:
        STATE.in_background = True
        try:
            while any(executor._run_due(min(t_ns, STATE.end_ns)) for executor in STATE.background):
                pass
        finally:
            STATE.in_background = False
    if t_ns > STATE.end_ns:
        STATE.now_ns = max(STATE.now_ns, STATE.end_ns)
        stop()
    set_now(t_ns)


def idle() -> None:
    """Nothing will ever happen again: the clock runs to the end of the run."""
    advance_to(STATE.end_ns)
    stop()


def sleep(seconds: float) -> None:
    """``time.sleep`` in the child: the virtual clock moves, no real time passes."""
    if not isinstance(seconds, (int, float)):
        raise TypeError(f"'{type(seconds).__name__}' object cannot be interpreted as an integer or float")
    if seconds < 0:
        raise ValueError("sleep length must be non-negative")
    STATE.sleeps += 1
    if math.isinf(seconds):
        idle()
    advance_to(STATE.now_ns + max(int(round(seconds * 1e9)), 0))


def caller() -> tuple[str, int]:
    """The file and line of the nearest caller outside the stand-in (the learner's code)."""
    import os
    import sys

    here = os.path.dirname(os.path.abspath(__file__))
    frame: Any = sys._getframe(1)
    while frame is not None and os.path.abspath(frame.f_code.co_filename).startswith(here):
        frame = frame.f_back
    if frame is None:
        return "", 0
    return frame.f_code.co_filename, frame.f_lineno


def record(node: str, topic: str, type_name: str, fields: dict) -> None:
    if STATE.now_ns == STATE.same_time_ns:
        STATE.same_time_count += 1
        if STATE.same_time_count > STORM:
            raise PublishStorm()
    else:
        STATE.same_time_ns, STATE.same_time_count = STATE.now_ns, 1
    if len(STATE.messages) >= MAX_MESSAGES:
        STATE.dropped += 1
        return
    STATE.messages.append((STATE.now_ns, node, topic, type_name, fields))


def log(level: str, node: str, text: str) -> None:
    import sys

    STATE.logs.append((STATE.now_ns, level, node, text))
    if STATE.echo:
        stamp = (START_NS + STATE.now_ns) / 1e9
        print(f"[{level}] [{stamp:.9f}] [{node}]: {text}", file=sys.stderr)


def not_simulated(module: str, name: str) -> Exception:
    """The error for ``module.name`` missing from the stand-in (private names stay AttributeError,
    so tools probing ``__wrapped__`` or ``__path__`` see what they expect)."""
    if name.startswith("_"):
        return AttributeError(f"module '{module}' has no attribute '{name}'")
    return NotSimulated(f"{module}.{name}")
