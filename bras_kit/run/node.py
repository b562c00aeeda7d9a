"""Running one node: ``bras-kit run``'s child under the containment, its record read back
(:mod:`bras_kit.ros.record_wire`), the limits it meets. The package's face is :mod:`bras_kit.run`."""

from __future__ import annotations

import mmap
import os
import struct
from typing import Any

from ..core.errors import BrasKitError
from ..core.message import M
from ..ros.locate import Target, locate
from ..ros.recording import Recording, stamp_seconds
from ..ros.topics import JOINT_STATES
from ..trust import scratch
from ..trust.contain import containment

DEFAULT_DURATION = 10.0
MAX_DURATION = 3600.0
CPU_SECONDS = 20
WALL_SECONDS = 60.0
MEMORY_BYTES = 1 << 30
MAX_LIVE_LINE = 1 << 20  # one JointState line from a live node to the relay (a 2,000-joint one is 70 KiB)
RESULT_BYTES = 64 << 20  # the most of a run's record this process reads (bras_kit.ros.record_wire)


class NodeRunError(BrasKitError):
    """The node could not be run to the end: it was stopped by a limit of the sandbox.
    ``kind`` is the limit ("cpu", "wall", "memory"...), ``time`` the simulated seconds reached."""

    def __init__(self, message, *, kind: str = "", time: float = 0.0, **where) -> None:
        super().__init__(message, **where)
        self.kind = kind
        self.time = time


def _child(target: Target, duration: float, echo: bool, workdir: str, shared: mmap.mmap,
           parameters: dict[str, Any], walls: Any = None, robot: Any = None, prefixes: list[str] | None = None,
           live: int | None = None, keep: bool = True):
    from ..ros.child import run_node_here

    if prefixes:  # as after `source install/setup.bash`: get_package_share_directory finds the package
        os.environ["AMENT_PREFIX_PATH"] = os.pathsep.join(prefixes)
    forward = _live_forwarder(live, keep) if live is not None else None

    def watch(t_ns: int) -> None:
        shared[:8] = struct.pack("<q", t_ns)
        if forward is not None:
            forward(t_ns)

    watcher = None
    if walls is not None:  # contained: what the walls stopped, with the learner's lines
        from ..ros.attempts import Watcher

        read, write = walls.granted()
        watcher = Watcher(target.root, tuple(write), tuple(read))
        watcher.install()
    def last() -> list[Any]:
        if forward is not None:
            forward(0)  # what was published at the last instant
        return watcher.finish() if watcher is not None else []

    return run_node_here(target, duration, echo, workdir, watch, parameters, robot, blocked=last)


def _live_forwarder(fd: int, keep: bool = True):
    """In the child, live beside ``bras-kit launch``: the simulated clock is held to the wall clock
    (the real time functions, taken before the stand-in patches them) and each JointState on
    /joint_states is written to ``fd`` as it is published, one JSON line (the parent puts it on
    the bus: Zenoh's threads are never used across a fork). Unless ``keep``, what was sent is not
    kept in the recording (nor the logs, already shown): a node live for hours stays the same size."""
    import json
    import time

    from ..ros.topics import JOINT_STATE_TYPE

    sleep, clock = time.sleep, time.perf_counter
    start = clock()
    sent = 0

    def forward(t_ns: int) -> None:
        nonlocal sent
        import _bras_sim

        messages = _bras_sim.STATE.messages  # the record's lines (bras_kit.ros.record_wire)
        while sent < len(messages):
            try:
                _, _, _, topic, kind, fields = json.loads(messages[sent])
            except (ValueError, TypeError):
                continue
            finally:
                sent += 1
            if topic == JOINT_STATES and kind == JOINT_STATE_TYPE:
                line = json.dumps({"name": [str(n) for n in fields.get("name", [])],
                                   "position": [float(p) for p in fields.get("position", [])],
                                   "stamp": stamp_seconds(fields) or 0.0}) + "\n"
                os.write(fd, line.encode())
        if not keep:
            del messages[:sent], _bras_sim.STATE.logs[:]
            _bras_sim.STATE.message_bytes = _bras_sim.STATE.log_bytes = sent = 0
        ahead = t_ns / 1e9 - (clock() - start)
        if ahead > 0:
            sleep(ahead)

    return forward


def _relay(fd: int, deliver: Any = None) -> Any:
    """In the parent: JSON lines from the child onto the bus (or to ``deliver``, called with each
    :class:`~bras_kit.ros.bus.BusJointState`), in a thread, until the child is done."""
    import json
    import threading

    from ..ros.bus import Bus, joint_state_of

    bus: Any = None
    if deliver is None:
        try:
            bus = Bus.connect()
        except BrasKitError:  # no Zenoh here: the node still runs, nothing reaches the launch
            bus = None
        if bus is not None:
            deliver = bus.publish_joint_state

    def pump() -> None:
        with open(fd, "rb") as stream:
            while True:
                # a line is read up to MAX_LIVE_LINE bytes; the rest of a longer one is drained, never held
                line = stream.readline(MAX_LIVE_LINE + 1)
                if not line:
                    break
                if len(line) > MAX_LIVE_LINE:
                    while line and not line.endswith(b"\n"):
                        line = stream.readline(MAX_LIVE_LINE)
                    continue
                if deliver is None:
                    continue  # drained all the same: the child never blocks on a full pipe
                try:
                    state = joint_state_of(json.loads(line))
                except (ValueError, KeyError, TypeError, RecursionError):
                    continue
                try:
                    deliver(state)
                except Exception:  # noqa: BLE001 - a browser that left mid-frame: the next state goes on
                    continue
        if bus is not None:
            bus.close()

    thread = threading.Thread(target=pump, daemon=True, name="bras-kit-relay")
    thread.start()
    return thread


def parse_parameters(items: list[str]) -> dict[str, Any]:
    """``NAME:=VALUE`` items, as ``ros2 run ... --ros-args -p NAME:=VALUE`` reads them: the value
    is YAML (``0.5`` a float, ``3`` an integer, ``true`` a boolean, ``[1.0, 2.0]`` a list, else text)."""
    import yaml

    from ..trust import yaml_gate

    out: dict[str, Any] = {}
    for item in items:
        name, sep, text = item.partition(":=")
        if not sep or not name.strip():
            raise BrasKitError(M("'{item}' is not NAME:=VALUE", item=item),
                               hint=M("write a parameter as -p amplitude:=0.5, as after ros2 run ... --ros-args"))
        try:
            value = yaml_gate.load(text, loader=yaml.SafeLoader) if text.strip() else ""
        except yaml.YAMLError:
            value = text
        if not isinstance(value, (bool, int, float, str, list)):
            value = text
        out[name.strip()] = value
    return out


def run_node(where: str, executable: str | None = None, *, duration: float = DEFAULT_DURATION,
             echo: bool = False, parameters: dict[str, Any] | None = None, cpu_seconds: int = CPU_SECONDS,
             memory_bytes: int = MEMORY_BYTES, wall_seconds: float = WALL_SECONDS,
             contain: str = "auto", live: bool = False, on_joint_state: Any = None, keep: bool = True,
             stop: Any = None, robot: Any = None, beside: list[str] | tuple[str, ...] = (),
             on_built: Any = None) -> Recording:
    """Run the node ``where`` names (a package folder and an executable of its console_scripts,
    or a ``.py`` file) for ``duration`` simulated seconds and return its recording.

    ``echo`` shows the node's logs and prints live (as ``ros2 run`` does); otherwise they are
    kept in the recording. ``parameters`` are the values ``--ros-args -p NAME:=VALUE`` would
    give the node's declared parameters. The node runs in a child process with a CPU, memory and wall-clock
    limit, in a temporary working folder, contained (:mod:`bras_kit.trust.contain`): ``contain``
    is "auto" (contained where this machine can, else not), "require" (a
    :class:`~bras_kit.trust.contain.ContainmentUnavailable` where it cannot) or "off". ``live``
    paces the simulated clock to the wall clock and publishes each /joint_states message on the
    bus (:mod:`bras_kit.ros.bus`) to a running ``bras-kit launch`` (or, given ``on_joint_state``,
    calls it with each :class:`~bras_kit.ros.bus.BusJointState` instead); unless ``keep``, a live
    run keeps no recording of what it sent, so its memory stays flat. ``stop`` (a
    :class:`threading.Event`) ends the run early: :class:`bras_kit.trust.sandbox.Stopped` is raised.
    ``robot`` (a :class:`~bras_kit.model.robot.Robot`) is the one robot_state_publisher would publish
    for the node's tf2_ros Buffer; by default the package's robot description, if any.
    ``beside``: the other package folders of its colcon workspace, built with it as colcon builds
    the whole workspace, so get_package_share_directory finds them too. ``on_built`` is called
    with what the package's setup.py tried that its walls stopped (a list of
    :class:`~bras_kit.ros.attempts.Attempt`, also the recording's ``build_blocked``) once it is
    built, before the node starts: a live run shows it then, not at Ctrl-C.
    """
    from ..ros.child import robot_joints
    from ..trust.sandbox import ResourceLimitError, run_limited

    if not 0 < duration <= MAX_DURATION:
        raise BrasKitError(M("the duration must be between 0 and {max} s of simulated time", max=MAX_DURATION),
                           hint=M("for example --duration 10"))
    target = locate(where, executable)
    _preload()
    shared = mmap.mmap(-1, 8)
    try:
        with scratch.folder("bras-kit-run-") as workdir:
            prefixes, build_blocked = _build(target, workdir, beside)
            if on_built is not None:
                on_built(list(build_blocked))
            walls = containment(contain, workdir, (target.root, target.package or target.root))
            joints = _robot_joints(where) if robot is None else robot_joints(robot)
            write_end: int | None = None
            relay, wall = None, wall_seconds
            if live:  # the node's JointStates go out through a pipe to the relay, on the wall clock
                import dataclasses

                read_end, write_end = os.pipe()
                relay = _relay(read_end, on_joint_state)
                wall = max(wall_seconds, duration + 30.0)
                cpu_seconds = max(cpu_seconds, int(duration / 10))  # a node live for an hour may use 6 min
                if walls is not None:  # the pipe to the relay is the one way out the contained node keeps
                    walls = dataclasses.replace(walls, keep=(write_end,))
            try:
                wire = run_limited(
                    _child, target, duration, echo, workdir, shared, dict(parameters or {}), walls, joints, prefixes,
                    write_end, keep, cpu_seconds=cpu_seconds, contain=walls, stop=stop, memory_bytes=memory_bytes,
                    wall_seconds=wall, what=f"the node {target.shown}", result_bytes=RESULT_BYTES)
                recording = _checked(wire, target)
                recording.build_blocked = build_blocked
                return recording
            except ResourceLimitError as exc:
                reached = struct.unpack("<q", shared[:8])[0] / 1e9
                raise _limit_error(exc.kind, target, reached, cpu_seconds, wall, memory_bytes) from None
            finally:
                if relay is not None and write_end is not None:
                    os.close(write_end)
                    relay.join(10)
    finally:
        shared.close()


def _checked(wire: Any, target: Target) -> Recording:
    """The record the node's process sent, read as a stranger's claim (typed, bounded, names re-checked)."""
    from ..ros.record_wire import WireError, read_record

    try:
        return read_record(wire)
    except WireError:
        raise NodeRunError(M("the node's process sent back no record bras-kit can read: it may have replaced "
                             "parts of the stand-in for rclpy"),
                           hint=M("a node publishes and logs through rclpy; it does not change rclpy itself"),
                           kind="record", path=target.path) from None


def robot_of(where: str, urdf: str | None = None) -> Any:
    """The robot the node drives: ``urdf`` when given, else the package's robot description
    (the one its launch file reads, else ``urdf/*.urdf``), else None (a lone .py file)."""
    from ..model.authoring import load

    if urdf is not None:
        return load(urdf)
    folder = where if os.path.isdir(where) else None
    if folder is None:  # a .py file: its package folder, when it sits in one
        parent = os.path.dirname(os.path.dirname(os.path.abspath(where)))
        folder = parent if os.path.isfile(os.path.join(parent, "setup.py")) else None
    if folder is None:
        return None
    from ..ros.package import Package

    return Package(folder).robot


def _robot_joints(where: str) -> Any:
    """The joints of the robot the node drives (tf2_ros's Buffer in the child moves them), or None."""
    from ..ros.child import robot_joints

    try:
        return robot_joints(robot_of(where))
    except Exception:  # noqa: BLE001 - no robot to read: tf2 then knows only what was broadcast
        return None


def _preload() -> None:
    """Jazzy's message definitions, read once in this process so that every child forked for a
    run finds them loaded (the stand-in makes its message classes from them)."""
    from rosbags.typesys import Stores, get_typestore

    get_typestore(Stores.ROS2_JAZZY)


def _build(target: Target, workdir: str, beside: list[str] | tuple[str, ...] = ()) -> tuple[list[str], list[Any]]:
    """The package built as colcon builds it (``ros2 run`` runs the installed package): the
    install prefixes to put in AMENT_PREFIX_PATH, and what its setup.py tried that its walls
    stopped. A build that stops is an error, in colcon's words."""
    if target.package is None:
        return [], []
    from ..ros.build import build_package

    record = build_package(target.package, os.path.join(workdir, "install"))
    if record.failure is not None:
        from ..findings.data import finding
        from ..findings.registry import RULES
        from ..validate.package.launch_rules import build_hits

        for hit in build_hits(record, target.package):
            found = finding(RULES["BK630"], hit)
            raise BrasKitError(found.message, hint=found.hint,
                               path=os.path.join(target.package, str(hit.params.get("file", ""))), line=hit.line)
        return [], []  # BK600's cases (no setup.py): locate() already said what it needs
    from ..ros.launching import simulated_ros_prefix
    from ..ros.workspace import build_others

    # one that does not build is missing, as after a colcon build stopped there: the node meets
    # ROS's own PackageNotFoundError
    built, _unbuilt = build_others(list(beside), os.path.join(workdir, "install"))
    return [record.prefix, *built, simulated_ros_prefix(workdir)], list(record.blocked)


def _limit_error(kind: str, target: Target, reached: float, cpu: int, wall: float, memory: int) -> NodeRunError:
    place = {"path": target.path}
    if kind == "cpu":
        return NodeRunError(
            M("the node used {cpu} s of CPU while its simulated clock stood still at t={time} s, and was stopped",
              cpu=cpu, time=reached),
            hint=M("a loop that never calls time.sleep(), rate.sleep() or rclpy.spin_once() runs flat out and "
                   "lets no time pass; publish from a timer (create_timer) and spin"),
            kind=kind, time=reached, **place)
    if kind == "wall":
        return NodeRunError(
            M("the node took more than {wall} s of real time (simulated clock at t={time} s) and was stopped",
              wall=wall, time=reached),
            hint=M("a loop that never sleeps nor spins (the clock cannot move), or a wait for something that "
                   "never comes (input(), a thread, a socket)"),
            kind=kind, time=reached, **place)
    if kind == "memory":
        return NodeRunError(
            M("the node needed more than {mib} MiB of memory (simulated clock at t={time} s) and was stopped",
              mib=memory >> 20, time=reached),
            hint=M("a list that grows at every tick without end, or a very deep recursion?"),
            kind=kind, time=reached, **place)
    return NodeRunError(M("the node's process died (simulated clock at t={time} s)", time=reached),
                        hint=M("it may use a library that crashes; try it with ros2 run on a ROS 2 machine"),
                        kind=kind, time=reached, **place)
