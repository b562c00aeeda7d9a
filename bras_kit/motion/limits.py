"""Joint limits over a motion: positions past lower/upper, speeds past the velocity limit, clamping.

The tutorial's pitfall "les articulations dépassent", found before anything moves.
"""

from __future__ import annotations

import math
from dataclasses import dataclass, replace
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
else:
    from ..core.lazy_numpy import np

from ..core.message import M, Message, Mn
from ..model.robot import Joint, Robot
from .core import JointStates

TOLERANCE = 1e-9  # how far past a limit still counts as on it (rounding)


@dataclass(frozen=True)
class LimitViolation:
    """A joint past a limit: first at ``time``; worst ``value`` at ``peak_time``, ``excess`` beyond ``bound``.

    ``kind`` is "position" (``side`` "upper" or "lower") or "velocity" (``bound`` is the speed
    limit, ``value`` the signed velocity). ``samples`` counts the samples past the limit.
    """

    joint: str
    kind: str
    time: float
    value: float
    bound: float
    excess: float
    peak_time: float = 0.0
    side: str = "upper"
    samples: int = 1
    unit: str = "rad"


def joint_unit(joint: Joint | None) -> str:
    """"m" for prismatic joints, "rad" for the others."""
    return "m" if joint is not None and joint.type == "prismatic" else "rad"


def speed_limit(joint: Joint | None) -> float | None:
    """The joint's velocity limit, or None when it has no positive one."""
    if joint is None or joint.limit is None or not joint.limit.velocity or joint.limit.velocity <= 0:
        return None
    return float(joint.limit.velocity)


def value_in_degrees(joint: Joint | None, value: float) -> bool:
    """A revolute joint's value past its limits that fits them once read as degrees (``coude=90``):
    the learner surely typed degrees. Radians past two turns, or whole numbers of 10 or more."""
    if joint is None or joint.type != "revolute" or joint.limit is None:
        return False
    lower, upper = joint.bounds()
    if lower <= value <= upper or abs(value) > 360:
        return False
    looks = abs(value) > 2 * math.pi or (abs(value) >= 10 and float(value).is_integer())
    return looks and lower <= math.radians(value) <= upper


def check_limits(robot: Robot, states: JointStates, tolerance: float = TOLERANCE) -> list[LimitViolation]:
    """Positions past lower/upper and speeds past the velocity limit, per joint.

    For each joint, at most one violation per kind and side: ``time`` is the first sample past
    the limit, ``value``/``peak_time``/``excess`` the worst one.
    """
    out = []
    for k, name in enumerate(states.names):
        joint = robot.joint(name)
        if joint is None:
            continue
        lower, upper = joint.bounds()
        unit = joint_unit(joint)
        position = states.positions[:, k]
        for side, bound, past in (("upper", upper, position - upper), ("lower", lower, lower - position)):
            if math.isfinite(bound):
                violation = _violation(states.times, past, position, name, "position", bound, side, unit, tolerance)
                if violation:
                    out.append(violation)
        limit = speed_limit(joint)
        if limit is not None:
            velocity = states.velocities[:, k]
            violation = _violation(states.times, np.abs(velocity) - limit, velocity, name, "velocity",
                                   limit, "speed", unit, tolerance)
            if violation:
                out.append(violation)
    return out


def _violation(times: np.ndarray, past: np.ndarray, values: np.ndarray, joint: str, kind: str,
               bound: float, side: str, unit: str, tolerance: float) -> LimitViolation | None:
    mask = past > tolerance
    if not mask.any():
        return None
    first, worst = int(np.argmax(mask)), int(np.argmax(past))
    return LimitViolation(joint, kind, float(times[first]), float(values[worst]), float(bound),
                          float(past[worst]), float(times[worst]), side, int(mask.sum()), unit)


def describe_violation(violation: LimitViolation) -> Message:
    """One line for people, e.g. "coude goes past its upper limit 2 by 0.5 rad at t=1.55 s (...)"."""
    v = violation
    span = Mn("first at t={time:.4g} s, {n} sample", "first at t={time:.4g} s, {n} samples", v.samples, time=v.time)
    if v.kind == "velocity":
        return M("{joint} moves at {speed:.4g} {unit}/s at t={peak:.4g} s, "
                 "{excess:.3g} {unit}/s over its velocity limit {bound:g} {unit}/s ({span})",
                 joint=v.joint, speed=abs(v.value), unit=v.unit, peak=v.peak_time, excess=v.excess, bound=v.bound,
                 span=span)
    if v.side == "upper":
        return M("{joint} goes past its upper limit {bound:g} by {excess:.3g} {unit} at t={peak:.4g} s ({span})",
                 joint=v.joint, bound=v.bound, excess=v.excess, unit=v.unit, peak=v.peak_time, span=span)
    return M("{joint} goes past its lower limit {bound:g} by {excess:.3g} {unit} at t={peak:.4g} s ({span})",
             joint=v.joint, bound=v.bound, excess=v.excess, unit=v.unit, peak=v.peak_time, span=span)


def clamp(robot: Robot, states: JointStates) -> JointStates:
    """Positions held inside each joint's limits; where a position was moved, its velocity is 0."""
    positions = states.positions.copy()
    velocities = states.velocities.copy()
    for k, name in enumerate(states.names):
        joint = robot.joint(name)
        if joint is None:
            continue
        lower, upper = joint.bounds()
        outside = (positions[:, k] < lower) | (positions[:, k] > upper)
        positions[:, k] = np.clip(positions[:, k], lower, upper)
        velocities[outside, k] = 0.0
    return replace(states, positions=positions, velocities=velocities)
