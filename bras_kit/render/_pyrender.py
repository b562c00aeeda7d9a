"""Drawing through pyrender (every patch it needs is listed in :mod:`._compat`), off-screen on EGL (Mesa's software rasteriser needs no GPU and no
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
import threading
import types
import weakref
from collections.abc import Iterable, Iterator
from typing import Any

import numpy as np

from ..core.errors import BackendError
from ..core.message import M
from ..core.wording import quoted
from ._compat import import_pyrender
from ._forward_pass import lean_forward_pass
from ._framebuffers import ColorReader, make_framebuffers
from ._gl import loaded_platform, pyopengl_version
from ._lifetime import delete_renderer, disown_renderer, release_renderer
from ._memo import BoundedMemo
from ._shading import use_flat_shading
from .camera import AMBIENT, Camera
from .scene import Scene

__all__ = ["PyrenderBackend", "choose_platform", "import_pyrender"]


def choose_platform(requested: str) -> str:
    """'egl' or 'osmesa' for ``requested`` ('auto', 'egl', 'osmesa'), with PYOPENGL_PLATFORM set.

    Raises :class:`BackendError` saying why when the platform cannot be used here.
    """
    loaded = loaded_platform()
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
            raise BackendError(M("no OpenGL library found (neither libEGL nor libOSMesa)"),
                               hint=M("on Debian/Ubuntu: apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri libgbm1"))
    else:
        wanted = requested
    if wanted not in ("egl", "osmesa"):
        raise BackendError(M("OpenGL is already set up for {platform} in this process, not for off-screen rendering",
                             platform=wanted),
                           hint=M("set PYOPENGL_PLATFORM=egl before starting Python, or use backend 'software'"))
    if loaded is not None and loaded != wanted:
        raise BackendError(M("OpenGL is already set up for {loaded} in this process, so {wanted} cannot start",
                             loaded=loaded, wanted=wanted),
                           hint=M("start a new process with PYOPENGL_PLATFORM={wanted}, or use backend {loaded}",
                                  wanted=wanted, loaded=loaded))
    if wanted == "osmesa" and pyopengl_version() < (3, 1, 5):
        raise BackendError(M("OSMesa needs PyOpenGL 3.1.5 or later, which pyrender's pin (3.1.0) excludes"),
                           hint=M("use backend egl (Mesa's EGL also works with no GPU) or software"))
    if loaded is None:
        os.environ["PYOPENGL_PLATFORM"] = wanted
    return wanted


EGL_PLATFORM_DEVICE_EXT = 0x313F


SUPERSAMPLED_MAX_SIDE = 8192  # largest side drawn for a supersampled picture (Mesa's limit is 16384)


def _warm_egl() -> threading.Thread:
    """Start EGL on the display pyrender is going to open, in a thread, while pyrender's modules
    load: ``eglInitialize`` loads and sets up Mesa's driver (0.03-0.04 s of C code, the GIL
    released), and a display that is already initialised costs nothing the second time. The
    same display as pyrender's: device number ``EGL_DEVICE_ID`` (0) through
    ``eglGetPlatformDisplayEXT``, or the default display without the device extension. Any
    failure is left for pyrender's own start to report."""

    def start() -> None:
        try:
            egl = ctypes.CDLL(ctypes.util.find_library("EGL") or "libEGL.so.1")
            egl.eglGetProcAddress.restype = ctypes.c_void_p
            egl.eglGetProcAddress.argtypes = [ctypes.c_char_p]
            egl.eglInitialize.argtypes = [ctypes.c_void_p, ctypes.c_void_p, ctypes.c_void_p]
            query_address = egl.eglGetProcAddress(b"eglQueryDevicesEXT")
            display_address = egl.eglGetProcAddress(b"eglGetPlatformDisplayEXT")
            if query_address and display_address:
                query = ctypes.CFUNCTYPE(ctypes.c_uint, ctypes.c_int, ctypes.c_void_p,
                                         ctypes.POINTER(ctypes.c_int))(query_address)
                get_display = ctypes.CFUNCTYPE(ctypes.c_void_p, ctypes.c_uint, ctypes.c_void_p,
                                               ctypes.c_void_p)(display_address)
                index = int(os.environ.get("EGL_DEVICE_ID", "0"))
                devices, count = (ctypes.c_void_p * 16)(), ctypes.c_int()
                if not query(16, devices, ctypes.byref(count)) or not 0 <= index < count.value:
                    return
                display = get_display(EGL_PLATFORM_DEVICE_EXT, devices[index], None)
            else:
                egl.eglGetDisplay.restype = ctypes.c_void_p
                egl.eglGetDisplay.argtypes = [ctypes.c_void_p]
                display = egl.eglGetDisplay(None)
            if display:
                egl.eglInitialize(display, None, None)
        except Exception:  # noqa: BLE001 - only a head start; pyrender's start says what is wrong
            pass

    thread = threading.Thread(target=start, name="bras-kit-egl-start", daemon=True)
    thread.start()
    return thread


def _linear(rgb: tuple[float, ...]) -> np.ndarray:
    """sRGB -> linear, so the shader's final gamma gives the material's colour back."""
    return np.clip(np.asarray(rgb[:3], dtype=float), 0.0, 1.0) ** 2.2


def _grouped(parts) -> dict[tuple[int, bool], dict[tuple[float, ...], list]]:
    """The parts by link and lighting, then by colour."""
    grouped: dict[tuple[int, bool], dict[tuple[float, ...], list]] = {}
    for part in parts:
        grouped.setdefault((part.link, part.unlit), {}).setdefault(tuple(part.color), []).append(part)
    return grouped


def _joined(members) -> tuple[np.ndarray, np.ndarray]:
    """The triangles of parts of one colour in one vertex array (float32) and one index array (uint32)."""
    starts = np.cumsum([0] + [len(p.vertices) for p in members])
    vertices = np.concatenate([p.vertices for p in members]).astype(np.float32)
    faces = np.concatenate([np.asarray(p.faces) + start for p, start in zip(members, starts)])
    return vertices, faces.astype(np.uint32)


def _shared_key(builder: object, unlit: bool, colours) -> tuple[object, ...] | None:
    """What a link's group of parts is made of, by identity, when every array in it is a shared
    read-only one (the placed mesh pieces of :func:`scene.robot_parts`, the same objects for
    the same mesh bytes, scale and origin); None when one may change (triads, targets...).
    ``builder`` (the function making primitives) is part of it: another one makes other meshes."""
    key: list[object] = [builder, unlit]
    for color, members in colours.items():
        if not all(_frozen(p.vertices) and _frozen(p.faces) for p in members):
            return None
        key.append((color, tuple((id(p.vertices), id(p.faces)) for p in members)))
    return tuple(key)


def _frozen(array: object) -> bool:
    return isinstance(array, np.ndarray) and not array.flags.writeable


# pyrender meshes kept with one OffscreenRenderer, by _shared_key, with the arrays their key names
# (so an id in a key is never reused): a robot drawn again (the next learner of a class handing in
# the same meshes, a reloaded file) reuses the mesh objects, already in the renderer's OpenGL
# context, and uploads nothing. A mesh in no scene any more has its buffers freed by pyrender at
# the next picture, and is uploaded again if it comes back.
MESH_MEMORY_BYTES = 128 << 20  # vertex and index arrays of meshes kept with one renderer


def _emissive(pyrender, rgb: tuple[float, ...]):
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
                 antialias: bool = True, supersample: bool = True) -> None:
        warming = _warm_egl() if platform == "egl" and "pyrender" not in sys.modules else None
        pyrender = import_pyrender()
        self.name = platform
        self._key = (platform, camera.width, camera.height, antialias, supersample)
        self._renderer: Any = _POOL.take(self._key)
        if warming is not None:
            warming.join(timeout=5.0)
        if self._renderer is None:
            self._renderer = self._open(pyrender, camera, platform, antialias, supersample)
        # a backend dropped without close() still hands its renderer back (see _RendererPool)
        self._finalizer = weakref.finalize(self, _POOL.give, self._key, self._renderer)
        memo = getattr(self._renderer, "_bras_kit_meshes", None)
        if memo is None:
            memo = self._renderer._bras_kit_meshes = BoundedMemo(MESH_MEMORY_BYTES)
        self._scene = pyrender.Scene(bg_color=[c / 255.0 for c in background] + [1.0],
                                     ambient_light=[AMBIENT] * 3)
        self._nodes: list[tuple[Any, int]] = []
        self._solids: list[Any] = []  # meshes hidden while the TF axes are drawn on top
        self._overlays: list[Any] = []  # TF axes and targets: drawn in a second pass, over the solids
        for (link, unlit), colours in _grouped(scene.parts).items():
            key = _shared_key(type(self)._primitive, unlit, colours)
            kept = memo.get(key) if key is not None else None
            mesh = kept[0] if kept is not None else None
            if mesh is None:
                merged = {color: _joined(members) for color, members in colours.items()}
                mesh = pyrender.Mesh([self._primitive(pyrender, vertices, faces, color, unlit)
                                      for color, (vertices, faces) in merged.items()])
                if key is not None:
                    arrays = [a for members in colours.values() for p in members for a in (p.vertices, p.faces)] \
                        + [a for pair in merged.values() for a in pair]
                    memo.put(key, (mesh, arrays), sum(a.nbytes for a in arrays))
            mesh.is_visible = True
            # named in order: nodes at the same distance are drawn in this order (see _forward_pass._nodes_in_order)
            self._nodes.append((self._scene.add(mesh, name=f"{len(self._nodes):06d}"), link))
            (self._overlays if unlit else self._solids).append(mesh)
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

    @staticmethod
    def _open(pyrender, camera: Camera, platform: str, antialias: bool,
              supersample: bool):
        """An OffscreenRenderer drawing ``camera``'s picture, read back by :class:`._framebuffers.ColorReader`.

        Smooth edges for pictures come from supersampling: the picture is drawn twice as wide
        and high and each 2x2 block averaged. Mesa's llvmpipe resolves a multisampled picture
        with a shader it compiles anew in every process (0.1 s on the first picture; the drawing
        shaders come from its disk cache). Sequences (``supersample`` False) and pictures past
        4096 pixels a side use 4x multisampling: 1.7x the frame rate of supersampling on llvmpipe."""
        scale = 2 if antialias and supersample and 2 * max(camera.width, camera.height) <= SUPERSAMPLED_MAX_SIDE \
            else 1
        samples = 4 if antialias and scale == 1 else 0
        try:
            renderer = pyrender.OffscreenRenderer(camera.width * scale, camera.height * scale)
        except Exception as exc:
            raise BackendError(M("cannot start OpenGL ({platform}): {reason}", platform=platform,
                                 reason=quoted(str(exc).strip())),
                               hint=M("use backend software, or install Mesa's EGL "
                                      "(libegl1 libegl-mesa0 libgl1-mesa-dri libgbm1)")) from None
        inner, platform_ = getattr(renderer, "_renderer", None), getattr(renderer, "_platform", None)
        if inner is None or platform_ is None or getattr(inner, "_main_fb", 1) is not None:
            delete_renderer(renderer)
            raise BackendError(M("this pyrender ({version}) is not the one bras-kit knows how to draw with",
                                 version=getattr(pyrender, "__version__", "?")),
                               hint=M("pip install 'pyrender==0.1.45', or use backend software"))
        platform_.make_current()
        spare = make_framebuffers(inner, camera.width * scale, camera.height * scale, samples, spare=not supersample)
        if scale > 1:
            from OpenGL import GL

            GL.glLineWidth(float(scale))  # the grid's lines keep one pixel once averaged
        reader = ColorReader(camera.width, camera.height, scale, spare)
        inner._read_main_framebuffer = types.MethodType(reader, inner)
        use_flat_shading(pyrender, inner)
        lean_forward_pass(pyrender, inner)
        renderer._bras_kit_reader = reader  # its spare framebuffer is deleted with the renderer (_delete)
        return renderer

    @staticmethod
    def _primitive(pyrender, vertices: np.ndarray, faces: np.ndarray,
                   color: tuple[float, ...], unlit: bool):
        """Indexed triangles of one colour, with no normals: the fragment shader lights each
        facet flat from the derivatives of its position (see :func:`._shading.use_flat_shading`),
        so a vertex shared by several facets is sent once."""
        rgb, alpha = color[:3], float(color[3])
        if unlit:
            material = _emissive(pyrender, rgb)
        else:
            material = pyrender.MetallicRoughnessMaterial(
                baseColorFactor=list(_linear(rgb)) + [alpha], metallicFactor=0.0, roughnessFactor=1.0,
                alphaMode="BLEND" if alpha < 1.0 else "OPAQUE")
        return pyrender.Primitive(positions=vertices, indices=faces, material=material)

    def render(self, transforms: np.ndarray) -> np.ndarray:
        """The picture for link transforms ``transforms`` (L, 4, 4): (H, W, 3) uint8.

        TF axes, when shown, are drawn in a second pass over the finished picture, as RViz's TF
        display does: an axis inside a segment (every joint sits in one) stays visible."""
        self._pose(transforms)
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

    def _pose(self, transforms: np.ndarray) -> None:
        """Move each part's node to its link's transform."""
        for node, link in self._nodes:
            self._scene.set_pose(node, transforms[link])

    def frames(self, transforms: Iterable[np.ndarray]) -> Iterator[np.ndarray]:
        """The pictures for each of ``transforms``; without TF axes, each picture is drawn while
        the one before is read back (see :class:`._framebuffers.ColorReader`)."""
        reader = getattr(self._renderer, "_bras_kit_reader", None)
        if self._overlays or reader is None or not reader.start():
            for each in transforms:
                yield self.render(each)
            return
        try:
            for each in transforms:
                self._pose(each)
                previous, _ = self._renderer.render(self._scene)
                if previous is not None:
                    yield previous
            platform = self._renderer._platform
            platform.make_current()
            last = reader.last()
            platform.make_uncurrent()
            if last is not None:
                yield last
        finally:
            reader.stop()

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
                disown_renderer(renderer)  # does eglTerminate too): this context is gone, open a new one
                return None
        return renderer

    def give(self, key: tuple[object, ...], renderer: object) -> None:
        if os.getpid() != self._pid:
            disown_renderer(renderer)
            return
        if key in self._kept:
            delete_renderer(renderer)
            return
        release_renderer(renderer)
        self._kept[key] = renderer

    def clear(self) -> None:
        kept, self._kept = self._kept, {}
        for renderer in kept.values():
            if os.getpid() == self._pid:
                delete_renderer(renderer)
            else:
                disown_renderer(renderer)


_POOL = _RendererPool()

