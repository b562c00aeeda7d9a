"""Where the browser's camera starts: on the robot's bounding box, in the part of the page the
control panel leaves free, as the pictures' iso view (the renderer's own camera fitting).

viser's camera is three.js's: a vertical field of view over the whole canvas, the control
panel floating over its right side. The camera is fitted to the free part (as if the picture
were only that wide), then turned sideways by the angle that brings the free part's centre to
the middle of the canvas, so the robot sits left of the panel and not under it.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

FOV_DEGREES = 45.0  # vertical field of view of the viewer's camera (three.js's default 75 bends the robot)
PANEL_PIXELS = 410  # viser's "large" control panel and its margin, on the right of the canvas
MIN_FREE_SHARE = 0.45  # a narrower canvas than that: the panel is folded away, frame the whole width
DEFAULT_CANVAS = (1280, 720)  # the canvas assumed before a browser has said its size
BOTTOM_PIXELS = 0  # a bar along the bottom (the exported page's player) the robot stays above
MARGIN = 1.3  # the box is framed this much larger: room for names, triads and a turn of the view


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
