"""Where the browser's camera starts: on the box the robot can sweep (every pose its joints'
limits allow, and every pose of the motion to play), in the part of the page the control panel
leaves free, as the pictures' iso view (the renderer's own camera fitting). Framing the first
pose only lets a learner drag the arm out of view, under the panel.

viser's camera is three.js's: a vertical field of view over the whole canvas, the control
panel floating over its right side. The camera is fitted to the free part (as if the picture
were only that wide), then turned sideways by the angle that brings the free part's centre to
the middle of the canvas, so the robot sits left of the panel and not under it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

FOV_DEGREES = 45.0  # vertical field of view of the viewer's camera (three.js's default 75 bends the robot)
PANEL_PIXELS = 410  # viser's "large" control panel and its margin, on the right of the canvas
MIN_FREE_SHARE = 0.45  # a narrower canvas than that: the panel is folded away, frame the whole width
DEFAULT_CANVAS = (1280, 720)  # the canvas assumed before a browser has said its size
BOTTOM_PIXELS = 0  # a bar along the bottom (the exported page's player) the robot stays above
MARGIN = 1.3  # the box is framed this much larger: room for names, triads and a turn of the view
REACH_SAMPLES = 64  # random poses within the limits, besides each joint at each of its limits
MOTION_SAMPLES = 64  # poses taken along the motion to play
MOTION_SECONDS = 10.0  # the part of an endless motion (the tutorial's sines) looked at
SWEPT_MARGIN = 1.1  # the swept box already holds every pose: a little room for names and triads
FREE_TURN = math.pi  # a joint without limits (continuous) is swept over one full turn


@dataclass(frozen=True)
class CameraPlacement:
    """A camera for viser: ``position`` and ``look_at`` in the world, ``fov`` in radians."""

    position: tuple[float, float, float]
    look_at: tuple[float, float, float]
    fov: float
    near: float
    far: float


def place_camera(points: np.ndarray, width: int = DEFAULT_CANVAS[0], height: int = DEFAULT_CANVAS[1], *,
                 panel: int = PANEL_PIXELS, bottom: int = BOTTOM_PIXELS,
                 fov_degrees: float = FOV_DEGREES, margin: float = MARGIN) -> CameraPlacement:
    """The camera that shows every one of ``points`` (N x 3, metres) in a ``width`` x ``height``
    canvas left of a ``panel`` pixels wide and above a ``bottom`` pixels high bar."""
    from ..render.camera import fit_camera
    from ..render.options import RenderOptions

    width, height = max(int(width), 8), max(int(height), 8)
    free_width = width - panel if width - panel >= MIN_FREE_SHARE * width else width
    free_height = max(height - bottom, 8)
    # fit for the free rectangle with the canvas's focal length: same vertical angle per pixel
    fov = 2.0 * math.atan(math.tan(math.radians(fov_degrees) / 2.0) * free_height / height)
    options = RenderOptions(size=(free_width, free_height), view="iso", fov=math.degrees(fov))
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    centre = (points.min(axis=0) + points.max(axis=0)) / 2.0
    camera = fit_camera(centre + margin * (points - centre), options)
    pose = camera.pose
    right, up, back = pose[:3, 0], pose[:3, 1], pose[:3, 2]
    position = pose[:3, 3]
    forward = -back
    depth = float((centre - position) @ forward)
    depth = max(depth, 1e-3)
    # the free rectangle's centre, in pixels from the canvas's centre, and the turn that puts it there
    focal = (height / 2.0) / math.tan(math.radians(fov_degrees) / 2.0)
    across = math.atan2((width - free_width) / 2.0, focal)
    down = math.atan2(bottom / 2.0, focal)
    look = math.cos(across) * math.cos(down) * forward + math.sin(across) * right - math.sin(down) * up
    look_at = position + depth * look / np.linalg.norm(look)
    size = float(np.ptp(points, axis=0).max()) if len(points) else 1.0
    return CameraPlacement(tuple(float(v) for v in position), tuple(float(v) for v in look_at),  # type: ignore[arg-type]
                           math.radians(fov_degrees), max(camera.znear * 0.2, 1e-3), max(camera.zfar, 100 * size))


def reach_points(model: Any, values: Mapping[str, float] | None = None, motion: Any = None,
                 fixed_frame: int = 0, *, samples: int = REACH_SAMPLES) -> np.ndarray:
    """Points (N x 3) the camera must keep in view: the robot's box in the poses ``values``,
    zero, each joint alone at each of its limits, ``samples`` random poses within the limits
    (a fixed seed: the same framing every time) and poses along ``motion`` (a Motion)."""
    sliders = list(model.sliders)
    configs: list[dict[str, float]] = [dict(values or {}), {}]
    bounds = [(s.joint, *_bounds(s.lower, s.upper)) for s in sliders]
    for joint, lower, upper in bounds:
        configs += [{joint: lower}, {joint: upper}]
    if bounds:
        random = np.random.default_rng(0).uniform(size=(samples, len(bounds)))
        lows = np.array([b[1] for b in bounds])
        highs = np.array([b[2] for b in bounds])
        for row in lows + random * (highs - lows):
            configs.append({b[0]: float(v) for b, v in zip(bounds, row)})
    if motion is not None:  # a Motion: positions(t) over its duration (endless ones: one loop)
        times = np.linspace(0.0, float(motion.duration or MOTION_SECONDS), MOTION_SAMPLES)
        for row in np.atleast_2d(motion.positions(times)):
            configs.append({name: float(v) for name, v in zip(motion.names, row) if math.isfinite(float(v))})
    return np.asarray(model.swept_points(configs, fixed_frame))


def _bounds(lower: float, upper: float) -> tuple[float, float]:
    lower = lower if math.isfinite(lower) else -FREE_TURN
    upper = upper if math.isfinite(upper) else FREE_TURN
    return (lower, upper) if lower <= upper else (upper, lower)
