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


class Aborted(BaseException):
    """The process would have died in C (an ``assert`` of the message conversion): nothing the
    node's Python can catch."""

    def __init__(self, what: str) -> None:
        super().__init__(what)
        self.what = what


class Baton:
    """Handed from thread to thread: a bare lock (``threading.Event`` is simulated in the child)."""

    def __init__(self) -> None:
        import _thread

        self._lock = _thread.allocate_lock()
        self._lock.acquire()

    def set(self) -> None:
        self._lock.release()

    def wait(self) -> None:
        self._lock.acquire()

    def clear(self) -> None:
        pass


class SimThread:
    """One thread of the node, on the simulated clock. Only one runs at a time: a thread runs
    until it waits (``time.sleep``, ``Rate.sleep``, an executor waiting for work, ``join``), then
    the thread due soonest runs (ties: the one started first), so every run is the same."""

    def __init__(self, seq: int, name: str, daemon: bool) -> None:
        self.seq = seq
        self.name = name
        self.daemon = daemon
        self.wake: int | None = 0  # when it wants to run again (None: until notified)
        self.baton = Baton()
        self.done = False
        self.yielding = False  # waiting "until now": the others due now go first
        self.pending: BaseException | None = None  # raised in it when it resumes (the end of the run)
        self.joiners: list = []


class State:
    def __init__(self) -> None:
        self.now_ns = 0  # simulated time since the start
        self.end_ns = 10 * 10**9
        self.stops = 0
        self.interrupted = False  # the end of the run was signalled (SIGINT)
        # each message's and log's line of the record, made when it was sent (bras_kit.ros.record_wire)
        self.messages: list[bytes] = []
        self.message_bytes = 0
        self.dropped = 0
        self.too_big = 0  # messages larger than one line of the record may be
        self.bytes_dropped = 0  # messages past the record's bytes
        self.logs: list[bytes] = []
        self.log_bytes = 0
        self.logs_dropped = 0
        self.echo = True
        self.nodes: list = []
        self.node_names: list[str] = []  # each node's name as the stand-in checked it, when it was made
        self.publishers: list[tuple[str, str, str, str, int]] = []  # (node, topic, type, file, line)
        self.subscriptions: list[tuple[str, str, str, str, int]] = []
        self.timers: list[tuple[str, float, str, int]] = []  # (node, period in s, file, line)
        self.rate_sleeps = 0  # Rate.sleep() calls with no executor spinning the rate's node
        self.same_time_count = 0
        self.same_time_ns = -1
        self.sleeps = 0
        self.parameters: dict = {}  # --ros-args -p NAME:=VALUE, for every node
        self.on_sigint: list = []  # what rclpy's SIGINT handler does (shut the contexts down)
        self.threads: list[SimThread] = [SimThread(0, "MainThread", False)]
        self.current: SimThread = self.threads[0]
        self.thread_failures: list = []  # (thread name, exception, time)
        # string-sequence fields given one string, split into letters: (node, topic, field, value, file, line)
        self.split_strings: list[tuple[str, str, str, str, str, int]] = []
        self.tf: list = []  # transforms broadcast: (t_ns, static, TransformStamped as data)
        self.robot: dict | None = None  # the robot's joints for tf2's FK (bras_kit.ros.child gives it)
        self.on_advance = None  # called with the new time (the parent watches it through shared memory)


STATE = State()
GRACE_NS = 2 * 10**9  # after the end is signalled, the node has this much simulated time to finish


def now_ns() -> int:
    return STATE.now_ns


def set_now(t_ns: int) -> None:
    if t_ns > STATE.now_ns:
        STATE.now_ns = t_ns
        if STATE.on_advance is not None:
            STATE.on_advance(t_ns)


def current() -> SimThread:
    return STATE.current


def main_thread() -> SimThread:
    return STATE.threads[0]


def wait_until(deadline_ns: int | None) -> None:
    """The running thread waits until ``deadline_ns`` (None: until :func:`notify`); the others
    due before run meanwhile. At the end of the run the main thread gets the KeyboardInterrupt
    that Ctrl-C raises in ``ros2 run``."""
    me = STATE.current
    me.wake = deadline_ns
    me.yielding = deadline_ns is not None and deadline_ns <= STATE.now_ns
    try:
        _switch(me)
    finally:
        me.yielding = False


def notify(thread: SimThread) -> None:
    """Wake ``thread`` now (a message for its executor, a thread it joined has ended...)."""
    if not thread.done and (thread.wake is None or thread.wake > STATE.now_ns):
        thread.wake = STATE.now_ns


def _pick() -> SimThread:
    """The thread to run next, the clock moved to its time (or the end of the run signalled)."""
    while True:
        ready = [t for t in STATE.threads if not t.done and t.wake is not None]
        me = STATE.current
        nxt = min(ready, key=lambda t: (t.wake, t is me and me.yielding, t.seq)) if ready else None
        limit = STATE.end_ns + (GRACE_NS if STATE.interrupted else 0)
        if nxt is None or nxt.wake > limit:  # type: ignore[operator]
            _signal_end(limit)
            continue
        set_now(nxt.wake)  # type: ignore[arg-type]
        return nxt


def _switch(me: SimThread) -> None:
    nxt = _pick()
    if nxt is not me:
        STATE.current = nxt
        nxt.baton.set()
        me.baton.wait()
        me.baton.clear()
    pending, me.pending = me.pending, None
    if pending is not None:
        raise pending


def _signal_end(limit: int) -> None:
    """Nothing is due before the end: SIGINT, as Ctrl-C sends it to ``ros2 run``. Python's own
    handler raises KeyboardInterrupt in the main thread, then rclpy's shuts every context down
    (rclpy/src/rclpy/signal_handler.cpp:298-301 chains to the original handler, then the
    deferred thread calls shutdown_contexts(), lines 143-144). A node that goes on after it
    gets the signal again, and is stopped the fourth time."""
    set_now(limit)
    STATE.stops += 1
    if not STATE.interrupted:
        STATE.interrupted = True
        for handler in list(STATE.on_sigint):
            handler()
        for thread in STATE.threads:
            notify(thread)
    main = main_thread()
    main.pending = RunStopped() if STATE.stops > 3 else DurationReached()
    main.wake = STATE.now_ns
    if STATE.stops > 3:
        for thread in STATE.threads[1:]:
            thread.wake = None  # only the main thread goes on, to be stopped


def spawn(name: str, daemon: bool) -> SimThread:
    thread = SimThread(len(STATE.threads), name, daemon)
    thread.wake = STATE.now_ns
    STATE.threads.append(thread)
    return thread


def enter(thread: SimThread) -> None:
    """First thing a new thread does: wait for its turn."""
    thread.baton.wait()
    thread.baton.clear()


def finish(thread: SimThread) -> None:
    """A thread ends: whoever joined it wakes, the next thread runs (this one never again)."""
    thread.done = True
    for joiner in thread.joiners:
        notify(joiner)
    nxt = _pick()
    STATE.current = nxt
    nxt.baton.set()


def join(thread: SimThread, timeout: float | None) -> None:
    me = STATE.current
    if thread.done:
        return
    thread.joiners.append(me)
    try:
        wait_until(None if timeout is None else STATE.now_ns + max(int(round(timeout * 1e9)), 0))
    finally:
        thread.joiners.remove(me)


def idle() -> None:
    """Nothing will ever happen again in this thread."""
    wait_until(None)


def advance_to(t_ns: int) -> None:
    """The running thread waits until ``t_ns``."""
    wait_until(max(t_ns, STATE.now_ns))


def sleep(seconds: float) -> None:
    """``time.sleep`` in the child: the virtual clock moves, no real time passes."""
    if not isinstance(seconds, (int, float)):
        raise TypeError(f"'{type(seconds).__name__}' object cannot be interpreted as an integer or float")
    if seconds < 0:
        raise ValueError("sleep length must be non-negative")
    STATE.sleeps += 1
    if math.isinf(seconds):
        idle()
        return
    wait_until(STATE.now_ns + max(int(round(seconds * 1e9)), 0))


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
    """A message published: serialised now, a copy (bras_kit.ros.record_wire), so that what the
    node changes afterwards changes nothing recorded; kept while it fits the record's bounds."""
    from bras_kit.ros import record_wire

    if STATE.now_ns == STATE.same_time_ns:
        STATE.same_time_count += 1
        if STATE.same_time_count > STORM:
            raise PublishStorm()
    else:
        STATE.same_time_ns, STATE.same_time_count = STATE.now_ns, 1
    if len(STATE.messages) >= MAX_MESSAGES:
        STATE.dropped += 1
        return
    line = record_wire.message_line(STATE.now_ns, node, topic, type_name, fields)
    if line is None:  # larger than one line of the record: counted (rule BK657), not kept
        STATE.too_big += 1
        return
    if STATE.message_bytes + len(line) > record_wire.MAX_MESSAGE_BYTES:  # the record is full (BK657)
        STATE.bytes_dropped += 1
        return
    STATE.message_bytes += len(line)
    STATE.messages.append(line)


def log(level: str, node: str, text: str) -> None:
    import sys

    from bras_kit.ros import record_wire

    if len(STATE.logs) < record_wire.MAX_LOGS and STATE.log_bytes < record_wire.MAX_LOG_BYTES:
        line = record_wire.log_line(STATE.now_ns, level, node, text)
        STATE.log_bytes += len(line)
        STATE.logs.append(line)
    else:
        STATE.logs_dropped += 1
    if STATE.echo:
        stamp = (START_NS + STATE.now_ns) / 1e9
        print(f"[{level}] [{stamp:.9f}] [{node}]: {text}", file=sys.stderr)


def not_simulated(module: str, name: str) -> Exception:
    """The error for ``module.name`` missing from the stand-in (private names stay AttributeError,
    so tools probing ``__wrapped__`` or ``__path__`` see what they expect)."""
    if name.startswith("_"):
        return AttributeError(f"module '{module}' has no attribute '{name}'")
    return NotSimulated(f"{module}.{name}")
