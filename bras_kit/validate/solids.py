"""Facts about primitive shapes (box, cylinder, sphere): extents in a link frame, solid inertia.

Meshes have no extents here (their files are not read), so rules that need a shape skip them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from ..kinematics import rpy_to_matrix
from ..model import Geometry, Origin

AXES = "xyz"


@dataclass(frozen=True)
class Bounds:
    """An axis-aligned box in a link frame: ``lo[k]..hi[k]`` along axis k (0 x, 1 y, 2 z)."""

    lo: tuple[float, float, float]
    hi: tuple[float, float, float]

    @property
    def lengths(self) -> tuple[float, float, float]:
        return (self.hi[0] - self.lo[0], self.hi[1] - self.lo[1], self.hi[2] - self.lo[2])

    @property
    def centre(self) -> tuple[float, float, float]:
        return ((self.lo[0] + self.hi[0]) / 2, (self.lo[1] + self.hi[1]) / 2, (self.lo[2] + self.hi[2]) / 2)

    def long_axis(self, ratio: float = 2.0) -> int | None:
        """The axis the shape is elongated along (at least ``ratio`` times longer than the others)."""
        lengths = self.lengths
        k = max(range(3), key=lambda i: lengths[i])
        others = [lengths[i] for i in range(3) if i != k]
        return k if lengths[k] >= ratio * max(others) else None

    def span(self, k: int) -> str:
        """``"z 0..0.6"``: where the shape runs along axis k (numbers as in a URDF)."""
        return f"{AXES[k]} {number(self.lo[k])}..{number(self.hi[k])}"

    def spans(self) -> str:
        return ", ".join(self.span(k) for k in range(3))


def number(value: float) -> str:
    """A number the way a person writes it in a URDF: ``0.6``, ``-1.57``, ``0.0305``, ``0``."""
    text = f"{value:.6g}"
    return "0" if text in ("-0", "0") else text


def vector(values: tuple[float, ...] | list[float]) -> str:
    return " ".join(number(v) for v in values)


def _finite(values: tuple[float, ...] | None) -> bool:
    return values is not None and all(isinstance(v, float) and math.isfinite(v) for v in values)


def half_extents(geometry: Geometry | None) -> tuple[float, float, float] | None:
    """Half sizes of a primitive in its own frame; None for meshes and unreadable or non-positive sizes."""
    if geometry is None:
        return None
    if geometry.kind == "box" and _finite(geometry.size):
        size = geometry.size
        assert size is not None
        if min(size) > 0:
            return (size[0] / 2, size[1] / 2, size[2] / 2)
    elif geometry.kind == "cylinder" and _finite((geometry.radius, geometry.length)):  # type: ignore[arg-type]
        r, length = geometry.radius, geometry.length
        assert r is not None and length is not None
        if r > 0 and length > 0:
            return (r, r, length / 2)
    elif geometry.kind == "sphere" and _finite((geometry.radius,)):  # type: ignore[arg-type]
        r = geometry.radius
        assert r is not None
        if r > 0:
            return (r, r, r)
    return None


def rotation(origin: Origin) -> np.ndarray:
    if origin.rpy == (0.0, 0.0, 0.0) or not _finite(origin.rpy):
        return np.eye(3)
    return rpy_to_matrix(origin.rpy)


def shape_bounds(origin: Origin, geometry: Geometry | None) -> Bounds | None:
    """Axis-aligned bounds of a primitive placed at ``origin`` (exact for quarter-turn rotations)."""
    half = half_extents(geometry)
    if half is None or not _finite(origin.xyz):
        return None
    reach = np.abs(rotation(origin)) @ np.array(half)
    centre = np.array(origin.xyz, dtype=float)
    lo, hi = centre - reach, centre + reach
    return Bounds(tuple(float(v) for v in lo), tuple(float(v) for v in hi))  # type: ignore[arg-type]


def solid_inertia(geometry: Geometry, mass: float) -> np.ndarray | None:
    """Inertia tensor of a uniform solid about its centre, in its own frame (kg m^2)."""
    half = half_extents(geometry)
    if half is None:
        return None
    if geometry.kind == "box":
        x, y, z = (2 * h for h in half)
        diagonal = (y * y + z * z, x * x + z * z, x * x + y * y)
        return np.diag([mass / 12.0 * d for d in diagonal])
    if geometry.kind == "cylinder":
        r, length = half[0], 2 * half[2]
        side = mass / 12.0 * (3 * r * r + length * length)
        return np.diag([side, side, mass * r * r / 2.0])
    r = half[0]
    return np.eye(3) * (2.0 / 5.0 * mass * r * r)
