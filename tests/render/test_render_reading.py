"""Reading the pictures (issue 22): the default camera fills the frame for real robots, frame
names that coincide stack, the axes' colours have a legend, ``geometry`` draws the collision
shapes, and the plot and workspace figures say what they show. Oracles: pixels of the pictures
and the texts matplotlib holds."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pytest

from bras_kit.model.authoring import load
from bras_kit.render import render_pose

ROBOTS = next((Path(base) / "cmeel.prefix" / "share" / "example-robot-data" / "robots" for base in sys.path
               if (Path(base) / "cmeel.prefix" / "share" / "example-robot-data").is_dir()), Path("missing"))
PACKAGES = str(ROBOTS.parent)
REAL = {
    "ur5": ROBOTS / "ur_description" / "urdf" / "ur5_robot.urdf",
    "panda": ROBOTS / "panda_description" / "urdf" / "panda.urdf",
    "talos": ROBOTS / "talos_data" / "robots" / "talos_reduced.urdf",
}


DARK = (48, 48, 48)  # RViz's background: Panda's white links stand out on it


def _robot_pixels(image: np.ndarray) -> np.ndarray:
    """Pixels that are not the dark background."""
    return np.abs(image.astype(int) - np.array(DARK)).sum(axis=2) > 30


@pytest.mark.parametrize("name", ["tutorial", *REAL])
def test_the_default_camera_fills_the_picture_with_the_robot(name, tutorial_robot):
    robot = tutorial_robot if name == "tutorial" else load(str(REAL[name]), package_paths=(PACKAGES,))
    image = render_pose(robot, None, grid=False, size=(320, 240), package_paths=(PACKAGES,), antialias=False,
                        background="rviz")
    rows, columns = np.nonzero(_robot_pixels(image))
    assert len(rows) > 500
    height = (rows.max() - rows.min() + 1) / image.shape[0]
    width = (columns.max() - columns.min() + 1) / image.shape[1]
    assert height >= 0.4 or width >= 0.4, (height, width)
    # and all of it in the picture: nothing touches the edges
    assert rows.min() > 0 and columns.min() > 0
    assert rows.max() < image.shape[0] - 1 and columns.max() < image.shape[1] - 1


def _dark_rows(image: np.ndarray) -> np.ndarray:
    return np.nonzero((image.astype(int).sum(axis=2) < 200).any(axis=1))[0]


def test_names_of_frames_at_one_place_are_written_one_above_the_other(tutorial_robot):
    from bras_kit.render import Renderer
    from bras_kit.render.renderer import frame_names

    with Renderer(tutorial_robot, size=(320, 240)) as renderer:
        camera = renderer.camera
    blank = np.full((240, 320, 3), 255, np.uint8)
    here = np.array([[0.0, 0.0, 0.3]])
    one = _dark_rows(frame_names(blank, camera, ["base"], here)[:200])  # above the legend
    two = _dark_rows(frame_names(blank, camera, ["base", "bras"], np.vstack([here, here]))[:200])
    assert len(one) > 5
    # the second name sits fully above the first: twice the rows of ink, none shared twice
    assert two.max() == one.max() and two.max() - two.min() + 1 >= 2 * (one.max() - one.min() + 1) - 2


def test_pictures_with_tf_axes_say_which_colour_is_which_axis(tutorial_robot):
    with_tf = render_pose(tutorial_robot, None, tf=True, size=(320, 240), antialias=False)
    without = render_pose(tutorial_robot, None, tf=False, size=(320, 240), antialias=False)
    corner = (slice(200, 240), slice(0, 140))  # the lower left corner, where the legend goes

    def columns(image: np.ndarray, channel: int) -> np.ndarray:
        others = [c for c in range(3) if c != channel]
        part = image[corner].astype(int)
        mask = (part[..., channel] > 200) & (part[..., others[0]] < 60) & (part[..., others[1]] < 60)
        return np.nonzero(mask)[1]

    red, green, blue = (columns(with_tf, c) for c in range(3))
    assert len(red) > 20 and len(green) > 20 and len(blue) > 20
    assert red.mean() < green.mean() < blue.mean()  # x, y, z from left to right
    assert all(len(columns(without, c)) == 0 for c in range(3))


def test_collision_geometry_shows_the_pandas_own_collision_meshes():
    robot = load(str(REAL["panda"]), package_paths=(PACKAGES,))
    options = dict(grid=False, size=(240, 320), package_paths=(PACKAGES,), antialias=False, background="rviz")
    visual = render_pose(robot, None, geometry="visual", **options)
    collision = render_pose(robot, None, geometry="collision", **options)
    both = render_pose(robot, None, geometry="both", **options)
    seen_visual, seen_collision = _robot_pixels(visual), _robot_pixels(collision)
    # panda's collision/*.stl are coarser, fatter hulls than its visual meshes: other pixels
    assert (seen_collision & ~seen_visual).sum() > 0.05 * seen_visual.sum()
    # drawn in the collision colour (green above red and blue), which the visuals never use
    pixels = collision[seen_collision].astype(int)
    assert np.mean((pixels[:, 1] > pixels[:, 0] + 20) & (pixels[:, 1] > pixels[:, 2] + 20)) > 0.8
    pixels = visual[seen_visual].astype(int)
    assert np.mean((pixels[:, 1] > pixels[:, 0] + 20) & (pixels[:, 1] > pixels[:, 2] + 20)) < 0.05
    union = seen_visual | seen_collision  # "both": the collision hulls see-through over the visuals
    assert (_robot_pixels(both) & union).sum() >= 0.97 * union.sum()


def test_unknown_geometry_is_refused_with_the_choices(tutorial_robot):
    from bras_kit.core.errors import ParameterError

    with pytest.raises(ParameterError) as error:
        render_pose(tutorial_robot, None, geometry="collisions")
    assert "visual" in str(error.value.hint) and "both" in str(error.value.hint)


def _texts(figure) -> list[str]:
    return [t.get_text() for t in figure.findobj(lambda a: hasattr(a, "get_text"))]


def _states(robot, spec: str):
    from bras_kit.motion import motion_from_specs, sample

    return sample(motion_from_specs(robot, [spec]), 3.0, 20)


def test_plot_names_the_plane_perpendicular_to_the_joint_axes_in_both_languages(tutorial_robot):
    from bras_kit.diagrams.plot import plot_motion

    states = _states(tutorial_robot, "coude=0.5*sin(t)")
    english = " ".join(_texts(plot_motion(tutorial_robot, states, lang="en")))
    french = " ".join(_texts(plot_motion(tutorial_robot, states, lang="fr")))
    assert "plane perpendicular to the joint axes" in english
    assert "plan perpendiculaire aux axes des articulations" in french
    assert "plan des axes" not in french


def test_plot_legend_shows_samples_beyond_a_limit_only_when_there_are_some(tutorial_robot):
    from bras_kit.diagrams.plot import plot_motion

    inside = _texts(plot_motion(tutorial_robot, _states(tutorial_robot, "coude=0.5*sin(t)"), lang="fr"))
    beyond = _texts(plot_motion(tutorial_robot, _states(tutorial_robot, "coude=2.5*sin(t)"), lang="fr"))
    assert not any("au-delà d'une limite" in t for t in inside)
    assert any("au-delà d'une limite" in t for t in beyond)


def test_workspace_figure_marks_and_names_the_region_below_the_floor(tutorial_robot):
    from matplotlib.patches import Polygon, Rectangle

    from bras_kit.ik import workspace_figure
    from bras_kit.kinematics.frames import tf_tree

    figure, axes, _summary = workspace_figure(tf_tree(tutorial_robot), 20_000)
    texts = [t.get_text() for t in axes.texts]
    assert any("below the floor" in text for text in texts), texts
    hatched = [p for p in axes.patches if isinstance(p, (Polygon, Rectangle)) and p.get_hatch()]
    assert len(hatched) == 1
    # from the bottom of the axes up to the floor: the base's bottom, its 0.1 m cylinder centred at z = 0
    ys = hatched[0].get_path().transformed(hatched[0].get_patch_transform()).vertices[:, 1] \
        if isinstance(hatched[0], Rectangle) else hatched[0].get_xy()[:, 1]
    assert min(ys) == pytest.approx(axes.get_ylim()[0]) and max(ys) == pytest.approx(-0.05, abs=1e-9)
