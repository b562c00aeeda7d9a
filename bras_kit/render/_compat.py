"""Every patch bras-kit applies to pyrender 0.1.45 and PyOpenGL 3.1.0, the exact versions pinned
in pyproject.toml, and where each one lives; this module imports pyrender with the first of them.
The drawing itself is in :mod:`._pyrender`.

Each patch leans on a detail of those versions (a private attribute, a method's behaviour, a
shader's text). ``tests/render/test_render_compat.py`` holds one test per patch that fails, naming
the patch, when the installed pyrender or PyOpenGL no longer has what the patch relies on:

* :func:`import_pyrender` (here) - stand-in modules for trimesh, networkx, freetype and
  pyrender's viewer while pyrender loads, and ``np.infty`` under numpy 2;
* :func:`._forward_pass._keep_uniform_locations` - ``ShaderProgram.set_uniform`` keeps uniform
  locations and skips values already set;
* :func:`._framebuffers.make_framebuffers` / :class:`._framebuffers.ColorReader` - pyrender's
  main framebuffers made by us, and ``Renderer._read_main_framebuffer`` replaced by a
  colour-only read-back;
* :func:`._shading.use_flat_shading` - ``Renderer._program_cache`` answering ``mesh.frag`` for
  primitives without normals with bras-kit's lean shader (``shaders/flat_mesh.frag``, derived
  from pyrender's, lit flat from screen derivatives);
* :func:`._forward_pass.draw_front_to_back` - ``Renderer._sorted_mesh_nodes`` draws opaque
  nodes nearest first (pyrender draws them farthest first, so every hidden facet is shaded);
* :func:`._forward_pass.lean_forward_pass` - ``Renderer._forward_pass`` choosing programs,
  camera and lights once a frame instead of once a primitive, the same calls and pixels otherwise;
* :func:`._lifetime.delete_renderer` / :func:`._lifetime.release_renderer` /
  :func:`._lifetime.disown_renderer` - renderers freed without pyrender's finalizers (which end
  the EGL display every context shares);
* :func:`._gl.register_byref_type` - the ``ctypes.byref`` argument type under the name Python
  3.12 gives it (``_ctypes.CArgObject``; PyOpenGL 3.1.0 knows it only as
  ``builtins.CArgObject``, so every call that passes an output argument by reference,
  ``glGenTextures`` among them, failed);
* :func:`._gl.loaded_platform` - which platform ``OpenGL.platform`` committed to.
"""

from __future__ import annotations

import sys
import types
from collections.abc import Iterator
from typing import Any

import numpy as np

from ..core import backends
from ._forward_pass import _keep_uniform_locations, draw_front_to_back
from ._gl import register_byref_type


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
