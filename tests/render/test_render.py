"""Pictures of the arm: where each segment lands, its colour, TF axes, grid, camera and backends.

Segments are found by colour: the material's hue (blue 0.2 0.4 0.9 is 223 degrees, orange
0.95 0.5 0.1 is 28 degrees) with a tolerance for shading, on a plain white background.
"""

from __future__ import annotations

import math
import os

import numpy as np
import pytest
from pixels import hsv

from bras_kit.core.errors import BackendError, ModelError, ParameterError
from bras_kit.render import Renderer, render_motion, render_pose

BLUE_HUE = 222.9  # hue of rgb (0.2, 0.4, 0.9)
ORANGE_HUE = 28.2  # hue of rgb (0.95, 0.5, 0.1)
FRONT = dict(view="front", grid=False, background="white", size=(320, 400))


def hue_mask(image: np.ndarray, hue: float, tolerance: float = 10.0) -> np.ndarray:
    h, s, v = hsv(image)
    distance = np.abs((h - hue + 180) % 360 - 180)
    return (distance < tolerance) & (s > 0.4) & (v > 0.25)


def grey_mask(image: np.ndarray) -> np.ndarray:
    _, s, v = hsv(image)
    return (s < 0.08) & (v < 0.75) & (v > 0.2)


def pure_mask(image: np.ndarray, channel: int) -> np.ndarray:
    others = [c for c in range(3) if c != channel]
    return (image[..., channel] > 200) & (image[..., others[0]] < 60) & (image[..., others[1]] < 60)


def rows_cols(mask: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    rows, cols = np.nonzero(mask)
    assert len(rows) > 0, "no pixel of that colour"
    return rows, cols


def principal_angle(mask: np.ndarray) -> float:
    """Angle of the mask's long axis in degrees above the image's horizontal (rows point down)."""
    rows, cols = rows_cols(mask)
    coords = np.column_stack([cols - cols.mean(), -(rows - rows.mean())])
    _, _, vt = np.linalg.svd(coords, full_matrices=False)
    dx, dy = vt[0]
    if dx < 0:
        dx, dy = -dx, -dy
    return math.degrees(math.atan2(dy, dx))


def silhouette(image: np.ndarray, background=(255, 255, 255)) -> np.ndarray:
    return np.abs(image.astype(int) - np.array(background)).sum(axis=2) > 30


@pytest.fixture(scope="module")
def zero_front(tutorial_robot):
    return render_pose(tutorial_robot, None, **FRONT)


@pytest.fixture(scope="module")
def bent_front(tutorial_robot):
    return render_pose(tutorial_robot, {"epaule": 0.8, "coude": 1.2}, **FRONT)


# ---------------------------------------------------------------- where the segments land


def test_picture_has_the_requested_size_and_type(zero_front):
    assert zero_front.shape == (400, 320, 3)
    assert zero_front.dtype == np.uint8


def test_zero_pose_upper_arm_is_a_vertical_bar_above_the_base(zero_front):
    blue_rows, blue_cols = rows_cols(hue_mask(zero_front, BLUE_HUE))
    grey_rows, grey_cols = rows_cols(grey_mask(zero_front))
    width = blue_cols.max() - blue_cols.min() + 1
    height = blue_rows.max() - blue_rows.min() + 1
    assert height > 5 * width  # 0.6 m tall, 0.08 m wide
    assert abs(blue_cols.mean() - grey_cols.mean()) < 1.5  # both centred on the z axis
    assert blue_rows.mean() < grey_rows.min()  # above the base
    assert blue_rows.max() <= grey_rows.max()  # and standing on it, not below
    # the bar is as wide as the base is, scaled: 0.08 m against the base's 0.30 m diameter
    assert width / (grey_cols.max() - grey_cols.min() + 1) == pytest.approx(0.08 / 0.30, rel=0.12)


def test_zero_pose_forearm_continues_the_upper_arm_straight_up(zero_front):
    blue_rows, blue_cols = rows_cols(hue_mask(zero_front, BLUE_HUE))
    orange_rows, orange_cols = rows_cols(hue_mask(zero_front, ORANGE_HUE))
    assert abs(orange_cols.mean() - blue_cols.mean()) < 1.5  # same column: straight
    assert orange_rows.max() <= blue_rows.min() + 2  # above the upper arm, touching it
    assert blue_rows.min() - orange_rows.max() <= 2
    # lengths 0.5 and 0.6 m, widths 0.06 and 0.08 m (the camera looks square at this plane)
    orange_height = orange_rows.max() - orange_rows.min() + 1
    blue_height = blue_rows.max() - blue_rows.min() + 1
    assert orange_height / blue_height == pytest.approx(0.5 / 0.6, rel=0.06)
    orange_width = orange_cols.max() - orange_cols.min() + 1
    blue_width = blue_cols.max() - blue_cols.min() + 1
    assert orange_width / blue_width == pytest.approx(0.06 / 0.08, rel=0.15)


def test_bent_pose_upper_arm_leans_right_at_the_shoulder_angle(bent_front):
    # epaule = 0.8 rad about y tilts the upper arm towards +x: 90 - 45.8 = 44.2 degrees above horizontal
    assert principal_angle(hue_mask(bent_front, BLUE_HUE)) == pytest.approx(90 - math.degrees(0.8), abs=2.0)


def test_bent_pose_forearm_slopes_down_towards_plus_x(bent_front):
    blue_rows, blue_cols = rows_cols(hue_mask(bent_front, BLUE_HUE))
    orange = hue_mask(bent_front, ORANGE_HUE)
    orange_rows, orange_cols = rows_cols(orange)
    assert orange_cols.mean() > blue_cols.max() - 5  # to the right of the elbow
    # the forearm points at 0.8 + 1.2 = 2.0 rad from vertical: 24.6 degrees below horizontal
    assert principal_angle(orange) == pytest.approx(-(math.degrees(2.0) - 90), abs=2.0)
    right_end = orange_rows[orange_cols > np.percentile(orange_cols, 90)].mean()
    left_end = orange_rows[orange_cols < np.percentile(orange_cols, 10)].mean()
    assert right_end > left_end + 20  # descending: lower in the picture at its tip


def test_colours_are_the_materials(zero_front):
    hue, saturation, _ = hsv(zero_front)
    coloured = saturation > 0.4
    near_blue = np.abs((hue - BLUE_HUE + 180) % 360 - 180) < 8
    near_orange = np.abs((hue - ORANGE_HUE + 180) % 360 - 180) < 8
    assert (near_blue | near_orange)[coloured].mean() > 0.97
    assert near_blue[coloured].sum() > 500 and near_orange[coloured].sum() > 300


def test_colour_follows_a_changed_material():
    from bras_kit.model.authoring import arm

    green_arm = arm(params={"bras_color": "0.1 0.8 0.2 1"})  # hue 128 degrees
    image = render_pose(green_arm, None, **FRONT)
    assert hue_mask(image, 128.0).sum() > 500
    assert hue_mask(image, BLUE_HUE).sum() == 0


def test_visual_without_material_is_grey():
    from bras_kit.model.robot import robot_from_xml
    from bras_kit.model.xmlio import parse_xml

    text = """<robot name="plain"><link name="a"><visual><geometry><sphere radius="0.2"/></geometry>
    </visual></link></robot>"""
    robot = robot_from_xml(parse_xml(text, "plain.urdf"), "plain.urdf", text)
    image = render_pose(robot, None, **FRONT)
    _, saturation, value = hsv(image)
    body = silhouette(image)
    assert body.sum() > 1000
    assert saturation[body].max() < 0.05


# ---------------------------------------------------------------- overlays and background


def test_tf_axes_add_pure_red_green_blue(tutorial_robot):
    pose = {"epaule": 0.8, "coude": 1.2}
    options = dict(view="iso", grid=False, size=(320, 240))
    plain = render_pose(tutorial_robot, pose, **options)
    axes = render_pose(tutorial_robot, pose, tf=True, **options)
    for channel in range(3):
        assert pure_mask(plain, channel).sum() == 0
        assert pure_mask(axes, channel).sum() > 15


def test_grid_adds_light_grey_lines_behind_the_arm(tutorial_robot):
    options = dict(view="iso", size=(320, 240), antialias=False)  # unblended edges: exact colours
    with_grid = render_pose(tutorial_robot, None, **options)
    without = render_pose(tutorial_robot, None, grid=False, **options)
    changed = (with_grid != without).any(axis=2)
    assert changed.sum() > 300
    assert np.abs(with_grid[changed].astype(int) - 199).max() <= 1  # grid grey 0.78 0.78 0.78
    arm = silhouette(without)
    inner = arm & np.roll(arm, 1, 0) & np.roll(arm, -1, 0) & np.roll(arm, 1, 1) & np.roll(arm, -1, 1)
    assert not (changed & inner).any()  # never drawn over the arm (a line may share its edge pixels)


@pytest.mark.parametrize(("background", "expected"), [("black", (0, 0, 0)), ("#336699", (51, 102, 153)),
                                                      ("0.5 0.5 0.5", (128, 128, 128)), ("rviz", (48, 48, 48))])
def test_background_colour(tutorial_robot, background, expected):
    image = render_pose(tutorial_robot, None, background=background, grid=False, size=(64, 48))
    assert tuple(image[0, 0]) == expected


def test_bad_options_are_refused_with_hints(tutorial_robot):
    with pytest.raises(ParameterError, match="not WIDTHxHEIGHT"):
        render_pose(tutorial_robot, size="640by480")
    with pytest.raises(ParameterError, match="out of range"):
        render_pose(tutorial_robot, size=(4, 4))
    with pytest.raises(ParameterError, match="unknown view 'back'"):
        render_pose(tutorial_robot, view="back")
    with pytest.raises(ParameterError, match="unknown render option zoom"):
        render_pose(tutorial_robot, zoom=2)
    with pytest.raises(ParameterError, match="not a colour"):
        render_pose(tutorial_robot, background="plaid")
    with pytest.raises(ParameterError, match="unknown joint 'poignet'"):
        render_pose(tutorial_robot, {"poignet": 1.0})


# ---------------------------------------------------------------- camera


def test_top_view_shows_the_arm_reaching_along_plus_x(tutorial_robot):
    image = render_pose(tutorial_robot, {"epaule": 1.2}, view="top", grid=False, size=(320, 320))
    blue_rows, blue_cols = rows_cols(hue_mask(image, BLUE_HUE))
    grey_rows, grey_cols = rows_cols(grey_mask(image))
    assert blue_cols.mean() > grey_cols.mean() + 20  # +x is to the right
    assert abs(blue_rows.mean() - grey_rows.mean()) < 3  # y = 0: same height in the picture


def test_side_view_sees_the_arm_edge_on(tutorial_robot):
    # from +x, a lean towards +x comes at the camera: the bar stays centred over the base
    image = render_pose(tutorial_robot, {"epaule": 0.5}, view="side", grid=False, size=(320, 320))
    blue_rows, blue_cols = rows_cols(hue_mask(image, BLUE_HUE))
    grey_rows, grey_cols = rows_cols(grey_mask(image))
    assert abs(blue_cols.mean() - grey_cols.mean()) < 2


def test_the_motion_never_leaves_the_picture(tutorial_robot):
    from bras_kit.motion import sample, tutorial_motion

    states = sample(tutorial_motion(tutorial_robot), 9.0, 2.0)  # 19 poses over the tutorial motion
    for frame in render_motion(tutorial_robot, states, view="iso", grid=False, size=(160, 120)):
        body = silhouette(frame)
        assert body.sum() > 100
        assert not (body[0].any() or body[-1].any() or body[:, 0].any() or body[:, -1].any())


def test_a_camera_too_close_cuts_the_arm(tutorial_robot):
    image = render_pose(tutorial_robot, None, view="front", grid=False, size=(160, 120), distance=0.8)
    body = silhouette(image)
    assert body[0].any() or body[-1].any()


def test_explicit_angles_override_the_view(tutorial_robot):
    front = render_pose(tutorial_robot, {"epaule": 0.8}, view="iso", azimuth=-90, elevation=0, grid=False,
                        size=(160, 120))
    same = render_pose(tutorial_robot, {"epaule": 0.8}, view="front", grid=False, size=(160, 120))
    assert np.array_equal(front, same)


def test_renderer_keeps_its_camera_between_poses(tutorial_robot):
    with Renderer(tutorial_robot, view="front", grid=False, size=(200, 200)) as renderer:
        first = renderer.render({"epaule": -1.0})
        second = renderer.render({"epaule": 1.0, "coude": 1.5})
    (rows_1, cols_1), (rows_2, cols_2) = rows_cols(grey_mask(first)), rows_cols(grey_mask(second))
    # the base did not move in the picture (its top may be hidden by the arm)
    assert (rows_1.max(), cols_1.min(), cols_1.max()) == (rows_2.max(), cols_2.min(), cols_2.max())
    assert (hue_mask(first, BLUE_HUE) != hue_mask(second, BLUE_HUE)).sum() > 200
    # the default camera fits every pose within the limits: both arms are whole
    for image in (first, second):
        body = silhouette(image)
        assert not (body[0].any() or body[:, 0].any() or body[:, -1].any())


# ---------------------------------------------------------------- backends


def test_software_backend_draws_the_same_silhouette_as_opengl(tutorial_robot):
    pose = {"epaule": 0.8, "coude": 1.2}
    options = dict(view="iso", grid=False, size=(320, 240), tf=True)
    with Renderer(tutorial_robot, fit=pose, backend="egl", **options) as gl:
        assert gl.backend == "egl"
        opengl = gl.render(pose)
    with Renderer(tutorial_robot, fit=pose, backend="software", **options) as sw:
        assert sw.backend == "software"
        software = sw.render(pose)
    a, b = silhouette(opengl), silhouette(software)
    assert (a & b).sum() / (a | b).sum() >= 0.9
    for hue in (BLUE_HUE, ORANGE_HUE):
        assert (hue_mask(opengl, hue) & hue_mask(software, hue)).sum() / hue_mask(opengl, hue).sum() > 0.85


def test_software_backend_draws_grid_behind_the_arm(tutorial_robot):
    image = render_pose(tutorial_robot, {"epaule": 0.8}, backend="software", view="iso", size=(200, 150))
    flat = (image.max(axis=2).astype(int) - image.min(axis=2)) < 6
    grid = flat & (image[..., 0] > 150) & (image[..., 0] < 245)
    assert grid.sum() > 100
    assert not (grid & hue_mask(image, BLUE_HUE)).any()


def test_auto_backend_falls_back_to_software_and_says_so(tutorial_robot, monkeypatch, capsys):
    from bras_kit.render import _pyrender, renderer

    def no_gl(requested):
        raise BackendError("no OpenGL library found (test)")

    monkeypatch.setattr(_pyrender, "choose_platform", no_gl)
    monkeypatch.setattr(renderer, "_announced_fallback", False)
    with Renderer(tutorial_robot, backend="auto", size=(64, 48)) as r:
        assert r.backend == "software"
    with Renderer(tutorial_robot, backend="auto", size=(64, 48)):
        pass
    err = capsys.readouterr().err
    assert err.count("using the software renderer") == 1
    assert len(err.strip().splitlines()) == 1
    with pytest.raises(BackendError, match="test"):
        Renderer(tutorial_robot, backend="egl", size=(64, 48))


def test_osmesa_cannot_start_once_opengl_runs_on_egl(tutorial_robot):
    render_pose(tutorial_robot, None, backend="egl", size=(32, 32))
    with pytest.raises(BackendError) as info:
        render_pose(tutorial_robot, None, backend="osmesa", size=(32, 32))
    assert "already set up for egl in this process, so osmesa cannot start" in str(info.value)
    assert "PYOPENGL_PLATFORM=osmesa" in str(info.value.hint)


def test_osmesa_needs_a_newer_pyopengl_than_pyrender_pins(monkeypatch):
    from bras_kit.render import _pyrender

    monkeypatch.setattr(_pyrender, "loaded_platform", lambda: None)
    monkeypatch.setenv("PYOPENGL_PLATFORM", "egl")
    monkeypatch.setattr(_pyrender, "pyopengl_version", lambda: (3, 1, 0))
    with pytest.raises(BackendError, match="PyOpenGL 3.1.5 or later"):
        _pyrender.choose_platform("osmesa")
    assert os.environ["PYOPENGL_PLATFORM"] == "egl"  # untouched: EGL still works in this process
    monkeypatch.setattr(_pyrender, "pyopengl_version", lambda: (3, 1, 7))
    assert _pyrender.choose_platform("osmesa") == "osmesa"
    assert os.environ["PYOPENGL_PLATFORM"] == "osmesa"


def test_auto_prefers_egl_then_osmesa(monkeypatch):
    from bras_kit.render import _pyrender

    monkeypatch.setattr(_pyrender, "loaded_platform", lambda: None)
    monkeypatch.delenv("PYOPENGL_PLATFORM", raising=False)
    monkeypatch.setattr(_pyrender, "pyopengl_version", lambda: (3, 1, 7))
    found = {"EGL": "libEGL.so.1", "OSMesa": "libOSMesa.so.8"}
    monkeypatch.setattr(_pyrender.ctypes.util, "find_library", lambda name: found.get(name))
    assert _pyrender.choose_platform("auto") == "egl"
    monkeypatch.delenv("PYOPENGL_PLATFORM")
    del found["EGL"]
    assert _pyrender.choose_platform("auto") == "osmesa"
    monkeypatch.delenv("PYOPENGL_PLATFORM")
    found.clear()
    with pytest.raises(BackendError, match="neither libEGL nor libOSMesa"):
        _pyrender.choose_platform("auto")


def test_odd_picture_width_is_read_without_row_padding(tutorial_robot):
    image = render_pose(tutorial_robot, None, view="front", grid=False, size=(161, 121))
    assert image.shape == (121, 161, 3)
    blue_cols = rows_cols(hue_mask(image, BLUE_HUE))[1]
    grey_cols = rows_cols(grey_mask(image))[1]
    assert abs(blue_cols.mean() - grey_cols.mean()) < 1.5  # a padded read would shear the picture


# ---------------------------------------------------------------- meshes


def _mesh_package(tmp_path, with_mesh: bool = True, filename="package://demo_description/meshes/cube.stl"):
    import trimesh

    package = tmp_path / "demo_description"
    (package / "meshes").mkdir(parents=True)
    (package / "urdf").mkdir()
    (package / "package.xml").write_text("<package><name>demo_description</name></package>")
    if with_mesh:
        trimesh.creation.box(extents=(1.0, 1.0, 1.0)).export(package / "meshes" / "cube.stl")
    urdf = package / "urdf" / "demo.urdf"
    urdf.write_text("""<robot name="demo">
  <link name="base">
    <visual>
      <geometry><mesh filename="FILENAME" scale="0.1 0.1 0.6"/></geometry>
      <material name="vert"><color rgba="0.1 0.8 0.2 1"/></material>
    </visual>
  </link>
</robot>
""".replace("FILENAME", filename))
    return urdf


def test_package_mesh_is_found_scaled_and_coloured(tmp_path):
    from bras_kit.model.authoring import load

    robot = load(_mesh_package(tmp_path))
    image = render_pose(robot, None, view="front", grid=False, size=(200, 200),
                        package_paths=[str(tmp_path)])
    rows, cols = rows_cols(hue_mask(image, 128.0))
    height, width = rows.max() - rows.min() + 1, cols.max() - cols.min() + 1
    assert height / width == pytest.approx(6.0, rel=0.12)  # scale 0.1 x 0.6


def test_missing_mesh_is_drawn_as_a_red_stand_in_with_one_warning(tmp_path, capsys):
    from bras_kit.model.authoring import load

    urdf = _mesh_package(tmp_path, with_mesh=False)
    text = urdf.read_text().replace("</robot>", """  <link name="arm">
    <visual><origin xyz="0.3 0 0"/><geometry><box size="0.1 0.1 0.1"/></geometry>
      <material name="blue"><color rgba="0.1 0.2 0.9 1"/></material></visual>
    <visual><geometry><mesh filename="package://demo_description/meshes/cube.stl"/></geometry></visual>
  </link>
  <joint name="j" type="fixed"><parent link="base"/><child link="arm"/></joint>
</robot>""")
    urdf.write_text(text)
    image = render_pose(load(urdf), None, view="front", grid=False, size=(200, 200),
                        package_paths=[str(tmp_path)])
    warnings = [line for line in capsys.readouterr().err.splitlines() if line.startswith("warning:")]
    assert len(warnings) == 1 and "cube.stl" in warnings[0]  # one warning for the file used twice
    assert hue_mask(image, 0.0).sum() > 100  # the red stand-ins
    assert hue_mask(image, 230.0).sum() > 100  # the rest of the robot is drawn
    assert hue_mask(image, 128.0).sum() == 0  # the mesh's own green is not pretended


@pytest.mark.parametrize("filename", ["package://demo_description/meshes/cube.stl", "../meshes/cube.stl"])
def test_mesh_beside_the_urdf_needs_no_package_path(tmp_path, filename):
    from bras_kit.model.authoring import load

    robot = load(_mesh_package(tmp_path, filename=filename))  # urdf/demo.urdf inside its package
    image = render_pose(robot, None, view="front", grid=False, size=(120, 120))
    assert hue_mask(image, 128.0).sum() > 200


def test_unknown_package_says_how_to_find_it(tmp_path):
    from bras_kit.model.authoring import load
    from bras_kit.render.scene import resolve_mesh_path

    robot = load(_mesh_package(tmp_path, filename="package://elsewhere/meshes/cube.stl"))
    with pytest.raises(ModelError) as info:
        resolve_mesh_path("package://elsewhere/meshes/cube.stl", robot)
    assert "package 'elsewhere' not found" in str(info.value)
    assert "--package-path" in str(info.value.hint)


def test_tf_axes_are_drawn_over_the_segments_with_their_names(tutorial_robot):
    """Every joint's triad sits inside a segment; RViz's TF display shows it anyway, on top."""
    pose = {"epaule": 0.8, "coude": 1.2}
    with Renderer(tutorial_robot, fit=pose, view="iso", grid=False, size=(320, 240), tf=True, antialias=False) as r:
        drawn = r.render(pose)
        for mesh in r._backend._solids:  # the same camera with the segments taken away
            mesh.is_visible = False
        axes_only = r.render(pose)
        for mesh in r._backend._solids:
            mesh.is_visible = True
        with Renderer(tutorial_robot, fit=pose, view="iso", grid=False, size=(320, 240), antialias=False) as plain_r:
            solids = silhouette(plain_r.render(pose))
    for channel in range(3):
        wanted = pure_mask(axes_only, channel)
        inside = wanted & solids
        assert inside.sum() > 20  # part of this axis runs inside a segment...
        assert (pure_mask(drawn, channel) & inside).sum() >= 0.95 * inside.sum()  # ...and is drawn
    # the names: dark text appears next to each frame origin, on top of whatever is there
    text = (drawn.max(axis=2) < 60) & ~(axes_only.max(axis=2) < 60)
    assert text.sum() == 0  # the names are part of both pictures (same camera, same origins)
    assert (drawn.max(axis=2) < 60).sum() > 40
