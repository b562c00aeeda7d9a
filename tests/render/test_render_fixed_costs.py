"""What the picture path pays once (issue 15): shapes built without trimesh, pyrender loaded
without trimesh/networkx/scipy, OpenGL renderers kept across robots, the GIF encoded in a
worker. Speed itself is measured in benchmarks/render_*.py, not here."""

from __future__ import annotations

import gc
import io
import math
import subprocess
import sys

import numpy as np
import pytest

from bras_kit.render import Renderer, render_pose
from bras_kit.render.scene import box_mesh, cylinder_mesh, rod_mesh, sphere_mesh
from bras_kit.render.sequence import GifWriter, _nearest

SIZE = (160, 120)


def signed_volume(vertices: np.ndarray, faces: np.ndarray) -> float:
    """Divergence theorem: positive when every triangle winds counter-clockwise seen from outside."""
    a, b, c = (vertices[faces[:, k]] for k in range(3))
    return float(np.einsum("ij,ij->i", a, np.cross(b, c)).sum() / 6.0)


def closed(faces: np.ndarray) -> bool:
    """Every edge used once in each direction: a closed surface, consistently wound."""
    edges = np.concatenate([faces[:, [0, 1]], faces[:, [1, 2]], faces[:, [2, 0]]])
    forward = {tuple(e) for e in edges.tolist()}
    return len(forward) == len(edges) and all((b, a) in forward for a, b in forward)


def test_box_is_closed_outward_and_has_its_volume():
    mesh = box_mesh([0.2, -0.4, 1.0])  # a negative size is a size
    assert closed(mesh.faces) and len(mesh.faces) == 12
    assert signed_volume(mesh.vertices, mesh.faces) == pytest.approx(0.2 * 0.4 * 1.0)
    assert np.allclose(mesh.vertices.min(axis=0), [-0.1, -0.2, -0.5])


def test_cylinder_is_a_closed_prism_of_its_polygon():
    n, r, length = 32, 0.05, 0.3
    mesh = cylinder_mesh(r, length, sections=n)
    assert closed(mesh.faces) and len(mesh.faces) == 4 * n
    polygon = n / 2 * r * r * math.sin(2 * math.pi / n)  # area of the regular n-gon inside the circle
    assert signed_volume(mesh.vertices, mesh.faces) == pytest.approx(polygon * length)
    assert np.allclose(np.linalg.norm(mesh.vertices[:2 * n, :2], axis=1), r)
    assert mesh.vertices[:, 2].min() == pytest.approx(-0.15) and mesh.vertices[:, 2].max() == pytest.approx(0.15)


def test_sphere_is_an_icosphere_on_its_radius():
    mesh = sphere_mesh(0.5, subdivisions=2)
    assert closed(mesh.faces)
    assert (len(mesh.vertices), len(mesh.faces)) == (162, 320)  # 10 * 4^2 + 2 vertices, 20 * 4^2 faces
    assert np.allclose(np.linalg.norm(mesh.vertices, axis=1), 0.5)
    volume = signed_volume(mesh.vertices, mesh.faces)
    assert 0.95 * (4 / 3 * math.pi * 0.125) < volume < 4 / 3 * math.pi * 0.125  # inscribed, close


def test_rod_runs_from_the_origin_to_its_end():
    end = np.array([0.0, 0.3, 0.4])
    rod = rod_mesh(0.01, end)
    axis = end / 0.5
    along = rod.vertices @ axis
    assert along.min() == pytest.approx(0.0, abs=1e-12) and along.max() == pytest.approx(0.5)
    off_axis = rod.vertices - np.outer(along, axis)
    assert np.linalg.norm(off_axis, axis=1).max() == pytest.approx(0.01)
    assert signed_volume(rod.vertices, rod.faces) > 0


def test_pictures_load_neither_trimesh_nor_networkx_nor_scipy():
    code = ("import sys, numpy as np\n"
            "from bras_kit.model.authoring import arm\n"
            "from bras_kit.render import render_pose, save_gif, render_motion\n"
            "import io\n"
            "image = render_pose(arm(), {'coude': 1.0}, size=(64, 48), tf=True)\n"
            "save_gif(render_motion(arm(), np.zeros((3, 2)), size=(64, 48)), io.BytesIO())\n"
            "print(sorted(m for m in ('trimesh', 'networkx', 'scipy', 'pyglet') if m in sys.modules))\n"
            "import trimesh, networkx, pyrender\n"  # the real ones still load afterwards
            "print(hasattr(trimesh, 'Trimesh'), hasattr(networkx, 'DiGraph'), callable(pyrender.Viewer))\n")
    result = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert result.stdout.split("\n")[:2] == ["[]", "True True True"]


def test_a_renderer_dropped_without_close_leaves_the_others_working(tutorial_robot):
    first = render_pose(tutorial_robot, {"epaule": 0.5}, size=SIZE)
    dropped = Renderer(tutorial_robot, size=SIZE, antialias=False)
    dropped.render({})
    del dropped  # never closed: pyrender's own clean-up would end the EGL display of every renderer
    gc.collect()
    with Renderer(tutorial_robot, size=SIZE, antialias=False) as again:
        plain = again.render({"epaule": 0.5})
    assert np.array_equal(render_pose(tutorial_robot, {"epaule": 0.5}, size=SIZE), first)
    assert (plain != 255).any(axis=2).sum() > 100  # the arm is drawn


def test_one_renderer_draws_the_same_picture_as_a_fresh_one(tutorial_robot):
    poses = [{"epaule": 0.1 * k, "coude": -0.2 * k} for k in range(4)]
    with Renderer(tutorial_robot, fit=poses, size=SIZE) as renderer:
        kept = [renderer.render(p) for p in poses]
    for pose, image in zip(poses, kept):
        with Renderer(tutorial_robot, fit=poses, size=SIZE) as fresh:
            assert np.array_equal(fresh.render(pose), image)


def test_nearest_palette_entry_is_exact():
    rng = np.random.default_rng(3)
    palette = rng.integers(0, 256, (255, 3))
    colours = rng.integers(0, 256, (5000, 3))
    chosen = _nearest(colours, palette)
    distances = ((colours[:, None, :] - palette[None, :, :]) ** 2).sum(axis=2)
    assert np.array_equal(distances[np.arange(len(colours)), chosen], distances.min(axis=1))


class FailingFile(io.BytesIO):
    def __init__(self, limit: int) -> None:
        super().__init__()
        self.limit = limit

    def write(self, data) -> int:  # type: ignore[no-untyped-def, override]
        if self.tell() + len(data) > self.limit:
            raise OSError(28, "No space left on device")
        return super().write(data)


def test_a_write_error_in_the_gif_worker_reaches_the_caller():
    rng = np.random.default_rng(5)
    frames = [rng.integers(0, 256, (40, 50, 3), dtype=np.uint8) for _ in range(12)]  # noise: kilobytes a frame
    writer = GifWriter(FailingFile(limit=6000), 10, frames[:4])
    with pytest.raises(OSError, match="No space left"):
        for frame in frames:
            writer.write(frame)
        writer.close()


def test_the_gif_writer_copies_frames_it_has_not_encoded_yet():
    from PIL import Image

    buffer = np.zeros((20, 30, 3), np.uint8)
    target = io.BytesIO()
    writer = GifWriter(target, 10, [np.zeros((20, 30, 3), np.uint8), np.full((20, 30, 3), 200, np.uint8)])
    for value in (0, 200, 0):
        buffer[:] = value  # the caller reuses one array
        writer.write(buffer)
    writer.close()
    image = Image.open(io.BytesIO(target.getvalue()))
    seen = []
    for index in range(image.n_frames):
        image.seek(index)
        seen.append(int(np.asarray(image.convert("RGB"))[0, 0, 0]))
    assert seen == [0, 200, 0]


def _ascii_stl(mesh) -> str:  # type: ignore[no-untyped-def]
    rows = ["solid t"]
    for face in mesh.faces:
        rows += ["facet normal 0 0 0", "outer loop"]
        rows += [f"vertex {x:.9g} {y:.9g} {z:.9g}" for x, y, z in mesh.vertices[face]]
        rows += ["endloop", "endfacet"]
    return "\n".join(rows + ["endsolid t", ""])


def test_mesh_files_are_read_once_and_mirroring_keeps_them_outward(tmp_path, tutorial_robot):
    from bras_kit.model.robot import Geometry, Origin, Visual
    from bras_kit.render import scene

    path = tmp_path / "cube.stl"
    path.write_text(_ascii_stl(box_mesh([0.1, 0.2, 0.3])))
    plain = scene.visual_mesh(tutorial_robot, Visual(Origin(), Geometry("mesh", filename=str(path))))
    mirrored = scene.visual_mesh(tutorial_robot, Visual(Origin((1.0, 0.0, 0.0)), Geometry(
        "mesh", filename=str(path), scale=(-2.0, 1.0, 1.0))))
    assert signed_volume(plain.vertices, plain.faces) == pytest.approx(0.006)
    assert signed_volume(mirrored.vertices, mirrored.faces) == pytest.approx(0.012)  # still outward
    assert np.allclose(mirrored.vertices[:, 0].min(), 0.9)
    from bras_kit import meshes

    key = next(k for k in meshes._memory if k[0] == str(path.resolve()))
    path.write_text(_ascii_stl(box_mesh([0.5, 0.5, 0.5])))  # a changed file is read again
    import os

    os.utime(path, ns=(key[1] + 10**9, key[1] + 10**9))
    again = scene.visual_mesh(tutorial_robot, Visual(Origin(), Geometry("mesh", filename=str(path))))
    assert signed_volume(again.vertices, again.faces) == pytest.approx(0.125)


def test_a_kept_renderer_serves_another_thread(tutorial_robot):
    from concurrent.futures import ThreadPoolExecutor

    here = render_pose(tutorial_robot, {"coude": 0.7}, size=SIZE)  # leaves a renderer of this size kept
    with ThreadPoolExecutor(1) as pool:
        there = pool.submit(render_pose, tutorial_robot, {"coude": 0.7}, size=SIZE).result()
    assert np.array_equal(here, there)
    assert np.array_equal(render_pose(tutorial_robot, {"coude": 0.7}, size=SIZE), here)  # and back here


def test_a_display_ended_by_another_library_gives_a_fresh_renderer():
    """MuJoCo's EGL context, when freed, ends the EGL display every context shares: the pooled
    renderer is then dead, and the next picture must open a new one rather than fail. (In a
    fresh process: ending the display would disturb the other tests' renderers.)"""
    script = (
        "import numpy as np\n"
        "from bras_kit.model.authoring import arm\n"
        "from bras_kit.render import _pyrender, render_pose\n"
        "robot = arm()\n"
        "first = render_pose(robot, {'coude': 0.7}, size=(96, 72), backend='egl')\n"
        "assert _pyrender._POOL._kept, 'the renderer went back to the pool'\n"
        "from OpenGL.EGL import eglTerminate\n"
        "for renderer in _pyrender._POOL._kept.values():\n"
        "    eglTerminate(renderer._platform._egl_display)  # what another library's clean-up does\n"
        "again = render_pose(robot, {'coude': 0.7}, size=(96, 72), backend='egl')\n"
        "assert np.array_equal(first, again)\n"
        "print('ok')\n"
    )
    done = subprocess.run([sys.executable, "-c", script], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0 and done.stdout.strip() == "ok", done.stderr


def _orange_columns(image: np.ndarray) -> float:
    """Mean column of the forearm's orange pixels (red high, blue low)."""
    red, blue = image[..., 0].astype(int), image[..., 2].astype(int)
    rows, columns = np.nonzero((red > 180) & (blue < 90))
    assert len(columns) > 20, "the orange forearm is not in the picture"
    return float(columns.mean())


def test_streamed_frames_are_the_poses_in_their_order(tutorial_robot):
    """A sequence renderer draws each frame while the one before is read back: every pose comes
    out once, in order, as the one-picture-at-a-time path draws it."""
    elbow = [0.0, 1.2, 0.6, -0.6, -1.2, 0.0, 1.2]
    poses = np.array([[0.0, q] for q in elbow])
    with Renderer(tutorial_robot, fit=poses, size=SIZE, view="front", sequence=True, antialias=False) as seq:
        streamed = list(seq.frames(poses))
    with Renderer(tutorial_robot, fit=poses, size=SIZE, view="front", antialias=False) as one:
        single = [one.render(q) for q in poses]
    assert len(streamed) == len(poses)
    assert all(np.array_equal(a, b) for a, b in zip(streamed, single))
    # the forearm leans one way, then the other, as sin(coude) says (a bent elbow moves it sideways)
    columns = [_orange_columns(image) for image in streamed]
    lean = np.sign(np.diff(columns)) * np.sign(-np.diff(np.sin(elbow)))
    assert abs(lean.sum()) == len(lean)


def test_a_stream_left_early_leaves_the_renderer_drawing_right(tutorial_robot):
    poses = np.array([[0.3 * k, -0.2 * k] for k in range(6)])
    with Renderer(tutorial_robot, fit=poses, size=SIZE, sequence=True, antialias=False) as seq:
        for count, _ in enumerate(seq.frames(poses), 1):
            if count == 2:
                break
        after = seq.render(poses[4])
        again = list(seq.frames(poses))
    with Renderer(tutorial_robot, fit=poses, size=SIZE, antialias=False) as fresh:
        expected = [fresh.render(q) for q in poses]
    assert np.array_equal(after, expected[4])
    assert len(again) == len(poses) and all(np.array_equal(a, b) for a, b in zip(again, expected))


def _ink(image: np.ndarray) -> float:
    """How much darker than the white background the picture is, summed over its pixels."""
    return float((255 - image.astype(float)).sum())


@pytest.mark.parametrize("size", [(320, 240), (4100, 48)])
def test_smooth_pictures_blend_edges_and_keep_each_shape_s_ink(tutorial_robot, size):
    """Pictures are antialiased (supersampled 2x2; multisampled past 4096 pixels a side): the
    edges get in-between colours, while averaging keeps the amount of colour each shape puts on
    the picture, the grid's thin lines included."""
    pictures = {}
    for smooth in (True, False):
        for grid in (True, False):
            pictures[smooth, grid] = render_pose(tutorial_robot, {"coude": 0.7}, size=size, grid=grid,
                                                 antialias=smooth)
    assert pictures[True, True].shape == (size[1], size[0], 3)
    colours = {smooth: len(np.unique(pictures[smooth, False].reshape(-1, 3), axis=0)) for smooth in (True, False)}
    assert colours[True] > 2 * colours[False]
    arm_ink = {smooth: _ink(pictures[smooth, False]) for smooth in (True, False)}
    grid_ink = {smooth: _ink(pictures[smooth, True]) - arm_ink[smooth] for smooth in (True, False)}
    assert arm_ink[True] == pytest.approx(arm_ink[False], rel=0.05)
    assert grid_ink[False] > 0 and grid_ink[True] == pytest.approx(grid_ink[False], rel=0.3)
