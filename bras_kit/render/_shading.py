"""bras-kit's lean fragment shader (``shaders/flat_mesh.frag``, derived from pyrender's
``mesh.frag``) answered by pyrender's program cache for primitives without normals, textures
or colours (:func:`use_flat_shading`)."""

from __future__ import annotations

import os

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
