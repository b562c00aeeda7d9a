"""What a run of a learner's node leaves: every message published, the logs, how it ended.

Plain data (picklable), made in the child process by :mod:`.child` and read in the parent.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from .attempts import Attempt

if TYPE_CHECKING:  # numpy is imported where a recording becomes joint states: a launch file's
    import numpy as np  # evaluation (bras_kit.ros.launched) reads this module and needs none of it

    from ..motion.core import JointStates

from .topics import JOINT_STATE_TYPE, JOINT_STATES


@dataclass(frozen=True)
class Published:
    time: float  # simulated seconds since the start of the run
    node: str
    topic: str
    type: str  # "sensor_msgs/msg/JointState"
    fields: dict[str, Any]


@dataclass(frozen=True)
class Endpoint:
    """A publisher or subscription the node created, and where (the learner's file and line)."""

    node: str
    topic: str  # resolved: "/joint_states"
    type: str
    path: str  # relative to the package folder ("" when not in the learner's files)
    line: int


@dataclass(frozen=True)
class TimerInfo:
    node: str
    period: float  # seconds
    path: str
    line: int


@dataclass(frozen=True)
class Frame:
    """One frame of the learner's own code in a traceback."""

    path: str  # as shown (relative to the package folder when inside it)
    line: int
    function: str
    text: str


@dataclass(frozen=True)
class NodeFailure:
    """The node raised: the exception, the learner's frames, the simulated time."""

    kind: str  # the exception's class name ("AssertionError", "NotSimulated", "SyntaxError"...)
    detail: str
    frames: list[Frame]
    time: float
    # what explains it beyond the traceback: the callback that raised ("callback", "def_path",
    # "def_line", "made_path", "made_line", "bound"), the thread ("thread")
    context: dict[str, Any] = field(default_factory=dict)


@dataclass(frozen=True)
class SplitString:
    """A string-sequence field (JointState.name) the node gave one string: sent as its letters."""

    node: str
    topic: str
    field: str
    value: str
    path: str
    line: int
    count: int  # messages sent so


@dataclass(frozen=True)
class Refusal:
    """A piece of a run's record that bras-kit's process left out: not what the stand-in makes
    (a node name outside ROS 2's rules, a field of the wrong type...). ``detail``: a short inert sample."""

    what: str
    detail: str


@dataclass
class Recording:
    target: str  # what ran: "bras_description animation" or a file
    source: str  # the file holding the function that ran (relative to the package)
    function: str
    duration: float  # simulated seconds asked for
    end: float  # simulated seconds when the node stopped
    ended: str  # "returned", "duration", "error", "stopped", "storm", "not_simulated"
    failure: NodeFailure | None = None
    messages: list[Published] = field(default_factory=list)
    dropped: int = 0
    logs: list[tuple[float, str, str, str]] = field(default_factory=list)
    publishers: list[Endpoint] = field(default_factory=list)
    subscriptions: list[Endpoint] = field(default_factory=list)
    timers: list[TimerInfo] = field(default_factory=list)
    nodes: list[str] = field(default_factory=list)
    rate_sleeps: int = 0
    wall_seconds: float = 0.0
    start_ns: int = 0  # the simulated wall clock at t = 0 (header stamps count from it)
    output: str = ""  # what the node printed, when not shown live: its first 64 KiB (bras_kit.ros.capture)
    output_tail: str = ""  # ... and its last 64 KiB, when more was printed
    output_dropped: int = 0  # characters printed between the two, not kept
    output_dropped_lines: int = 0
    blocked: list[Attempt] = field(default_factory=list)  # what the containment stopped (contained runs)
    build_blocked: list[Attempt] = field(default_factory=list)  # what the package's setup.py tried (BK639)
    split_strings: list[SplitString] = field(default_factory=list)
    # what bras-kit's process left out of the record the node's process sent (bras_kit.ros.record_wire)
    refused: list[Refusal] = field(default_factory=list)  # the first ones, with a sample
    refused_count: int = 0
    overflow: dict[str, int] = field(default_factory=dict)  # past a bound: "messages", "logs", "line"...

    def topics(self) -> dict[str, int]:
        """Messages published per topic, in order of first publication."""
        out: dict[str, int] = {}
        for message in self.messages:
            out[message.topic] = out.get(message.topic, 0) + 1
        return out

    def on(self, topic: str) -> list[Published]:
        return [m for m in self.messages if m.topic == topic]

    def joint_state_messages(self, topic: str = JOINT_STATES) -> list[Published]:
        return [m for m in self.messages if m.topic == topic and m.type == JOINT_STATE_TYPE]


def stamp_seconds(fields: dict[str, Any]) -> float | None:
    """header.stamp of a recorded message in seconds, or None when it has no header."""
    header = fields.get("header")
    if not isinstance(header, dict):
        return None
    stamp = header.get("stamp") or {}
    return float(stamp.get("sec", 0)) + float(stamp.get("nanosec", 0)) * 1e-9


def joint_states(recording: Recording, topic: str = JOINT_STATES) -> JointStates:
    """The JointState messages published on ``topic`` as a joint-state sequence (time = when
    each was published). Joints are those of the first message; a message that names other
    joints or gives fewer positions is left out (the findings say so)."""
    import numpy as np

    from ..motion.core import JointStates

    messages = recording.joint_state_messages(topic)
    names: list[str] = []
    times: list[float] = []
    positions: list[list[float]] = []
    velocities: list[list[float]] = []
    for message in messages:
        fields = message.fields
        if not names:
            names = list(fields.get("name") or [])
        if list(fields.get("name") or []) != names or len(fields.get("position") or []) != len(names):
            continue
        position = [float(v) for v in fields["position"]]
        velocity = [float(v) for v in fields.get("velocity") or []]
        if len(velocity) != len(names) or not all(math.isfinite(v) for v in velocity):
            velocity = [0.0] * len(names)
        times.append(message.time)
        positions.append(position)
        velocities.append(velocity)
    n = len(names)
    return JointStates(np.array(times, dtype=float), names,
                       np.array(positions, dtype=float).reshape(len(times), n),
                       np.array(velocities, dtype=float).reshape(len(times), n))


def states_for(recording: Recording, dof: list[str] | tuple[str, ...], topic: str = JOINT_STATES) -> JointStates:
    """The joint states on ``topic`` in the robot's joint order ``dof``, as robot_state_publisher
    reads them: each message sets the joints it names (unknown names are ignored), the others
    keep their last value (0 at first). Messages whose name and position lengths differ are
    dropped, as robot_state_publisher drops them."""
    import numpy as np

    from ..motion.core import JointStates

    index = {name: k for k, name in enumerate(dof)}
    current = np.zeros(len(dof))
    times: list[float] = []
    rows: list[np.ndarray] = []
    for message in recording.joint_state_messages(topic):
        names = list(message.fields.get("name") or [])
        position = list(message.fields.get("position") or [])
        if len(names) != len(position):
            continue
        for name, value in zip(names, position):
            if name in index and math.isfinite(float(value)):
                current[index[name]] = float(value)
        times.append(message.time)
        rows.append(current.copy())
    positions = np.array(rows, dtype=float).reshape(len(rows), len(dof))
    time_array = np.array(times, dtype=float)
    velocities = (np.gradient(positions, time_array, axis=0) if len(rows) > 1 and np.all(np.diff(time_array) > 0)
                  else np.zeros_like(positions))
    return JointStates(time_array, list(dof), positions, velocities)


def sent_joint_states(recording: Recording, topic: str = JOINT_STATES) -> list[dict[str, Any]]:
    """The JointState messages on ``topic`` as the node sent them, for ``run -o``: the node's
    names, positions, velocities and efforts (empty when it set none: nothing is filled in) and
    its header.stamp (``stamp``, seconds, 0.0 when left at zero), with ``time`` (when it published)."""
    out = []
    for message in recording.joint_state_messages(topic):
        fields = message.fields
        found = fields.get("header")
        header: dict[str, Any] = found if isinstance(found, dict) else {}
        stamp = header.get("stamp") or {}
        out.append({"time": message.time,
                    "stamp": {"sec": int(stamp.get("sec", 0)), "nanosec": int(stamp.get("nanosec", 0))},
                    "frame_id": str(header.get("frame_id", "")),
                    "name": [str(n) for n in fields.get("name") or []],
                    "position": [float(v) for v in fields.get("position") or []],
                    "velocity": [float(v) for v in fields.get("velocity") or []],
                    "effort": [float(v) for v in fields.get("effort") or []]})
    return out
