"""Off-screen OpenGL through pyrender, on EGL (Mesa's software rasteriser needs no GPU and no
display) or OSMesa.

PyOpenGL reads ``PYOPENGL_PLATFORM`` once, when it is first imported, so the platform is
chosen here before anything imports OpenGL, and a later wish for another one in the same
process is refused with a clear message.
"""

from __future__ import annotations

import atexit
import ctypes
import ctypes.util
import os
import sys
import types

import numpy as np

from ..errors import BackendError
from .camera import AMBIENT, Camera
from .scene import Scene

_PLATFORM_CLASSES = {"EGLPlatform": "egl", "OSMesaPlatform": "osmesa"}


def _loaded_platform() -> str | None:
    """The platform PyOpenGL already committed to in this process ('egl', 'osmesa', other), or None."""
    module = sys.modules.get("OpenGL.platform")
    if module is None:
        return None
    platform = getattr(module, "PLATFORM", None)
    return _PLATFORM_CLASSES.get(type(platform).__name__, type(platform).__name__)


def choose_platform(requested: str) -> str:
    """'egl' or 'osmesa' for ``requested`` ('auto', 'egl', 'osmesa'), with PYOPENGL_PLATFORM set.

    Raises :class:`BackendError` saying why when the platform cannot be used here.
    """
    loaded = _loaded_platform()
    if requested == "auto":
        if loaded is not None:
            wanted = loaded
        elif os.environ.get("PYOPENGL_PLATFORM") in ("egl", "osmesa"):
            wanted = os.environ["PYOPENGL_PLATFORM"]
        elif ctypes.util.find_library("EGL"):
            wanted = "egl"
        elif ctypes.util.find_library("OSMesa"):
            wanted = "osmesa"
        else:
            raise BackendError("no OpenGL library found (neither libEGL nor libOSMesa)",
                               hint="on Debian/Ubuntu: apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri libgbm1")
    else:
        wanted = requested
    if wanted not in ("egl", "osmesa"):
        raise BackendError(f"OpenGL is already set up for {wanted} in this process, not for off-screen rendering",
                           hint="set PYOPENGL_PLATFORM=egl before starting Python, or use backend 'software'")
    if loaded is not None and loaded != wanted:
        raise BackendError(f"OpenGL is already set up for {loaded} in this process, so {wanted} cannot start",
                           hint=f"start a new process with PYOPENGL_PLATFORM={wanted}, or use backend {loaded}")
    if wanted == "osmesa" and _pyopengl_version() < (3, 1, 5):
        raise BackendError("OSMesa needs PyOpenGL 3.1.5 or later, which pyrender's pin (3.1.0) excludes",
                           hint="use backend egl (Mesa's EGL also works with no GPU) or software")
    if loaded is None:
        os.environ["PYOPENGL_PLATFORM"] = wanted
    return wanted


def _pyopengl_version() -> tuple[int, ...]:
    try:
        import OpenGL  # the package alone: the platform is chosen by OpenGL.platform, not here
    except ImportError:
        raise BackendError("PyOpenGL is not installed", hint="pip install pyrender (it brings PyOpenGL)") from None
    return tuple(int(p) for p in OpenGL.__version__.split(".")[:3] if p.isdigit())


def import_pyrender():  # type: ignore[no-untyped-def]
    """pyrender, importable under numpy 2 (it still uses ``np.infty``)."""
    if not hasattr(np, "infty"):
        np.infty = np.inf  # type: ignore[attr-defined]
    import pyrender

    return pyrender


def _linear(rgb: tuple[float, ...]) -> np.ndarray:
    """sRGB -> linear, so the shader's final gamma gives the material's colour back."""
    return np.clip(np.asarray(rgb[:3], dtype=float), 0.0, 1.0) ** 2.2


def _make_framebuffers(inner, width: int, height: int, samples: int) -> None:  # type: ignore[no-untyped-def]
    """Create pyrender's main framebuffers ourselves, before its first frame, with ``samples``
    samples per pixel (pyrender always asks 4; Mesa's llvmpipe takes about twice as long then)."""
    from OpenGL import GL

    inner._main_cb, inner._main_db = GL.glGenRenderbuffers(2)
    GL.glBindRenderbuffer(GL.GL_RENDERBUFFER, inner._main_cb)
    GL.glRenderbufferStorage(GL.GL_RENDERBUFFER, GL.GL_RGBA, width, height)
    GL.glBindRenderbuffer(GL.GL_RENDERBUFFER, inner._main_db)
    GL.glRenderbufferStorage(GL.GL_RENDERBUFFER, GL.GL_DEPTH_COMPONENT24, width, height)
    inner._main_fb = GL.glGenFramebuffers(1)
    GL.glBindFramebuffer(GL.GL_DRAW_FRAMEBUFFER, inner._main_fb)
    GL.glFramebufferRenderbuffer(GL.GL_DRAW_FRAMEBUFFER, GL.GL_COLOR_ATTACHMENT0, GL.GL_RENDERBUFFER, inner._main_cb)
    GL.glFramebufferRenderbuffer(GL.GL_DRAW_FRAMEBUFFER, GL.GL_DEPTH_ATTACHMENT, GL.GL_RENDERBUFFER, inner._main_db)
    inner._main_cb_ms, inner._main_db_ms = GL.glGenRenderbuffers(2)
    GL.glBindRenderbuffer(GL.GL_RENDERBUFFER, inner._main_cb_ms)
    GL.glRenderbufferStorageMultisample(GL.GL_RENDERBUFFER, samples, GL.GL_RGBA, width, height)
    GL.glBindRenderbuffer(GL.GL_RENDERBUFFER, inner._main_db_ms)
    GL.glRenderbufferStorageMultisample(GL.GL_RENDERBUFFER, samples, GL.GL_DEPTH_COMPONENT24, width, height)
    inner._main_fb_ms = GL.glGenFramebuffers(1)
    GL.glBindFramebuffer(GL.GL_DRAW_FRAMEBUFFER, inner._main_fb_ms)
    GL.glFramebufferRenderbuffer(GL.GL_DRAW_FRAMEBUFFER, GL.GL_COLOR_ATTACHMENT0, GL.GL_RENDERBUFFER,
                                 inner._main_cb_ms)
    GL.glFramebufferRenderbuffer(GL.GL_DRAW_FRAMEBUFFER, GL.GL_DEPTH_ATTACHMENT, GL.GL_RENDERBUFFER,
                                 inner._main_db_ms)
    inner._main_fb_dims = (width, height)


def _color_reader(width: int, height: int):  # type: ignore[no-untyped-def]
    """Stands in for pyrender's ``Renderer._read_main_framebuffer``: resolves the multisampled
    picture and reads the colour alone, straight into one reused buffer, rows unpadded.
    (pyrender also reads and converts the depth buffer, copies through PyOpenGL's wrapper, and
    fails on widths that are not a multiple of 4.)"""
    from OpenGL import GL
    from OpenGL.raw.GL.VERSION.GL_1_0 import glReadPixels

    buffer = np.empty((height, width, 3), dtype=np.uint8)
    pointer = ctypes.c_void_p(buffer.ctypes.data)

    def read(self, scene, flags):  # type: ignore[no-untyped-def]
        GL.glBindFramebuffer(GL.GL_READ_FRAMEBUFFER, self._main_fb_ms)
        GL.glBindFramebuffer(GL.GL_DRAW_FRAMEBUFFER, self._main_fb)
        GL.glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL.GL_COLOR_BUFFER_BIT, GL.GL_NEAREST)
        GL.glBindFramebuffer(GL.GL_READ_FRAMEBUFFER, self._main_fb)
        GL.glPixelStorei(GL.GL_PACK_ALIGNMENT, 1)
        glReadPixels(0, 0, width, height, GL.GL_RGB, GL.GL_UNSIGNED_BYTE, pointer)
        return buffer[::-1].copy(), None

    return read


def _emissive(pyrender, rgb: tuple[float, ...]):  # type: ignore[no-untyped-def]
    """A material that shows exactly ``rgb`` whatever the lights: black metal (no diffuse light, no
    specular reflection at the shader's floor of 4 %) that glows; the shader squares the glow."""
    return pyrender.MetallicRoughnessMaterial(
        baseColorFactor=[0.0, 0.0, 0.0, 1.0], emissiveFactor=np.sqrt(_linear(rgb)),
        metallicFactor=1.0, roughnessFactor=1.0)


def _look_pose(direction: np.ndarray) -> np.ndarray:
    """A node pose whose -z axis travels along ``-direction`` (pyrender lights shine along -z)."""
    back = direction / np.linalg.norm(direction)
    helper = np.array([0.0, 0.0, 1.0]) if abs(back[2]) < 0.9 else np.array([1.0, 0.0, 0.0])
    right = np.cross(helper, back)
    right /= np.linalg.norm(right)
    pose = np.eye(4)
    pose[:3, :3] = np.column_stack([right, np.cross(back, right), back])
    return pose


class PyrenderBackend:
    """One OffscreenRenderer and one scene; each frame only moves the part nodes."""

    def __init__(self, scene: Scene, camera: Camera, background: tuple[int, int, int], platform: str,
                 antialias: bool = True) -> None:
        pyrender = import_pyrender()
        self.name = platform
        self._scene = pyrender.Scene(bg_color=[c / 255.0 for c in background] + [1.0],
                                     ambient_light=[AMBIENT] * 3)
        self._nodes = []
        for part in scene.parts:
            mesh = pyrender.Mesh([self._primitive(pyrender, part)])
            self._nodes.append((self._scene.add(mesh), part.link))
        if scene.grid is not None:
            material = _emissive(pyrender, scene.grid.color)
            lines = pyrender.Primitive(positions=scene.grid.segments.reshape(-1, 3).astype(np.float32),
                                       mode=pyrender.constants.GLTF.LINES, material=material)
            self._scene.add(pyrender.Mesh([lines]))
        cam = pyrender.PerspectiveCamera(yfov=camera.yfov, znear=camera.znear, zfar=camera.zfar,
                                         aspectRatio=camera.aspect)
        self._scene.add(cam, pose=camera.pose)
        for direction, intensity in camera.world_lights():
            self._scene.add(pyrender.DirectionalLight(color=np.ones(3), intensity=intensity),
                            pose=_look_pose(direction))
        self._key = (platform, camera.width, camera.height, antialias)
        self._renderer = _POOL.take(self._key)
        if self._renderer is not None:
            return
        try:
            self._renderer = pyrender.OffscreenRenderer(camera.width, camera.height)
        except Exception as exc:
            raise BackendError(f"cannot start OpenGL ({platform}): {exc}".rstrip(),
                               hint="use backend software, or install Mesa's EGL "
                               "(libegl1 libegl-mesa0 libgl1-mesa-dri libgbm1)") from None
        inner, platform_ = getattr(self._renderer, "_renderer", None), getattr(self._renderer, "_platform", None)
        if inner is not None and platform_ is not None and getattr(inner, "_main_fb", 1) is None:
            platform_.make_current()
            _make_framebuffers(inner, camera.width, camera.height, 4 if antialias else 0)
            inner._read_main_framebuffer = types.MethodType(_color_reader(camera.width, camera.height), inner)

    @staticmethod
    def _primitive(pyrender, part):  # type: ignore[no-untyped-def]
        triangles = part.vertices[part.faces]  # (F, 3, 3)
        normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
        lengths = np.linalg.norm(normals, axis=1, keepdims=True)
        normals = normals / np.where(lengths > 0, lengths, 1.0)
        rgb, alpha = part.color[:3], float(part.color[3])
        if part.unlit:
            material = _emissive(pyrender, rgb)
        else:
            material = pyrender.MetallicRoughnessMaterial(
                baseColorFactor=list(_linear(rgb)) + [alpha], metallicFactor=0.0, roughnessFactor=1.0,
                alphaMode="BLEND" if alpha < 1.0 else "OPAQUE")
        return pyrender.Primitive(positions=triangles.reshape(-1, 3).astype(np.float32),
                                  normals=np.repeat(normals, 3, axis=0).astype(np.float32),
                                  material=material)

    def render(self, transforms: np.ndarray) -> np.ndarray:
        """The picture for link transforms ``transforms`` (L, 4, 4): (H, W, 3) uint8."""
        for node, link in self._nodes:
            self._scene.set_pose(node, transforms[link])
        color, _ = self._renderer.render(self._scene)
        return np.ascontiguousarray(color)

    def close(self) -> None:
        renderer, self._renderer = getattr(self, "_renderer", None), None
        if renderer is not None:
            _POOL.give(self._key, renderer)


class _RendererPool:
    """Closed OffscreenRenderers kept for the next picture of the same size: opening one (an
    OpenGL context, shaders) and deleting it (pyrender runs a full garbage collection) cost
    more than drawing a small robot. One per size, in this process only (a forked child
    never uses its parent's context), deleted at exit."""

    def __init__(self) -> None:
        self._kept: dict[tuple[object, ...], object] = {}
        self._pid = os.getpid()
        atexit.register(self.clear)

    def take(self, key: tuple[object, ...]) -> object | None:
        if os.getpid() != self._pid:  # a forked child: the parent's contexts are not ours
            self._kept, self._pid = {}, os.getpid()
        renderer = self._kept.pop(key, None)
        if renderer is not None:
            platform = getattr(renderer, "_platform", None)
            if platform is not None:
                platform.make_current()
        return renderer

    def give(self, key: tuple[object, ...], renderer: object) -> None:
        if os.getpid() != self._pid or key in self._kept:
            if os.getpid() == self._pid:
                renderer.delete()  # type: ignore[attr-defined]
            return
        self._kept[key] = renderer

    def clear(self) -> None:
        kept, self._kept = self._kept, {}
        if os.getpid() == self._pid:
            for renderer in kept.values():
                try:
                    renderer.delete()  # type: ignore[attr-defined]
                except Exception:  # noqa: BLE001 - the context may already be gone at exit
                    pass


_POOL = _RendererPool()
