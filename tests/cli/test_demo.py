"""bras-kit demo: everything the tutorial builds, in one folder, with the figures drawn by a
second process while the first renders (a failure there falls back to drawing in-process)."""

from __future__ import annotations

import os
import tempfile

import numpy as np
import pytest
from PIL import Image

EXPECTED = ["bras.gif", "bras_description", "frames.pdf", "frames.png", "motion.png", "pose.png"]


@pytest.fixture
def private_tmp(tmp_path, monkeypatch):
    folder = tmp_path / "tmp"
    folder.mkdir()
    monkeypatch.setattr(tempfile, "tempdir", str(folder))
    return folder


def _frame_tree_png(path) -> np.ndarray:
    from bras_kit.cli.demo import DEMO_POSE
    from bras_kit.diagrams import frame_diagram
    from bras_kit.model.authoring import arm

    frame_diagram(arm(), DEMO_POSE, path=str(path))
    return np.asarray(Image.open(path))


def test_demo_writes_what_the_tutorial_builds(run_cli, tmp_path, private_tmp):
    folder = tmp_path / "demo"
    code, out, err = run_cli("demo", str(folder), "--duration", "2", "--fps", "10")
    assert code == 0, err
    assert sorted(p.name for p in folder.iterdir() if not p.name.startswith(".")) == EXPECTED
    assert (folder / "bras_description" / "package.xml").is_file()
    assert (folder / "frames.pdf").read_bytes().startswith(b"%PDF")
    with Image.open(folder / "bras.gif") as gif:
        assert gif.n_frames == 2 * 10  # duration x fps
    # the figure the second process drew is the one drawn here
    assert np.array_equal(np.asarray(Image.open(folder / "frames.png")), _frame_tree_png(tmp_path / "here.png"))
    assert list(private_tmp.iterdir()) == []  # its temporary folder is gone
    assert out.index("frame tree") > out.index("animating")  # steps reported in order


def test_demo_draws_the_figures_itself_when_the_second_process_fails(run_cli, tmp_path, private_tmp, monkeypatch):
    import bras_kit.cli.demo as demo

    parent, original = os.getpid(), demo._draw_diagrams

    def fails_in_the_child(*args):  # type: ignore[no-untyped-def]
        if os.getpid() != parent:
            raise RuntimeError("worker lost")
        original(*args)

    monkeypatch.setattr(demo, "_draw_diagrams", fails_in_the_child)
    folder = tmp_path / "demo"
    code, _, err = run_cli("demo", str(folder), "--duration", "1", "--fps", "5")
    assert code == 0, err
    assert np.array_equal(np.asarray(Image.open(folder / "frames.png")), _frame_tree_png(tmp_path / "here.png"))
    assert (folder / "motion.png").stat().st_size > 1000
    assert list(private_tmp.iterdir()) == []


def test_demo_reruns_in_its_folder_and_refuses_a_foreign_one(run_cli, tmp_path, private_tmp):
    folder = tmp_path / "demo"
    assert run_cli("demo", str(folder), "--duration", "1", "--fps", "5")[0] == 0
    assert run_cli("demo", str(folder), "--duration", "1", "--fps", "5")[0] == 0  # its own files: refreshed
    (folder / "notes.txt").write_text("a learner's notes")
    code, _, err = run_cli("demo", str(folder), "--duration", "1", "--fps", "5")
    assert code != 0 and "notes.txt" in err and "--force" in err
    assert (folder / "notes.txt").read_text() == "a learner's notes"
    assert list(private_tmp.iterdir()) == []  # refused before any second process or temporary folder
