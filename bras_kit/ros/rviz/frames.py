"""From joint states to the links RViz can place: robot_state_publisher, tf2 and RViz's frame lookup.

Three steps, each following the tool's own source (the file and lines are cited beside each rule):

1. :class:`RobotStatePublisher` does what robot_state_publisher 3.3.3 (Jazzy's) does with each
   ``sensor_msgs/JointState`` (``src/robot_state_publisher.cpp``, ``callbackJointState``): the size
   check, the publish interval on stamps, mimic joints, then one transform per moving joint it
   knows, stamped with the message's stamp. Fixed joints go out once, on /tf_static.
2. A small tf2 buffer (``tf2/src/buffer_core.cpp``, ``tf2/src/cache.cpp``, ros2/geometry2 jazzy)
   keeps what it accepts: NaN refused, 10 s of history per frame, data older than that refused.
3. :func:`placed_links` asks, for each link, what RViz's RobotModel asks (``tf_link_updater.cpp``):
   a transform from the link to the Fixed Frame at time zero, that is the latest common time of the
   chain. Age alone never hides a link (RViz's frame manager looks up "latest" when it is not
   synchronised, ``rviz_common/src/rviz_common/frame_manager.cpp:155-181``).

Times are integer nanoseconds, as ``builtin_interfaces/Time`` holds them.

::

    rsp = RobotStatePublisher(robot)
    got = rsp.on_joint_state(JointStateIn(stamp_ns, ("epaule", "coude"), (0.1, 0.2)))
    placed_links(robot, "base", rsp.transforms())   # {"base": None, "bras": None, ...}
"""

from __future__ import annotations

import math
from collections.abc import Iterable
from dataclasses import dataclass

from ...core.errors import ParameterError
from ...core.message import M, Message
from ...model.robot import Joint, Robot

MOVING_TYPES = ("revolute", "continuous", "prismatic")  # kdl_parser.cpp (rolling) toKdl: RotAxis/TransAxis
# tf2's default history per frame: BUFFER_CORE_DEFAULT_CACHE_TIME, tf2/include/tf2/buffer_core.h:72
CACHE_NS = 10 * 1_000_000_000


@dataclass(frozen=True)
class Tf:
    """One transform as robot_state_publisher sends it and tf2 holds it: ``child`` in ``parent``.

    ``joint`` and ``position`` say which joint value made it (empty and 0 for a fixed joint);
    ``nan`` is True when the transform holds a NaN, which tf2 refuses (buffer_core.cpp:235-242)."""

    parent: str
    child: str
    stamp_ns: int
    static: bool
    joint: str = ""
    position: float = 0.0
    nan: bool = False


@dataclass(frozen=True)
class JointStateIn:
    """One ``sensor_msgs/JointState`` as received: its header stamp, names and positions, who sent
    it, and what robot_state_publisher's clock read when it came (None: not known)."""

    stamp_ns: int
    names: tuple[str, ...]
    positions: tuple[float, ...]
    publisher: str = ""
    received_ns: int | None = None


@dataclass(frozen=True)
class Received:
    """robot_state_publisher's answer to one message: what went out on /tf (empty when nothing
    did), why not or what it or tf2 logs (None when all is well), and the names it had no moving
    joint for (fixed joints, names not in the robot), which it skips without a word."""

    published: tuple[Tf, ...]
    reason: Message | None
    ignored: tuple[str, ...] = ()


@dataclass(frozen=True)
class _Segment:
    parent: str
    child: str
    joint: Joint


def _seconds(ns: int) -> float:
    return ns / 1e9


def _holds_nan(joint: Joint, position: float) -> bool:
    """Whether the transform KDL computes for ``position`` holds a NaN.

    A rotation of a NaN or infinite angle is NaN throughout. A prismatic joint moves by
    ``axis * q`` with the axis turned into the parent frame (kdl_parser.cpp, rolling, lines 80-83),
    so an infinite q gives NaN exactly where that axis has a zero component (0 * inf)."""
    if math.isnan(position):
        return True
    if joint.type != "prismatic":
        return not math.isfinite(position)
    if math.isfinite(position):
        return False
    from ...kinematics.frames import rpy_to_matrix

    axis = [float(v) for v in rpy_to_matrix(joint.origin.rpy) @ list(joint.axis_or_default)]
    return any(math.isnan(component * position) for component in axis)


class RobotStatePublisher:
    """robot_state_publisher 3.3.3 with one robot, message by message.

    ``start_ns`` is its clock when it starts (the stamp of /tf_static, robot_state_publisher.cpp:
    288-291). ``ignore_timestamp`` is its parameter of that name (line 339)."""

    def __init__(self, robot: Robot, publish_frequency: float = 20.0, *, ignore_timestamp: bool = False,
                 start_ns: int = 0) -> None:
        # robot_state_publisher.cpp:118-121: the node refuses to start outside these bounds; 0 is
        # let through there but then divides 1000 by zero (line 337), so it is refused here too
        if not 0.0 < publish_frequency <= 1000.0:
            raise ParameterError(M("publish_frequency must be between 0 and 1000"))
        # line 336-337: the interval is whole milliseconds, cut down (30 Hz gives 33 ms)
        self.interval_ns = int(1000.0 / publish_frequency) * 1_000_000
        self.ignore_timestamp = ignore_timestamp
        self._moving: dict[str, _Segment] = {}
        self._fixed: list[_Segment] = []
        links = set(robot.link_names)
        for joint in robot.joints:
            if not (joint.name and joint.parent in links and joint.child in links and joint.type):
                continue
            segment = _Segment(str(joint.parent), str(joint.child), joint)
            if joint.type in MOVING_TYPES:
                self._moving.setdefault(joint.name, segment)  # line 243: segments_ keyed by joint name
            elif joint.type != "floating":  # lines 229-236: a floating joint is skipped, not fixed
                # kdl_parser's toKdl turns every other type (planar included) into a fixed joint
                self._fixed.append(segment)
        # lines 186-197: every joint with a <mimic>, in a std::map (so by name)
        self._mimic: dict[str, tuple[str, float, float]] = {}
        for joint in sorted(robot.joints, key=lambda j: str(j.name)):
            if joint.name and joint.mimic is not None and joint.mimic.joint:
                self._mimic[joint.name] = (joint.mimic.joint, joint.mimic.multiplier, joint.mimic.offset)
        self._static = [Tf(s.parent, s.child, start_ns, True, s.joint.name or "") for s in
                        sorted(self._fixed, key=lambda s: str(s.joint.name))]
        self._last_publish: dict[str, int] = {}  # last_publish_time_, by name as received
        self._last_callback: int | None = None
        self._latest: dict[str, Tf] = {}

    def static(self) -> list[Tf]:
        """What goes out on /tf_static when it starts: one transform per fixed joint (lines 279-298)."""
        return list(self._static)

    def transforms(self) -> list[Tf]:
        """The latest transform sent for each child link, the static ones included."""
        return self._static + list(self._latest.values())

    def positions(self) -> dict[str, float]:
        """Each moving joint's value in the latest transform sent for it (what RViz draws)."""
        return {tf.joint: tf.position for tf in self._latest.values() if not tf.nan}

    def on_joint_state(self, msg: JointStateIn) -> Received:
        """callbackJointState (lines 300-363), step by step."""
        names, positions = msg.names, msg.positions
        if len(names) != len(positions):  # lines 303-312: nothing else is checked before this
            if not positions:
                return Received((), M("Robot state publisher ignored a JointState message about joint(s) "
                                      "\"{name}\"(,...) whose position member was empty.", name=names[0]))
            return Received((), M("Robot state publisher ignored an invalid JointState message"))
        now = msg.received_ns  # None: rsp's clock not known, so never seen going backwards
        went_back = now is not None and self._last_callback is not None and self._last_callback > now
        if went_back:  # lines 316-321: a clock gone backwards (a bag replayed) forgets the stamps
            self._last_publish.clear()
        if now is not None:
            self._last_callback = now
        if not names:  # lines 325-340: the bar is then rsp's clock plus the interval, never reached
            return Received((), M("robot_state_publisher published nothing: the message names no joint"))
        # lines 325-329: the joint published longest ago, 0 for a name seen the first time (a clock
        # behind every stamp lowers the bar to the clock)
        last = min(self._last_publish.get(name, 0) for name in names)
        if now is not None:
            last = min(last, now)
        if not (self.ignore_timestamp or msg.stamp_ns >= last + self.interval_ns):  # lines 334-340
            return Received((), M("robot_state_publisher published nothing: the stamp {stamp:.3f} s is not "
                                  "{interval} ms past {last:.3f} s, the stamp it last published for these joints",
                                  stamp=_seconds(msg.stamp_ns), interval=self.interval_ns // 1_000_000,
                                  last=_seconds(last)))
        values: dict[str, float] = {}
        for name, position in zip(names, positions):
            values.setdefault(name, position)  # line 345: std::map::insert keeps the first of a name
        for joint, (leader, multiplier, offset) in self._mimic.items():  # lines 348-354
            if leader in values:
                values.setdefault(joint, values[leader] * multiplier + offset)
        published = []
        for name in sorted(values):  # lines 264-274: only names with a moving segment
            segment = self._moving.get(name)
            if segment is not None:
                value = values[name]
                published.append(Tf(segment.parent, segment.child, msg.stamp_ns, False, name, value,
                                    _holds_nan(segment.joint, value)))
        for name in names:  # lines 359-361: every name of the message, known or not
            self._last_publish[name] = msg.stamp_ns
        for tf in published:
            if not tf.nan:  # tf2 keeps the one before (buffer_core.cpp:235-242)
                self._latest[tf.child] = tf
        ignored = tuple(dict.fromkeys(n for n in names if n not in self._moving))
        return Received(tuple(published), _why(published, names, ignored, went_back), ignored)


def _why(published: list[Tf], names: tuple[str, ...], ignored: tuple[str, ...], went_back: bool) -> Message | None:
    refused = [tf for tf in published if tf.nan]
    if refused:
        # buffer_core.cpp:239-242, tf2's code word for it, with the joint value that caused it
        return M("TF_NAN_INPUT: tf2 ignores the transform of {child}, {joint} is {value}",
                 child=refused[0].child, joint=refused[0].joint, value=repr(refused[0].position))
    if not published:
        return M("robot_state_publisher published nothing: no name in the message is a moving joint "
                 "of the robot ({names})", names=", ".join(dict.fromkeys(names)) or "-")
    if went_back:
        return M("Moved backwards in time, re-publishing joint transforms!")  # line 318-319
    return None


# ---------------------------------------------------------------- tf2's buffer, as RViz's listener fills it


class _Buffer:
    """tf2's BufferCore, reduced to what decides whether a lookup succeeds: per child frame a
    static entry or a history of (stamp, parent), newest first, as TimeCache keeps it."""

    def __init__(self) -> None:
        self.static: dict[str, str] = {}
        self.history: dict[str, list[tuple[int, str]]] = {}
        self.frames: set[str] = set()

    def insert(self, tf: Tf) -> None:
        if tf.nan or not tf.parent or not tf.child or tf.parent == tf.child:
            return  # buffer_core.cpp:203-256 (setTransformImpl): refused before any frame is made
        self.frames.update((tf.child, tf.parent))
        if tf.static:  # lines 268-279: a static transform replaces whatever the frame held
            self.static[tf.child] = tf.parent
            self.history.pop(tf.child, None)
            return
        self.static.pop(tf.child, None)
        items = self.history.setdefault(tf.child, [])
        if items:  # cache.cpp:255-290: prune by the newest held, then refuse what is older still
            latest = items[0][0]
            while items[-1][0] + CACHE_NS < latest:  # the oldest are at the end (pruneList, :340-346)
                items.pop()
            if tf.stamp_ns < latest - CACHE_NS:
                return  # TF_OLD_DATA
        at = next((i for i, item in enumerate(items) if item[0] <= tf.stamp_ns), len(items))
        same = at
        while same < len(items) and items[same][0] == tf.stamp_ns:  # the same transform twice: kept once
            if items[same][1] == tf.parent:
                return
            same += 1
        items.insert(at, (tf.stamp_ns, tf.parent))

    def _up(self, frame: str) -> tuple[str, int] | None:
        """The frame's parent and the stamp of its latest transform (0 for a static one)."""
        if frame in self.static:
            return self.static[frame], 0
        items = self.history.get(frame)
        return (items[0][1], items[0][0]) if items else None

    def _chain(self, frame: str) -> list[tuple[str, str, int]]:
        chain: list[tuple[str, str, int]] = []
        seen = {frame}
        while (step := self._up(frame)) is not None:
            chain.append((frame, step[0], step[1]))
            frame = step[0]
            if frame in seen:  # buffer_core.cpp:1101-1110: a loop fails the lookup
                return []
            seen.add(frame)
        return chain

    def _has(self, frame: str, time: int) -> bool:
        """TimeCache::findClosest (cache.cpp:123-166): at ``time`` without extrapolation."""
        if frame in self.static or time == 0:
            return True
        items = self.history.get(frame, [])
        if len(items) == 1:
            return items[0][0] == time
        return bool(items) and items[-1][0] <= time <= items[0][0]

    def can_transform(self, target: str, source: str) -> bool:
        """lookupTransform(target, source, time zero): the latest common time of the chain, then
        each frame of it at that time."""
        if target == source:  # buffer_core.cpp:763: the identity, asked of no frame
            return True
        if target not in self.frames or source not in self.frames:
            return False
        up_source, up_target = self._chain(source), self._chain(target)
        above_source = [source] + [parent for _, parent, _ in up_source]
        above_target = [target] + [parent for _, parent, _ in up_target]
        common = next((frame for frame in above_target if frame in above_source), None)
        if common is None:  # two trees: "Could not find a connection between ..."
            return False
        path = (up_source[:above_source.index(common)] + up_target[:above_target.index(common)])
        stamps = [stamp for _, _, stamp in path if stamp != 0]  # getLatestCommonTime, lines 1044-1140
        time = min(stamps) if stamps else 0
        return all(self._has(child, time) for child, _, _ in path)


def placed_links(robot: Robot, fixed_frame: str, transforms: Iterable[Tf]) -> dict[str, Message | None]:
    """Each link: None when RViz can place it in ``fixed_frame`` (a chain of transforms), else RViz's
    status words (e.g. "No transform from [avant_bras] to [base]").

    ``transforms`` are those RViz's tf2 listener received, in the order it received them (the
    history matters to tf2; :meth:`RobotStatePublisher.transforms` gives the latest of each)."""
    buffer = _Buffer()
    for tf in transforms:
        buffer.insert(tf)
    placed: dict[str, Message | None] = {}
    for link in robot.link_names:
        # frame_manager.cpp:197-199: no Fixed Frame, no transform; tf_link_updater.cpp:71-75: RViz's words
        if fixed_frame and buffer.can_transform(fixed_frame, link):
            placed[link] = None
        else:
            placed[link] = M("No transform from [{link}] to [{fixed}]", link=link, fixed=fixed_frame)
    return placed
