"""Facts about primitive shapes (box, cylinder, sphere): extents in a link frame, solid inertia.

Meshes have no extents here (their files are not read), so rules that need a shape skip them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
else:
    from ..core.lazy_numpy import np

from ..core.message import number as format_number
from ..kinematics.frames import rpy_to_matrix
from ..model.robot import Geometry, Origin

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

    def moved(self, origin: Origin) -> Bounds:
        """These bounds seen from the parent frame of ``origin`` (a joint's origin), still axis-aligned."""
        half = [(self.hi[i] - self.lo[i]) / 2 for i in range(3)]
        centre = self.centre
        if origin.rpy != (0.0, 0.0, 0.0):
            turn = rotation(origin)
            half = [float(v) for v in np.abs(turn) @ np.array(half)]
            centre = tuple(float(v) for v in turn @ np.array(centre))  # type: ignore[assignment]
        c = [centre[i] + origin.xyz[i] for i in range(3)]
        return Bounds((c[0] - half[0], c[1] - half[1], c[2] - half[2]),
                      (c[0] + half[0], c[1] + half[1], c[2] + half[2]))

    def gap(self, other: Bounds) -> float:
        """Distance between the two boxes (0 when they touch or overlap)."""
        return math.hypot(*(max(0.0, other.lo[i] - self.hi[i], self.lo[i] - other.hi[i]) for i in range(3)))

    def span(self, k: int) -> str:
        """``"z 0..0.6"``: where the shape runs along axis k (numbers as in a URDF)."""
        return f"{AXES[k]} {number(self.lo[k])}..{number(self.hi[k])}"

    def spans(self) -> str:
        return ", ".join(self.span(k) for k in range(3))


def number(value: float) -> str:
    """A number the way a person writes it in a URDF: ``0.6``, ``-1.57``, ``0.0305``, ``0``
    (the one formatter of numbers in text, :func:`bras_kit.core.message.number`)."""
    return format_number(float(value))


def vector(values: tuple[float, ...] | list[float]) -> str:
    return " ".join(number(v) for v in values)


def finite(*values: float | None) -> bool:
    """True when every value is a finite number (parsed values may be None, nan or inf)."""
    try:
        return all(map(math.isfinite, values))  # type: ignore[arg-type]
    except TypeError:  # None
        return False


def half_extents(geometry: Geometry | None) -> tuple[float, float, float] | None:
    """Half sizes of a primitive in its own frame; None for meshes and unreadable or non-positive sizes."""
    if geometry is None:
        return None
    if geometry.kind == "box" and geometry.size is not None and finite(*geometry.size):
        size = geometry.size
        assert size is not None
        if min(size) > 0:
            return (size[0] / 2, size[1] / 2, size[2] / 2)
    elif geometry.kind == "cylinder" and finite(geometry.radius, geometry.length):
        r, length = geometry.radius, geometry.length
        assert r is not None and length is not None
        if r > 0 and length > 0:
            return (r, r, length / 2)
    elif geometry.kind == "sphere" and finite(geometry.radius):
        r = geometry.radius
        assert r is not None
        if r > 0:
            return (r, r, r)
    return None


def rotation(origin: Origin) -> np.ndarray:
    """The origin's rotation; NaN for a non-finite rpy (callers check :func:`finite` first)."""
    if origin.rpy == (0.0, 0.0, 0.0):
        return np.eye(3)
    return rpy_to_matrix(origin.rpy)


def shape_bounds(origin: Origin, geometry: Geometry | None) -> Bounds | None:
    """Axis-aligned bounds of a primitive placed at ``origin`` (exact for quarter-turn rotations)."""
    half = half_extents(geometry)
    if half is None or not finite(*origin.xyz, *origin.rpy):
        return None
    if origin.rpy == (0.0, 0.0, 0.0):  # the common case, without numpy: many links, tiny vectors
        reach = half
    else:
        reach = tuple(float(v) for v in np.abs(rotation(origin)) @ np.array(half))  # type: ignore[assignment]
    x, y, z = origin.xyz
    return Bounds((x - reach[0], y - reach[1], z - reach[2]), (x + reach[0], y + reach[1], z + reach[2]))


def solid_moments(geometry: Geometry, mass: float) -> tuple[float, float, float] | None:
    """Principal moments (ixx, iyy, izz) of a uniform solid about its centre, in its own frame."""
    half = half_extents(geometry)
    if half is None:
        return None
    if geometry.kind == "box":
        x, y, z = (2 * h for h in half)
        return (mass / 12.0 * (y * y + z * z), mass / 12.0 * (x * x + z * z), mass / 12.0 * (x * x + y * y))
    if geometry.kind == "cylinder":
        r, length = half[0], 2 * half[2]
        side = mass / 12.0 * (3 * r * r + length * length)
        return (side, side, mass * r * r / 2.0)
    r = half[0]
    sphere = 2.0 / 5.0 * mass * r * r
    return (sphere, sphere, sphere)
