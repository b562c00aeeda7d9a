"""One test per patch of bras_kit/render/_compat.py: each fails, naming its patch, as soon as the
installed pyrender or PyOpenGL no longer has what the patch relies on (an attribute, a
signature, a line of source or of a shader). Read with inspect and ast, not through bras-kit."""

from __future__ import annotations

import ast
import importlib.metadata
import inspect
import re
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parent.parent


def _pyrender():
    from bras_kit.render._compat import import_pyrender

    return import_pyrender()


def _source(obj) -> str:
    return textwrap.dedent(inspect.getsource(obj))


def test_pyproject_pins_the_very_versions_installed():
    text = (ROOT / "pyproject.toml").read_text()
    for package in ("pyrender", "PyOpenGL"):
        pinned = re.search(rf'"{package}==([^"]+)"', text)
        assert pinned, f"{package} is not pinned to one version in pyproject.toml"
        assert importlib.metadata.version(package) == pinned.group(1), \
            f"{package} {importlib.metadata.version(package)} installed, the patches were written for {pinned.group(1)}"


def test_patch_numpy_infty_is_still_what_pyrender_uses():
    mesh = Path(inspect.getfile(_pyrender().mesh))
    assert "np.infty" in mesh.read_text(), "pyrender no longer uses np.infty: drop the shim in import_pyrender"


def test_patch_networkx_stand_in_covers_every_graph_call_of_pyrender():
    from bras_kit.render._compat import _ParentGraph

    tree = ast.parse(Path(inspect.getfile(_pyrender().scene)).read_text())
    networkx_uses, graph_calls = set(), set()
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Name) and node.value.id == "nx":
            networkx_uses.add(node.attr)
        if isinstance(node, ast.Attribute) and isinstance(node.value, ast.Attribute) \
                and node.value.attr == "_digraph":
            graph_calls.add(node.attr)
    assert networkx_uses == {"DiGraph", "shortest_path"}, f"pyrender.scene now uses networkx's {networkx_uses}"
    assert graph_calls <= set(vars(_ParentGraph)), f"the stand-in lacks {graph_calls - set(vars(_ParentGraph))}"


def test_patch_stand_ins_keep_trimesh_networkx_freetype_and_the_viewer_unloaded():
    code = ("import sys, numpy as np\n"
            "from bras_kit.render._compat import import_pyrender\n"
            "pyrender = import_pyrender()\n"
            "heavy = [m for m in ('networkx', 'freetype', 'pyglet', 'trimesh.base', 'scipy') if m in sys.modules]\n"
            "assert not heavy, heavy\n"
            "scene = pyrender.Scene()\n"
            "parent = pyrender.Node(matrix=np.eye(4)); scene.add_node(parent)\n"
            "pose = np.eye(4); pose[0, 3] = 2.0\n"
            "child = pyrender.Node(matrix=pose); scene.add_node(child, parent_node=parent)\n"
            "assert scene.get_pose(child)[0, 3] == 2.0\n"
            "import trimesh; assert trimesh.Trimesh  # the real one, loaded on demand\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr[-2000:]
    init = Path(inspect.getfile(_pyrender())).read_text()
    assert "from .viewer import Viewer" in init, "pyrender no longer imports its viewer: drop that stand-in"


def test_patch_uniform_locations_replaces_a_lookup_pyrender_still_makes_each_call():
    program = _pyrender().shader_program.ShaderProgram
    assert list(inspect.signature(program.set_uniform).parameters) == ["self", "name", "value", "unsigned"]
    original = _source(program.set_uniform) if not getattr(program, "_bras_kit_locations", False) else \
        Path(inspect.getfile(program)).read_text()
    assert "glGetUniformLocation" in original
    assert {(3, "f"), (4, "f"), (4, 4), (3, 3)} <= set(program._FUNC_MAP)
    assert "self._program_id = " in Path(inspect.getfile(program)).read_text()


def test_patch_framebuffers_and_reader_rely_on_pyrenders_main_framebuffer_attributes():
    renderer = _pyrender().renderer.Renderer
    source = Path(inspect.getfile(renderer)).read_text()
    for attribute in ("_main_fb", "_main_cb", "_main_db", "_main_fb_ms", "_main_cb_ms", "_main_db_ms",
                      "_main_fb_dims"):
        assert f"self.{attribute} = " in source, f"pyrender's Renderer no longer has {attribute}"
    assert "if self._main_fb is None:" in source, "pyrender would make its own framebuffers over ours"
    assert list(inspect.signature(renderer._read_main_framebuffer).parameters) == ["self", "scene", "flags"]


def test_patch_flat_shading_shader_follows_pyrenders_mesh_frag_and_its_uniform_names():
    import hashlib

    from bras_kit.render._compat import FLAT_SHADER, PYRENDER_MESH_FRAG_SHA256

    pyrender = _pyrender()
    theirs = (Path(inspect.getfile(pyrender)).parent / "shaders" / "mesh.frag").read_bytes()
    assert hashlib.sha256(theirs).hexdigest() == PYRENDER_MESH_FRAG_SHA256, \
        "pyrender's mesh.frag changed: derive flat_mesh.frag from it again"
    ours = Path(FLAT_SHADER).read_text()
    setter = Path(inspect.getfile(pyrender.renderer)).read_text()
    for uniform in re.findall(r"^uniform \w+ (\w+)", ours, flags=re.M):
        if uniform in ("material", "directional_lights"):
            continue
        assert f"'{uniform}'" in setter, f"pyrender no longer sets the uniform {uniform}"
    for field in ("emissive_factor", "base_color_factor", "metallic_factor", "roughness_factor"):
        assert f"'{field}'" in setter
    assert "'directional_lights[{}].'" in setter
    for field in ("direction", "color", "intensity"):
        assert f"b + '{field}'" in setter
    cache = pyrender.shader_program.ShaderProgramCache
    assert list(inspect.signature(cache.get_program).parameters) == [
        "self", "vertex_shader", "fragment_shader", "geometry_shader", "defines"]
    assert "os.path.join(self.shader_dir, fn)" in _source(cache.get_program)  # keeps an absolute path
    program = _source(pyrender.renderer.Renderer._get_primitive_program)
    assert "fragment_shader = 'mesh.frag'" in program and "defines['USE_METALLIC_MATERIAL'] = 1" in program
    assert "defines['NORMAL_LOC'] = buf_idx" in program
    assert "self._program_cache = ShaderProgramCache()" in setter


def test_patch_front_to_back_replaces_pyrenders_farthest_first_order():
    import numpy as np

    pyrender = _pyrender()
    source = Path(inspect.getfile(pyrender.renderer)).read_text()
    assert re.search(r"solid_nodes\.sort\(\s*key=lambda n: -np\.linalg\.norm", source), \
        "pyrender no longer sorts opaque nodes farthest first: drop draw_front_to_back"
    scene = pyrender.Scene()
    scene.add(pyrender.PerspectiveCamera(yfov=1.0), pose=np.eye(4))
    box = pyrender.Mesh([pyrender.Primitive(positions=np.eye(3, dtype=np.float32), indices=np.array([[0, 1, 2]]))])
    nodes = []
    for distance in (5.0, 1.0, 3.0):
        pose = np.eye(4)
        pose[2, 3] = -distance
        nodes.append(scene.add(pyrender.Mesh(box.primitives), pose=pose))
    ordered = pyrender.renderer.Renderer._sorted_mesh_nodes(None, scene)
    assert ordered == [nodes[1], nodes[2], nodes[0]]


def test_patch_finalizers_are_those_pyrender_runs_and_that_end_the_shared_display():
    pyrender = _pyrender()
    assert "self.delete()" in _source(pyrender.renderer.Renderer.__del__)
    import importlib.util

    egl = Path(importlib.util.find_spec("pyrender.platforms.egl").origin).read_text()
    assert "def delete_context(self):" in egl and "eglTerminate(self._egl_display)" in egl
    assert "self._egl_context = " in egl and "self._egl_display = " in egl
    offscreen = Path(importlib.util.find_spec("pyrender.offscreen").origin).read_text()
    assert "self._renderer = " in offscreen and "self._platform = " in offscreen


@pytest.mark.parametrize(("module", "name"), [("OpenGL.platform.egl", "EGLPlatform"),
                                              ("OpenGL.platform.osmesa", "OSMesaPlatform")])
def test_patch_loaded_platform_knows_pyopengls_platform_classes(module, name):
    import importlib.util

    from bras_kit.render._compat import _PLATFORM_CLASSES

    spec = importlib.util.find_spec(module)
    assert spec is not None and f"class {name}(" in Path(spec.origin).read_text()
    assert name in _PLATFORM_CLASSES
    import os

    if os.environ.get("PYOPENGL_PLATFORM") == name[:-len("Platform")].lower():
        from bras_kit.render._compat import loaded_platform

        _pyrender()  # loads OpenGL.platform for this platform
        assert type(sys.modules["OpenGL.platform"].PLATFORM).__name__ == name
        assert loaded_platform() == _PLATFORM_CLASSES[name]
