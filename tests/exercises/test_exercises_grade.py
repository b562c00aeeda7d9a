"""bras-kit grade reads the exercise track a learner hands in: a column of the exercises its
progress.json records as passed (and no such column for a class without tracks)."""

from __future__ import annotations

import csv
import io
import json
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from paths import REPO

from bras_kit.exercises import check_exercise, copy_files, init_track, open_track
from bras_kit.grade.exercises import exercises_passed


def _walk(folder: Path, count: int) -> None:
    init_track(folder)
    track, progress = open_track(folder)
    for exercise in track.exercises[:count]:
        copy_files(exercise, folder / exercise.id, "solution")
        assert check_exercise(track, progress, exercise, "en").state == "passed"


def _grades(klass: Path, out: Path) -> list[dict[str, str]]:
    done = subprocess.run([sys.executable, "-m", "bras_kit", "grade", str(klass), "-o", str(out), "--jobs", "1",
                           "--no-pictures"], capture_output=True, text=True, timeout=300)
    assert done.returncode in (0, 1), done.stderr
    return list(csv.DictReader(io.StringIO((out / "grades.csv").read_text())))


@pytest.mark.slow
def test_grade_counts_the_exercises_passed(tmp_path):
    klass = tmp_path / "class"
    _walk(klass / "alice" / "exos", 3)
    _walk(klass / "bob", 0)
    shutil.copyfile(REPO / "bras_kit" / "exercises" / "track" / "01-links" / "solution" /
                    "bras.urdf", klass / "carol.urdf")
    rows = {row["identifier"]: row for row in _grades(klass, tmp_path / "out")}
    assert rows["alice"]["exercises"] == "3/14"
    assert rows["bob"]["exercises"] == "0/14"
    assert rows["carol"]["exercises"] == ""


@pytest.mark.slow
def test_no_column_without_a_track(tmp_path):
    klass = tmp_path / "class"
    klass.mkdir()
    shutil.copyfile(REPO / "bras_kit" / "exercises" / "track" / "01-links" / "solution" /
                    "bras.urdf", klass / "carol.urdf")
    rows = _grades(klass, tmp_path / "out")
    assert "exercises" not in rows[0]


def test_a_progress_file_that_cannot_be_read_counts_nothing(tmp_path):
    (tmp_path / "progress.json").write_text("{not json")
    assert exercises_passed(str(tmp_path)) == ""
    (tmp_path / "progress.json").write_text(json.dumps({"set": "/elsewhere/set", "exercises": {
        "a": {"passed": True}, "b": {"passed": False}}}))
    assert exercises_passed(str(tmp_path)) == "1"
