"""What runs in the child process: the stand-in installed, time simulated, the node's main().

Everything here happens after ``fork`` (:func:`bras_kit.sandbox.run_limited`): the import
hook, the patched ``time`` functions and the working folder belong to the child alone.
"""

from __future__ import annotations

import importlib
import importlib.abc
import importlib.machinery
import io
import os
import sys
import traceback
from typing import Any

from .locate import Target
from .recording import Endpoint, Frame, NodeFailure, Published, Recording, TimerInfo

STANDIN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "_standin")
SIMULATED = ("rclpy", "sensor_msgs", "std_msgs", "builtin_interfaces", "geometry_msgs", "_bras_sim", "_bras_msgs")
# other ROS 2 Python packages a node may import: refused with a clear message, never taken
# from a real install (the stand-in's rclpy cannot drive them)
ROS_PACKAGES = ("launch", "launch_ros", "ament_index_python", "tf2_ros", "tf2_py", "tf_transformations",
                "rosidl_runtime_py", "rclpy_message_converter", "message_filters", "rosbag2_py",
                "rcl_interfaces", "action_msgs", "robot_state_publisher", "urdf_parser_py", "xacro")
ROS_SUFFIXES = ("_msgs", "_srvs", "_interfaces", "_actions")
MAX_OUTPUT = 200_000  # characters of the node's own prints kept when not shown live


def is_ros_name(top: str) -> bool:
    return top in SIMULATED or top in ROS_PACKAGES or top.endswith(ROS_SUFFIXES)


class StandinFinder(importlib.abc.MetaPathFinder):
    """First on sys.meta_path in the child: ROS names come from the stand-in folder or stop."""

    def find_spec(self, fullname: str, path: Any = None, target: Any = None) -> Any:
        top = fullname.partition(".")[0]
        if not is_ros_name(top):
            return None
        search = [STANDIN] if path is None or "." not in fullname else path
        spec = importlib.machinery.PathFinder.find_spec(fullname, search)
        if spec is None:
            import _bras_sim

            raise _bras_sim.NotSimulated(fullname)
        return spec


def _install() -> None:
    for name in list(sys.modules):
        if is_ros_name(name.partition(".")[0]):
            del sys.modules[name]
    sys.meta_path.insert(0, StandinFinder())


def _patch_time(sim: Any) -> dict[str, Any]:
    import time

    saved = {name: getattr(time, name) for name in
             ("sleep", "time", "time_ns", "monotonic", "monotonic_ns", "perf_counter", "perf_counter_ns")}
    start = sim.START_NS
    time.sleep = sim.sleep  # type: ignore[assignment]
    time.time = lambda: (start + sim.STATE.now_ns) / 1e9  # type: ignore[assignment]
    time.time_ns = lambda: start + sim.STATE.now_ns  # type: ignore[assignment]
    time.monotonic = time.perf_counter = lambda: sim.STATE.now_ns / 1e9  # type: ignore[assignment]
    time.monotonic_ns = time.perf_counter_ns = lambda: sim.STATE.now_ns  # type: ignore[assignment]
    return saved


def _restore_time(saved: dict[str, Any]) -> None:
    import time

    for name, function in saved.items():
        setattr(time, name, function)


def _patch_threads(sim: Any) -> Any:
    """``threading.Thread(target=rclpy.spin, args=(node,)).start()`` (or an executor's ``spin``)
    is simulated: the executor runs its callbacks while the main thread sleeps. Any other thread
    is not simulated and says so."""
    import threading

    original = threading.Thread.start

    def start(thread: threading.Thread) -> None:
        import rclpy
        from rclpy.executors import Executor

        target = getattr(thread, "_target", None)
        args = tuple(getattr(thread, "_args", ()))
        kwargs = dict(getattr(thread, "_kwargs", {}) or {})
        executor = None
        if target is rclpy.spin and (args or "node" in kwargs):
            node = args[0] if args else kwargs["node"]
            executor = (args[1] if len(args) > 1 else kwargs.get("executor")) or rclpy.get_global_executor()
            executor.add_node(node)
        elif getattr(target, "__func__", None) is Executor.spin and isinstance(getattr(target, "__self__", None),
                                                                            Executor):
            executor = target.__self__  # type: ignore[union-attr]
        if executor is None:
            raise sim.NotSimulated("threading.Thread")
        sim.STATE.background.append(executor)

    threading.Thread.start = start  # type: ignore[method-assign,assignment]
    return original


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


def _place(path: str, line: int, target: Target) -> tuple[str, int]:
    full = os.path.abspath(path) if path else ""
    if full.startswith(target.root + os.sep):
        return os.path.relpath(full, target.root).replace(os.sep, "/"), line
    return "", 0


def run_node_here(target: Target, duration: float, echo: bool, workdir: str, watch: Any = None,
                  parameters: dict[str, Any] | None = None) -> Recording:
    """Run the node in this (child) process and return what it did."""
    import time

    wall = time.perf_counter
    started = wall()
    os.chdir(workdir)
    _install()
    import _bras_sim as sim

    sim.STATE.end_ns = int(round(duration * 1e9))
    sim.STATE.echo = echo
    sim.STATE.parameters = dict(parameters or {})
    if watch is not None:
        sim.STATE.on_advance = watch
    sys.path.insert(0, target.root)
    sys.argv = [target.path]
    output = io.StringIO()
    saved_stdout = sys.stdout
    if not echo:
        sys.stdout = output
    saved = _patch_time(sim)
    import threading

    saved_start = _patch_threads(sim)
    ended, failure = "returned", None
    try:
        module = importlib.import_module(target.module)
        function = getattr(module, target.function, None)
        if not callable(function):
            raise sim.NotSimulated(f"{target.module}:{target.function}")
        function()
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
    except Exception as exc:  # noqa: BLE001 - the learner's error, reported as data
        ended, failure = "error", NodeFailure(type(exc).__name__, str(exc)[:2000], _learner_frames(exc, target),
                                              sim.STATE.now_ns / 1e9)
    finally:
        _restore_time(saved)
        threading.Thread.start = saved_start  # type: ignore[method-assign]
        sys.stdout = saved_stdout
    state = sim.STATE
    return Recording(
        target=target.shown, source=os.path.relpath(target.path, target.root).replace(os.sep, "/"),
        function=target.function, duration=duration, end=state.now_ns / 1e9, ended=ended, failure=failure,
        messages=[Published(t / 1e9, node, topic, kind, fields) for t, node, topic, kind, fields in state.messages],
        dropped=state.dropped, logs=[(t / 1e9, level, node, text) for t, level, node, text in state.logs],
        publishers=[Endpoint(n, topic, kind, *_place(path, line, target)) for n, topic, kind, path, line in state.publishers],
        subscriptions=[Endpoint(n, topic, kind, *_place(path, line, target))
                       for n, topic, kind, path, line in state.subscriptions],
        timers=[TimerInfo(n, period, *_place(path, line, target)) for n, period, path, line in state.timers],
        nodes=[node.get_name() for node in state.nodes], rate_sleeps=state.rate_sleeps,
        wall_seconds=wall() - started, start_ns=sim.START_NS, output=output.getvalue()[:MAX_OUTPUT],
    )
