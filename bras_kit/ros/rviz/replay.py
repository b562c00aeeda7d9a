"""Recorded joint states replayed through the model: what RViz showed while the graph was watched.

The probe records every ``sensor_msgs/JointState`` it receives; :func:`replay` hands them, in
order, to :class:`~.frames.RobotStatePublisher` (started when the watch started, so its
/tf_static is there), feeds what it publishes to RViz's tf2 buffer, and says how the arm moved:
how many messages went out as transforms, why the others did not, which joint values tf2
refused, where the drawn arm ended and which links RViz could place. ``doctor --ros`` words its
verdicts from this, ``view --ros`` draws the arm from it.
"""

from __future__ import annotations

import math
from collections import Counter
from collections.abc import Iterable
from dataclasses import dataclass, field

from ...core.message import Message
from ...model.robot import Robot
from .frames import JointStateIn, RobotStatePublisher, Tf, placed_links

# why a message went out as nothing: the kind of each reason, for the rules that already explain it
SIZES = "sizes"  # names and positions differ (BK819)
STAMP = "stamp"  # not one publish interval after the last (robot_state_publisher.cpp:334-340)
ZERO = "zero"  # the stamp left at zero: never one interval after zero (BK814)
UNKNOWN = "unknown"  # no name of the message is a moving joint (BK816)
NAN = "nan"  # published, refused by tf2 (TF_NAN_INPUT)


@dataclass(frozen=True)
class Sample:
    """One recorded message: when it came (seconds, this machine's clock), its stamp (ns), its lists."""

    received: float
    stamp_ns: int
    names: tuple[str, ...]
    positions: tuple[float, ...]


@dataclass(frozen=True)
class Replay:
    received: int
    published: int  # messages that sent at least one transform tf2 accepts
    moves: int  # of those, the ones that changed a drawn joint value
    reasons: tuple[tuple[str, Message, int], ...]  # (kind, the first words, count), most common first
    refused: dict[str, tuple[int, float]] = field(default_factory=dict)  # joint -> (count, a value) tf2 refused
    placed: dict[str, Message | None] = field(default_factory=dict)
    positions: dict[str, float] = field(default_factory=dict)
    first_move: float | None = None  # when (received) the first and last transforms went out
    last_move: float | None = None
    last_received: float | None = None
    inferred: bool = True  # the links were placed from the model's transforms, /tf itself not seen

    def reason_of(self, kind: str) -> int:
        return sum(count for k, _, count in self.reasons if k == kind)



def _kind(message: JointStateIn, reason: Message | None, published: tuple[Tf, ...]) -> str:
    if any(tf.nan for tf in published):
        return NAN
    if "ignored" in (reason.id if reason else ""):
        return SIZES
    if not published and message.stamp_ns == 0:
        return ZERO
    if reason is not None and "no name in the message" in reason.id:
        return UNKNOWN
    return STAMP


def replay(robot: Robot, samples: Iterable[Sample], fixed_frame: str, start: float | None = None,
           publish_frequency: float = 20.0, seen: Iterable[Tf] | None = None) -> Replay:
    """The messages through robot_state_publisher, then RViz with ``fixed_frame`` (robot_state_publisher
    started at ``start``, seconds: its /tf_static is stamped then). ``seen``: the transforms received
    on /tf and /tf_static, in order, when they could be read: RViz's buffer is then filled from them,
    not from the model's."""
    samples = list(samples)
    begin = start if start is not None else (samples[0].received if samples else 0.0)
    rsp = RobotStatePublisher(robot, publish_frequency, start_ns=int(begin * 1e9))
    sent: list[Tf] = rsp.static()
    reasons: Counter[tuple[str, str]] = Counter()
    first_words: dict[tuple[str, str], Message] = {}
    refused: dict[str, tuple[int, float]] = {}
    published = moves = 0
    first_move = last_move = None
    drawn: dict[str, float] = {}
    for sample in samples:
        message = JointStateIn(sample.stamp_ns, sample.names, sample.positions, received_ns=int(sample.received * 1e9))
        got = rsp.on_joint_state(message)
        sent += got.published
        for tf in got.published:
            if tf.nan:
                count, _ = refused.get(tf.joint, (0, tf.position))
                refused[tf.joint] = (count + 1, tf.position)
        if got.reason is not None and (got.reason.id != "Moved backwards in time, re-publishing joint transforms!"):
            key = (_kind(message, got.reason, got.published), got.reason.id)
            reasons[key] += 1
            first_words.setdefault(key, got.reason)
        accepted = [tf for tf in got.published if not tf.nan]
        if not accepted:
            continue
        published += 1
        changed = any(not math.isclose(drawn.get(tf.joint, math.nan), tf.position, abs_tol=1e-9) for tf in accepted)
        for tf in accepted:
            drawn[tf.joint] = tf.position
        if changed:
            moves += 1
            first_move = sample.received if first_move is None else first_move
            last_move = sample.received
    ordered = tuple((kind, first_words[(kind, text)], count)
                    for (kind, text), count in reasons.most_common())
    seen = list(seen) if seen is not None else None
    placed = placed_links(robot, fixed_frame, sent if seen is None else seen)
    return Replay(len(samples), published, moves, ordered, refused, placed, rsp.positions(), first_move, last_move,
                  samples[-1].received if samples else None, inferred=seen is None)
