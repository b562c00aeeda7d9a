"""grade --run-nodes runs a class's nodes contained, refuses where it cannot, and
--unsafe-run-nodes is the only way past; run says in one line when it runs without walls;
doctor reports the containment.

Oracles: the exit codes and the files of a fake home folder (a hostile hand-in's node writes
there when it is not contained), the line of the hostile node read by hand."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.core.message import M
from bras_kit.doctor import install as doctor
from bras_kit.trust import contain

DATA = TESTS / "data"
TUTORIAL = DATA / "tutorial_package"
HOSTILE_NODE = DATA / "hostile_code" / "nodes" / "write_home.py"
WITHOUT = """
import sys
from bras_kit.core.message import M
from bras_kit.trust import contain
from bras_kit.trust.contain import modes
contain.available = modes.available = lambda: contain.Status(False, M("the kernel refuses new namespaces to this user (test)"),
                                           M("unprivileged user namespaces"),
                                           M("enable them: sudo sysctl -w kernel.unprivileged_userns_clone=1"))
from bras_kit.cli import main
sys.exit(main(sys.argv[1:]))
"""


@pytest.fixture
def klass(tmp_path):
    """Two hand-ins: the tutorial's package, and the same whose node writes in the home folder."""
    root = tmp_path / "copies"
    shutil.copytree(TUTORIAL, root / "alice")
    shutil.copytree(TUTORIAL, root / "mallory")
    shutil.copy(HOSTILE_NODE, root / "mallory" / "bras_description" / "animation.py")
    home = tmp_path / "home"
    home.mkdir()
    return root, home


def bras_kit(home: Path, *args: str, without_containment: bool = False) -> subprocess.CompletedProcess:
    command = [sys.executable, "-c", WITHOUT] if without_containment else [sys.executable, "-m", "bras_kit"]
    return subprocess.run([*command, *args], capture_output=True, text=True, timeout=600,
                          env={**os.environ, "HOME": str(home), "LANG": "C.UTF-8", "LANGUAGE": "en"})


def findings(out: Path, learner: str) -> set[tuple[str, str, int | None]]:
    learners = json.loads((out / "results.json").read_text())["learners"]
    (result,) = [r for r in learners if r["learner"] == learner]
    return {(f["code"], f["file"], f["line"]) for f in result["findings"] if f["code"] >= "BK640"}


@pytest.mark.slow
def test_run_nodes_grades_a_hostile_hand_in_contained(klass, tmp_path):
    root, home = klass
    done = bras_kit(home, "grade", str(root), "-o", str(tmp_path / "out"), "--run-nodes", "--no-pictures",
                    "--jobs", "1")
    assert done.returncode == 0, done.stderr
    assert ("BK659", "bras_description/animation.py", 6) in findings(tmp_path / "out", "mallory")
    assert not any(code == "BK659" for code, _, _ in findings(tmp_path / "out", "alice"))
    assert os.listdir(home) == []  # the node's write was refused


@pytest.mark.slow
def test_run_nodes_also_builds_and_launches_each_package(tmp_path):
    """--run-nodes runs the learners' code: their launch files too, as validate PKG does, so a
    launch file that names a package that does not exist (BK631, at its line) is found there,
    and only there."""
    root = tmp_path / "copies"
    shutil.copytree(TUTORIAL, root / "alice")
    shutil.copytree(DATA / "launch" / "wrong_package" / "bras_description", root / "bob")
    home = tmp_path / "home"
    home.mkdir()

    def launch_findings(out: Path, learner: str) -> set[tuple[str, str, int | None]]:
        learners = json.loads((out / "results.json").read_text())["learners"]
        (result,) = [r for r in learners if r["learner"] == learner]
        return {(f["code"], f["file"], f["line"]) for f in result["findings"] if "BK630" <= f["code"] <= "BK633"}

    done = bras_kit(home, "grade", str(root), "-o", str(tmp_path / "ran"), "--run-nodes", "--no-pictures",
                    "--jobs", "1")
    assert done.returncode == 0, done.stderr
    # the line of get_package_share_directory('bras_descripton'), read by hand
    assert launch_findings(tmp_path / "ran", "bob") == {("BK631", "launch/affichage.launch.py", 7)}
    assert launch_findings(tmp_path / "ran", "alice") == set()
    done = bras_kit(home, "grade", str(root), "-o", str(tmp_path / "read"), "--no-pictures", "--jobs", "1")
    assert done.returncode == 0, done.stderr
    assert launch_findings(tmp_path / "read", "bob") == set()  # without it, no learner's code runs


def test_run_nodes_is_refused_where_nodes_cannot_be_contained(klass, tmp_path):
    root, home = klass
    done = bras_kit(home, "grade", str(root), "-o", str(tmp_path / "out"), "--run-nodes", "--no-pictures",
                    without_containment=True)
    assert done.returncode != 0 and "Traceback" not in done.stderr
    assert "cannot be contained on this machine" in done.stderr
    assert "unprivileged user namespaces" in done.stderr  # what is missing
    assert "sudo sysctl -w kernel.unprivileged_userns_clone=1" in done.stderr  # how to get it
    assert "--unsafe-run-nodes" in done.stderr
    assert not (tmp_path / "out").exists() and os.listdir(home) == []


@pytest.mark.slow
def test_unsafe_run_nodes_runs_them_uncontained_and_says_so(klass, tmp_path):
    root, home = klass
    done = bras_kit(home, "grade", str(root), "-o", str(tmp_path / "out"), "--unsafe-run-nodes", "--no-pictures",
                    "--jobs", "1", without_containment=True)
    assert done.returncode == 0, done.stderr
    assert "warning: the nodes run NOT contained" in done.stderr
    assert os.listdir(home) == ["bk_pwned.txt"]  # what the walls prevent above


def test_run_says_in_one_line_that_it_runs_without_walls(tmp_path):
    home = tmp_path / "home"
    home.mkdir()
    args = ("run", str(TUTORIAL), "animation", "--duration", "0.2", "--quiet")
    without = bras_kit(home, *args, without_containment=True)
    assert without.returncode == 0, without.stderr
    notes = [line for line in without.stderr.splitlines() if "without walls" in line]
    assert notes == ["note: your code runs without walls here (this machine lacks unprivileged user namespaces): "
                     "it has your rights, as under ros2 run"]
    within = bras_kit(home, *args)
    assert within.returncode == 0 and "without walls" not in within.stderr


def test_doctor_reports_the_containment(monkeypatch):
    check = doctor.check_containment()
    assert (check.status, check.fix) == (doctor.OK, None)
    missing = contain.Status(False, M("test"), M("unprivileged user namespaces"),
                             M("enable them"))
    monkeypatch.setattr(contain, "available", lambda: missing)
    check = doctor.check_containment()
    assert check.status == doctor.NOTE and "grade --run-nodes" in str(check.fix.params) + check.fix.id
