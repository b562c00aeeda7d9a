"""What runs in the child process: the stand-in installed, time simulated, the node's main().

Everything here happens after ``fork`` (:func:`bras_kit.trust.sandbox.run_limited`): the import
hook, the patched ``time`` functions and the working folder belong to the child alone.
"""

from __future__ import annotations

import importlib
import os
import sys
import traceback
from typing import Any

from . import record_wire
from .capture import HeadTail
from .finder import JAZZY_UNSIMULATED, ROS_SUFFIXES, STANDIN, install
from .locate import Target
from .recording import Frame, NodeFailure


def _patch_time(sim: Any) -> dict[str, Any]:
    import time

    saved = {name: getattr(time, name) for name in
             ("sleep", "time", "time_ns", "monotonic", "monotonic_ns", "perf_counter", "perf_counter_ns")}
    start = sim.START_NS
    time.sleep = sim.sleep
    time.time = lambda: (start + sim.STATE.now_ns) / 1e9
    time.time_ns = lambda: start + sim.STATE.now_ns
    time.monotonic = time.perf_counter = lambda: sim.STATE.now_ns / 1e9
    time.monotonic_ns = time.perf_counter_ns = lambda: sim.STATE.now_ns
    return saved


def _restore_time(saved: dict[str, Any]) -> None:
    import time

    for name, function in saved.items():
        setattr(time, name, function)


def _patch_threads(sim: Any) -> dict[str, Any]:
    """Threads the node starts run on the simulated clock (``_bras_sim.SimThread``): one at a
    time, switching where a thread waits, so a worker thread with ``rate.sleep()``,
    ``rclpy.spin`` in a thread or a MultiThreadedExecutor run the same way every time."""
    import threading

    saved: dict[str, Any] = {"start": threading.Thread.start, "join": threading.Thread.join,
             "is_alive": threading.Thread.is_alive, "wait": threading.Event.wait}

    def start(thread: threading.Thread) -> None:
        if getattr(thread, "_bras_sim", None) is not None:
            raise RuntimeError("threads can only be started once")
        simulated = sim.spawn(thread.name, thread.daemon)
        thread._bras_sim = simulated  # type: ignore[attr-defined]
        run = thread.run

        def body() -> None:
            _run_simulated(sim, simulated, run)

        thread.run = body  # type: ignore[method-assign]
        saved["start"](thread)

    def join(thread: threading.Thread, timeout: float | None = None) -> None:
        simulated = getattr(thread, "_bras_sim", None)
        if simulated is None:
            raise RuntimeError("cannot join thread before it is started")
        if simulated is sim.current():
            raise RuntimeError("cannot join current thread")
        sim.join(simulated, timeout)

    def is_alive(thread: threading.Thread) -> bool:
        simulated = getattr(thread, "_bras_sim", None)
        return simulated is not None and not simulated.done

    def wait(event: threading.Event, timeout: float | None = None) -> bool:
        code = sys._getframe(1).f_code
        if code.co_filename == threading.__file__ and code.co_name == "start":  # Thread.start's own wait
            return saved["wait"](event, timeout)
        # Event.wait on the simulated clock: poll each simulated millisecond (set() may come
        # from any thread, which only runs while this one waits)
        end = None if timeout is None else sim.now_ns() + int(timeout * 1e9)
        while not event.is_set():
            if end is not None and sim.now_ns() >= end:
                return False
            step = sim.now_ns() + 1_000_000
            sim.wait_until(step if end is None else min(step, end))
        return True

    threading.Thread.start = start  # type: ignore[method-assign,assignment]
    threading.Thread.join = join  # type: ignore[method-assign,assignment]
    threading.Thread.is_alive = is_alive  # type: ignore[method-assign,assignment]
    threading.Event.wait = wait  # type: ignore[method-assign,assignment]
    sim.start_worker = lambda name, function: _start_worker(sim, saved["start"], name, function)
    return saved


def _run_simulated(sim: Any, simulated: Any, function: Any) -> None:
    """The body of a simulated thread: wait for its turn, run, hand over when done. What it
    raised is kept (Python prints it and the thread dies; the node goes on); what ends the
    run (a C abort, a storm...) is passed to the main thread."""
    sim.enter(simulated)
    try:
        function()
    except (sim.Aborted, sim.PublishStorm, sim.NotSimulated, sim.RunStopped) as exc:
        main = sim.main_thread()
        main.pending, main.wake = exc, sim.now_ns()
    except BaseException as exc:  # noqa: BLE001 - the learner's, reported as data
        sim.STATE.thread_failures.append((simulated.name, exc, sim.now_ns(), sim.STATE.interrupted))
    finally:
        sim.finish(simulated)


def _start_worker(sim: Any, start: Any, name: str, function: Any) -> Any:
    """A thread of the stand-in itself (a MultiThreadedExecutor's pool), on the simulated clock."""
    import threading

    simulated = sim.spawn(name, True)
    thread = threading.Thread(target=lambda: _run_simulated(sim, simulated, function), name=name, daemon=True)
    start(thread)
    return simulated


def _restore_threads(saved: dict[str, Any]) -> None:
    import threading

    threading.Thread.start = saved["start"]  # type: ignore[method-assign]
    threading.Thread.join = saved["join"]  # type: ignore[method-assign]
    threading.Thread.is_alive = saved["is_alive"]  # type: ignore[method-assign]
    threading.Event.wait = saved["wait"]  # type: ignore[method-assign]


def robot_joints(robot: Any) -> list[dict[str, Any]] | None:
    """The robot's joints as plain data for the child (tf2_ros answers from them)."""
    if robot is None:
        return None
    return [{"name": j.name, "type": j.type, "parent": j.parent, "child": j.child,
             "xyz": tuple(j.origin.xyz), "rpy": tuple(j.origin.rpy), "axis": tuple(j.axis_or_default)}
            for j in robot.joints]


def _learner_frames(exc: BaseException, target: Target) -> list[Frame]:
    root = target.root + os.sep
    frames = []
    for summary in traceback.extract_tb(exc.__traceback__):
        filename = os.path.abspath(summary.filename)
        if filename.startswith(root) and not filename.startswith(STANDIN):
            frames.append(Frame(os.path.relpath(filename, target.root).replace(os.sep, "/"),
                                summary.lineno or 0, summary.name, (summary.line or "").strip()))
    if isinstance(exc, SyntaxError) and exc.filename and os.path.abspath(exc.filename).startswith(root):
        frames.append(Frame(os.path.relpath(os.path.abspath(exc.filename), target.root).replace(os.sep, "/"),
                            exc.lineno or 0, "", (exc.text or "").strip()))
    return frames


def _failure(exc: BaseException, target: Target, sim: Any, t_ns: int, thread: str = "") -> NodeFailure:
    context = _context(exc, target, sim)
    if thread:
        context["thread"] = thread
    return NodeFailure(type(exc).__name__, str(exc)[:2000], _learner_frames(exc, target), t_ns / 1e9, context)


def _context(exc: BaseException, target: Target, sim: Any) -> dict[str, Any]:
    """What the explanation of a failure needs beyond the traceback: the callback that raised,
    where its ``def`` is and where it was handed to create_timer/create_subscription."""
    out: dict[str, Any] = {}
    for key in ("field", "held"):
        if hasattr(exc, key):
            out[key] = getattr(exc, key)
    if isinstance(exc, ImportError) and str(exc).startswith("cannot import name '"):
        import _messages  # `from std_msgs.msg import JointState`: the modules that do define it

        out["homes"] = _messages.homes_of(str(exc).split("'")[1])
        out["near"] = _messages.near_names(str(exc).split("'")[1])
    missing = (exc.name or "").partition(".")[0] if isinstance(exc, ModuleNotFoundError) else ""
    if missing.endswith(ROS_SUFFIXES):
        import _messages  # `import sensors_msgs`: the interface packages of Jazzy named alike

        out["near_packages"] = _messages.near_packages(missing, JAZZY_UNSIMULATED)
    node_class = _uninitialised_node(exc)
    if node_class is not None:
        out["node_class"] = node_class.__name__
        code = getattr(node_class.__dict__.get("__init__"), "__code__", None)
        path, line = _place(code.co_filename if code else "", code.co_firstlineno if code else 0, target)
        if path:
            out["def_path"], out["def_line"] = path, line
    callback = getattr(exc, "_bras_callback", None)
    if callback:
        out.update({"callback_kind": callback["kind"], "callback": callback["name"],
                    "bound": callback["bound"]})
        for key in ("def", "made"):
            path, line = _place(callback[f"{key}_path"], callback[f"{key}_line"], target)
            if path:
                out[f"{key}_path"], out[f"{key}_line"] = path, line
    return out


def _uninitialised_node(exc: BaseException) -> Any:
    """The class of a Node subclass whose __init__ never ran Node.__init__ (super().__init__
    forgotten), found as ``self`` in the traceback of an AttributeError."""
    if not isinstance(exc, AttributeError):
        return None
    from rclpy.node import Node

    tb = exc.__traceback__
    while tb is not None:
        candidate = tb.tb_frame.f_locals.get("self")
        if isinstance(candidate, Node) and "_name" not in vars(candidate):
            return type(candidate)
        tb = tb.tb_next
    return None


def _join_threads(sim: Any) -> None:
    for thread in list(sim.STATE.threads[1:]):
        if not thread.daemon and not thread.done:
            sim.join(thread, None)


def _place(path: str, line: int, target: Target) -> tuple[str, int]:
    full = os.path.abspath(path) if path else ""
    if full.startswith(target.root + os.sep):
        return os.path.relpath(full, target.root).replace(os.sep, "/"), line
    return "", 0


def run_node_here(target: Target, duration: float, echo: bool, workdir: str, watch: Any = None,
                  parameters: dict[str, Any] | None = None, robot: list[dict[str, Any]] | None = None,
                  blocked: Any = None) -> bytes:
    """Run the node in this (child) process and return what it did: the record's bytes
    (:func:`bras_kit.ros.record_wire.write_record`), read back by :func:`~bras_kit.ros.record_wire.read_record`.
    ``blocked`` (called at the end) gives what the walls stopped, as :class:`~bras_kit.ros.attempts.Attempt`."""
    import time

    wall = time.perf_counter
    started = wall()
    os.chdir(workdir)
    install()
    import _bras_sim as sim

    sim.STATE.end_ns = int(round(duration * 1e9))
    sim.STATE.echo = echo
    sim.STATE.parameters = dict(parameters or {})
    sim.STATE.robot = robot  # the joints tf2_ros's Buffer moves, as robot_state_publisher would
    if watch is not None:
        sim.STATE.on_advance = watch
    sys.path.insert(0, target.root)
    sys.argv = [target.path]
    output = HeadTail()  # the first and last 64 KiB of what the node prints (bras_kit.ros.capture)
    saved_stdout, saved_stderr = sys.stdout, sys.stderr
    if not echo:
        sys.stdout = output
    else:  # shown live: the learner's prints and logs with their control characters shown, not obeyed
        from ..trust.inert import TerminalWriter

        sys.stdout, sys.stderr = TerminalWriter(sys.stdout), TerminalWriter(sys.stderr)
    saved = _patch_time(sim)
    saved_threads = _patch_threads(sim)
    ended, failure = "returned", None
    try:
        module = importlib.import_module(target.module)
        function = getattr(module, target.function, None)
        if function is None:
            # the console script's entry point (importlib.metadata EntryPoint.load) does
            # getattr(module, 'main'): ros2 run stops with this AttributeError
            raise AttributeError(f"module '{target.module}' has no attribute '{target.function}'")
        function()
        _join_threads(sim)  # Python waits for the threads that are not daemons before it exits
    except sim.DurationReached:
        ended = "duration"
    except sim.RunStopped:
        ended = "stopped"
    except sim.PublishStorm:
        ended = "storm"
    except KeyboardInterrupt:  # the node raised one itself
        ended = "duration"
    except SystemExit as exc:
        if exc.code not in (None, 0):
            ended, failure = "error", NodeFailure("SystemExit", str(exc.code), _learner_frames(exc, target),
                                                  sim.STATE.now_ns / 1e9)
    except sim.NotSimulated as exc:
        ended, failure = "not_simulated", NodeFailure("NotSimulated", exc.what, _learner_frames(exc, target),
                                                      sim.STATE.now_ns / 1e9)
    except sim.Aborted as exc:
        ended, failure = "error", NodeFailure("Aborted", exc.what, _learner_frames(exc, target),
                                              sim.STATE.now_ns / 1e9, _context(exc, target, sim))
    except Exception as exc:  # noqa: BLE001 - the learner's error, reported as data
        ended, failure = "error", _failure(exc, target, sim, sim.STATE.now_ns)
    finally:
        _restore_time(saved)
        _restore_threads(saved_threads)
        sys.stdout, sys.stderr = saved_stdout, saved_stderr
    if failure is None:
        # an exception in another thread: Python prints it and that thread ends; the first
        # before the end of the run is the node's failure (one at Ctrl-C is only noise)
        for name, raised, t_ns, interrupted in sim.STATE.thread_failures:
            if not interrupted:
                ended, failure = "error", _failure(raised, target, sim, t_ns, thread=name)
                break
    state = sim.STATE
    printed = output.kept()
    attempts = list(blocked() if blocked is not None else [])[:record_wire.MAX_ENTRIES]
    summary = {
        "target": target.shown, "source": os.path.relpath(target.path, target.root).replace(os.sep, "/"),
        "function": target.function, "duration": duration, "end": state.now_ns / 1e9, "ended": ended,
        "failure": _failure_data(failure), "dropped": state.dropped,
        "publishers": [[n, topic, kind, *_place(path, line, target)]
                       for n, topic, kind, path, line in state.publishers[:record_wire.MAX_ENTRIES]],
        "subscriptions": [[n, topic, kind, *_place(path, line, target)]
                          for n, topic, kind, path, line in state.subscriptions[:record_wire.MAX_ENTRIES]],
        "timers": [[n, period, *_place(path, line, target)]
                   for n, period, path, line in state.timers[:record_wire.MAX_ENTRIES]],
        "nodes": list(state.node_names[:record_wire.MAX_ENTRIES]), "rate_sleeps": state.rate_sleeps,
        "wall_seconds": wall() - started, "start_ns": sim.START_NS,
        "output": printed.head, "output_tail": printed.tail, "output_dropped": printed.dropped_chars,
        "output_dropped_lines": printed.dropped_lines,
        "split_strings": _split_strings(state.split_strings, target)[:record_wire.MAX_ENTRIES],
        "blocked": [[a.kind, a.detail, a.path, a.line] for a in attempts],
        "overflow": {"logs": state.logs_dropped, "too_big": state.too_big, "messages": state.bytes_dropped,
                     "entries": sum(max(0, len(entries) - record_wire.MAX_ENTRIES) for entries in (
                         state.publishers, state.subscriptions, state.timers, state.node_names))},
    }
    return record_wire.write_record(summary, state.messages, state.logs)


def _failure_data(failure: NodeFailure | None) -> dict[str, Any] | None:
    if failure is None:
        return None
    return {"kind": failure.kind, "detail": failure.detail, "time": failure.time, "context": failure.context,
            "frames": [[f.path, f.line, f.function, f.text] for f in failure.frames[:100]]}


def _split_strings(found: list[tuple[str, str, str, str, str, int]], target: Target) -> list[list[Any]]:
    """One per place and field (the first value), with how many messages were sent so."""
    counts: dict[tuple[str, str, str, str, int], int] = {}
    values: dict[tuple[str, str, str, str, int], str] = {}
    for node, topic, field, value, path, line in found:
        key = (node, topic, field, *_place(path, line, target))
        counts[key] = counts.get(key, 0) + 1
        values.setdefault(key, value)
    return [[node, topic, field, values[key], path, line, counts[key]]
            for key in counts for node, topic, field, path, line in [key]]
