"""Real robots in their own colours: a mesh's materials win over the URDF's (RViz's rule), in
pictures, grading pictures and the MuJoCo model; and the indexed, derivative-lit meshes look
as the per-facet normals did.

Oracles: each .dae read with xml.etree (the diffuse colours of its COLLADA effects); lighting
scales the three channels of a colour alike, so a material's hue survives it; a grey sphere of
a known colour, drawn with the same lights, bounds what a surface of that grey can show."""

from __future__ import annotations

import colorsys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest
from pixels import hsv
from robot_corpus import ROBOTS, SHARE

from bras_kit.model.authoring import load
from bras_kit.render import render_pose

pytestmark = pytest.mark.slow

COLLADA = {"c": "http://www.collada.org/2005/11/COLLADASchema"}
SIZE = (320, 240)
BACKGROUND_TOLERANCE = 6


def _dae_colours(*paths: Path) -> list[tuple[float, float, float]]:
    out = []
    for path in paths:
        root = ET.parse(path).getroot()
        for colour in root.iterfind(".//c:effect//c:diffuse/c:color", COLLADA):
            out.append(tuple(float(v) for v in colour.text.split()[:3]))
    return out


def _saturated_hues(colours) -> list[float]:
    """Hues (degrees) of the clearly coloured (not grey) diffuse colours."""
    hues = []
    for r, g, b in colours:
        h, s, v = colorsys.rgb_to_hsv(r, g, b)
        if s > 0.25 and v > 0.2:
            hues.append(360.0 * h)
    return hues


def _robot_pixels(image: np.ndarray) -> np.ndarray:
    """Pixels that are not the background or the grid (both near-neutral light greys)."""
    h, s, v = hsv(image)
    corner = image[0, 0].astype(int)
    background = (np.abs(image.astype(int) - corner).max(axis=2) <= BACKGROUND_TOLERANCE)
    grid = (s < 0.05) & (v > 0.7) & (v < 0.85)
    return ~background & ~grid


def _hue_fraction(image: np.ndarray, hue: float, tolerance: float = 8.0) -> float:
    h, s, v = hsv(image)
    near = (np.abs((h - hue + 180) % 360 - 180) < tolerance) & (s > 0.2) & (v > 0.1)
    robot = _robot_pixels(image)
    return float((near & robot).sum() / max(robot.sum(), 1))


def _ur5():
    return load(str(ROBOTS / "ur_description" / "urdf" / "ur5_robot.urdf"), package_paths=[str(SHARE)])


def test_ur5_shows_the_blue_of_its_dae_files_which_its_urdf_never_names():
    visual = ROBOTS / "ur_description" / "meshes" / "ur5" / "visual"
    hues = _saturated_hues(_dae_colours(*sorted(visual.glob("*.dae"))))
    assert hues, "the oracle found no coloured material in the UR5's files"
    image = render_pose(_ur5(), None, size=SIZE, package_paths=[str(SHARE)])
    for hue in set(round(h) for h in hues):
        assert _hue_fraction(image, hue) > 0.03, f"no pixel of the DAE's hue {hue} degrees"
    dark = (hsv(image)[2] < 0.2) & _robot_pixels(image)
    assert dark.sum() > 50  # the near-black 0.064 parts (a grey 0.7 robot has none)


def _grey_sphere_values(tmp_path: Path, grey: float) -> np.ndarray:
    """The brightness (0..1) of every pixel of a sphere of colour ``grey``, same lights and size."""
    urdf = tmp_path / f"sphere{grey}.urdf"
    urdf.write_text(f'<robot name="s"><link name="a"><visual><geometry><sphere radius="0.1"/></geometry>'
                    f'<material name="g"><color rgba="{grey} {grey} {grey} 1"/></material></visual></link></robot>')
    image = render_pose(load(str(urdf)), None, size=SIZE, grid=False)
    return hsv(image)[2][_robot_pixels(image)]


def test_panda_shows_its_white_light_and_dark_grey_materials(tmp_path):
    link0 = ROBOTS / "panda_description" / "meshes" / "visual" / "link0.dae"
    greys = sorted({round(c[0], 2) for c in _dae_colours(link0)})
    assert greys[0] <= 0.3 and greys[-1] >= 0.9  # the oracle: dark grey and white in the file
    robot = load(str(ROBOTS / "panda_description" / "urdf" / "panda.urdf"), package_paths=[str(SHARE)])
    image = render_pose(robot, None, size=SIZE, package_paths=[str(SHARE)])
    values = hsv(image)[2][_robot_pixels(image)]
    default_grey = _grey_sphere_values(tmp_path, 0.7)  # what the robot was before: one grey
    white = _grey_sphere_values(tmp_path, greys[-1])
    dark = _grey_sphere_values(tmp_path, greys[0])
    brighter = values > default_grey.max() + 0.02  # only a lighter material gives these
    assert brighter.mean() > 0.2
    assert values.max() <= white.max() + 0.02
    in_dark_range = (values >= np.percentile(dark, 5)) & (values <= np.percentile(dark, 95))
    assert (in_dark_range & (values < np.percentile(default_grey, 5))).sum() > 30


def test_anymal_hips_are_orange_from_their_dae_and_feet_are_drawn_with_one_warning(capsys):
    hips = sorted((ROBOTS / "anymal_b_simple_description" / "meshes" / "hip").glob("*.dae"))
    orange = [h for h in _saturated_hues(_dae_colours(*hips)) if 10 <= h <= 40]
    assert orange, "the oracle found no orange in the hips"
    robot = load(str(ROBOTS / "anymal_b_simple_description" / "robots" / "anymal.urdf"), package_paths=[str(SHARE)])
    image = render_pose(robot, None, size=SIZE, package_paths=[str(SHARE)])
    assert _hue_fraction(image, orange[0], 6.0) > 0.002
    warnings = [line for line in capsys.readouterr().err.splitlines() if line.startswith("warning:")]
    assert len(warnings) == 1 and "anymal_foot.dae" in warnings[0] and "carbon_uv_texture" in warnings[0]
    assert "stand-in" not in warnings[0]
    assert _hue_fraction(image, 0.0, 4.0) < 0.001  # no red stand-in


def test_a_grading_picture_shows_the_mesh_colours(tmp_path):
    from bras_kit.grade.worker import Options, _picture

    picture = _picture(_ur5(), "ur5", Options(pictures=str(tmp_path)), (str(SHARE),))
    assert picture == "pictures/ur5.png"
    from PIL import Image

    image = np.asarray(Image.open(tmp_path / "ur5.png").convert("RGB"))
    hue = _saturated_hues(_dae_colours(ROBOTS / "ur_description" / "meshes" / "ur5" / "visual" / "shoulder.dae"))[0]
    assert _hue_fraction(image, hue) > 0.02


def test_mujoco_geoms_carry_each_material_piece_colour():
    from bras_kit.physics.mjcf import build_mjcf

    model = build_mjcf(_ur5(), package_paths=[str(SHARE)]).compile()
    import mujoco

    base = ROBOTS / "ur_description" / "meshes" / "ur5" / "visual" / "base.dae"
    wanted = {tuple(round(c, 3) for c in colour) for colour in _dae_colours(base)}
    names = [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, g) for g in range(model.ngeom)]
    got = {tuple(round(float(c), 3) for c in model.geom_rgba[g][:3]) for g, name in enumerate(names)
           if name and name.startswith("base_link/visual")}
    assert got == wanted


def test_indexed_meshes_lit_from_derivatives_look_as_per_facet_normals_did():
    """The old primitives (three vertices per facet, each with the facet's normal, through
    pyrender's own shader path) against the indexed ones with no normals: the same picture."""
    from bras_kit.render import _pyrender

    robot = _ur5()
    new = render_pose(robot, {"shoulder_lift_joint": -0.8}, size=SIZE, package_paths=[str(SHARE)])

    def per_facet(pyrender, vertices, faces, color, unlit):  # the look before
        triangles = vertices[faces]
        normals = np.cross(triangles[:, 1] - triangles[:, 0], triangles[:, 2] - triangles[:, 0])
        lengths = np.linalg.norm(normals, axis=1, keepdims=True)
        normals = normals / np.where(lengths > 0, lengths, 1.0)
        primitive = original(pyrender, vertices, faces, color, unlit)
        return pyrender.Primitive(positions=triangles.reshape(-1, 3).astype(np.float32),
                                  normals=np.repeat(normals, 3, axis=0).astype(np.float32),
                                  material=primitive.material)

    original = _pyrender.PyrenderBackend._primitive
    try:
        _pyrender.PyrenderBackend._primitive = staticmethod(per_facet)
        old = render_pose(robot, {"shoulder_lift_joint": -0.8}, size=SIZE, package_paths=[str(SHARE)])
    finally:
        _pyrender.PyrenderBackend._primitive = staticmethod(original)
    difference = np.abs(new.astype(int) - old.astype(int)).max(axis=2)
    assert _robot_pixels(old).sum() > 2000
    assert difference.mean() < 1.0 and (difference > 24).mean() < 0.005


def test_the_viewer_gets_each_dae_colour_one_mesh_per_link_and_colour():
    from bras_kit.view.model import view_model

    robot = load(str(ROBOTS / "panda_description" / "urdf" / "panda.urdf"), package_paths=[str(SHARE)])
    model = view_model(robot, [str(SHARE)])
    link0 = model.tree.index("panda_link0")
    colours = {m.color for m in model.visuals if m.link == link0}
    wanted = {tuple(int(round(255 * c)) for c in colour)
              for colour in _dae_colours(ROBOTS / "panda_description" / "meshes" / "visual" / "link0.dae")}
    assert colours == wanted
    assert len([m for m in model.visuals if m.link == link0]) == len(wanted)
