"""A pure-numpy renderer for machines with no OpenGL at all: z-buffered flat-shaded triangles.

It follows the OpenGL pipeline the pyrender backend uses (same camera matrices, same lights,
back faces culled, sRGB output), so both draw the same silhouettes; it has no antialiasing
and drops triangles that cross the camera's near plane.
"""

from __future__ import annotations

import math

import numpy as np

from .camera import AMBIENT, Camera
from .scene import Scene

# pyrender's diffuse term for a dielectric: (1 - F0) * (1 - F0) / pi per unit of light intensity
_DIFFUSE = 0.96 * 0.96 / math.pi


class SoftwareBackend:
    name = "software"

    def __init__(self, scene: Scene, camera: Camera, background: tuple[int, int, int]) -> None:
        self._parts = scene.parts
        self._camera = camera
        self._background = np.asarray(background, dtype=np.uint8)
        self._matrix = camera.projection() @ camera.view()
        self._lights = camera.world_lights()
        self._grid = scene.grid
        self._base = np.concatenate([np.tile(np.clip(p.color[:3], 0, 1), (len(p.faces), 1)) for p in scene.parts]) \
            if scene.parts else np.zeros((0, 3))
        self._unlit = np.concatenate([np.full(len(p.faces), p.unlit) for p in scene.parts]) \
            if scene.parts else np.zeros(0, dtype=bool)

    def _world_triangles(self, transforms: np.ndarray) -> np.ndarray:
        out = []
        for part in self._parts:
            m = transforms[part.link]
            out.append((part.vertices @ m[:3, :3].T + m[:3, 3])[part.faces])
        return np.concatenate(out) if out else np.zeros((0, 3, 3))

    def _face_colors(self, triangles: np.ndarray) -> np.ndarray:
        """sRGB uint8 colour of each face: ambient plus the camera's lights on the face normal."""
        normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
        lengths = np.linalg.norm(normals, axis=1, keepdims=True)
        normals = normals / np.where(lengths > 0, lengths, 1.0)
        light = np.full(len(triangles), AMBIENT)
        for direction, intensity in self._lights:
            light += intensity * _DIFFUSE * np.clip(normals @ direction, 0.0, None)
        linear = (self._base ** 2.2) * light[:, None]
        linear[self._unlit] = self._base[self._unlit] ** 2.2
        return np.round(np.clip(linear, 0.0, 1.0) ** (1.0 / 2.2) * 255.0).astype(np.uint8)

    def render(self, transforms: np.ndarray) -> np.ndarray:
        width, height = self._camera.width, self._camera.height
        depth = np.full((height, width), np.inf, dtype=np.float64)
        ids = np.full((height, width), -1, dtype=np.int32)
        triangles = self._world_triangles(transforms)
        palette = self._face_colors(triangles)
        if len(triangles):
            self._draw_triangles(triangles, depth, ids)
        grid_id = len(palette)
        if self._grid is not None:
            self._draw_lines(self._grid.segments, depth, ids, grid_id)
        grid_rgb = np.round(np.asarray(self._grid.color if self._grid else (0, 0, 0)) * 255.0).astype(np.uint8)
        colors = np.vstack([palette, grid_rgb[None, :], self._background[None, :]])
        ids[ids < 0] = len(colors) - 1
        return colors[ids]

    def _screen(self, points: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        """World points (..., 3) -> pixel coordinates with NDC depth (..., 3), and clip w (...)."""
        clip = points @ self._matrix[:3, :3].T + self._matrix[:3, 3]
        w = points @ self._matrix[3, :3] + self._matrix[3, 3]
        ndc = clip / w[..., None]
        screen = np.empty_like(ndc)
        screen[..., 0] = (ndc[..., 0] + 1.0) * 0.5 * self._camera.width
        screen[..., 1] = (1.0 - ndc[..., 1]) * 0.5 * self._camera.height
        screen[..., 2] = ndc[..., 2]
        return screen, w

    def _draw_triangles(self, triangles: np.ndarray, depth: np.ndarray, ids: np.ndarray) -> None:
        height, width = depth.shape
        screen, w = self._screen(triangles)
        x, y = screen[..., 0], screen[..., 1]
        # counter-clockwise in NDC is clockwise once y points down: negative area faces the camera
        area = (x[:, 1] - x[:, 0]) * (y[:, 2] - y[:, 0]) - (x[:, 2] - x[:, 0]) * (y[:, 1] - y[:, 0])
        keep = (w > self._camera.znear * 0.999).all(axis=1) & (area < 0)
        keep &= (x.max(axis=1) >= 0) & (x.min(axis=1) <= width) & (y.max(axis=1) >= 0) & (y.min(axis=1) <= height)
        for face in np.flatnonzero(keep):
            (x0, x1, x2), (y0, y1, y2), (z0, z1, z2) = x[face], y[face], screen[face, :, 2]
            left = max(int(math.floor(min(x0, x1, x2) - 0.5)), 0)
            right = min(int(math.ceil(max(x0, x1, x2) - 0.5)), width - 1)
            top = max(int(math.floor(min(y0, y1, y2) - 0.5)), 0)
            bottom = min(int(math.ceil(max(y0, y1, y2) - 0.5)), height - 1)
            if left > right or top > bottom:
                continue
            px = np.arange(left, right + 1) + 0.5
            py = (np.arange(top, bottom + 1) + 0.5)[:, None]
            inv = 1.0 / area[face]
            # barycentric weights of each pixel centre (edge functions over the signed area)
            b0 = ((x1 - px) * (y2 - py) - (x2 - px) * (y1 - py)) * inv
            b1 = ((x2 - px) * (y0 - py) - (x0 - px) * (y2 - py)) * inv
            b2 = 1.0 - b0 - b1
            inside = (b0 >= 0) & (b1 >= 0) & (b2 >= 0)
            if not inside.any():
                continue
            z = b0 * z0 + b1 * z1 + b2 * z2
            window = depth[top:bottom + 1, left:right + 1]
            nearer = inside & (z < window)
            window[nearer] = z[nearer]
            ids[top:bottom + 1, left:right + 1][nearer] = face

    def _draw_lines(self, segments: np.ndarray, depth: np.ndarray, ids: np.ndarray, value: int) -> None:
        """One-pixel lines, depth-tested against the triangles, clipped at the near plane."""
        height, width = depth.shape
        view = self._camera.view()
        cam = segments @ view[:3, :3].T + view[:3, 3]  # (S, 2, 3), visible points have z < -znear
        limit = -self._camera.znear
        a, b = cam[:, 0], cam[:, 1]
        keep = (a[:, 2] < limit) | (b[:, 2] < limit)
        a, b = a[keep].copy(), b[keep].copy()
        for first, second in ((a, b), (b, a)):
            behind = first[:, 2] >= limit
            t = (limit - second[behind, 2]) / (first[behind, 2] - second[behind, 2])
            first[behind] = second[behind] + t[:, None] * (first[behind] - second[behind])
        world_pose = self._camera.pose
        ends = np.stack([a, b], axis=1) @ world_pose[:3, :3].T + world_pose[:3, 3]
        screen, _ = self._screen(ends)
        samples = []
        for (x0, y0, z0), (x1, y1, z1) in screen:
            count = int(min(max(abs(x1 - x0), abs(y1 - y0)), 4 * (width + height))) + 2
            t = np.linspace(0.0, 1.0, count)
            samples.append(np.column_stack([x0 + t * (x1 - x0), y0 + t * (y1 - y0), z0 + t * (z1 - z0)]))
        if not samples:
            return
        points = np.concatenate(samples)
        col, row = np.floor(points[:, 0]).astype(np.int64), np.floor(points[:, 1]).astype(np.int64)
        inside = (col >= 0) & (col < width) & (row >= 0) & (row < height)
        col, row, z = col[inside], row[inside], points[inside, 2]
        visible = z <= depth[row, col] + 1e-6
        ids[row[visible], col[visible]] = value

    def close(self) -> None:
        self._parts = []
