"""What the solvers return: :class:`IKResult`, its elbow solutions and limit excesses."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from ..core.message import M, Message


@dataclass(frozen=True)
class LimitExcess:
    """A joint value a solution needs beyond the joint's limit."""

    joint: str
    value: float
    bound: float
    side: str  # "lower" or "upper"
    unit: str = "rad"

    @property
    def excess(self) -> float:
        return abs(self.value - self.bound)

    def describe(self) -> Message:
        if self.side == "upper":
            return M("{joint} would need {value:.4f} {unit}, {excess:.4f} {unit} past its upper limit {bound:g}",
                     joint=self.joint, value=self.value, unit=self.unit, excess=self.excess, bound=self.bound)
        return M("{joint} would need {value:.4f} {unit}, {excess:.4f} {unit} past its lower limit {bound:g}",
                 joint=self.joint, value=self.value, unit=self.unit, excess=self.excess, bound=self.bound)


@dataclass
class ElbowSolution:
    """One of the two closed-form solutions of a two-joint planar arm."""

    elbow: str  # "up" or "down"
    joints: dict[str, float]
    violations: list[LimitExcess] = field(default_factory=list)

    @property
    def within_limits(self) -> bool:
        return not self.violations


@dataclass
class IKResult:
    """What a solver found.

    ``reachable`` is True when ``joints`` put the tip on the target (within the solver's
    tolerance) and within every limit. Otherwise ``joints`` is the closest pose found within
    the limits, ``reason`` says why (``too_far``, ``too_close``, ``off_plane``, ``limits``,
    ``out_of_reach``) and ``message`` says it in words. ``singular`` marks a reachable target on
    a singular pose (fully stretched or folded arm, tip on the shoulder axis).
    """

    reachable: bool
    joints: dict[str, float]
    tip: np.ndarray
    target: np.ndarray
    residual: float  # m, distance from tip to target
    message: Message  # worded where it is shown (str(message) is the English)
    method: str  # "analytic" or "numeric"
    reason: str = "ok"
    iterations: int = 0
    elbow: str | None = None
    singular: bool = False
    rotation_residual: float | None = None  # rad, when an orientation was asked
    violations: list[LimitExcess] = field(default_factory=list)
    solutions: list[ElbowSolution] = field(default_factory=list)

    def as_dict(self) -> dict[str, object]:
        out: dict[str, object] = {
            "reachable": bool(self.reachable),
            "joints": {k: float(v) for k, v in self.joints.items()},
            "tip": [float(v) for v in self.tip],
            "target": [float(v) for v in self.target],
            "residual": float(self.residual),
            "message": str(self.message),
            "method": self.method,
            "reason": self.reason,
            "singular": bool(self.singular),
            "iterations": int(self.iterations),
        }
        if self.elbow is not None:
            out["elbow"] = self.elbow
        if self.rotation_residual is not None:
            out["rotation_residual"] = float(self.rotation_residual)
        if self.violations:
            out["violations"] = [{"joint": v.joint, "value": v.value, "bound": v.bound, "side": v.side,
                                  "excess": v.excess} for v in self.violations]
        if self.solutions:
            out["solutions"] = [{"elbow": s.elbow, "joints": s.joints, "within_limits": s.within_limits}
                                for s in self.solutions]
        return out
