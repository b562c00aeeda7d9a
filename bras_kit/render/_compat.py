"""Every patch bras-kit applies to pyrender 0.1.45 and PyOpenGL 3.1.0, the exact versions pinned
in pyproject.toml, kept here and nowhere else; the drawing itself is in :mod:`._pyrender`.

Each patch leans on a detail of those versions (a private attribute, a method's behaviour, a
shader's text). ``tests/test_render_compat.py`` holds one test per patch that fails, naming
the patch, when the installed pyrender or PyOpenGL no longer has what the patch relies on:

* :func:`import_pyrender` - stand-in modules for trimesh, networkx, freetype and pyrender's
  viewer while pyrender loads, and ``np.infty`` under numpy 2;
* :func:`_keep_uniform_locations` - ``ShaderProgram.set_uniform`` keeps uniform locations
  and skips values already set;
* :func:`_make_framebuffers` / :class:`_ColorReader` - pyrender's main framebuffers made by
  us, and ``Renderer._read_main_framebuffer`` replaced by a colour-only read-back;
* :func:`use_flat_shading` - ``Renderer._program_cache`` answering ``mesh.frag`` for
  primitives without normals with bras-kit's lean shader (``shaders/flat_mesh.frag``, derived
  from pyrender's, lit flat from screen derivatives);
* :func:`draw_front_to_back` - ``Renderer._sorted_mesh_nodes`` draws opaque nodes nearest
  first (pyrender draws them farthest first, so every hidden facet is shaded);
* :func:`lean_forward_pass` - ``Renderer._forward_pass`` choosing programs, camera and lights
  once a frame instead of once a primitive, the same calls and pixels otherwise;
* :func:`_delete` / :func:`_release` / :func:`_disown` - renderers freed without pyrender's
  finalizers (which end the EGL display every context shares);
* :func:`register_byref_type` - the ``ctypes.byref`` argument type under the name Python 3.12
  gives it (``_ctypes.CArgObject``; PyOpenGL 3.1.0 knows it only as ``builtins.CArgObject``, so
  every call that passes an output argument by reference, ``glGenTextures`` among them, failed);
* :func:`loaded_platform` - which platform ``OpenGL.platform`` committed to.
"""

from __future__ import annotations

import ctypes
import os
import sys
import types
from collections.abc import Iterator
from typing import Any

import numpy as np

from ..core import backends

_PLATFORM_CLASSES = {"EGLPlatform": "egl", "OSMesaPlatform": "osmesa"}


def loaded_platform() -> str | None:
    """The platform PyOpenGL already committed to in this process ('egl', 'osmesa', other), or None."""
    module = sys.modules.get("OpenGL.platform")
    if module is None:
        return None
    platform = getattr(module, "PLATFORM", None)
    return _PLATFORM_CLASSES.get(type(platform).__name__, type(platform).__name__)


def pyopengl_version() -> tuple[int, ...]:
    OpenGL = backends.opengl()  # noqa: N806  (the package alone: the platform is chosen by OpenGL.platform)
    return tuple(int(p) for p in OpenGL.__version__.split(".")[:3] if p.isdigit())


def register_byref_type() -> None:
    """Make PyOpenGL 3.1.0 find its handler for ``ctypes.byref(...)`` arguments on every Python.

    PyOpenGL picks an array handler by the argument type's ``module.name``. 3.1.0 registers
    ``ctypes.byref``'s type as ``builtins.CArgObject`` (``OpenGL/__init__.py``, the
    ``ctypesparameter`` FormatHandler), which it is up to Python 3.11; Python 3.12 moved it to
    ``_ctypes.CArgObject``, and ``glGenTextures(1)`` (any textured primitive) failed with "No
    array-type handler for type _ctypes.type". PyOpenGL 3.1.7 added that name to the same list;
    this adds it to 3.1.0's (pyrender pins 3.1.0), on every Python alike.
    """
    from OpenGL import plugins

    byref_type = type(ctypes.byref(ctypes.c_int()))
    name = f"{byref_type.__module__}.{byref_type.__name__}"
    handler = plugins.FormatHandler.by_name("ctypesparameter")
    if handler is None or handler.check is None:
        raise RuntimeError("PyOpenGL no longer registers a 'ctypesparameter' array handler")
    if name not in handler.check:
        handler.check.append(name)


def import_pyrender():
    """pyrender, importable under numpy 2 (it still uses ``np.infty``), in a third of its usual time.

    pyrender's ``__init__`` loads trimesh (about 0.5 s with scipy), networkx (0.1 s), FreeType
    (0.02 s) and its interactive viewer with pyglet and imageio (0.07 s), none of which
    off-screen drawing of ready-made triangles needs. While pyrender loads, stand-ins take their place in
    ``sys.modules`` (see :func:`_stand_ins`); they are taken out right after, so any later
    ``import trimesh`` / ``networkx`` / ``pyrender.viewer`` in the process loads the real module.
    """
    if not hasattr(np, "infty"):
        np.infty = np.inf
    if "pyrender" in sys.modules:
        return backends.pyrender()
    stand_ins = _stand_ins()
    for name, module in stand_ins.items():
        sys.modules[name] = module
    try:
        pyrender = backends.pyrender()
    finally:
        for name, module in stand_ins.items():
            _forget(name, module)
    register_byref_type()
    _keep_uniform_locations(pyrender.shader_program.ShaderProgram)
    draw_front_to_back(pyrender.renderer.Renderer)
    return pyrender


def _keep_uniform_locations(program_class) -> None:
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

    def set_uniform(self, name, value, unsigned=False):
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


def _real(name: str, stand_in: types.ModuleType):
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


def make_framebuffers(inner, width: int, height: int, samples: int,
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
# pyrender's shaders/mesh.frag that flat_mesh.frag was derived from (formulas and uniform names)
PYRENDER_MESH_FRAG_SHA256 = "b00bcadffa76bcc4645e10b13d550fb4735485131ae4178532a104821618fc38"
_NOT_FLAT = ("NORMAL_LOC", "TANGENT_LOC", "TEXCOORD_0_LOC", "TEXCOORD_1_LOC", "COLOR_0_LOC")


def use_flat_shading(pyrender, inner) -> None:
    """Give pyrender's renderer ``inner`` a shader cache that answers ``mesh.frag``, for a
    metallic-roughness primitive with no normals, textures, colours or shadows, with bras-kit's
    ``shaders/flat_mesh.frag``: pyrender's formulas for directional lights alone, each facet lit
    flat from the screen derivatives of its position (pyrender's own would face every pixel to
    the camera). Meshes are then sent indexed, each vertex once instead of three times per
    facet, and the lean shader takes about a third less time per pixel on Mesa's llvmpipe.
    Anything else keeps pyrender's shader."""
    base = pyrender.shader_program.ShaderProgramCache

    class FlatShaderCache(base):  # type: ignore[misc, valid-type]
        def get_program(self, vertex_shader, fragment_shader, geometry_shader=None, defines=None):
            given = defines or {}
            if fragment_shader == "mesh.frag" and given.get("USE_METALLIC_MATERIAL") \
                    and not any(k in _NOT_FLAT or k.startswith("HAS_") or k.endswith("_SHADOWS") for k in given):
                fragment_shader = FLAT_SHADER  # an absolute path: os.path.join keeps it
            return super().get_program(vertex_shader, fragment_shader, geometry_shader, defines)

    inner._program_cache.clear()
    inner._program_cache = FlatShaderCache()


class ColorReader:
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

    def __call__(self, inner, scene, flags):
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


def delete_renderer(renderer: Any) -> None:
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
    disown_renderer(renderer)


def release_renderer(renderer: Any) -> None:
    """Make a kept EGL context current nowhere, so the next renderer may take it in any thread
    (a context current in one thread cannot be made current in another)."""
    platform: Any = getattr(renderer, "_platform", None)
    if getattr(platform, "_egl_context", None) is not None:
        try:
            from OpenGL.EGL import EGL_NO_CONTEXT, EGL_NO_SURFACE, eglMakeCurrent

            eglMakeCurrent(platform._egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT)
        except Exception:  # noqa: BLE001 - the next make_current reports a real problem
            pass


def disown_renderer(renderer: Any) -> None:
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


def draw_front_to_back(renderer_class) -> None:
    """pyrender sorts opaque mesh nodes farthest first (``Renderer._sorted_mesh_nodes``), the
    worst order for the depth test: every facet behind another is shaded, then painted over.
    Nearest first, Mesa's rasteriser skips the shading of what is already hidden (a fifth of
    the time of a frame of Talos on llvmpipe). Transparent nodes keep pyrender's order, farthest
    first, as blending needs; the pixels are the same."""
    if getattr(renderer_class, "_bras_kit_front_to_back", False):
        return

    def sorted_mesh_nodes(self, scene):
        return [node for node, _ in _nodes_in_order(scene, scene.get_pose(scene.main_camera_node)[:3, 3])]

    renderer_class._sorted_mesh_nodes = sorted_mesh_nodes
    renderer_class._bras_kit_front_to_back = True


def lean_forward_pass(pyrender, inner) -> None:
    """Give pyrender's renderer ``inner`` a forward pass that does per frame what pyrender's
    ``Renderer._forward_pass`` does per primitive: choose the program, set the camera and the
    lights (uniforms are the program's own state, so once a frame is enough), and ask each node's
    pose of the scene graph; and per primitive it sets only what changed since the primitive
    before (blending, culling, the vertex array). Talos draws 54 primitives a frame: pyrender's
    pass spent about 30 ms of Python on them, three quarters of a frame's time on llvmpipe.

    The calls that draw are pyrender's and PyOpenGL's, in pyrender's order, with pyrender's
    values, so the pixels are the same (``tests/test_render_compat.py`` compares both passes).
    A primitive with textures, instances, points, wireframe or another material than
    metallic-roughness (the only one bras-kit makes) is drawn by pyrender's own
    ``_bind_and_draw_primitive``; shadows, segmentation, depth-only, flat or wireframe flags,
    more lights than the shader takes, or an on-screen window use pyrender's whole pass."""
    from OpenGL import GL

    flags_ = pyrender.constants.RenderFlags
    program_flags = pyrender.constants.ProgramFlags
    points = pyrender.constants.GLTF.POINTS
    unusual = (flags_.SEG | flags_.DEPTH_ONLY | flags_.FLAT | flags_.SHADOWS_DIRECTIONAL | flags_.SHADOWS_SPOT
               | flags_.SHADOWS_POINT | flags_.ALL_WIREFRAME | flags_.FLIP_WIREFRAME | flags_.SKIP_CULL_FACES)
    metallic = pyrender.material.MetallicRoughnessMaterial
    original = inner._forward_pass
    programs: dict[tuple[object, ...], Any] = {}
    null = ctypes.c_void_p(0)

    def forward_pass(self, scene, flags, seg_node_map=None):
        camera = scene.main_camera_node
        limits = self._compute_max_n_lights(flags)
        if flags & unusual or not flags & flags_.OFFSCREEN or camera is None \
                or len(scene.directional_light_nodes) > limits[0] or len(scene.spot_light_nodes) > limits[1] \
                or len(scene.point_light_nodes) > limits[2]:
            return original(scene, flags, seg_node_map=seg_node_map)
        self._configure_forward_pass_viewport(flags)
        GL.glClearColor(*scene.bg_color)
        GL.glClear(GL.GL_COLOR_BUFFER_BIT | GL.GL_DEPTH_BUFFER_BIT)
        GL.glEnable(GL.GL_MULTISAMPLE)
        V, P = self._get_camera_matrices(scene)  # noqa: N806 - pyrender's names
        camera_position = scene.get_pose(camera)[:3, 3]
        GL.glPolygonMode(GL.GL_FRONT_AND_BACK, GL.GL_FILL)
        GL.glDisable(GL.GL_PROGRAM_POINT_SIZE)
        program = bound = None
        direct = _DirectCalls.get()
        ready: set[int] = set()
        blend = cull = None
        for node, pose in _nodes_in_order(scene, camera_position):
            mesh = node.mesh
            if not mesh.is_visible:
                continue
            for primitive in mesh.primitives:
                material = primitive.material
                key = (primitive.buf_flags, material.tex_flags, type(material), flags)
                chosen = programs.get(key)
                if chosen is None or not chosen._in_context():
                    chosen = programs[key] = self._get_primitive_program(primitive, flags, program_flags.USE_MATERIAL)
                if chosen is not program:
                    if bound is not None:
                        bound._unbind()
                        bound = None
                    program = chosen
                    program._bind()
                    if id(program) not in ready:
                        ready.add(id(program))
                        program.set_uniform("V", V)
                        program.set_uniform("P", P)
                        program.set_uniform("cam_pos", camera_position)
                        self._bind_lighting(scene, program, node, flags)
                if material.tex_flags or primitive.poses is not None or primitive.mode == points \
                        or material.wireframe or not isinstance(material, metallic):
                    if bound is not None:
                        bound._unbind()
                        bound = None
                    if direct is not None:
                        direct.forget(program)  # set_uniform sets them again: its record is stale
                    self._bind_and_draw_primitive(primitive=primitive, pose=pose, program=program, flags=flags)
                    self._reset_active_textures()
                    blend = cull = None
                    GL.glPolygonMode(GL.GL_FRONT_AND_BACK, GL.GL_FILL)
                    GL.glDisable(GL.GL_PROGRAM_POINT_SIZE)
                    continue
                if direct is None:
                    program.set_uniform("M", pose)
                    primitive._bind()
                    for name, value in zip(DIRECT_UNIFORMS[1:], (material.emissiveFactor, material.baseColorFactor,
                                                                 material.metallicFactor, material.roughnessFactor)):
                        program.set_uniform(name, value)
                else:
                    direct.draw_setup(program, primitive, pose, material)
                bound = primitive
                wanted = material.alphaMode == "BLEND"
                if wanted is not blend:
                    if blend is None:
                        GL.glEnable(GL.GL_BLEND)
                    GL.glBlendFunc(*((GL.GL_SRC_ALPHA, GL.GL_ONE_MINUS_SRC_ALPHA) if wanted else (GL.GL_ONE, GL.GL_ZERO)))
                    blend = wanted
                wanted = not material.doubleSided
                if wanted is not cull:
                    if wanted:
                        GL.glEnable(GL.GL_CULL_FACE)
                        GL.glCullFace(GL.GL_BACK)
                    else:
                        GL.glDisable(GL.GL_CULL_FACE)
                    cull = wanted
                if direct is not None and primitive.indices is not None:
                    direct.draw_elements(primitive.mode, primitive.indices.size, GL.GL_UNSIGNED_INT, None, 1)
                elif primitive.indices is not None:
                    GL.glDrawElementsInstanced(primitive.mode, primitive.indices.size, GL.GL_UNSIGNED_INT, null, 1)
                else:
                    GL.glDrawArraysInstanced(primitive.mode, 0, len(primitive.positions), 1)
        if bound is not None:
            bound._unbind()
        if program is not None:
            program._unbind()
        if direct is not None:
            direct.forget_all()
        GL.glFlush()
        return self._read_main_framebuffer(scene, flags)

    inner._forward_pass = types.MethodType(forward_pass, inner)


DIRECT_UNIFORMS = ("M", "material.emissive_factor", "material.base_color_factor", "material.metallic_factor",
                   "material.roughness_factor")


class _DirectCalls:
    """The five OpenGL calls the lean pass makes for every primitive (its pose, its material's
    four factors, its vertex array) and the draw, made straight through ctypes at the addresses
    the platform's ``getExtensionProcedure`` gives PyOpenGL. PyOpenGL's wrappers convert every
    argument and check for errors after each call (10 to 20 microseconds a call, about half of
    the lean pass's Python time on Talos); the values are those ``set_uniform`` would send
    (float32, the pose transposed by OpenGL as pyrender asks). ``set_uniform``'s record of what
    a program holds is wiped for these names, so its next call sets them again. None when the
    platform does not give the addresses: the pass then uses PyOpenGL's calls."""

    _made: _DirectCalls | None = None
    _tried = False

    def __init__(self, address) -> None:
        c = ctypes

        def entry(name: str, *arguments: Any) -> Any:
            where = address(name.encode())
            if not where:
                raise LookupError(name)
            return c.CFUNCTYPE(None, *arguments)(where)

        self.uniform_matrix4 = entry("glUniformMatrix4fv", c.c_int, c.c_int, c.c_ubyte, c.c_void_p)
        self.uniform3 = entry("glUniform3fv", c.c_int, c.c_int, c.c_void_p)
        self.uniform4 = entry("glUniform4fv", c.c_int, c.c_int, c.c_void_p)
        self.uniform1 = entry("glUniform1f", c.c_int, c.c_float)
        self.bind_vertex_array = entry("glBindVertexArray", c.c_uint)
        self.draw_elements = entry("glDrawElementsInstanced", c.c_uint, c.c_int, c.c_uint, c.c_void_p, c.c_int)
        self.touched: dict[int, Any] = {}

    @classmethod
    def get(cls) -> _DirectCalls | None:
        if not cls._tried:
            cls._tried = True
            try:
                from OpenGL import platform

                cls._made = cls(platform.PLATFORM.getExtensionProcedure)
            except Exception:  # noqa: BLE001 - PyOpenGL's own calls still draw
                cls._made = None
        return cls._made

    def draw_setup(self, program, primitive, pose: np.ndarray, material) -> None:
        identifier = program._program_id
        known = program.__dict__.get("_bras_kit_direct")
        if known is None or known[0] != identifier:  # kept on the program, as set_uniform keeps its own
            from OpenGL import GL

            known = program._bras_kit_direct = (identifier, tuple(GL.glGetUniformLocation(identifier, name)
                                                                  for name in DIRECT_UNIFORMS))
        where = known[1]
        self.touched[id(program)] = program
        matrix = np.ascontiguousarray(pose, dtype=np.float32)
        emissive = np.ascontiguousarray(material.emissiveFactor, dtype=np.float32)
        base = np.ascontiguousarray(material.baseColorFactor, dtype=np.float32)
        self.uniform_matrix4(where[0], 1, 1, matrix.ctypes.data)  # -1 (not in the program): OpenGL ignores it
        self.uniform3(where[1], 1, emissive.ctypes.data)
        self.uniform4(where[2], 1, base.ctypes.data)
        self.uniform1(where[3], float(material.metallicFactor))
        self.uniform1(where[4], float(material.roughnessFactor))
        self.bind_vertex_array(primitive._vaid)

    def forget(self, program) -> None:
        """Wipe ``set_uniform``'s record of these uniforms in ``program`` (see :func:`_keep_uniform_locations`)."""
        state = program.__dict__.get("_bras_kit_uniforms")
        if state:
            for name in DIRECT_UNIFORMS:
                known = state.get((program._program_id, name))
                if known is not None:
                    state[(program._program_id, name)] = (known[0], None)

    def forget_all(self) -> None:
        for program in self.touched.values():
            self.forget(program)
        self.touched.clear()


def _nodes_in_order(scene, camera: np.ndarray) -> list[tuple[Any, np.ndarray]]:
    """The scene's mesh nodes, each with its pose (asked of the scene graph once), opaque ones
    nearest ``camera`` first, then transparent ones farthest first (see :func:`draw_front_to_back`).
    Nodes at the same distance (a link's TF axes and its target, say) keep the order of their
    names, so the same scene gives the same picture in every process (not the order of their
    memory addresses)."""
    solid: list[tuple[float, str, int, Any, np.ndarray]] = []
    clear: list[tuple[float, str, int, Any, np.ndarray]] = []
    for node in scene.mesh_nodes:
        pose = scene.get_pose(node)
        distance = float(np.linalg.norm(pose[:3, 3] - camera))
        (clear if node.mesh.is_transparent else solid).append((distance, node.name or "", id(node), node, pose))
    solid.sort(key=lambda item: item[:3])
    clear.sort(key=lambda item: (-item[0], item[1], item[2]))
    return [(node, pose) for *_, node, pose in solid] + [(node, pose) for *_, node, pose in clear]
