"""Motions as data, and sampling them like recorded /joint_states.

:func:`sample` takes ``k / rate`` for ``k = 0 .. floor(duration * rate)``: 10 s at 20 Hz is 201
samples, both ends included. Velocities are exact derivatives, not finite differences.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ..errors import ParameterError, UnknownJointError
from ..kinematics import TFTree

DEFAULT_RATE = 20.0  # Hz, like the tutorial's animation node (a 0.05 s timer)
DEFAULT_DURATION = 10.0  # seconds, for motions without a natural end
MAX_VALUES = 20_000_000  # samples x joints kept in memory

Evaluate = Callable[[np.ndarray], "tuple[np.ndarray, np.ndarray]"]


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
            raise UnknownJointError(f"unknown joint '{joint}'", joint, hint="joints: " + ", ".join(self.names)) from None

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
    source: str  # what drives it, for people: "0.8*sin(t)", "held at 0", "waypoints.csv (cubic)"
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

    def sources(self) -> dict[str, str]:
        return {track.joint: track.source for track in self.tracks}


def check_joint(tree: TFTree, name: str, path: str | None = None, line: int | None = None) -> None:
    """Raise unless ``name`` is a joint a motion can drive (movable, not a mimic)."""
    if name in tree.dof:
        return
    joint = tree.robot.joint(name)
    if joint is None:
        why = f"unknown joint '{name}'"
    elif joint.mimic is not None:
        why = f"joint '{name}' mimics '{joint.mimic.joint}' and follows it: it cannot be driven"
    else:
        why = f"joint '{name}' is {joint.type} and cannot move"
    raise UnknownJointError(why, name, path=path, line=line, hint="movable joints: " + (", ".join(tree.dof) or "none"))


def sample_count(duration: float, rate: float) -> int:
    """Samples at k/rate for k = 0..floor(duration*rate): duration*rate + 1 when that is whole."""
    return int(math.floor(duration * rate + 1e-9)) + 1


def sample(motion: Motion, duration: float | None = None, rate: float = DEFAULT_RATE) -> JointStates:
    """The motion at ``k / rate`` seconds for k = 0 .. floor(duration * rate) (both ends included).

    ``duration`` defaults to the motion's natural duration, else :data:`DEFAULT_DURATION`.
    Raises :class:`ParameterError` when a position is not a finite number (say ``log(t)`` at 0).
    """
    if duration is None:
        duration = motion.duration if motion.duration is not None else DEFAULT_DURATION
    duration, rate = float(duration), float(rate)
    if not math.isfinite(duration) or duration < 0:
        raise ParameterError(f"duration {duration:g} s is not a time", hint="give a duration of 0 s or more")
    if not math.isfinite(rate) or rate <= 0:
        raise ParameterError(f"rate {rate:g} Hz is not a rate", hint="give samples per second above 0, e.g. 20")
    count = sample_count(duration, rate)
    if count * max(len(motion.names), 1) > MAX_VALUES:
        raise ParameterError(f"{count} samples of {len(motion.names)} joints is too many",
                             hint="lower --duration or --rate")
    times = np.arange(count) / rate
    with np.errstate(all="ignore"):
        positions, velocities = motion.evaluate(times)
    bad = ~np.isfinite(positions)
    if bad.any():
        k, j = np.argwhere(bad)[0]
        track = motion.tracks[j]
        raise ParameterError(f"the motion of {track.joint} ({track.source}) is not a number at t={times[k]:g} s",
                             hint="log, sqrt, asin, acos and division are undefined for some values; "
                                  "keep their arguments in range (e.g. sqrt(abs(...)), log(1 + t))")
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
        raise ParameterError(f"{duration:g} s at {fps:g} fps is less than one frame",
                             hint="raise --duration or --fps")
    return sample(motion, (count - 1) / fps, fps)
