"""Curves through waypoints: linear, or the shape-preserving cubic (PCHIP), with exact velocities."""

from __future__ import annotations

from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
else:
    from ..core.lazy_numpy import np

from .core import Evaluate

INTERPOLATIONS = ("linear", "cubic")


def interpolator(times: np.ndarray, values: np.ndarray, interpolation: str) -> Evaluate:
    """Positions and velocities through (times, values); held still outside the waypoints."""
    if len(times) == 1:
        value = float(values[0])
        return lambda t: (np.full(t.shape, value), np.zeros(t.shape))
    slopes = cubic_slopes(times, values) if interpolation == "cubic" else None

    def evaluate(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        t = np.asarray(t, dtype=float)
        index = np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2)
        start, width = times[index], times[index + 1] - times[index]
        u = (t - start) / width
        y0, y1 = values[index], values[index + 1]
        if slopes is None:
            position = (1.0 - u) * y0 + u * y1  # exact at both ends of a segment
            velocity = (y1 - y0) / width
        else:
            position, velocity = hermite(u, width, y0, y1, slopes[index], slopes[index + 1])
        before, after = t < times[0], t > times[-1]
        position = np.where(before, values[0], np.where(after, values[-1], position))
        velocity = np.where(before | after, 0.0, velocity)
        return position, velocity

    return evaluate


def hermite(u: np.ndarray, width: np.ndarray, y0: np.ndarray, y1: np.ndarray,
            s0: np.ndarray, s1: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Cubic Hermite segment: position and time derivative at fraction ``u`` of the segment."""
    u2, u3 = u * u, u * u * u
    position = ((2 * u3 - 3 * u2 + 1) * y0 + (u3 - 2 * u2 + u) * width * s0
                + (-2 * u3 + 3 * u2) * y1 + (u3 - u2) * width * s1)
    velocity = ((6 * u2 - 6 * u) * y0 + (3 * u2 - 4 * u + 1) * width * s0
                + (-6 * u2 + 6 * u) * y1 + (3 * u2 - 2 * u) * width * s1) / width
    return position, velocity


def cubic_slopes(times: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Knot velocities of the shape-preserving cubic (PCHIP, Fritsch-Butland) through the values.

    Zero at the first and last waypoint (start and end at rest) and at every interior waypoint
    where the motion turns back; elsewhere a weighted harmonic mean of the neighbouring slopes.
    The curve is C1 and never overshoots: between two waypoints it stays between their values.
    """
    slopes = np.zeros(len(times))
    if len(times) < 3:
        return slopes
    h = np.diff(times)
    d = np.diff(values) / h
    h0, h1, d0, d1 = h[:-1], h[1:], d[:-1], d[1:]
    w0, w1 = 2 * h1 + h0, h1 + 2 * h0
    same = d0 * d1 > 0
    with np.errstate(all="ignore"):
        mean = (w0 + w1) / (w0 / d0 + w1 / d1)
    slopes[1:-1] = np.where(same, mean, 0.0)
    return slopes


def segment_peaks(times: np.ndarray, values: np.ndarray, interpolation: str) -> np.ndarray:
    """The largest speed within each segment between consecutive waypoints."""
    h = np.diff(times)
    if interpolation != "cubic":
        return np.abs(np.diff(values) / h)
    s = cubic_slopes(times, values)
    y0, y1, s0, s1 = values[:-1], values[1:], s[:-1], s[1:]
    # acceleration is linear in u: a*u + b; the speed peaks at u = -b/a when inside the segment
    a = 12 * y0 + 6 * h * s0 - 12 * y1 + 6 * h * s1
    b = -6 * y0 - 4 * h * s0 + 6 * y1 - 2 * h * s1
    with np.errstate(all="ignore"):
        vertex = np.where(a != 0, -b / a, 0.0)
    vertex = np.clip(np.nan_to_num(vertex), 0.0, 1.0)
    peaks = np.zeros_like(h)
    for u in (np.zeros_like(h), np.ones_like(h), vertex):
        peaks = np.maximum(peaks, np.abs(hermite(u, h, y0, y1, s0, s1)[1]))
    return peaks
