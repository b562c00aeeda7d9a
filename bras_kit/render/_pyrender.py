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
import weakref
from collections.abc import Iterator
from typing import Any

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
    """pyrender, importable under numpy 2 (it still uses ``np.infty``), in a third of its usual time.

    pyrender's ``__init__`` loads trimesh (about 0.5 s with scipy), networkx (0.1 s) and its
    interactive viewer with pyglet and imageio (0.07 s), none of which off-screen drawing of
    ready-made triangles needs. While pyrender loads, stand-ins take their place in
    ``sys.modules`` (see :func:`_stand_ins`); they are taken out right after, so any later
    ``import trimesh`` / ``networkx`` / ``pyrender.viewer`` in the process loads the real module.
    """
    if not hasattr(np, "infty"):
        np.infty = np.inf  # type: ignore[attr-defined]
    if "pyrender" in sys.modules:
        import pyrender

        return pyrender
    stand_ins = _stand_ins()
    for name, module in stand_ins.items():
        sys.modules[name] = module
    try:
        import pyrender
    finally:
        for name, module in stand_ins.items():
            _forget(name, module)
    return pyrender


def _stand_ins() -> dict[str, types.ModuleType]:
    """Light modules pyrender imports in place of trimesh, networkx and its viewer, when they are
    not loaded yet; each hands over to the real module the first time it is really used."""
    import importlib
    import importlib.util

    stand_ins: dict[str, types.ModuleType] = {}
    spec = importlib.util.find_spec("trimesh") if "trimesh" not in sys.modules else None
    if spec is not None and spec.submodule_search_locations:
        # a bare package: ``import trimesh.transformations`` (pyrender.node) loads that one module
        trimesh = types.ModuleType("trimesh")
        trimesh.__path__ = list(spec.submodule_search_locations)
        trimesh.__file__ = spec.origin
        trimesh.__getattr__ = _real("trimesh", trimesh)  # type: ignore[method-assign]
        stand_ins["trimesh"] = trimesh
    if "networkx" not in sys.modules:
        networkx = types.ModuleType("networkx")
        networkx.DiGraph = _ParentGraph  # type: ignore[attr-defined]
        networkx.shortest_path = _path_to  # type: ignore[attr-defined]
        networkx.__getattr__ = _real("networkx", networkx)  # type: ignore[method-assign]
        stand_ins["networkx"] = networkx
    viewer = types.ModuleType("pyrender.viewer")

    class Viewer:
        """pyrender's interactive viewer, loaded (with pyglet) when one is opened."""

        def __new__(cls, *args: object, **kwargs: object) -> Any:
            real = importlib.import_module("pyrender.viewer").Viewer
            if real is cls:
                raise ImportError("pyrender.viewer cannot be loaded")
            return real(*args, **kwargs)

    viewer.Viewer = Viewer  # type: ignore[attr-defined]
    stand_ins["pyrender.viewer"] = viewer
    return stand_ins


def _real(name: str, stand_in: types.ModuleType):  # type: ignore[no-untyped-def]
    """A module ``__getattr__`` giving the real module's attribute, loading it if need be."""
    import importlib

    def getattr_(attribute: str) -> object:
        if attribute.startswith("__"):
            raise AttributeError(attribute)
        _forget(name, stand_in)
        return getattr(importlib.import_module(name), attribute)

    return getattr_


def _forget(name: str, stand_in: types.ModuleType) -> None:
    """Take a stand-in, and the submodules loaded under it, out of ``sys.modules``."""
    if sys.modules.get(name) is stand_in:
        del sys.modules[name]
        for sub in [n for n in sys.modules if n.startswith(name + ".")]:
            del sys.modules[sub]


class _ParentGraph:
    """What pyrender's scene asks of ``networkx.DiGraph``: a tree of nodes, each with an edge
    to its parent, up to ``'world'`` (add_node, add_edge, neighbors, remove_node)."""

    def __init__(self) -> None:
        self._parent: dict[object, object | None] = {}

    def add_node(self, node: object) -> None:
        self._parent.setdefault(node, None)

    def add_edge(self, node: object, parent: object) -> None:
        self.add_node(parent)
        self._parent[node] = parent

    def neighbors(self, node: object) -> Iterator[object]:
        parent = self._parent[node]
        return iter(() if parent is None else (parent,))

    def remove_node(self, node: object) -> None:
        del self._parent[node]
        for child, parent in self._parent.items():
            if parent is node:
                self._parent[child] = None


def _path_to(graph: _ParentGraph, source: object, target: object) -> list[object]:
    """``networkx.shortest_path`` on a :class:`_ParentGraph`: from a node up its parents to ``target``."""
    path = [source]
    while path[-1] != target:
        parent = graph._parent.get(path[-1])
        if parent is None:
            raise ValueError(f"no path from {source!r} to {target!r}")
        path.append(parent)
    return path


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
        self._solids: list[Any] = []  # meshes hidden while the TF axes are drawn on top
        self._overlays: list[Any] = []  # TF axes and targets: drawn in a second pass, over the solids
        for part in scene.parts:
            mesh = pyrender.Mesh([self._primitive(pyrender, part)])
            self._nodes.append((self._scene.add(mesh), part.link))
            (self._overlays if part.unlit else self._solids).append(mesh)
        if scene.grid is not None:
            material = _emissive(pyrender, scene.grid.color)
            lines = pyrender.Primitive(positions=scene.grid.segments.reshape(-1, 3).astype(np.float32),
                                       mode=pyrender.constants.GLTF.LINES, material=material)
            grid = pyrender.Mesh([lines])
            self._scene.add(grid)
            self._solids.append(grid)
        self._background = np.asarray(background, dtype=np.uint8)
        cam = pyrender.PerspectiveCamera(yfov=camera.yfov, znear=camera.znear, zfar=camera.zfar,
                                         aspectRatio=camera.aspect)
        self._scene.add(cam, pose=camera.pose)
        for direction, intensity in camera.world_lights():
            self._scene.add(pyrender.DirectionalLight(color=np.ones(3), intensity=intensity),
                            pose=_look_pose(direction))
        self._key = (platform, camera.width, camera.height, antialias)
        self._renderer: Any = _POOL.take(self._key)
        if self._renderer is None:
            self._renderer = self._open(pyrender, camera, platform, antialias)
        # a backend dropped without close() still hands its renderer back (see _RendererPool)
        self._finalizer = weakref.finalize(self, _POOL.give, self._key, self._renderer)

    @staticmethod
    def _open(pyrender, camera: Camera, platform: str, antialias: bool):  # type: ignore[no-untyped-def]
        try:
            renderer = pyrender.OffscreenRenderer(camera.width, camera.height)
        except Exception as exc:
            raise BackendError(f"cannot start OpenGL ({platform}): {exc}".rstrip(),
                               hint="use backend software, or install Mesa's EGL "
                               "(libegl1 libegl-mesa0 libgl1-mesa-dri libgbm1)") from None
        inner, platform_ = getattr(renderer, "_renderer", None), getattr(renderer, "_platform", None)
        if inner is not None and platform_ is not None and getattr(inner, "_main_fb", 1) is None:
            platform_.make_current()
            _make_framebuffers(inner, camera.width, camera.height, 4 if antialias else 0)
            inner._read_main_framebuffer = types.MethodType(_color_reader(camera.width, camera.height), inner)
        return renderer

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
        """The picture for link transforms ``transforms`` (L, 4, 4): (H, W, 3) uint8.

        TF axes, when shown, are drawn in a second pass over the finished picture, as RViz's TF
        display does: an axis inside a segment (every joint sits in one) stays visible."""
        for node, link in self._nodes:
            self._scene.set_pose(node, transforms[link])
        if not self._overlays:
            color, _ = self._renderer.render(self._scene)
            return np.ascontiguousarray(color)
        for mesh in self._overlays:
            mesh.is_visible = False
        base, _ = self._renderer.render(self._scene)
        base = base.copy()
        for mesh in self._overlays:
            mesh.is_visible = True
        for mesh in self._solids:
            mesh.is_visible = False
        try:
            axes, _ = self._renderer.render(self._scene)
        finally:
            for mesh in self._solids:
                mesh.is_visible = True
        drawn = (axes != self._background).any(axis=2)
        base[drawn] = axes[drawn]
        return base

    def close(self) -> None:
        self._renderer = None
        finalizer = getattr(self, "_finalizer", None)
        if finalizer is not None:
            finalizer()  # gives the renderer back to the pool, once


class _RendererPool:
    """Closed OffscreenRenderers kept for the next picture of the same size: opening one (an
    OpenGL context, shaders) costs more than drawing a small robot. One per size, in this
    process only (a forked child never uses its parent's context), deleted at exit.

    Renderers are deleted here, never by pyrender: pyrender's ``delete`` (also run by its
    ``__del__`` on a renderer nobody closed) ends with ``eglTerminate`` on the EGL display that
    every context of the process shares, which breaks all the other renderers, and with a full
    garbage collection. :meth:`give` keeps the renderer of a backend dropped without ``close``.
    """

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
            try:
                if platform is not None:
                    platform.make_current()
            except Exception:  # noqa: BLE001 - someone else ended the display (MuJoCo's GL context
                _disown(renderer)  # does eglTerminate too): this context is gone, open a new one
                return None
        return renderer

    def give(self, key: tuple[object, ...], renderer: object) -> None:
        if os.getpid() != self._pid:
            _disown(renderer)
            return
        if key in self._kept:
            _delete(renderer)
            return
        _release(renderer)
        self._kept[key] = renderer

    def clear(self) -> None:
        kept, self._kept = self._kept, {}
        for renderer in kept.values():
            if os.getpid() == self._pid:
                _delete(renderer)
            else:
                _disown(renderer)


def _delete(renderer: Any) -> None:
    """Free an OffscreenRenderer's OpenGL objects and its context, leaving the display alone."""
    platform: Any = getattr(renderer, "_platform", None)
    inner: Any = getattr(renderer, "_renderer", None)
    try:
        if platform is not None and inner is not None:
            platform.make_current()
            inner.delete()
        context = getattr(platform, "_egl_context", None)
        if context is not None:
            from OpenGL.EGL import EGL_NO_CONTEXT, EGL_NO_SURFACE, eglDestroyContext, eglMakeCurrent

            eglMakeCurrent(platform._egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT)
            eglDestroyContext(platform._egl_display, context)
            platform._egl_context = None
        elif platform is not None and hasattr(platform, "delete_context"):
            platform.delete_context()  # OSMesa: a context of its own, nothing shared
    except Exception:  # noqa: BLE001 - the context may already be gone at exit
        pass
    _disown(renderer)


def _release(renderer: Any) -> None:
    """Make a kept EGL context current nowhere, so the next renderer may take it in any thread
    (a context current in one thread cannot be made current in another)."""
    platform: Any = getattr(renderer, "_platform", None)
    if getattr(platform, "_egl_context", None) is not None:
        try:
            from OpenGL.EGL import EGL_NO_CONTEXT, EGL_NO_SURFACE, eglMakeCurrent

            eglMakeCurrent(platform._egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT)
        except Exception:  # noqa: BLE001 - the next make_current reports a real problem
            pass


def _disown(renderer: Any) -> None:
    """Leave pyrender's ``__del__`` nothing to free (it would terminate the shared EGL display)."""
    renderer._renderer = None
    renderer._platform = None


_POOL = _RendererPool()
