"""Motions as data, and sampling them like recorded /joint_states.

:func:`sample` takes ``k / rate`` for ``k = 0 .. floor(duration * rate)``: 10 s at 20 Hz is 201
samples, both ends included. Velocities are exact derivatives, not finite differences.
"""

from __future__ import annotations

import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np

    from ..model.robot import Robot
else:
    from ..core.lazy_numpy import np

from ..core.errors import ParameterError, UnknownJointError
from ..core.message import M, Message
from ..kinematics.frames import TFTree, movable_joints_hint

DEFAULT_RATE = 20.0  # Hz, like the tutorial's animation node (a 0.05 s timer)
DEFAULT_DURATION = 10.0  # seconds, for motions without a natural end
MAX_VALUES = 20_000_000  # samples x joints kept in memory

Evaluate = Callable[["np.ndarray"], "tuple[np.ndarray, np.ndarray]"]


@dataclass
class JointStates:
    """A sequence of joint states, like the messages recorded on /joint_states.

    ``positions`` and ``velocities`` have shape (len(times), len(names)); names follow
    ``tree.dof``.
    """

    times: np.ndarray
    names: list[str]
    positions: np.ndarray
    velocities: np.ndarray

    def __len__(self) -> int:
        return len(self.times)

    def column(self, joint: str) -> int:
        try:
            return self.names.index(joint)
        except ValueError:
            raise UnknownJointError(M("unknown joint '{name}'", name=joint), joint,
                                    hint=M("joints: {names}", names=", ".join(self.names))) from None

    def config(self, index: int) -> dict[str, float]:
        """The joint values of sample ``index`` by name."""
        return {name: float(v) for name, v in zip(self.names, self.positions[index])}


@dataclass(frozen=True)
class Waypoints:
    """Times and joint values read from a waypoint file (``lines``: where each waypoint is)."""

    times: np.ndarray  # (K,)
    joints: list[str]
    values: np.ndarray  # (K, J)
    interpolation: str = "linear"
    path: str | None = None
    lines: tuple[int | None, ...] = ()

    @property
    def duration(self) -> float:
        return float(self.times[-1])


@dataclass(frozen=True)
class Track:
    """How one joint moves: ``evaluate(t)`` gives its positions and velocities at the times ``t``."""

    joint: str
    evaluate: Evaluate
    source: str | Message  # what drives it, for people: "0.8*sin(t)", "held at 0", "waypoints.csv (cubic)"
    waypoints: Waypoints | None = None


@dataclass
class Motion:
    """Every movable joint's position as a function of time.

    ``duration`` is the natural length (the last waypoint's time) or None for endless motions.
    ``notes`` are messages about the input the motion came from (a recording's gaps, unknown
    joints...), for the command to show as warnings.
    """

    names: list[str]
    tracks: list[Track]
    duration: float | None = None
    label: str = ""
    notes: list[Any] = field(default_factory=list)

    def evaluate(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Positions and velocities, each of shape (len(t), len(names))."""
        times = np.atleast_1d(np.asarray(t, dtype=float))
        positions = np.zeros((times.size, len(self.names)))
        velocities = np.zeros_like(positions)
        for k, track in enumerate(self.tracks):
            positions[:, k], velocities[:, k] = track.evaluate(times)
        return positions, velocities

    def positions(self, t: np.ndarray | float) -> np.ndarray:
        return self.evaluate(t)[0]

    def velocities(self, t: np.ndarray | float) -> np.ndarray:
        return self.evaluate(t)[1]

    def sources(self) -> dict[str, str | Message]:
        return {track.joint: track.source for track in self.tracks}


def check_joint(tree: TFTree, name: str, path: str | None = None, line: int | None = None) -> None:
    """Raise unless ``name`` is a joint a motion can drive (movable, not a mimic)."""
    check_joint_of(tree.robot, tree.dof, name, path, line)


def check_joint_of(robot: Robot, dof: Sequence[str], name: str, path: str | None = None,
                   line: int | None = None) -> None:
    """:func:`check_joint` given the robot and its driven joints (a :class:`TFTree`'s ``dof``)."""
    if name in dof:
        return
    joint = robot.joint(name)
    if joint is None:
        why = M("unknown joint '{name}'", name=name)
    elif joint.mimic is not None:
        why = M("joint '{name}' mimics '{leader}' and follows it: it cannot be driven", name=name,
                leader=joint.mimic.joint)
    else:
        why = M("joint '{name}' is {type} and cannot move", name=name, type=joint.type)
    raise UnknownJointError(why, name, path=path, line=line, hint=movable_joints_hint(dof))


def sample_count(duration: float, rate: float) -> int:
    """Samples at k/rate for k = 0..floor(duration*rate): duration*rate + 1 when that is whole."""
    return int(math.floor(duration * rate + 1e-9)) + 1


def checked_count(duration: float, rate: float, joints: int) -> tuple[int, float]:
    """How many samples :func:`sample` takes of ``joints`` joints over ``duration`` s at ``rate`` Hz,
    and the rate as a float; ParameterError where either is not a time or a rate, or too many."""
    duration, rate = float(duration), float(rate)
    if not math.isfinite(duration) or duration < 0:
        raise ParameterError(M("duration {duration:g} s is not a time", duration=duration),
                             hint=M("give a duration of 0 s or more"))
    if not math.isfinite(rate) or rate <= 0:
        raise ParameterError(M("rate {rate:g} Hz is not a rate", rate=rate), hint=M("give samples per second above 0, e.g. 20"))
    count = sample_count(duration, rate)
    if count * max(joints, 1) > MAX_VALUES:
        raise ParameterError(M("{count} samples of {joints} joints is too many", count=count, joints=joints),
                             hint=M("lower --duration or --rate"))
    return count, rate


def sample(motion: Motion, duration: float | None = None, rate: float = DEFAULT_RATE) -> JointStates:
    """The motion at ``k / rate`` seconds for k = 0 .. floor(duration * rate) (both ends included).

    ``duration`` defaults to the motion's natural duration, else :data:`DEFAULT_DURATION`.
    Raises :class:`ParameterError` when a position is not a finite number (say ``log(t)`` at 0).
    """
    if duration is None:
        duration = motion.duration if motion.duration is not None else DEFAULT_DURATION
    count, rate = checked_count(duration, rate, len(motion.names))
    times = np.arange(count) / rate
    with np.errstate(all="ignore"):
        positions, velocities = motion.evaluate(times)
    bad = ~np.isfinite(positions)
    if bad.any():
        k, j = np.argwhere(bad)[0]
        track = motion.tracks[j]
        raise ParameterError(M("the motion of {joint} ({source}) is not a number at t={time:g} s", joint=track.joint,
                               source=track.source, time=times[k]),
                             hint=M("log, sqrt, asin, acos and division are undefined for some values; "
                                    "keep their arguments in range (e.g. sqrt(abs(...)), log(1 + t))"))
    steep = ~np.isfinite(velocities)
    if steep.any():  # e.g. sqrt(t) at 0: fall back on the slope between neighbouring samples
        slope = np.gradient(positions, times, axis=0) if count > 1 else np.zeros_like(positions)
        velocities = np.where(steep, slope, velocities)
    return JointStates(times, list(motion.names), positions, velocities)


def sample_loop(motion: Motion, duration: float | None = None, fps: float = DEFAULT_RATE) -> JointStates:
    """``round(duration * fps)`` frames at ``k / fps``: an animation loop whose end is the next start.

    Unlike :func:`sample`, the last instant is left out, so a GIF of 9 s at 20 fps has 180 frames.
    """
    if duration is None:
        duration = motion.duration if motion.duration is not None else DEFAULT_DURATION
    count = round(float(duration) * float(fps)) if math.isfinite(duration) and math.isfinite(fps) else 0
    if count < 1:
        raise ParameterError(M("{duration:g} s at {fps:g} fps is less than one frame", duration=duration, fps=fps),
                             hint=M("raise --duration or --fps"))
    return sample(motion, (count - 1) / fps, fps)
