"""The chain as plain Python floats: tip pose and Jacobian rows for the numeric solver's inner loop."""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np


@dataclass(frozen=True)
class _Kernel:
    """The chain's constants as plain Python floats, for the solver's inner loop.

    On 3x3 matrices numpy spends more time per call than on arithmetic: the unrolled float
    products below run several times faster than the same products as small numpy arrays.
    Rotations are row-major 9-tuples. Before joint k: ``pre_pos[k]``, ``pre_axis[k]`` (the
    joint's axis in the previous moving joint's frame); Rodrigues, premultiplied by the
    constant rotation: pre_rot Rot(a, t) = outer + cos t rest + sin t skew.
    """

    revolute: tuple[bool, ...]
    var: tuple[int, ...]  # variable driving each joint
    gain: tuple[float, ...]
    offset: tuple[float, ...]
    pre_pos: tuple[tuple[float, float, float], ...]
    pre_axis: tuple[tuple[float, float, float], ...]
    pre_rot: tuple[tuple[float, ...], ...]
    outer: tuple[tuple[float, ...], ...]
    rest: tuple[tuple[float, ...], ...]
    skew: tuple[tuple[float, ...], ...]
    end_point: tuple[float, float, float]
    end_rot: tuple[float, ...]
    size: int  # number of variables


def _flat(matrix: np.ndarray) -> tuple[float, ...]:
    return tuple(float(v) for v in np.asarray(matrix).reshape(-1))


def _product(a: Sequence[float], b: Sequence[float]) -> tuple[float, ...]:
    """Row-major 3x3 product a b."""
    a0, a1, a2, a3, a4, a5, a6, a7, a8 = a
    b0, b1, b2, b3, b4, b5, b6, b7, b8 = b
    return (a0 * b0 + a1 * b3 + a2 * b6, a0 * b1 + a1 * b4 + a2 * b7, a0 * b2 + a1 * b5 + a2 * b8,
            a3 * b0 + a4 * b3 + a5 * b6, a3 * b1 + a4 * b4 + a5 * b7, a3 * b2 + a4 * b5 + a5 * b8,
            a6 * b0 + a7 * b3 + a8 * b6, a6 * b1 + a7 * b4 + a8 * b7, a6 * b2 + a7 * b5 + a8 * b8)


def _forward(kernel: _Kernel, x: Sequence[float], with_rotation: bool = False):
    """Tip point, tip rotation (9-tuple, or None), joint origins and world axes for variables x."""
    r: Sequence[float] = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
    px = py = pz = 0.0
    origins, axes = [], []
    for k, revolute in enumerate(kernel.revolute):
        value = x[kernel.var[k]] * kernel.gain[k] + kernel.offset[k]
        r0, r1, r2, r3, r4, r5, r6, r7, r8 = r
        bx, by, bz = kernel.pre_pos[k]
        px, py, pz = px + r0 * bx + r1 * by + r2 * bz, py + r3 * bx + r4 * by + r5 * bz, pz + r6 * bx + r7 * by + r8 * bz
        ax, ay, az = kernel.pre_axis[k]
        wx, wy, wz = r0 * ax + r1 * ay + r2 * az, r3 * ax + r4 * ay + r5 * az, r6 * ax + r7 * ay + r8 * az
        if revolute:
            c, s = math.cos(value), math.sin(value)
            local = [o + c * e + s * w for o, e, w in zip(kernel.outer[k], kernel.rest[k], kernel.skew[k])]
        else:
            local = kernel.pre_rot[k]  # type: ignore[assignment]
            px, py, pz = px + value * wx, py + value * wy, pz + value * wz
        r = _product(r, local)
        origins.append((px, py, pz))
        axes.append((wx, wy, wz))
    r0, r1, r2, r3, r4, r5, r6, r7, r8 = r
    ex, ey, ez = kernel.end_point
    tip = (px + r0 * ex + r1 * ey + r2 * ez, py + r3 * ex + r4 * ey + r5 * ez, pz + r6 * ex + r7 * ey + r8 * ez)
    return tip, (_product(r, kernel.end_rot) if with_rotation else None), origins, axes


def _jacobian_rows(kernel: _Kernel, tip, origins, axes, orientation: bool) -> list[list[float]]:
    """Geometric Jacobian as rows (3 or 6) of ``kernel.size`` columns, world frame."""
    rows = [[0.0] * kernel.size for _ in range(6 if orientation else 3)]
    tx, ty, tz = tip
    for k, revolute in enumerate(kernel.revolute):
        column, g = kernel.var[k], kernel.gain[k]
        ax, ay, az = axes[k]
        if revolute:
            ox, oy, oz = origins[k]
            dx, dy, dz = tx - ox, ty - oy, tz - oz
            rows[0][column] += g * (ay * dz - az * dy)
            rows[1][column] += g * (az * dx - ax * dz)
            rows[2][column] += g * (ax * dy - ay * dx)
            if orientation:
                rows[3][column] += g * ax
                rows[4][column] += g * ay
                rows[5][column] += g * az
        else:
            rows[0][column] += g * ax
            rows[1][column] += g * ay
            rows[2][column] += g * az
    return rows
