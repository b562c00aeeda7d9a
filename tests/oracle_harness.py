"""One learner node under the REAL rclpy of Jazzy, recorded from inside its own process.

Run by ``tests/ros/test_rclpy_oracle.py`` with the oracle's interpreter (``realros.oracle_python()``)
inside a loopback-only network namespace (``realros.run_isolated``); never imported by bras-kit.

    python oracle_harness.py NODE.py FUNCTION SECONDS OUT.jsonl

What it does, as ``ros2 run`` then Ctrl-C would: imports the node's module, calls FUNCTION,
sends SIGINT to itself after SECONDS of wall time (rclpy's handler chains to Python's, which
raises KeyboardInterrupt in the main thread: rclpy/src/rclpy/signal_handler.cpp), and writes one
JSON line per event to OUT as it happens: ``start``, each ``publish`` (wrapping
``rclpy.publisher.Publisher.publish``: every message the node sent, in order, with the system
clock's time, which is the node's ROS clock without use_sim_time), each exception of another
thread, then ``end``. A node still running GRACE seconds after the SIGINT is written ``hang``.
A process killed in C (an ``assert`` of a message's conversion) writes no ``end``: the test reads
its exit status. A recorder joining over DDS would miss the first messages (discovery takes
1-2.5 s); this one misses none.
"""

from __future__ import annotations

import array
import importlib
import json
import os
import signal
import sys
import threading
import time
import traceback

NO_NODE = 10.0  # seconds to wait for a first Node (a loaded machine takes several to start DDS)
GRACE = 2.0  # the stand-in gives a node 2 s of its time to end after Ctrl-C (_bras_sim.GRACE_NS)


def to_data(value):
    """A message as plain data, field by field (``get_fields_and_field_types``, rosidl's order)."""
    if hasattr(type(value), "get_fields_and_field_types"):
        return {name: to_data(getattr(value, name)) for name in type(value).get_fields_and_field_types()}
    if isinstance(value, array.array) or type(value).__name__ == "ndarray":
        return value.tolist()
    if isinstance(value, (list, tuple)):
        return [to_data(v) for v in value]
    if isinstance(value, (bool, int, float, str)) or value is None:
        return value
    return repr(value)


def type_name(message_type) -> str:
    package = message_type.__module__.split(".")[0]
    return f"{package}/msg/{message_type.__name__}"


def main() -> None:
    path, function, seconds, out = sys.argv[1], sys.argv[2], float(sys.argv[3]), sys.argv[4]
    folder = os.path.dirname(os.path.abspath(path))
    module_name = os.path.splitext(os.path.basename(path))[0]
    stream = open(out, "w", buffering=1)
    lock = threading.Lock()

    def emit(event: dict) -> None:
        with lock:
            stream.write(json.dumps(event) + "\n")
            stream.flush()

    def learner_line(exc: BaseException) -> int:
        line = 0
        for frame in traceback.extract_tb(exc.__traceback__):
            if os.path.abspath(frame.filename).startswith(folder + os.sep):
                line = frame.lineno or 0
        if isinstance(exc, SyntaxError) and exc.filename and os.path.abspath(exc.filename).startswith(folder):
            line = exc.lineno or 0
        return line

    def described(exc: BaseException) -> dict:
        return {"type": type(exc).__name__, "message": str(exc), "line": learner_line(exc)}

    def end(event: dict) -> None:
        emit({"event": "end", "t_ns": time.time_ns(), **event})
        stream.close()
        os._exit(0)  # DDS's teardown is not the node's: its time stays out of the suite's

    import rclpy.publisher
    from rclpy.serialization import deserialize_message, serialize_message

    publish = rclpy.publisher.Publisher.publish

    def recording_publish(self, msg):  # type: ignore[no-untyped-def]
        t_ns = time.time_ns()
        publish(self, msg)  # first: what the C conversion refuses was never sent
        kind = type_name(type(msg)) if hasattr(type(msg), "get_fields_and_field_types") else repr(type(msg))
        try:  # what went out: the message through the same C conversion, read back
            fields = to_data(deserialize_message(serialize_message(msg), type(msg)))
        except Exception:  # noqa: BLE001 - published all the same: recorded as the node holds it
            fields = to_data(msg)
        emit({"event": "publish", "t_ns": t_ns, "topic": self.topic_name, "type": kind, "fields": fields})

    rclpy.publisher.Publisher.publish = recording_publish  # type: ignore[method-assign]

    def thread_failed(hook: threading.ExceptHookArgs) -> None:
        if hook.exc_value is not None:
            emit({"event": "thread_error", "t_ns": time.time_ns(), "thread": getattr(hook.thread, "name", ""),
                  **described(hook.exc_value)})

    threading.excepthook = thread_failed
    sys.path.insert(0, folder)
    sys.argv = [path]
    os.chdir(os.environ.get("ORACLE_WORKDIR", folder))
    # the node's time starts with its first Node (rcl and DDS take a second or more to start on
    # a loaded machine, which the stand-in's clock does not count): Ctrl-C comes SECONDS later
    import rclpy.node

    born: list[int] = []
    node_init = rclpy.node.Node.__init__

    def noted_init(self, *args, **kwargs):  # type: ignore[no-untyped-def]
        node_init(self, *args, **kwargs)
        if not born:  # once rcl_node_init has returned: DDS's start-up is not the node's time
            born.append(time.time_ns())
            emit({"event": "node", "t_ns": born[0]})

    rclpy.node.Node.__init__ = noted_init  # type: ignore[method-assign]
    started = time.time_ns()
    emit({"event": "start", "t_ns": started})

    def watch() -> None:
        # a node that never makes a Node (it fails first, or loops without one) gets NO_NODE s
        while (time.time_ns() - born[0]) / 1e9 < seconds if born else (time.time_ns() - started) / 1e9 < NO_NODE:
            time.sleep(0.005)
        os.kill(os.getpid(), signal.SIGINT)
        time.sleep(GRACE)
        end({"ended": "hang"})

    threading.Thread(target=watch, daemon=True, name="oracle-watch").start()
    try:
        module = importlib.import_module(module_name)
        entry = getattr(module, function)  # importlib.metadata EntryPoint.load, as ros2 run's script
        entry()
    except KeyboardInterrupt:
        end({"ended": "interrupted"})
    except SystemExit as exc:
        code = exc.code
        end({"ended": "returned" if code in (None, 0) else "exit", "code": str(code)})
    except BaseException as exc:  # noqa: BLE001 - the learner's, recorded as data
        end({"ended": "error", **described(exc)})
    # main() returned: the interpreter's exit waits for the threads that are not daemons (and
    # stops concurrent.futures' pools, threading._register_atexit); atexit comes after that
    import atexit

    atexit.register(lambda: end({"ended": "returned"}))


if __name__ == "__main__":
    main()
