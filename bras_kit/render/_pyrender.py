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
import threading
import types
import weakref
from collections.abc import Iterable, Iterator
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

    pyrender's ``__init__`` loads trimesh (about 0.5 s with scipy), networkx (0.1 s), FreeType
    (0.02 s) and its interactive viewer with pyglet and imageio (0.07 s), none of which
    off-screen drawing of ready-made triangles needs. While pyrender loads, stand-ins take their place in
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
    _keep_uniform_locations(pyrender.shader_program.ShaderProgram)
    return pyrender


def _keep_uniform_locations(program_class) -> None:  # type: ignore[no-untyped-def]
    """pyrender's ``ShaderProgram.set_uniform`` asks OpenGL where each uniform is at every call,
    and sets every light and material again for every primitive (72 calls a frame for the
    tutorial arm, about 1,000 for Talos: a fifth to a third of a frame's time). This one keeps each location per
    program object, as OpenGL guarantees it until the program is linked again (a new program
    id), and skips a value the program already holds (uniforms are the program's own state);
    the values it sets are passed exactly as pyrender passes them."""
    if getattr(program_class, "_bras_kit_locations", False):
        return
    from OpenGL import GL

    original = program_class.set_uniform
    functions = program_class._FUNC_MAP

    def set_uniform(self, name, value, unsigned=False):  # type: ignore[no-untyped-def]
        key = (self._program_id, name)
        state = self.__dict__.setdefault("_bras_kit_uniforms", {})
        if isinstance(value, np.ndarray):
            token: object = (value.dtype.str, value.shape, value.tobytes(), unsigned)
        elif isinstance(value, (float, int)):
            token = (type(value), value, unsigned)
        else:
            token = None
        known = state.get(key)
        if known is not None:
            location, held = known
            if token is not None and held == token:
                return
        else:
            location = GL.glGetUniformLocation(self._program_id, name)
        if location == -1:
            state[key] = (location, token)
            return  # pyrender ignores uniforms the program does not have
        try:
            if isinstance(value, np.ndarray) and value.ndim == 1 and value.dtype == np.float64 and not unsigned:
                functions[(value.shape[0], "f")](location, 1, value.astype(np.float32))
            elif isinstance(value, np.ndarray) and value.ndim == 2:
                functions[(value.shape[0], value.shape[1])](location, 1, GL.GL_TRUE, value)
            elif isinstance(value, float):
                GL.glUniform1f(location, value)
            elif isinstance(value, int) and not isinstance(value, bool) and not unsigned:
                GL.glUniform1i(location, value)
            else:
                original(self, name, value, unsigned)
        except Exception:  # noqa: BLE001 - as pyrender's own set_uniform: a value the shader refuses is skipped
            token = None
        state[key] = (location, token)

    program_class.set_uniform = set_uniform
    program_class._bras_kit_locations = True


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
    if "freetype" not in sys.modules and importlib.util.find_spec("freetype") is not None:
        # pyrender.font loads FreeType (0.02 s) for on-screen text, which off-screen drawing never asks
        freetype = types.ModuleType("freetype")
        freetype.__getattr__ = _real("freetype", freetype)  # type: ignore[method-assign]
        stand_ins["freetype"] = freetype
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


def _make_framebuffers(inner, width: int, height: int, samples: int,  # type: ignore[no-untyped-def]
                       spare: bool = False) -> tuple[int, int, int] | None:
    """Create pyrender's main framebuffers ourselves, before its first frame, with ``samples``
    samples per pixel (pyrender always asks 4; Mesa's llvmpipe takes about twice as long then,
    and resolving them costs 0.1 s on the first picture). With no samples, pyrender draws
    straight into the framebuffer that is read back: no copy between the two. ``spare``: a
    second framebuffer (name, colour, depth) for :class:`_ColorReader`'s streams, returned."""
    from OpenGL import GL

    def framebuffer(samples: int) -> tuple[int, int, int]:
        colour, depth = GL.glGenRenderbuffers(2)
        for buffer, kind in ((colour, GL.GL_RGBA), (depth, GL.GL_DEPTH_COMPONENT24)):
            GL.glBindRenderbuffer(GL.GL_RENDERBUFFER, buffer)
            if samples:
                GL.glRenderbufferStorageMultisample(GL.GL_RENDERBUFFER, samples, kind, width, height)
            else:
                GL.glRenderbufferStorage(GL.GL_RENDERBUFFER, kind, width, height)
        name = GL.glGenFramebuffers(1)
        GL.glBindFramebuffer(GL.GL_DRAW_FRAMEBUFFER, name)
        GL.glFramebufferRenderbuffer(GL.GL_DRAW_FRAMEBUFFER, GL.GL_COLOR_ATTACHMENT0, GL.GL_RENDERBUFFER, colour)
        GL.glFramebufferRenderbuffer(GL.GL_DRAW_FRAMEBUFFER, GL.GL_DEPTH_ATTACHMENT, GL.GL_RENDERBUFFER, depth)
        return int(name), int(colour), int(depth)

    inner._main_fb, inner._main_cb, inner._main_db = framebuffer(0)
    if samples:
        inner._main_fb_ms, inner._main_cb_ms, inner._main_db_ms = framebuffer(samples)
    else:  # pyrender deletes both; OpenGL ignores a name deleted twice
        inner._main_fb_ms, inner._main_cb_ms, inner._main_db_ms = inner._main_fb, inner._main_cb, inner._main_db
    inner._main_fb_dims = (width, height)
    return framebuffer(0) if spare and not samples else None


FLAT_SHADER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "shaders", "flat_mesh.frag")


def use_flat_shading(pyrender, inner) -> None:  # type: ignore[no-untyped-def]
    """Give pyrender's renderer ``inner`` a shader cache whose lit meshes (``mesh.frag``) use
    bras-kit's copy of that shader, where a primitive with no normals is lit flat, facet by
    facet, from the screen derivatives of its position (pyrender's own faces it to the camera).
    Meshes are then sent indexed, each vertex once, instead of three times per facet."""
    base = pyrender.shader_program.ShaderProgramCache

    class FlatShaderCache(base):  # type: ignore[misc, valid-type]
        def get_program(self, vertex_shader, fragment_shader, geometry_shader=None, defines=None):  # type: ignore[no-untyped-def]
            if fragment_shader == "mesh.frag":
                fragment_shader = FLAT_SHADER  # an absolute path: os.path.join keeps it
            return super().get_program(vertex_shader, fragment_shader, geometry_shader, defines)

    inner._program_cache.clear()
    inner._program_cache = FlatShaderCache()


class _ColorReader:
    """Stands in for pyrender's ``Renderer._read_main_framebuffer``: reads the colour alone,
    straight into reused buffers, rows unpadded, as a ``height`` x ``width`` picture. With
    ``scale`` 2 the picture was drawn at twice the size and each 2x2 block is averaged
    (supersampling), read in bands so the read-back never holds the large picture at once.
    (pyrender also reads and converts the depth buffer, copies through PyOpenGL's wrapper, and
    fails on widths that are not a multiple of 4.)

    Streams (with a ``spare`` framebuffer): between :meth:`start` and :meth:`stop`, each frame
    is handed to Mesa's rasteriser threads (``glFlush``) and drawing moves to the other
    framebuffer; the call returns the frame before, whose pixels were drawn while Python
    prepared this one (None for the first), and :meth:`last` reads the final one. The same
    pictures, about 10 % more frames a second on two cores."""

    def __init__(self, width: int, height: int, scale: int = 1, spare: tuple[int, int, int] | None = None) -> None:
        self.width, self.height, self.scale, self.spare = width, height, scale, spare
        self.picture = np.empty((height, width, 3), dtype=np.uint8)
        self.rows = max(1, min(height, (1 << 22) // (width * 3 * scale * scale)))  # output rows per band
        self.band = np.empty((self.rows * scale, width * scale, 3), dtype=np.uint8)
        self.total = np.empty((self.rows, width, 3), dtype=np.uint16)
        self.streaming = False
        self.pending: int | None = None

    def __call__(self, inner, scene, flags):  # type: ignore[no-untyped-def]
        from OpenGL import GL

        if not (self.streaming and self.spare is not None):
            if inner._main_fb_ms != inner._main_fb:  # resolve the samples
                width, height = self.width * self.scale, self.height * self.scale
                GL.glBindFramebuffer(GL.GL_READ_FRAMEBUFFER, inner._main_fb_ms)
                GL.glBindFramebuffer(GL.GL_DRAW_FRAMEBUFFER, inner._main_fb)
                GL.glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL.GL_COLOR_BUFFER_BIT, GL.GL_NEAREST)
            return self.read(inner._main_fb), None
        GL.glFlush()
        drawn = (inner._main_fb, inner._main_cb, inner._main_db)
        inner._main_fb, inner._main_cb, inner._main_db = self.spare
        inner._main_fb_ms, inner._main_cb_ms, inner._main_db_ms = self.spare
        self.spare = drawn
        previous, self.pending = self.pending, drawn[0]
        return (None if previous is None else self.read(previous)), None

    def start(self) -> bool:
        """Start a stream; False when this reader cannot (no spare framebuffer)."""
        self.streaming, self.pending = self.spare is not None, None
        return self.streaming

    def last(self) -> np.ndarray | None:
        """The stream's final picture (the context must be current)."""
        pending, self.pending = self.pending, None
        return None if pending is None else self.read(pending)

    def stop(self) -> None:
        self.streaming, self.pending = False, None

    def read(self, framebuffer: int) -> np.ndarray:
        from OpenGL import GL
        from OpenGL.raw.GL.VERSION.GL_1_0 import glReadPixels

        width, height, scale, rows, picture = self.width, self.height, self.scale, self.rows, self.picture
        GL.glBindFramebuffer(GL.GL_READ_FRAMEBUFFER, framebuffer)
        GL.glPixelStorei(GL.GL_PACK_ALIGNMENT, 1)
        for top in range(0, height, rows):  # OpenGL's row 0 is the bottom one
            count = min(rows, height - top)
            part = self.band[:count * scale]
            glReadPixels(0, top * scale, width * scale, count * scale, GL.GL_RGB, GL.GL_UNSIGNED_BYTE,
                         ctypes.c_void_p(part.ctypes.data))
            if scale == 1:
                picture[height - top - count:height - top] = part[::-1]
                continue
            blocks = part.reshape(count, scale, width, scale, 3)
            sums = self.total[:count]
            np.add(blocks[:, 0, :, 0], blocks[:, 0, :, 1], out=sums, dtype=np.uint16)
            sums += blocks[:, 1, :, 0]
            sums += blocks[:, 1, :, 1]
            sums += 2  # round to nearest
            sums >>= 2
            picture[height - top - count:height - top] = sums[::-1]
        return picture.copy()


def _merged(parts) -> dict[tuple[int, bool], dict[tuple[float, ...], tuple[np.ndarray, np.ndarray]]]:  # type: ignore[no-untyped-def]
    """The parts grouped by link and lighting, then by colour, each group's triangles in one
    vertex array (float32) and one index array (uint32): one scene node per link and one draw
    call per colour, however many visuals and material pieces the link's meshes have."""
    grouped: dict[tuple[int, bool], dict[tuple[float, ...], list]] = {}  # type: ignore[type-arg]
    for part in parts:
        grouped.setdefault((part.link, part.unlit), {}).setdefault(tuple(part.color), []).append(part)
    out: dict[tuple[int, bool], dict[tuple[float, ...], tuple[np.ndarray, np.ndarray]]] = {}
    for key, colours in grouped.items():
        out[key] = {}
        for color, members in colours.items():
            starts = np.cumsum([0] + [len(p.vertices) for p in members])
            vertices = np.concatenate([p.vertices for p in members]).astype(np.float32)
            faces = np.concatenate([np.asarray(p.faces) + start for p, start in zip(members, starts)])
            out[key][color] = (vertices, faces.astype(np.uint32))
    return out


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
                 antialias: bool = True, supersample: bool = True) -> None:
        warming = _warm_egl() if platform == "egl" and "pyrender" not in sys.modules else None
        pyrender = import_pyrender()
        self.name = platform
        self._scene = pyrender.Scene(bg_color=[c / 255.0 for c in background] + [1.0],
                                     ambient_light=[AMBIENT] * 3)
        self._nodes = []
        self._solids: list[Any] = []  # meshes hidden while the TF axes are drawn on top
        self._overlays: list[Any] = []  # TF axes and targets: drawn in a second pass, over the solids
        for (link, unlit), groups in _merged(scene.parts).items():
            mesh = pyrender.Mesh([self._primitive(pyrender, vertices, faces, color, unlit)
                                  for color, (vertices, faces) in groups.items()])
            self._nodes.append((self._scene.add(mesh), link))
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
        self._key = (platform, camera.width, camera.height, antialias, supersample)
        self._renderer: Any = _POOL.take(self._key)
        if warming is not None:
            warming.join(timeout=5.0)
        if self._renderer is None:
            self._renderer = self._open(pyrender, camera, platform, antialias, supersample)
        # a backend dropped without close() still hands its renderer back (see _RendererPool)
        self._finalizer = weakref.finalize(self, _POOL.give, self._key, self._renderer)

    @staticmethod
    def _open(pyrender, camera: Camera, platform: str, antialias: bool,  # type: ignore[no-untyped-def]
              supersample: bool):
        """An OffscreenRenderer drawing ``camera``'s picture, read back by :class:`_ColorReader`.

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
            raise BackendError(f"cannot start OpenGL ({platform}): {exc}".rstrip(),
                               hint="use backend software, or install Mesa's EGL "
                               "(libegl1 libegl-mesa0 libgl1-mesa-dri libgbm1)") from None
        inner, platform_ = getattr(renderer, "_renderer", None), getattr(renderer, "_platform", None)
        if inner is None or platform_ is None or getattr(inner, "_main_fb", 1) is not None:
            _delete(renderer)
            raise BackendError(f"this pyrender ({getattr(pyrender, '__version__', '?')}) is not the one bras-kit "
                               "knows how to draw with", hint="pip install 'pyrender==0.1.45', or use backend software")
        platform_.make_current()
        spare = _make_framebuffers(inner, camera.width * scale, camera.height * scale, samples, spare=not supersample)
        if scale > 1:
            from OpenGL import GL

            GL.glLineWidth(float(scale))  # the grid's lines keep one pixel once averaged
        reader = _ColorReader(camera.width, camera.height, scale, spare)
        inner._read_main_framebuffer = types.MethodType(reader, inner)
        use_flat_shading(pyrender, inner)
        renderer._bras_kit_reader = reader  # its spare framebuffer is deleted with the renderer (_delete)
        return renderer

    @staticmethod
    def _primitive(pyrender, vertices: np.ndarray, faces: np.ndarray,  # type: ignore[no-untyped-def]
                   color: tuple[float, ...], unlit: bool):
        """Indexed triangles of one colour, with no normals: the fragment shader lights each
        facet flat from the derivatives of its position (see :func:`_compat.use_flat_shading`),
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
        the one before is read back (see :class:`_ColorReader`)."""
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
            spare = getattr(getattr(renderer, "_bras_kit_reader", None), "spare", None)
            if spare is not None:
                from OpenGL import GL

                GL.glDeleteFramebuffers(1, [spare[0]])
                GL.glDeleteRenderbuffers(2, [spare[1], spare[2]])
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
    """Leave pyrender's finalizers nothing to do. Three objects have one: the OffscreenRenderer,
    its inner renderer and its platform. Run later by the garbage collector, the inner one would
    delete OpenGL objects by number in whatever context is current then (another renderer's
    framebuffer 1, say), and the platform's would end the EGL display every context of the
    process shares. Both are switched off here, not only unlinked, since either may outlive
    the OffscreenRenderer."""
    inner, platform = getattr(renderer, "_renderer", None), getattr(renderer, "_platform", None)
    if inner is not None:
        inner.delete = _nothing  # its __del__ calls self.delete()
    if platform is not None:
        platform.delete_context = _nothing  # the platform's __del__ calls it: eglTerminate
    renderer._renderer = None
    renderer._platform = None


def _nothing() -> None:
    """Stands in for a pyrender clean-up already done, or not ours to do."""


_POOL = _RendererPool()
