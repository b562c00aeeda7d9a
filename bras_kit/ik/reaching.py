"""Reaching motions: a smooth joint-space move to a solution, slow enough for every velocity limit."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..core.errors import ParameterError
from ..core.message import M
from ..kinematics.frames import TFTree
from ..model.robot import Robot
from ._inputs import _as_tree, _joints_dict, _start_vector, _unit_of
from ._limits import _bounds, _violations
from .results import LimitExcess

QUINTIC_PEAK = 15.0 / 8.0  # peak of d/dtau of 10 tau^3 - 15 tau^4 + 6 tau^5, at tau = 1/2


def _velocity_limits(tree: TFTree) -> np.ndarray:
    """Velocity limit per dof (inf when absent or not positive)."""
    out = []
    for joint in tree.dof_joints():
        v = joint.limit.velocity if joint.limit is not None else None
        out.append(float(v) if v is not None and v > 0 and math.isfinite(v) else math.inf)
    return np.array(out)


def minimum_duration(model: TFTree | Robot, start: np.ndarray, goal: np.ndarray) -> float:
    """Shortest quintic move from start to goal whose peak speed stays within every velocity limit.

    The quintic's peak speed is 15/8 |dq| / T, so T = 15/8 max_i |dq_i| / v_i (at least the
    plain max_i |dq_i| / v_i of a constant-speed move).
    """
    limits = _velocity_limits(_as_tree(model))
    delta = np.abs(np.asarray(goal, dtype=float) - np.asarray(start, dtype=float))
    ratio = np.where(np.isfinite(limits), delta / np.where(np.isfinite(limits), limits, 1.0), 0.0)
    return float(QUINTIC_PEAK * ratio.max(initial=0.0))


@dataclass(frozen=True)
class ReachMotion:
    """A joint-space move with quintic time scaling: zero speed and acceleration at both ends.

    Same shape as :class:`bras_kit.motion.Motion`: ``names``, ``positions(t)``, ``duration``.
    """

    names: tuple[str, ...]
    start: np.ndarray
    goal: np.ndarray
    duration: float

    def _phase(self, t: np.ndarray) -> np.ndarray:
        if self.duration <= 0:
            return np.ones_like(t)
        return np.clip(np.asarray(t, dtype=float) / self.duration, 0.0, 1.0)

    def positions(self, t: np.ndarray | float) -> np.ndarray:
        tau = self._phase(np.atleast_1d(np.asarray(t, dtype=float)))
        s = tau ** 3 * (10.0 - 15.0 * tau + 6.0 * tau ** 2)
        return self.start[None, :] + s[:, None] * (self.goal - self.start)[None, :]

    def velocities(self, t: np.ndarray | float) -> np.ndarray:
        times = np.atleast_1d(np.asarray(t, dtype=float))
        if self.duration <= 0:
            return np.zeros((len(times), len(self.names)))
        tau = self._phase(times)
        inside = (times >= 0) & (times <= self.duration)
        ds = np.where(inside, 30.0 * tau ** 2 * (1.0 - tau) ** 2 / self.duration, 0.0)
        return ds[:, None] * (self.goal - self.start)[None, :]

    def evaluate(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Positions and velocities, as :meth:`bras_kit.motion.Motion.evaluate` (so ``sample`` takes it)."""
        return self.positions(t), self.velocities(t)

    def peak_velocities(self) -> np.ndarray:
        if self.duration <= 0:
            return np.zeros(len(self.names))
        return QUINTIC_PEAK * np.abs(self.goal - self.start) / self.duration

    def times(self, rate: float = 20.0) -> np.ndarray:
        count = max(int(math.ceil(self.duration * rate - 1e-9)), 1) + 1
        return np.linspace(0.0, self.duration, count)


def reach_motion(model: TFTree | Robot, start: Mapping[str, float] | np.ndarray | None,
                 goal: Mapping[str, float] | np.ndarray, duration: float | None = None) -> ReachMotion:
    """The move from ``start`` to ``goal`` (dicts by joint name or dof vectors).

    ``duration`` defaults to :func:`minimum_duration`; a shorter one is refused, naming the
    joint that would be too fast and the shortest duration that works.
    """
    tree = _as_tree(model)
    q0, q1 = _start_vector(tree, start), _start_vector(tree, goal)
    shortest = minimum_duration(tree, q0, q1)
    if duration is None:
        duration = shortest
    elif not math.isfinite(duration) or duration < 0:
        raise ParameterError(M("the duration {duration:g} s is not a positive number", duration=duration))
    elif duration < shortest * (1.0 - 1e-12):
        limits = _velocity_limits(tree)
        speeds = QUINTIC_PEAK * np.abs(q1 - q0) / max(duration, 1e-300)
        i = int(np.argmax(np.where(np.isfinite(limits), speeds / np.where(np.isfinite(limits), limits, 1), 0)))
        raise ParameterError(
            M("a {duration:g} s move is too fast: {joint} would turn at {speed:.3g} {unit}/s, above its velocity "
              "limit {limit:g}", duration=duration, joint=tree.dof[i], speed=speeds[i], unit=_unit_of(tree, tree.dof[i]),
              limit=limits[i]),
            hint=M("give a duration of at least {shortest:g} s, or leave it out",
                   shortest=math.ceil(shortest * 1000) / 1000))
    return ReachMotion(tuple(tree.dof), q0, q1, float(duration))


def motion_violations(model: TFTree | Robot, motion: ReachMotion) -> list[LimitExcess]:
    """Exact limit check of a reach motion: positions lie between start and goal, peak speeds are known."""
    tree = _as_tree(model)
    lower, upper = _bounds(tree)
    out = []
    for point in (motion.start, motion.goal):
        out += _violations(tree, _joints_dict(tree, point), lower, upper, tolerance=1e-9)
    limits = _velocity_limits(tree)
    for i, speed in enumerate(motion.peak_velocities()):
        if speed > limits[i] * (1.0 + 1e-9):
            out.append(LimitExcess(tree.dof[i], float(speed), float(limits[i]), "velocity",
                                   _unit_of(tree, tree.dof[i]) + "/s"))
    return out
