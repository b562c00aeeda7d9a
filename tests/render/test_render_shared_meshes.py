"""What one process shares between the robots it draws (a grading worker draws a whole class):
mesh files decoded once, their pieces placed once per origin, their OpenGL buffers uploaded once
per renderer; and nothing of it changes a picture.

Oracles: hand-placed vertices of a tetrahedron written by hand (tests/data/shared_mesh), the
decoder itself run afresh, pyrender's own upload calls counted, and pictures of the same
submission drawn by a process that drew nothing before."""

from __future__ import annotations

import contextlib
import os
import shutil
import site
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest
from paths import TESTS

from bras_kit import meshes
from bras_kit.kinematics.frames import fk_batch, tf_tree
from bras_kit.model.authoring import load
from bras_kit.render import scene

DATA = TESTS / "data"
TIP = np.array([[0, 0, 0], [0.2, 0, 0], [0, 0.1, 0], [0, 0, 0.3]])  # the vertices written in tip.stl


def _share() -> Path:
    for base in map(Path, site.getsitepackages()):
        if (base / "cmeel.prefix" / "share" / "example-robot-data").is_dir():
            return base / "cmeel.prefix" / "share" / "example-robot-data"
    raise AssertionError("example-robot-data (the dev extra) is needed for these tests")


UR = _share() / "robots" / "ur_description"


def _ur5_copy(folder: Path) -> Path:
    """A learner's folder holding example-robot-data's UR5 with its own copies of the visual meshes."""
    (folder / "meshes" / "visual").mkdir(parents=True)
    for mesh in (UR / "meshes" / "ur5" / "visual").iterdir():
        shutil.copyfile(mesh, folder / "meshes" / "visual" / mesh.name)
    text = (UR / "urdf" / "ur5_robot.urdf").read_text()
    text = text.replace("package://example-robot-data/robots/ur_description/meshes/ur5/", "meshes/")
    text = text.replace("meshes/collision/", "meshes/visual/").replace(".stl", ".dae")  # no collision meshes here
    (folder / "ur5.urdf").write_text(text)
    return folder


def _rows(array: np.ndarray) -> np.ndarray:
    return np.array(sorted(map(tuple, np.round(np.asarray(array, dtype=float), 9))))


@pytest.fixture
def fresh(monkeypatch):
    """Nothing remembered by this process, and no disk cache: every file is decoded here."""
    monkeypatch.setattr(meshes, "_memory", {})
    monkeypatch.setattr(meshes, "_by_content", {})
    monkeypatch.setattr(meshes, "_by_bytes", {})
    monkeypatch.setattr(meshes, "_disk", False)
    monkeypatch.setattr(scene, "_placed", scene.BoundedMemo(scene.PLACED_MEMORY_BYTES))



@contextlib.contextmanager
def _counted_uploads():
    """The primitives pyrender (as bras-kit loads it) sends to OpenGL while the block runs."""
    from bras_kit.render._compat import import_pyrender

    primitive = import_pyrender().primitive.Primitive
    uploads: list[object] = []
    real = primitive._add_to_context

    def counted(self):  # noqa: ANN001, ANN202
        uploads.append(self)
        return real(self)

    primitive._add_to_context = counted
    try:
        yield uploads
    finally:
        primitive._add_to_context = real

def test_copies_of_a_mesh_file_are_hashed_and_decoded_once_and_give_a_fresh_decode(fresh, tmp_path, monkeypatch):
    from bras_kit.meshes import cache, decode

    real, calls = decode.decode, []
    monkeypatch.setattr(decode, "decode", lambda *args: calls.append(args) or real(*args))
    hash_, hashed = cache.content_key, []
    monkeypatch.setattr(cache, "content_key", lambda *args: hashed.append(args) or hash_(*args))
    source = UR / "meshes" / "ur5" / "visual" / "forearm.dae"
    copies = [tmp_path / "a.dae", tmp_path / "b" / "forearm.dae"]
    copies[1].parent.mkdir()
    for copy in copies:
        shutil.copyfile(source, copy)
    first, second = (meshes.load_mesh(str(copy)) for copy in copies)
    assert len(calls) == 1 and len(hashed) == 1  # the copy's bytes are compared with the first's, not hashed
    changed = bytearray(source.read_bytes())
    changed[-40] ^= 1  # one bit in the last lines: the same length, other bytes
    (tmp_path / "c.dae").write_bytes(bytes(changed))
    meshes.load_mesh(str(tmp_path / "c.dae"))
    assert len(hashed) == 2  # bytes of the same length that differ are hashed (and looked up) on their own
    alone = real(str(source), None, source.read_bytes())
    for got in (first, second):
        assert np.array_equal(got.vertices, alone.vertices) and np.array_equal(got.faces, alone.faces)
        assert np.array_equal(got.colors, alone.colors, equal_nan=True)


def test_two_learners_copies_share_pieces_placed_where_their_origins_say(fresh, tmp_path):
    robots = []
    for learner in ("a", "b"):
        shutil.copytree(DATA / "shared_mesh", tmp_path / learner)
        robots.append(load(str(tmp_path / learner / "two_tips.urdf")))
    parts_a, parts_b = (scene.robot_parts(tf_tree(robot)) for robot in robots)
    # base: a quarter turn about z, then xyz 1 2 3: (x, y, z) -> (1 - y, 2 + x, 3 + z)
    turned = np.column_stack([1 - TIP[:, 1], 2 + TIP[:, 0], 3 + TIP[:, 2]])
    assert np.allclose(_rows(parts_a[0].vertices), _rows(turned), atol=1e-7)
    assert np.allclose(_rows(parts_a[1].vertices), _rows(2 * TIP + [0, 0, 0.5]), atol=1e-7)  # scale 2, up 0.5
    for mine, theirs in zip(parts_a, parts_b):
        assert mine.vertices is theirs.vertices and mine.faces is theirs.faces
        assert np.array_equal(mine.bounds, [mine.vertices.min(axis=0), mine.vertices.max(axis=0)])
        with pytest.raises(ValueError):
            mine.vertices[0, 0] = 5.0  # shared with the other scene: refused, never changed in place


def test_part_corners_and_floor_are_those_of_each_parts_box(fresh):
    tree = tf_tree(load(str(DATA / "shared_mesh" / "two_tips.urdf")))
    parts = scene.robot_parts(tree)
    corners = scene.part_corners(parts)
    low, high = TIP.min(axis=0), TIP.max(axis=0)  # the tip link's box: the tetrahedron's, doubled and raised
    wanted = [(x, y, z) for x in (2 * low[0], 2 * high[0]) for y in (2 * low[1], 2 * high[1])
              for z in (2 * low[2] + 0.5, 2 * high[2] + 0.5)]
    assert np.allclose(corners[1], wanted, atol=1e-6)  # float32 mesh vertices
    poses = fk_batch(tree, np.array([[0.0], [0.5]]))  # the tip moves, the base does not
    assert scene.floor_height(parts, poses) == pytest.approx(3.0)  # the base's lowest point: z = 3 + 0


DRAW_ALONE = """
import sys
import numpy as np
from bras_kit.model.authoring import load
from bras_kit.render import render_pose
np.save(sys.argv[2], render_pose(load(sys.argv[1]), {}, size=(480, 360)))
"""


def test_a_robot_drawn_after_others_is_the_one_drawn_alone_and_sends_its_meshes_once(fresh, tmp_path):
    """Without TF axes: pyrender breaks ties between axes at one distance by object address, so
    pictures with axes may differ in a few pixels from one process to another (before this too)."""
    from bras_kit.render import render_pose

    first, second = _ur5_copy(tmp_path / "first"), _ur5_copy(tmp_path / "second")
    other = tmp_path / "other"
    shutil.copytree(DATA / "shared_mesh", other)
    env = {**os.environ, "PYOPENGL_PLATFORM": "egl", "BRAS_KIT_NO_CACHE": "1"}
    subprocess.run([sys.executable, "-c", DRAW_ALONE, str(second / "ur5.urdf"), str(tmp_path / "alone.npy")], env=env,
                   check=True, timeout=300)
    wanted = np.load(tmp_path / "alone.npy")

    drawn = []
    with _counted_uploads() as uploads:
        for urdf in (first / "ur5.urdf", second / "ur5.urdf", other / "two_tips.urdf", second / "ur5.urdf"):
            before = len(uploads)
            image = render_pose(load(str(urdf)), {}, size=(480, 360))
            drawn.append((len(uploads) - before, image))
    (first_uploads, _), (second_uploads, after_one), _, (_, after_other) = drawn
    assert np.array_equal(after_one, wanted)  # drawn with the buffers of the first learner's meshes
    assert np.array_equal(after_other, wanted)  # and after another robot made the renderer free them
    assert first_uploads >= 7 and second_uploads == 1  # the second UR5 sends only its ground grid


def test_grading_a_class_sends_a_learners_copy_of_the_same_robot_once(fresh, tmp_path):
    from bras_kit.grade.rubric import load_rubric
    from bras_kit.grade.submissions import Submission
    from bras_kit.grade.worker import Options, grade

    pictures = tmp_path / "pictures"
    pictures.mkdir()
    learners = [(name, _ur5_copy(tmp_path / "class" / name)) for name in ("first", "second")]
    counts, results = [], []
    with _counted_uploads() as uploads:
        for learner, folder in learners:
            before = len(uploads)
            results.append(grade(Submission(learner, str(folder), "folder"), load_rubric(None),
                                 Options(pictures=str(pictures))))
            counts.append(len(uploads) - before)
    assert [r["picture"] for r in results] == ["pictures/first.png", "pictures/second.png"]
    assert results[0]["items"] == results[1]["items"] and results[0]["findings"] == results[1]["findings"]
    assert counts[0] >= 7 + 1 and counts[1] == 1  # meshes and the TF axes once; then the ground grid only
    assert np.array_equal(_robot_mask(_picture(pictures / "first.png")), _robot_mask(_picture(pictures / "second.png")))


def _robot_mask(image: np.ndarray) -> np.ndarray:
    """Where the picture is not its white background."""
    return (image < 250).any(axis=2)


def _picture(path: Path) -> np.ndarray:
    from PIL import Image

    with Image.open(path) as image:
        return np.asarray(image.convert("RGB"))


def test_frame_names_are_rendered_once_per_process_with_the_pixels_of_pillows_own_font(monkeypatch):
    from PIL import Image, ImageDraw, ImageFont

    from bras_kit.render.renderer import label_font

    def names(font) -> np.ndarray:  # noqa: ANN001
        image = Image.new("RGB", (320, 120), (90, 140, 200))
        draw = ImageDraw.Draw(image)
        for k, name in enumerate(("epaule", "coude", "avant_bras")):
            draw.text((10.3 + 3 * k, 12.6 + 30 * k), name, fill=(20, 20, 20), font=font, stroke_width=2,
                      stroke_fill=(255, 255, 255))
        return np.asarray(image)

    wanted = names(ImageFont.load_default(size=13))
    first = names(label_font(13))
    real, rendered = ImageFont.FreeTypeFont.getmask2, []
    monkeypatch.setattr(ImageFont.FreeTypeFont, "getmask2", lambda *a, **k: rendered.append(a) or real(*a, **k))
    again = names(label_font(13))
    assert np.array_equal(first, wanted) and np.array_equal(again, wanted)
    assert rendered == []  # the same names at the same places: FreeType is not asked again
