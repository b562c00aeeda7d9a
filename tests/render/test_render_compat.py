"""One test per patch listed in bras_kit/render/_compat.py: each fails, naming its patch, as soon as the
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
from paths import REPO

ROOT = REPO


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

    from bras_kit.render._shading import FLAT_SHADER, PYRENDER_MESH_FRAG_SHA256

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

    from bras_kit.render._gl import _PLATFORM_CLASSES

    spec = importlib.util.find_spec(module)
    assert spec is not None and f"class {name}(" in Path(spec.origin).read_text()
    assert name in _PLATFORM_CLASSES
    import os

    if os.environ.get("PYOPENGL_PLATFORM") == name[:-len("Platform")].lower():
        from bras_kit.render._gl import loaded_platform

        _pyrender()  # loads OpenGL.platform for this platform
        assert type(sys.modules["OpenGL.platform"].PLATFORM).__name__ == name
        assert loaded_platform() == _PLATFORM_CLASSES[name]


def test_patch_lean_forward_pass_repeats_the_steps_of_pyrenders_own_pass():
    """The lean pass (``_forward_pass.lean_forward_pass``) makes pyrender's per-primitive calls once a
    frame: it relies on these steps, helpers and values being pyrender's."""
    def squeezed(text: str) -> str:
        return re.sub(r"\s+", "", text)

    renderer = _pyrender().renderer.Renderer
    forward = squeezed(_source(renderer._forward_pass))
    for step in ("self._configure_forward_pass_viewport(flags)", "glClearColor(*scene.bg_color)",
                 "glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT)", "glEnable(GL_MULTISAMPLE)",
                 "V, P = self._get_camera_matrices(scene)", "if not mesh.is_visible:",
                 "self._get_primitive_program(\n                    primitive, flags, ProgramFlags.USE_MATERIAL",
                 "program.set_uniform('V', V)", "program.set_uniform('P', P)",
                 "'cam_pos', scene.get_pose(scene.main_camera_node)[:3,3]",
                 "self._bind_lighting(scene, program, node, flags)", "pose=scene.get_pose(node)",
                 "self._reset_active_textures()", "program._unbind()", "glFlush()",
                 "return self._read_main_framebuffer(scene, flags)"):
        assert squeezed(step) in forward, f"pyrender's _forward_pass no longer has {step!r}: review lean_forward_pass"
    draw = squeezed(_source(renderer._bind_and_draw_primitive))
    for step in ("program.set_uniform('M', pose)", "primitive._bind()", "b.format('emissive_factor')",
                 "b.format('base_color_factor')", "b.format('metallic_factor')", "b.format('roughness_factor')",
                 "if material.alphaMode == 'BLEND':", "glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA)",
                 "glBlendFunc(GL_ONE, GL_ZERO)", "glPolygonMode(GL_FRONT_AND_BACK, GL_FILL)",
                 "if material.doubleSided or flags & RenderFlags.SKIP_CULL_FACES:", "glCullFace(GL_BACK)",
                 "glDisable(GL_PROGRAM_POINT_SIZE)", "primitive.mode, primitive.indices.size, GL_UNSIGNED_INT",
                 "glDrawArraysInstanced(\n                primitive.mode, 0, len(primitive.positions), n_instances",
                 "primitive._unbind()"):
        assert squeezed(step) in draw, f"pyrender's _bind_and_draw_primitive no longer has {step!r}: review lean_forward_pass"
    lighting = _source(renderer._bind_lighting)
    assert "self._sorted_nodes_by_distance(" in lighting  # only past the shader's light limits: excluded
    assert list(inspect.signature(renderer._forward_pass).parameters) == ["self", "scene", "flags", "seg_node_map"]


def _scene_of_every_kind(pyrender):
    """A pyrender scene with a primitive of each kind the lean pass draws itself or hands back."""
    import numpy as np

    scene = pyrender.Scene(bg_color=[0.1, 0.2, 0.3, 1.0], ambient_light=[0.2] * 3)
    box = np.array([[x, y, z] for x in (-0.5, 0.5) for y in (-0.5, 0.5) for z in (-0.5, 0.5)], dtype=np.float32)
    faces = np.array([[0, 2, 1], [1, 2, 3], [4, 5, 6], [5, 7, 6], [0, 1, 4], [1, 5, 4],
                      [2, 6, 3], [3, 6, 7], [0, 4, 2], [2, 4, 6], [1, 3, 5], [3, 7, 5]], dtype=np.uint32)

    def metal(rgba, **extra):
        return pyrender.MetallicRoughnessMaterial(baseColorFactor=rgba, metallicFactor=0.0, roughnessFactor=1.0,
                                                  **extra)

    def at(x, y, z=0.0):
        pose = np.eye(4)
        pose[:3, 3] = (x, y, z)
        return pose

    scene.add(pyrender.Mesh([pyrender.Primitive(positions=box, indices=faces, material=metal([0.8, 0.1, 0.1, 1.0]))]),
              pose=at(-1.2, 0.6))
    scene.add(pyrender.Mesh([pyrender.Primitive(positions=box, indices=faces,
                                                material=metal([0.1, 0.8, 0.1, 0.5], alphaMode="BLEND"))]),
              pose=at(-0.6, 0.4, 0.5))
    scene.add(pyrender.Mesh([pyrender.Primitive(positions=box[[0, 1, 2]], indices=np.array([[0, 2, 1]]),
                                                material=metal([0.9, 0.9, 0.1, 1.0], doubleSided=True))]),
              pose=at(0.3, 0.6))
    normals = box / np.linalg.norm(box, axis=1, keepdims=True)
    scene.add(pyrender.Mesh([pyrender.Primitive(positions=box, normals=normals.astype(np.float32), indices=faces,
                                                material=metal([0.2, 0.3, 0.9, 1.0]))]), pose=at(1.2, 0.6))
    # RGBA: a row of two RGB texels is 6 bytes, and OpenGL reads rows 4-byte aligned
    # (GL_UNPACK_ALIGNMENT, which pyrender leaves at 4): it read 2 bytes past the end of the
    # array, whatever memory held there, and the cube's colours changed from run to run
    texture = pyrender.Texture(source=np.array([[[255, 0, 0, 255], [0, 255, 0, 255]],
                                                [[0, 0, 255, 255], [255, 255, 255, 255]]], dtype=np.uint8),
                               source_channels="RGBA")
    uv = (box[:, :2] + 0.5).astype(np.float32)
    scene.add(pyrender.Mesh([pyrender.Primitive(positions=box, texcoord_0=uv, indices=faces,
                                                material=metal([1.0, 1.0, 1.0, 1.0], baseColorTexture=texture))]),
              pose=at(-1.2, -0.8))
    scene.add(pyrender.Mesh([pyrender.Primitive(positions=box, mode=pyrender.constants.GLTF.POINTS,
                                                material=metal([1.0, 1.0, 1.0, 1.0]))]), pose=at(1.2, -0.8))
    scene.add(pyrender.Mesh([pyrender.Primitive(positions=box[[0, 7, 1, 6]], mode=pyrender.constants.GLTF.LINES,
                                                material=metal([0.0, 0.0, 0.0, 1.0], emissiveFactor=[1.0, 0.5, 0.0]))]),
              pose=at(0.6, -0.2, 0.4))
    hidden = scene.add(pyrender.Mesh([pyrender.Primitive(positions=box, indices=faces,
                                                         material=metal([1.0, 1.0, 1.0, 1.0]))]), pose=at(0, 0, 1.5))
    hidden.mesh.is_visible = False
    scene.add(pyrender.PerspectiveCamera(yfov=0.9, aspectRatio=4 / 3), pose=at(0.0, 0.0, 4.0))
    light = np.eye(4)
    light[:3, :3] = [[1, 0, 0], [0, 0.8, -0.6], [0, 0.6, 0.8]]
    scene.add(pyrender.DirectionalLight(color=np.ones(3), intensity=3.0), pose=light)
    scene.add(pyrender.PointLight(color=[1.0, 0.8, 0.6], intensity=4.0), pose=at(0.5, 1.0, 2.0))
    scene.add(pyrender.SpotLight(color=[0.6, 0.8, 1.0], intensity=6.0, outerConeAngle=0.8), pose=at(-0.5, 0.0, 3.0))
    return scene


def test_patch_lean_forward_pass_draws_what_pyrenders_own_pass_draws():
    """Every kind of primitive (opaque, blended, double-sided, with normals, textured,
    points, lines, hidden) and of light: pyrender's own pass is the oracle, pixel for pixel and
    in depth, drawn twice so the second frame starts from the state the first one left."""
    import numpy as np

    from bras_kit.render._forward_pass import lean_forward_pass
    from bras_kit.render._lifetime import delete_renderer, disown_renderer

    pyrender = _pyrender()
    flags = pyrender.constants.RenderFlags
    scene = _scene_of_every_kind(pyrender)
    pictures = {}
    for lean in (False, True):
        renderer = pyrender.OffscreenRenderer(160, 120)
        try:
            if lean:
                lean_forward_pass(pyrender, renderer._renderer)
            first = renderer.render(scene)
            second = renderer.render(scene)
            flat = renderer.render(scene, flags=flags.FLAT)  # a flag the lean pass leaves to pyrender
        finally:
            delete_renderer(renderer)
            disown_renderer(renderer)
        assert np.array_equal(first[0], second[0]) and np.array_equal(first[1], second[1])
        pictures[lean] = (first, flat)
    (color, depth), flat = pictures[False]
    assert len(np.unique(color.reshape(-1, 3), axis=0)) > 50  # the scene is drawn, not a blank
    assert np.array_equal(pictures[True][0][0], color)
    assert np.array_equal(pictures[True][0][1], depth)
    assert np.array_equal(pictures[True][1][0], flat[0])


def test_nodes_at_the_same_distance_are_drawn_in_the_order_of_their_names_not_of_their_addresses():
    """A link's TF axes and its neighbours' sit at one distance from the camera: the order they
    are drawn in decides which pixels win, so it must not hang on memory addresses."""
    import numpy as np

    from bras_kit.render._forward_pass import _nodes_in_order

    pyrender = _pyrender()
    scene = pyrender.Scene()
    triangle = pyrender.Primitive(positions=np.eye(3, dtype=np.float32), indices=np.array([[0, 1, 2]]))
    names = ["000004", "000001", "000003", "000000", "000002"]
    for name in names:  # made (and placed in memory) in another order than their names'
        scene.add(pyrender.Mesh([triangle]), name=name)
    ordered = [node.name for node, _ in _nodes_in_order(scene, np.array([0.0, 0.0, 5.0]))]
    assert ordered == sorted(names)


def test_patch_byref_type_is_registered_under_the_name_this_python_gives_it():
    """PyOpenGL 3.1.0 registers ``ctypes.byref``'s type by name; Python 3.12 renamed it
    (``builtins.CArgObject`` -> ``_ctypes.CArgObject``). The patch must add this Python's name."""
    import ctypes

    from OpenGL import plugins

    _pyrender()
    byref_type = type(ctypes.byref(ctypes.c_int()))
    handler = plugins.FormatHandler.by_name("ctypesparameter")
    assert handler is not None, "PyOpenGL no longer has the ctypesparameter handler: drop register_byref_type"
    assert f"{byref_type.__module__}.{byref_type.__name__}" in handler.check
    assert plugins.FormatHandler.match(byref_type) is handler


def test_a_textured_primitive_draws_its_texture_on_this_python():
    """glGenTextures passes its output by reference: a quad textured half red, half blue, seen
    from the front in white ambient light, shows red on its left half and blue on its right,
    whatever the Python."""
    import numpy as np

    from bras_kit.render._lifetime import delete_renderer, disown_renderer

    pyrender = _pyrender()
    image = np.zeros((8, 8, 3), dtype=np.uint8)
    image[:, :4] = (255, 0, 0)
    image[:, 4:] = (0, 0, 255)
    texture = pyrender.Texture(source=image, source_channels="RGB",
                               sampler=pyrender.Sampler(magFilter=9728, minFilter=9728))  # GL_NEAREST
    material = pyrender.MetallicRoughnessMaterial(baseColorTexture=texture, baseColorFactor=(1, 1, 1, 1),
                                                  metallicFactor=0.0, roughnessFactor=1.0)
    positions = np.array([[-1, -1, 0], [1, -1, 0], [1, 1, 0], [-1, 1, 0]], dtype=np.float32)
    uv = np.array([[0, 0], [1, 0], [1, 1], [0, 1]], dtype=np.float32)
    primitive = pyrender.Primitive(positions=positions, texcoord_0=uv, indices=np.array([[0, 1, 2], [0, 2, 3]]),
                                   material=material)
    scene = pyrender.Scene(ambient_light=(1.0, 1.0, 1.0), bg_color=(0, 0, 0))
    scene.add(pyrender.Mesh([primitive]))
    camera_pose = np.eye(4)
    camera_pose[2, 3] = 2.0
    scene.add(pyrender.OrthographicCamera(xmag=1.0, ymag=1.0), pose=camera_pose)
    renderer = pyrender.OffscreenRenderer(64, 64)
    try:
        color, _ = renderer.render(scene)
    finally:
        delete_renderer(renderer)
        disown_renderer(renderer)
    left, right = color[32, 8].astype(int), color[32, 56].astype(int)
    # pyrender's ambient term dims the colour; the texture's halves must still come out pure
    assert left[0] > 10 and left[1] == left[2] == 0, left
    assert right[2] > 10 and right[0] == right[1] == 0, right
