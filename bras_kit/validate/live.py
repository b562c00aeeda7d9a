"""BK8xx: the live ROS 2 graph (``bras-kit doctor --ros``), what keeps RViz empty or the arm still.

Each rule is a small function over one :class:`LiveGraph` (a snapshot of the graph, and the
robot read from the text received on /robot_description), as ros2doctor's checks
(``ros2doctor/api/topic.py``, ``qos_compatibility.py``) and ROS 1's tfwtf are: it yields hits,
never words. The hits carry ``file``: the topic or node the finding is about, shown where a file
would be. The robot's own defects are the URDF rules' findings (BK1xx-BK5xx), run by
:func:`bras_kit.live.doctor.diagnose` on the received text.
"""

from __future__ import annotations

import difflib
import math
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..findings.registry import ERROR, INFO, WARNING, Hit, hit, rule
from ..model.robot import Robot
from ..ros.topics import CLOCK, DESCRIPTION, JOINT_STATES

if TYPE_CHECKING:  # the snapshot's records are imported with a live graph (doctor --ros), not by validate
    from ..ros.graph import Snapshot

TUTORIAL_RATE = 20.0  # the tutorial's node: create_timer(0.05, ...)
SLOW_RATE = 15.0  # below this the arm visibly steps (a fifth under the tutorial's rate, with jitter)
SLIDER_NODE = "joint_state_publisher"  # the slider window's node name (10 Hz by default: its 'rate')
FAR_STAMP = 5.0  # seconds between a stamp and this machine's clock before it is "far"
MAX_SAMPLES_NAMED = 8
MOVING = ("revolute", "continuous", "prismatic")  # the joints rsp has a moving segment for (kdl_parser)


@dataclass(frozen=True)
class LiveGraph:
    """What the live rules read: one snapshot, and the robot its description gives (None when
    no description was received or it is not a URDF)."""

    snapshot: Snapshot
    robot: Robot | None = None


LiveCheck = Callable[[LiveGraph], Iterable[Hit]]
LIVE_CHECKS: dict[str, LiveCheck] = {}


def live_rule(code: str, name: str, severity: str) -> Callable[[LiveCheck], LiveCheck]:
    """Register a live rule: it runs on a :class:`LiveGraph`, never on a robot file."""

    def decorate(check: LiveCheck) -> LiveCheck:
        def on_context(context: Any) -> Iterable[Hit]:
            return check(context) if isinstance(context, LiveGraph) else ()

        rule(code, name, severity)(on_context)
        LIVE_CHECKS[code] = check
        return check

    return decorate


def _at(where: str, variant: str = "", **params: object) -> Hit:
    return hit("file", None, None, variant, file=where, **params)


def _nodes(endpoints: Iterable[Any]) -> list[str]:
    return sorted({e.node for e in endpoints if e.node})


# ---------------------------------------------------------------- nobody here

@live_rule("BK800", "graph-empty", ERROR)
def graph_empty(graph: LiveGraph) -> Iterator[Hit]:
    snap = graph.snapshot
    if snap.nodes:
        return
    if snap.elsewhere:
        there = snap.elsewhere[0]
        if there.domain != snap.domain:
            yield _at(f"ROS_DOMAIN_ID={snap.domain}", "domain", domain=snap.domain, other=there.domain,
                      nodes=list(there.nodes), command=f"export ROS_DOMAIN_ID={there.domain}")
        else:
            command = f"export ROS_AUTOMATIC_DISCOVERY_RANGE={there.discovery_range}"
            yield _at(f"ROS_DOMAIN_ID={snap.domain}", "range", domain=snap.domain, other=there.discovery_range,
                      ours=snap.discovery_range or "SUBNET", nodes=list(there.nodes), command=command)
        return
    yield _at(f"ROS_DOMAIN_ID={snap.domain}", domain=snap.domain, seconds=round(snap.duration, 1))


# ---------------------------------------------------------------- /robot_description

@live_rule("BK801", "robot-description-not-published", ERROR)
def description_not_published(graph: LiveGraph) -> Iterator[Hit]:
    snap = graph.snapshot
    if snap.nodes and not snap.publishers(DESCRIPTION) and not snap.descriptions:
        near = near_topics(snap, DESCRIPTION, STRING)
        if near:  # another namespace, a remap, a typo: the graph shows where it went
            topic, nodes = near[0]
            yield _at(DESCRIPTION, "near", topic=topic, nodes=nodes)
            return
        readers = _nodes(snap.subscribers(DESCRIPTION))
        yield _at(DESCRIPTION, "readers" if readers else "", readers=readers, nodes=list(snap.nodes))


STRING = "std_msgs/msg/String"
JOINT_STATE = "sensor_msgs/msg/JointState"


def near_topics(snap: Snapshot, expected: str, kind: str) -> list[tuple[str, list[str]]]:
    """Published topics that look meant for ``expected``: the same last name under another namespace,
    a name a typo away, or (for JointState, a type no other topic of the tutorial carries) any name."""
    want = expected.rsplit("/", 1)[-1]
    found = []
    for name, topic in sorted(snap.topics.items()):
        if name == expected or not topic.publishers:
            continue
        last = name.rsplit("/", 1)[-1]
        close = last == want or difflib.SequenceMatcher(None, last, want).ratio() >= 0.8
        if (kind in topic.types and (close or kind == JOINT_STATE)) or (close and not topic.types):
            found.append((name, _nodes(topic.publishers)))
    return found


@live_rule("BK802", "robot-description-volatile", ERROR)
def description_volatile(graph: LiveGraph) -> Iterator[Hit]:
    for endpoint in graph.snapshot.publishers(DESCRIPTION):
        if endpoint.durability == "volatile":
            yield _at(DESCRIPTION, node=endpoint.node)


@live_rule("BK803", "robot-description-not-received", ERROR)
def description_not_received(graph: LiveGraph) -> Iterator[Hit]:
    snap = graph.snapshot
    publishers = snap.publishers(DESCRIPTION)
    if publishers and not snap.descriptions and not any(e.durability == "volatile" for e in publishers):
        yield _at(DESCRIPTION, nodes=_nodes(publishers), seconds=round(snap.duration, 1))


def description_kind(text: str) -> str:
    """What a received description is: "urdf" (XML), "empty", "path" (a file's name) or "other"."""
    stripped = text.strip()
    if not stripped:
        return "empty"
    if stripped.startswith("<"):
        return "urdf"
    if "\n" not in stripped and (stripped.endswith((".urdf", ".xacro", ".xml", ".sdf")) or "/" in stripped
                                 or stripped.startswith("package://")):
        return "path"
    return "other"


@live_rule("BK804", "robot-description-not-urdf", ERROR)
def description_not_urdf(graph: LiveGraph) -> Iterator[Hit]:
    if not graph.snapshot.descriptions:
        return
    text = graph.snapshot.descriptions[-1].text
    kind = description_kind(text)
    if kind == "urdf":
        return
    stripped = text.strip()
    yield _at(DESCRIPTION, kind, text=stripped[:200], length=len(text))


# ---------------------------------------------------------------- /joint_states

@live_rule("BK810", "joint-states-not-published", ERROR)
def joint_states_not_published(graph: LiveGraph) -> Iterator[Hit]:
    snap = graph.snapshot
    if not snap.nodes or snap.publishers(JOINT_STATES) or snap.joint_states:
        return
    near = near_topics(snap, JOINT_STATES, JOINT_STATE)
    if near:  # "start your node" would be wrong: it runs, and publishes elsewhere
        topic, nodes = near[0]
        yield _at(JOINT_STATES, "near", topic=topic, nodes=nodes)
        return
    robot = graph.robot
    moving = [j.child for j in robot.movable_joints() if j.child] if robot else []
    root = _root_link(robot)
    yield _at(JOINT_STATES, "links" if moving and root else "", link=moving[-1] if moving else "",
              root=root or "", readers=_nodes(snap.subscribers(JOINT_STATES)))


def _root_link(robot: Robot | None) -> str | None:
    if robot is None:
        return None
    children = {j.child for j in robot.joints}
    roots = [name for name in robot.link_names if name not in children]
    return roots[0] if roots else None


@live_rule("BK811", "joint-states-several-publishers", WARNING)
def joint_states_several_publishers(graph: LiveGraph) -> Iterator[Hit]:
    nodes = _nodes(graph.snapshot.publishers(JOINT_STATES))
    sets = {frozenset(s.name) for s in graph.snapshot.joint_states}
    if len(sets) >= 2 and all(not (a & b) for a in sets for b in sets if a != b):
        # each source drives joints of its own (a second node for the wrist): robot_state_publisher
        # keeps a stamp per joint (src/robot_state_publisher.cpp:326-329, 359-361), nothing jumps
        return
    if len(nodes) >= 2:
        slider = [n for n in nodes if n.rsplit("/", 1)[-1].startswith(SLIDER_NODE)]
        yield _at(JOINT_STATES, "slider" if slider else "", nodes=nodes, n=len(nodes),
                  slider=slider[0] if slider else "")


@live_rule("BK812", "joint-states-not-received", ERROR)
def joint_states_not_received(graph: LiveGraph) -> Iterator[Hit]:
    snap = graph.snapshot
    publishers = snap.publishers(JOINT_STATES)
    types = [t for t in snap.topics[JOINT_STATES].types if t != JOINT_STATE] if publishers else []
    if publishers and types and not snap.joint_states:  # the probe reads JointState only, as rsp does
        yield _at(JOINT_STATES, "type", nodes=_nodes(publishers), types=types)
        return
    if publishers and not snap.joint_states:
        sim = sorted(n for n in _nodes(publishers) if snap.use_sim_time.get(n))
        no_clock = not snap.publishers(CLOCK)
        yield _at(JOINT_STATES, "sim" if sim and no_clock else "", nodes=_nodes(publishers),
                  seconds=round(snap.duration, 1), sim=sim)


def measured_rate(graph: LiveGraph) -> float | None:
    """Messages per second on /joint_states (None under 3 messages), over the time they were sent
    (DDS's source timestamps: a loaded machine delivers in bursts), else over their reception."""
    samples = graph.snapshot.joint_states
    if len(samples) < 3:
        return None
    sent = [s.sent for s in samples if s.sent is not None]
    times = sent if len(sent) == len(samples) else [s.received for s in samples]
    span = max(times) - min(times)
    return (len(samples) - 1) / span if span > 0 else None


@live_rule("BK813", "joint-states-slow", WARNING)
def joint_states_slow(graph: LiveGraph) -> Iterator[Hit]:
    nodes = _nodes(graph.snapshot.publishers(JOINT_STATES))
    if any(n.rsplit("/", 1)[-1].startswith(SLIDER_NODE) for n in nodes):
        return  # the slider window's 10 Hz is its default, and it only moves when a slider does
    rate = measured_rate(graph)
    if rate is not None and rate < SLOW_RATE:
        yield _at(JOINT_STATES, rate=round(rate, 1), expected=TUTORIAL_RATE, period=round(1.0 / rate, 3),
                  nodes=nodes, count=len(graph.snapshot.joint_states))


@live_rule("BK814", "joint-states-stamp-zero", ERROR)
def joint_states_stamp_zero(graph: LiveGraph) -> Iterator[Hit]:
    samples = graph.snapshot.joint_states
    zero = [s for s in samples if s.stamp == (0, 0)]
    if zero:
        yield _at(JOINT_STATES, "all" if len(zero) == len(samples) else "some", count=len(zero), total=len(samples),
                  nodes=_nodes(graph.snapshot.publishers(JOINT_STATES)))


@live_rule("BK815", "joint-states-stamp-far", WARNING)
def joint_states_stamp_far(graph: LiveGraph) -> Iterator[Hit]:
    offsets = [s.stamp_seconds - s.received for s in graph.snapshot.joint_states if s.stamp != (0, 0)]
    if not offsets:
        return
    worst = max(offsets, key=abs)
    if abs(worst) > FAR_STAMP:
        yield _at(JOINT_STATES, "behind" if worst < 0 else "ahead", seconds=round(abs(worst), 1),
                  stamp=round(worst + graph.snapshot.joint_states[-1].received, 3))


def _names_seen(graph: LiveGraph) -> list[str]:
    seen: list[str] = []
    for sample in graph.snapshot.joint_states:
        for name in sample.name:
            if name not in seen:
                seen.append(name)
    return seen


@live_rule("BK816", "joint-states-unknown-joint", ERROR)
def joint_states_unknown_joint(graph: LiveGraph) -> Iterator[Hit]:
    if graph.robot is None:
        return
    movable = [j.name for j in graph.robot.movable_joints() if j.name]
    # a mimic joint sent by name is used as sent: rsp's std::map::insert keeps the message's value
    # over the one the mimic would compute (robot_state_publisher.cpp:343-354)
    mimics = {j.name for j in graph.robot.joints if j.name and j.mimic is not None and j.type in MOVING}
    others = {j.name for j in graph.robot.joints if j.name} - set(movable) - mimics
    for name in _names_seen(graph):
        if name in movable or name in mimics:
            continue
        if name in others:
            yield _at(JOINT_STATES, "fixed", joint=name)
            continue
        near = difflib.get_close_matches(name, movable, n=1, cutoff=0.5)
        yield _at(JOINT_STATES, "near" if near else "", joint=name, near=near[0] if near else "", movable=movable)


@live_rule("BK817", "joint-states-joint-missing", ERROR)
def joint_states_joint_missing(graph: LiveGraph) -> Iterator[Hit]:
    if graph.robot is None or not graph.snapshot.joint_states:
        return
    seen = set(_names_seen(graph))
    for joint in graph.robot.movable_joints():
        if joint.name and joint.name not in seen:
            yield _at(JOINT_STATES, joint=joint.name, link=joint.child or "", seen=sorted(seen))


@live_rule("BK818", "joint-states-past-limits", WARNING)
def joint_states_past_limits(graph: LiveGraph) -> Iterator[Hit]:
    if graph.robot is None:
        return
    worst: dict[str, tuple[float, float, float]] = {}
    for sample in graph.snapshot.joint_states:
        for name, value in zip(sample.name, sample.position):
            joint = graph.robot.joint(name)
            if joint is None or not joint.movable or not math.isfinite(value):
                continue
            lower, upper = joint.bounds()
            excess = max(lower - value, value - upper)
            if excess > 1e-9 and excess > worst.get(name, (0.0, 0.0, 0.0))[0]:
                worst[name] = (excess, value, lower if value < lower else upper)
    degrees = _in_degrees(graph.robot, graph.snapshot.joint_states)
    for name, (excess, value, bound) in sorted(worst.items()):
        lower, upper = graph.robot.joint(name).bounds()  # type: ignore[union-attr]
        if degrees:  # the limit is not the mistake: the unit is
            yield _at(JOINT_STATES, "degrees", joint=name, value=round(value, 3),
                      radians=round(math.radians(value), 3), lower=lower, upper=upper, bound=bound,
                      excess=round(excess, 3))
            continue
        yield _at(JOINT_STATES, "lower" if value < bound else "upper", joint=name, value=round(value, 3),
                  bound=bound, excess=round(excess, 3), lower=lower, upper=upper)


def _in_degrees(robot: Robot, samples: Iterable[Any]) -> bool:
    """Angles that read as degrees: some past a full turn (2 pi rad), and every value of every
    revolute joint within its limits once converted to radians (URDF's unit)."""
    past_a_turn = False
    for sample in samples:
        for name, value in zip(sample.name, sample.position):
            joint = robot.joint(name)
            if joint is None or joint.type != "revolute" or not joint.movable or not math.isfinite(value):
                continue
            lower, upper = joint.bounds()
            if not lower - 1e-6 <= math.radians(value) <= upper + 1e-6:
                return False
            past_a_turn = past_a_turn or abs(value) > 2 * math.pi
    return past_a_turn


@live_rule("BK819", "joint-states-names-and-positions-differ", ERROR)
def joint_states_lengths_differ(graph: LiveGraph) -> Iterator[Hit]:
    bad = [s for s in graph.snapshot.joint_states if len(s.name) != len(s.position)]
    if bad:
        sample = bad[-1]
        yield _at(JOINT_STATES, "empty" if not sample.position else "", count=len(bad),
                  total=len(graph.snapshot.joint_states), names=len(sample.name), positions=len(sample.position))


# ---------------------------------------------------------------- QoS, clock

@live_rule("BK820", "qos-incompatible", ERROR)
def qos_incompatible(graph: LiveGraph) -> Iterator[Hit]:
    for pair in graph.snapshot.mismatches:
        if pair.level == "error":
            yield _at(pair.topic, _qos_variant(pair), publisher=pair.publisher.node, subscriber=pair.subscriber.node,
                      offered=f"{pair.publisher.reliability}, {pair.publisher.durability}",
                      requested=f"{pair.subscriber.reliability}, {pair.subscriber.durability}",
                      reason=pair.reason or "-", policies=", ".join(rclpy_policies(pair.reason)) or "-")


# rmw's words in rclpy.qos.qos_check_compatible's reason (rmw/src/qos_profiles.c,
# rmw_qos_profile_check_compatible), each "ERROR: ...;" naming one policy
RCLPY_POLICIES = (("best effort publisher and reliable subscription", "reliability"),
                  ("volatile publisher and transient local subscription", "durability"),
                  ("deadline", "deadline"), ("lease duration", "liveliness_lease_duration"),
                  ("liveliness", "liveliness"))


def rclpy_policies(reason: str) -> list[str]:
    """The policies rclpy's reason names, in its order ("reliability", "durability", ...)."""
    found = []
    for clause in (c.strip() for c in reason.split(";")):
        lowered = clause.lower()
        if not lowered.startswith("error"):
            continue
        policy = next((name for words, name in RCLPY_POLICIES if words in lowered), None)
        if policy is not None and policy not in found:
            found.append(policy)
    return found


def _qos_variant(pair: Any) -> str:
    if pair.reason:  # rclpy judged the pair: its own words name the policy
        policies = rclpy_policies(pair.reason)
        return policies[0] if policies in (["durability"], ["reliability"]) else ""
    # a look recorded without rclpy's reason: the two policies the graph shows
    if pair.publisher.durability == "volatile" and pair.subscriber.durability == "transient_local":
        return "durability"
    if pair.publisher.reliability == "best_effort" and pair.subscriber.reliability == "reliable":
        return "reliability"
    return ""


@live_rule("BK830", "use-sim-time-without-clock", ERROR)
def use_sim_time_without_clock(graph: LiveGraph) -> Iterator[Hit]:
    snap = graph.snapshot
    if snap.publishers(CLOCK):
        return
    for node, value in sorted(snap.use_sim_time.items()):
        if value:
            yield _at(node, node=node)


# ---------------------------------------------------------------- RViz's arm, from the model of rsp and tf2

STEP_RATE = 5.0  # moves a second under which the arm RViz draws visibly jumps
STOP_GAP = 1.0  # seconds without a message, at the end of the watch, before the source "stopped"


def rviz_fixed_frame(graph: LiveGraph) -> Any:
    """RViz's Fixed Frame as the running rviz2 sets it (:func:`bras_kit.ros.rviz.running.fixed_frame`)."""
    from ..ros.rviz.running import fixed_frame

    return fixed_frame(graph.snapshot.rviz)


def judged_frame(graph: LiveGraph) -> str:
    """The frame the links are placed in: RViz's Fixed Frame when it is a link of the robot, else the
    root link (the frame step 6 sets; a Fixed Frame that is no frame of the robot is BK846's)."""
    frame = rviz_fixed_frame(graph).frame
    if graph.robot is not None and frame in graph.robot.link_names:
        return str(frame)
    return _root_link(graph.robot) or ""


def rviz_replay(graph: LiveGraph) -> Any:
    """The recorded joint states through robot_state_publisher and RViz (:mod:`bras_kit.ros.rviz.replay`),
    links placed in :func:`judged_frame`. None without a robot.

    Where the probe read /tf and /tf_static, RViz's buffer is filled from what was seen; else from
    what the model of robot_state_publisher publishes (the report says which)."""
    if graph.robot is None or not graph.snapshot.joint_states:
        return None
    from ..core.errors import BrasKitError
    from ..ros.rviz.replay import Sample, replay

    samples = [Sample(s.received, s.stamp[0] * 1_000_000_000 + s.stamp[1], s.name, s.position)
               for s in graph.snapshot.joint_states]
    try:
        return replay(graph.robot, samples, judged_frame(graph), start=graph.snapshot.started,
                      seen=_seen_transforms(graph))
    except BrasKitError:
        return None


def _seen_transforms(graph: LiveGraph) -> Any:
    """The transforms received on /tf and /tf_static as the model's :class:`Tf` (None: not read)."""
    if graph.snapshot.transforms is None:
        return None
    from ..ros.rviz.frames import Tf

    return [Tf(t.parent, t.child, t.stamp[0] * 1_000_000_000 + t.stamp[1], t.static, nan=t.nan)
            for t in graph.snapshot.transforms]


@live_rule("BK840", "rviz-arm-still", ERROR)
def rviz_arm_still(graph: LiveGraph) -> Iterator[Hit]:
    from ..ros.rviz.replay import NAN, SIZES, STAMP, UNKNOWN, ZERO

    seen = rviz_replay(graph)
    if seen is None or seen.received < 2 or not seen.reasons:
        return
    kind, words, _ = seen.reasons[0]
    if kind in (SIZES, ZERO, UNKNOWN, NAN):  # BK819, BK814, BK816 and BK841 name these causes
        return
    if seen.moves > 1:
        # it moved, then the stamps stopped clearing the bar while messages kept coming
        # (stamps gone back: a bag replayed in a loop, a counter restarted)
        still = (seen.last_received or 0.0) - (seen.last_move or 0.0)
        if kind == STAMP and seen.last_move is not None and still > STOP_GAP:
            yield _at(JOINT_STATES, "stops", after=round(seen.last_move - graph.snapshot.started, 1),
                      seconds=round(still, 1), dropped=seen.reason_of(STAMP), reason=words)
        return
    yield _at(JOINT_STATES, "stamp" if kind == STAMP else "", received=seen.received, published=seen.published,
              reason=words, nodes=_nodes(graph.snapshot.publishers(JOINT_STATES)))


@live_rule("BK841", "joint-states-not-finite", ERROR)
def joint_states_not_finite(graph: LiveGraph) -> Iterator[Hit]:
    seen = rviz_replay(graph)
    if seen is None or graph.robot is None:
        return
    for joint, (count, value) in sorted(seen.refused.items()):
        found = graph.robot.joint(joint)
        link = (found.child if found else "") or ""
        placed = seen.placed.get(link)
        yield _at(JOINT_STATES, "never" if placed is not None else "", joint=joint, value=repr(value), count=count,
                  total=seen.received, link=link, rviz=placed or "")


@live_rule("BK842", "joint-states-stopped", ERROR)
def joint_states_stopped(graph: LiveGraph) -> Iterator[Hit]:
    snap = graph.snapshot
    samples = snap.joint_states
    if not samples:
        return
    gaps = sorted(b.received - a.received for a, b in zip(samples, samples[1:])) or [0.0]
    period = gaps[len(gaps) // 2]  # one message alone: no period, the gap alone decides
    silent = snap.ended - samples[-1].received
    if silent > max(STOP_GAP, 5 * period):
        yield _at(JOINT_STATES, "" if snap.publishers(JOINT_STATES) else "left", seconds=round(silent, 1),
                  after=round(samples[-1].received - snap.started, 1), count=len(samples))


@live_rule("BK843", "rviz-arm-steps", WARNING)
def rviz_arm_steps(graph: LiveGraph) -> Iterator[Hit]:
    from ..ros.rviz.replay import STAMP

    seen = rviz_replay(graph)
    if seen is None or seen.moves < 2 or not seen.reason_of(STAMP) or seen.first_move is None:
        return
    span = (seen.last_move or 0.0) - seen.first_move
    rate = (seen.moves - 1) / span if span > 0 else 0.0
    # a 20 Hz timer's jitter alone drops about one message in three (a gap of 49.9 ms): only a
    # rate far under that, with most messages dropped, is the stepping the learner sees
    if rate >= STEP_RATE or seen.moves > 0.5 * seen.received:
        return
    stamps = sorted({s.stamp for s in graph.snapshot.joint_states})
    steps = sorted((b[0] - a[0]) + (b[1] - a[1]) * 1e-9 for a, b in zip(stamps, stamps[1:]))
    yield _at(JOINT_STATES, moves=seen.moves, received=seen.received, rate=round(rate, 1),
              step=round(steps[len(steps) // 2], 3) if steps else 0)


# ---------------------------------------------------------------- the graph as a whole

@live_rule("BK844", "node-name-shared", WARNING)
def node_name_shared(graph: LiveGraph) -> Iterator[Hit]:
    for node, count in sorted(graph.snapshot.shared_names.items()):
        yield _at(node, node=node, count=count)


def _robot_names(text: str) -> tuple[set[str], set[str]] | None:
    """The link and joint names of a URDF text (None when it does not read)."""
    from ..core.errors import BrasKitError
    from ..model.robot import robot_from_xml
    from ..model.xmlio import parse_xml

    try:
        robot = robot_from_xml(parse_xml(text, DESCRIPTION), path=DESCRIPTION, source_text=text)
    except BrasKitError:
        return None
    return set(robot.link_names), set(robot.joint_names)


@live_rule("BK845", "robot-description-two-robots", ERROR)
def description_two_robots(graph: LiveGraph) -> Iterator[Hit]:
    snap = graph.snapshot
    texts = list(dict.fromkeys(d.text for d in snap.descriptions))
    publishers = _nodes(snap.publishers(DESCRIPTION))
    if len(texts) < 2 or len(publishers) < 2:
        return  # one publisher that replaced its robot is a new description, not two robots
    first, last = _robot_names(texts[0]), _robot_names(texts[-1])
    if first is None or last is None:
        differ = []
    else:
        differ = sorted((first[0] ^ last[0]) | (first[1] ^ last[1]))
    yield _at(DESCRIPTION, "names" if differ else "", nodes=publishers, n=len(texts),
              names=", ".join(differ[:MAX_SAMPLES_NAMED]))


@live_rule("BK846", "rviz-fixed-frame-not-in-robot", WARNING)
def rviz_fixed_frame_not_in_robot(graph: LiveGraph) -> Iterator[Hit]:
    """RViz's Fixed Frame, as the running rviz2 set it, names no link of the robot: RViz's Global
    Status says "Frame [map] does not exist" and no link is drawn (visualization_manager.cpp:431-451)."""
    seen = rviz_fixed_frame(graph)
    if graph.robot is None or seen.pid is None or seen.frame in graph.robot.link_names:
        return
    root = _root_link(graph.robot) or ""
    if seen.launch:  # not running: only what the learner wrote in the launch or its .rviz is named
        if seen.source in ("argument", "file"):
            yield _at(seen.launch, "launch", frame=seen.frame, root=root, path=seen.path, launch=seen.launch)
        return
    yield _at(f"rviz2 ({seen.pid})", seen.source, frame=seen.frame, root=root,
              path=seen.path or "~/.rviz2/default.rviz", pid=seen.pid)


JOIN_GRACE = 2.5  # seconds over which nodes started together are discovered (_probe.py's measure)


def timeline(graph: LiveGraph) -> list[tuple[float, str, dict[str, object]]]:
    """Who joined, left, began or ceased publishing, replaced the description, fell silent during the
    watch: (seconds from its start, kind, what), in order. Nodes found while discovery was still
    finding the graph's first ones were there from the start, not "joined"."""
    snap = graph.snapshot
    origin = snap.origin if snap.origin is not None else snap.started
    events = sorted(snap.events, key=lambda e: e.time)
    first = min((e.time for e in events if e.kind in ("joined", "publishes")), default=origin)
    out: list[tuple[float, str, dict[str, object]]] = []
    for event in events:
        if event.kind in ("joined", "publishes") and event.time <= first + JOIN_GRACE:
            continue
        out.append((event.time - origin, event.kind, {"node": event.node, "topic": event.topic}))
    texts: list[str] = []
    for description in snap.descriptions:
        if description.text in texts:
            continue
        texts.append(description.text)
        if len(texts) > 1 and description.received > snap.descriptions[0].received + JOIN_GRACE:
            out.append((description.received - origin, "replaced", {"n": len(texts)}))
    samples = snap.joint_states
    if samples and snap.ended - samples[-1].received > STOP_GAP:
        still = _nodes(snap.publishers(JOINT_STATES))
        out.append((samples[-1].received - origin, "silent" if still else "silent-left", {"nodes": still}))
    return sorted(out, key=lambda item: item[0])


@live_rule("BK847", "graph-timeline", INFO)
def graph_timeline(graph: LiveGraph) -> Iterator[Hit]:
    for at, kind, what in timeline(graph):
        yield _at("timeline", kind, at=round(max(0.0, at), 1), **what)
