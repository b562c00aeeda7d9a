"""A live run's angles against the robot's limits (``bras-kit run`` beside ``bras-kit launch``):
nothing of the messages is kept, only, per joint and side, the first time past the limit, the
worst value and the count, which make BK649 at Ctrl-C as a batch run makes it from its recording
(:func:`bras_kit.validate.package.run_rules.past_limits_hits`)."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

from ..motion.limits import TOLERANCE, LimitViolation, joint_unit


@dataclass
class _Past:
    first: float
    value: float
    bound: float
    excess: float
    peak: float
    unit: str
    count: int = 0


@dataclass
class LimitWatch:
    robot: Any
    past: dict[tuple[str, str], _Past] = field(default_factory=dict)  # (joint, side) -> so far

    def see(self, names: Sequence[str], positions: Sequence[float], time: float) -> list[LimitViolation]:
        """One JointState at ``time`` (s since the run began); the joints it takes past a limit for
        the first time."""
        first: list[LimitViolation] = []
        for name, value in zip(names, positions):
            joint = self.robot.joint(name) if self.robot is not None else None
            if joint is None or not math.isfinite(float(value)):
                continue  # an unknown joint, a NaN: BK647, BK648 in a batch run
            lower, upper = joint.bounds()
            for side, bound, excess in (("upper", upper, value - upper), ("lower", lower, lower - value)):
                if not math.isfinite(bound) or excess <= TOLERANCE:
                    continue
                key = (name, side)
                seen = self.past.get(key)
                if seen is None:
                    seen = self.past[key] = _Past(time, float(value), float(bound), float(excess), time,
                                                  joint_unit(joint))
                elif excess > seen.excess:
                    seen.value, seen.excess, seen.peak = float(value), float(excess), time
                seen.count += 1
                if seen.count == 1:
                    first.append(self._violation(key, seen))
        return first

    @staticmethod
    def _violation(key: tuple[str, str], p: _Past) -> LimitViolation:
        return LimitViolation(key[0], "position", p.first, p.value, p.bound, p.excess, p.peak, key[1], p.count, p.unit)

    def violations(self) -> list[LimitViolation]:
        """Every joint and side past its limit so far (as motion.check_limits gives them)."""
        return sorted((self._violation(k, p) for k, p in self.past.items()), key=lambda v: (v.time, v.joint))
