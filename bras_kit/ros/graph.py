"""One look at a live ROS 2 graph, as data: what the probe (``_probe.py``) saw in a few seconds.

The probe prints JSON; :func:`snapshot_from_json` turns it into these frozen records and is the
one place that reads it: a field of the wrong type, a name that is not text, a number that is not
finite is dropped there (the probe runs in another interpreter, and what a graph holds is written
by whoever joined it). The rules (:mod:`bras_kit.validate.live`) read only these records.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

MAX_NAMES = 10_000
MAX_TRANSFORMS = 20_000


@dataclass(frozen=True)
class Endpoint:
    """A publisher or a subscription of a topic: its node and the QoS it offers or asks for."""

    node: str
    reliability: str = ""
    durability: str = ""


@dataclass(frozen=True)
class Topic:
    name: str
    types: tuple[str, ...] = ()
    publishers: tuple[Endpoint, ...] = ()
    subscribers: tuple[Endpoint, ...] = ()


@dataclass(frozen=True)
class QosMismatch:
    """A publisher and a subscription of one topic whose QoS rmw says cannot match (or may not)."""

    topic: str
    publisher: Endpoint
    subscriber: Endpoint
    level: str  # "error" (they never communicate) or "warning" (rmw cannot tell)
    reason: str


@dataclass(frozen=True)
class Description:
    """A text received on /robot_description, and when (seconds since the epoch)."""

    text: str
    received: float
    length: int


@dataclass(frozen=True)
class JointStateSample:
    received: float  # wall clock of this machine, seconds
    stamp: tuple[int, int]  # header.stamp (sec, nanosec)
    name: tuple[str, ...]
    position: tuple[float, ...]
    sent: float | None = None  # the DDS source timestamp (the publisher's clock), seconds

    @property
    def stamp_seconds(self) -> float:
        return self.stamp[0] + self.stamp[1] * 1e-9


@dataclass(frozen=True)
class GraphEvent:
    """A change the probe saw during the watch: a node ``joined`` or ``left``, a node began
    (``publishes``) or ceased (``unpublishes``) publishing ``topic``; ``time`` in seconds since the epoch."""

    time: float
    kind: str
    node: str
    topic: str = ""


EVENT_KINDS = ("joined", "left", "publishes", "unpublishes")


@dataclass(frozen=True)
class TfSample:
    """One transform received on /tf or /tf_static (where the probe could read them)."""

    parent: str
    child: str
    stamp: tuple[int, int]
    static: bool
    received: float
    nan: bool = False


@dataclass(frozen=True)
class RvizProcess:
    """An rviz2 process of this machine on this graph: its command line, the configuration file
    it loaded (``config``; ``given``: named with -d, else ~/.rviz2/default.rviz), that file's text
    (None: could not be read), and the frame given with -f."""

    pid: int
    argv: tuple[str, ...]
    config: str
    given: bool
    text: str | None
    fixed_frame_argument: str = ""
    launch: str = ""  # not running: the launch file that would start it (pid 0)


@dataclass(frozen=True)
class Snapshot:
    """The graph of one domain as the probe saw it between ``started`` and ``ended``."""

    domain: int
    discovery_range: str
    rmw: str
    started: float
    ended: float
    nodes: tuple[str, ...] = ()
    topics: Mapping[str, Topic] = field(default_factory=dict)
    mismatches: tuple[QosMismatch, ...] = ()
    descriptions: tuple[Description, ...] = ()
    joint_states: tuple[JointStateSample, ...] = ()
    use_sim_time: Mapping[str, bool | None] = field(default_factory=dict)
    shared_names: Mapping[str, int] = field(default_factory=dict)  # a node name -> how many nodes bear it
    # filled in by the caller when this domain was empty: other places the nodes were seen
    elsewhere: tuple[Elsewhere, ...] = ()
    events: tuple[GraphEvent, ...] = ()
    transforms: tuple[TfSample, ...] | None = None  # None: /tf was not read (no tf2_msgs where the probe ran)
    rviz: tuple[RvizProcess, ...] = ()  # filled in by the caller: the rviz2 processes of this machine
    origin: float | None = None  # when the watch began, for the timeline (None: ``started``; view --ros: its start)

    @property
    def duration(self) -> float:
        return max(0.0, self.ended - self.started)

    def publishers(self, topic: str) -> tuple[Endpoint, ...]:
        found = self.topics.get(topic)
        return found.publishers if found else ()

    def subscribers(self, topic: str) -> tuple[Endpoint, ...]:
        found = self.topics.get(topic)
        return found.subscribers if found else ()


@dataclass(frozen=True)
class Elsewhere:
    """Nodes seen with other settings than this terminal's: another domain, another discovery range."""

    domain: int
    discovery_range: str
    nodes: tuple[str, ...]


def _text(value: Any, limit: int = 10_000) -> str:
    return value[:limit] if isinstance(value, str) else ""


def _number(value: Any, default: float = 0.0) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        return default
    return float(value)


def _list(value: Any) -> list[Any]:
    return value[:MAX_NAMES] if isinstance(value, list) else []


def _endpoint(value: Any) -> Endpoint:
    data = value if isinstance(value, dict) else {}
    return Endpoint(_text(data.get("node"), 300), _text(data.get("reliability"), 40), _text(data.get("durability"), 40))


def _joint_state(value: Any) -> JointStateSample | None:
    if not isinstance(value, dict):
        return None
    stamp = value.get("stamp")
    if not (isinstance(stamp, list) and len(stamp) == 2 and all(isinstance(v, int) for v in stamp)):
        return None
    names = tuple(_text(n, 300) for n in _list(value.get("name")) if isinstance(n, str))
    positions = tuple(_number(p, math.nan) for p in _list(value.get("position")))
    sent = _number(value.get("sent"), math.nan) * 1e-9
    return JointStateSample(_number(value.get("received")), (int(stamp[0]), int(stamp[1])), names, positions,
                            sent if math.isfinite(sent) and sent > 0 else None)


def _event(value: Any) -> GraphEvent | None:
    if not isinstance(value, dict) or value.get("kind") not in EVENT_KINDS:
        return None
    node = _text(value.get("node"), 300)
    return GraphEvent(_number(value.get("time")), str(value["kind"]), node, _text(value.get("topic"), 300)) \
        if node else None


def _tf(value: Any) -> TfSample | None:
    if not isinstance(value, dict):
        return None
    stamp = value.get("stamp")
    if not (isinstance(stamp, list) and len(stamp) == 2 and all(isinstance(v, int) for v in stamp)):
        return None
    return TfSample(_text(value.get("parent"), 300), _text(value.get("child"), 300), (int(stamp[0]), int(stamp[1])),
                    value.get("static") is True, _number(value.get("received")), value.get("nan") is True)


def _rviz(value: Any) -> RvizProcess | None:
    if not isinstance(value, dict) or not isinstance(value.get("pid"), int) or isinstance(value.get("pid"), bool):
        return None
    text = value.get("text")
    return RvizProcess(int(value["pid"]), tuple(_text(a, 4000) for a in _list(value.get("argv"))[:64]),
                       _text(value.get("config"), 4000), value.get("given") is True,
                       text[:1 << 20] if isinstance(text, str) else None, _text(value.get("fixed_frame"), 300),
                       _text(value.get("launch"), 4000))


def snapshot_from_json(data: Any) -> Snapshot:
    """The probe's JSON object as a :class:`Snapshot` (what does not fit is left out)."""
    data = data if isinstance(data, dict) else {}
    topics: dict[str, Topic] = {}
    raw_topics = data.get("topics")
    for name, value in (raw_topics.items() if isinstance(raw_topics, dict) else ()):
        if not isinstance(name, str) or not isinstance(value, dict):
            continue
        topics[name] = Topic(name, tuple(_text(t, 300) for t in _list(value.get("types"))),
                             tuple(e for e in map(_endpoint, _list(value.get("publishers"))) if e.node),
                             tuple(e for e in map(_endpoint, _list(value.get("subscribers"))) if e.node))
    mismatches = tuple(
        QosMismatch(_text(m.get("topic"), 300), _endpoint(m.get("publisher")), _endpoint(m.get("subscriber")),
                    "error" if m.get("level") == "error" else "warning", _text(m.get("reason"), 1000))
        for m in _list(data.get("incompatible")) if isinstance(m, dict)
    )
    descriptions = tuple(
        Description(_text(d.get("text"), 10_000_000), _number(d.get("received")),
                    int(_number(d.get("length"))))
        for d in _list(data.get("descriptions")) if isinstance(d, dict)
    )
    samples = tuple(s for s in (_joint_state(v) for v in _list(data.get("joint_states"))) if s is not None)
    raw_sim = data.get("use_sim_time")
    sim = {k: (v if isinstance(v, bool) else None) for k, v in raw_sim.items()
           if isinstance(k, str)} if isinstance(raw_sim, dict) else {}
    raw_shared = data.get("shared_names")
    shared = {k: int(v) for k, v in raw_shared.items() if isinstance(k, str) and isinstance(v, int)
              and not isinstance(v, bool) and 1 < v < MAX_NAMES} if isinstance(raw_shared, dict) else {}
    domain = data.get("domain")
    elsewhere = tuple(
        Elsewhere(e["domain"], _text(e.get("range"), 40), tuple(_text(n, 300) for n in _list(e.get("nodes"))))
        for e in _list(data.get("elsewhere"))
        if isinstance(e, dict) and isinstance(e.get("domain"), int) and not isinstance(e.get("domain"), bool)
    )
    raw_tf = data.get("transforms")
    transforms = tuple(t for t in map(_tf, raw_tf[:MAX_TRANSFORMS]) if t is not None) \
        if isinstance(raw_tf, list) else None
    return Snapshot(
        events=tuple(e for e in map(_event, _list(data.get("events"))) if e is not None),
        transforms=transforms,
        rviz=tuple(r for r in map(_rviz, _list(data.get("rviz"))[:8]) if r is not None),
        origin=_number(data.get("origin"), math.nan) if math.isfinite(_number(data.get("origin"), math.nan)) else None,
        domain=domain if isinstance(domain, int) and not isinstance(domain, bool) else 0,
        discovery_range=_text(data.get("range"), 40),
        rmw=_text(data.get("rmw"), 100),
        started=_number(data.get("started")),
        ended=_number(data.get("ended")),
        nodes=tuple(sorted({_text(n, 300) for n in _list(data.get("nodes")) if isinstance(n, str)})),
        topics=topics,
        mismatches=mismatches,
        descriptions=descriptions,
        joint_states=samples,
        use_sim_time=sim,
        shared_names=shared,
        elsewhere=elsewhere,
    )


def merge_stream(hello: Mapping[str, Any], graph: Mapping[str, Any] | None, descriptions: Sequence[Mapping[str, Any]],
                 joint_states: Sequence[Mapping[str, Any]], started: float, ended: float) -> Snapshot:
    """A :class:`Snapshot` made from the probe's stream (``view --ros``): its last graph, the
    descriptions and the joint states of the last few seconds."""
    data: dict[str, Any] = {**(graph or {}), **hello, "descriptions": list(descriptions),
                            "joint_states": list(joint_states), "started": started, "ended": ended}
    return snapshot_from_json(data)
