"""The camera: where it stands for each view, how far it must be to keep every pose in the picture,
and the lights that travel with it.

Conventions are OpenGL's (the camera looks along its -z axis, y up), so the same
:class:`Camera` drives pyrender and the software rasteriser and both give the same picture.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .options import VIEWS, RenderOptions

FILL = 0.86  # the framed points use at most this share of the picture's width and height
AMBIENT = 0.28  # linear ambient light, as a share of the material's colour
# Directional lights fixed to the camera: (direction towards the light in the camera frame, intensity).
# The key light comes from the upper left of the camera, the fill light from the lower right,
# so faces at different angles get different shades and the shape reads clearly.
LIGHTS = (
    ((-0.45, 0.6, 1.0), 2.6),
    ((0.7, -0.3, 0.6), 0.9),
)


@dataclass(frozen=True)
class Camera:
    """A perspective camera: ``pose`` maps camera coordinates to the world."""

    pose: np.ndarray
    yfov: float  # radians
    width: int
    height: int
    znear: float
    zfar: float

    @property
    def aspect(self) -> float:
        return self.width / self.height

    def projection(self) -> np.ndarray:
        """OpenGL's perspective matrix (the one pyrender's PerspectiveCamera builds)."""
        t = math.tan(self.yfov / 2.0)
        n, f = self.znear, self.zfar
        out = np.zeros((4, 4))
        out[0, 0] = 1.0 / (self.aspect * t)
        out[1, 1] = 1.0 / t
        out[2, 2] = (f + n) / (n - f)
        out[2, 3] = 2.0 * f * n / (n - f)
        out[3, 2] = -1.0
        return out

    def view(self) -> np.ndarray:
        """World -> camera transform."""
        return np.linalg.inv(self.pose)

    def world_lights(self) -> list[tuple[np.ndarray, float]]:
        """Each light as (unit direction towards the light in the world, intensity)."""
        out = []
        for direction, intensity in LIGHTS:
            d = self.pose[:3, :3] @ np.asarray(direction, dtype=float)
            out.append((d / np.linalg.norm(d), intensity))
        return out


def view_direction(azimuth: float, elevation: float) -> np.ndarray:
    """Unit vector from the target towards the camera (angles in degrees, azimuth from +x towards +y)."""
    az, el = math.radians(azimuth), math.radians(elevation)
    return np.array([math.cos(el) * math.cos(az), math.cos(el) * math.sin(az), math.sin(el)])


def look_rotation(direction: np.ndarray, azimuth: float) -> np.ndarray:
    """Camera rotation (columns: right, up, back) for a camera at ``direction`` from its target.

    World z is up in the picture; looking straight down or up, the horizontal direction the
    camera faces is up instead, so the top view keeps the front view's x to the right.
    """
    back = direction / np.linalg.norm(direction)
    up = np.array([0.0, 0.0, 1.0])
    if abs(back[2]) > 0.999:
        az = math.radians(azimuth)
        up = -np.sign(back[2]) * np.array([math.cos(az), math.sin(az), 0.0])
    right = np.cross(up, back)
    right /= np.linalg.norm(right)
    true_up = np.cross(back, right)
    return np.column_stack([right, true_up, back])


def camera_angles(options: RenderOptions) -> tuple[float, float]:
    azimuth, elevation = VIEWS[options.view]
    if options.azimuth is not None:
        azimuth = options.azimuth
    if options.elevation is not None:
        elevation = options.elevation
    return azimuth, elevation


def fit_camera(points: np.ndarray, options: RenderOptions) -> Camera:
    """A camera looking from the view's direction that keeps every point in the picture, centred.

    The distance is the smallest at which each point fits inside the field of view (unless
    ``options.distance`` fixes it); the aim is then moved sideways so the points' extent is centred.
    """
    points = np.asarray(points, dtype=float).reshape(-1, 3)
    azimuth, elevation = camera_angles(options)
    rotation = look_rotation(view_direction(azimuth, elevation), azimuth)
    right, up, back = rotation[:, 0], rotation[:, 1], rotation[:, 2]
    yfov = math.radians(options.fov)
    ty = math.tan(yfov / 2.0) * FILL
    tx = ty * options.width / options.height
    low, high = points.min(axis=0), points.max(axis=0)
    target = (low + high) / 2.0
    size = max(float(np.linalg.norm(high - low)), 1e-3)

    def fitting(target: np.ndarray) -> float:  # the nearest distance at which every point is in the picture
        if options.distance is not None:
            return float(options.distance)
        rel = points - target
        x, y, z = rel @ right, rel @ up, rel @ back
        return float(max(np.max(z + np.abs(x) / tx), np.max(z + np.abs(y) / ty), np.max(z) + 0.05 * size))

    for _ in range(6):
        distance = fitting(target)
        rel = points - target
        x, y, z = rel @ right, rel @ up, rel @ back
        depth = np.maximum(distance - z, 1e-6)
        sx, sy = x / depth, y / depth
        shift_x = (sx.max() + sx.min()) / 2.0 * distance
        shift_y = (sy.max() + sy.min()) / 2.0 * distance
        if abs(shift_x) + abs(shift_y) < 1e-6 * size:
            break
        target = target + right * shift_x + up * shift_y
    # the last move of the aim may have pushed points out (a pose seen from above, deep towards the
    # camera, is centred in more than six steps): the distance is worked out for where the aim ended
    distance = fitting(target)
    pose = np.eye(4)
    pose[:3, :3] = rotation
    pose[:3, 3] = target + back * distance
    depth = distance - (points - target) @ back
    znear = max(float(depth.min()) * 0.5, distance * 0.01, 1e-3)
    zfar = max(float(depth.max()), distance) * 20.0 + 10.0 * size
    return Camera(pose, yfov, options.width, options.height, znear, zfar)
