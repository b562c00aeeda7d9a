"""Joint position limits as the solvers use them: bounds per dof, angles fitted within them, excesses."""

from __future__ import annotations

import math
from collections.abc import Mapping

import numpy as np

from ..kinematics.frames import TFTree
from ._inputs import _unit_of
from .results import LimitExcess

TWO_PI = 2.0 * math.pi


def _bounds(tree: TFTree) -> tuple[np.ndarray, np.ndarray]:
    pairs = [joint.bounds() for joint in tree.dof_joints()]
    lower = np.array([p[0] for p in pairs], dtype=float)
    upper = np.array([p[1] for p in pairs], dtype=float)
    return lower, upper


def _fit_angle(value: float, lower: float, upper: float, reference: float) -> float:
    """``value`` + 2 pi k: within [lower, upper] and nearest ``reference`` if possible, else least outside."""
    base = math.remainder(value, TWO_PI)
    if not (math.isfinite(lower) and math.isfinite(upper)):
        return base + TWO_PI * round((reference - base) / TWO_PI)
    first = math.ceil((lower - base) / TWO_PI - 1e-12)  # turns that land inside the range
    last = math.floor((upper - base) / TWO_PI + 1e-12)
    if first <= last:
        return base + TWO_PI * min(max(round((reference - base) / TWO_PI), first), last)
    below, above = base + TWO_PI * last, base + TWO_PI * first
    return below if lower - below <= above - upper else above


def _violations(tree: TFTree, values: Mapping[str, float], lower: np.ndarray, upper: np.ndarray,
                tolerance: float = 1e-12) -> list[LimitExcess]:
    out = []
    for name, value in values.items():
        i = tree.dof.index(name)
        if value < lower[i] - tolerance:
            out.append(LimitExcess(name, value, float(lower[i]), "lower", _unit_of(tree, name)))
        elif value > upper[i] + tolerance:
            out.append(LimitExcess(name, value, float(upper[i]), "upper", _unit_of(tree, name)))
    return out
