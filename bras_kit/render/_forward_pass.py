"""pyrender's drawing pass made cheaper, the same OpenGL calls and pixels: uniform locations kept
per program (:func:`_keep_uniform_locations`), opaque nodes drawn nearest first
(:func:`draw_front_to_back`), and a forward pass that sets per frame what pyrender sets per
primitive, its per-primitive calls made straight through ctypes (:func:`lean_forward_pass`)."""

from __future__ import annotations

import ctypes
import types
from typing import Any

import numpy as np


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
    values, so the pixels are the same (``tests/render/test_render_compat.py`` compares both passes).
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
