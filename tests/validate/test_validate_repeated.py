"""A finding that repeats on many links or joints of one file is reported once with its count
(issue 43: a 17,133-link file printed 17,132 copies of one warning); the JSON report keeps each
one, and the totals count them all. Also: what made the large file slower than at round 3."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.findings.report import REPEATED
from bras_kit.validate import validate_path
from bras_kit.validate._dmass import UrdfInertial, _valid, valid_mass_matrix

DATA = TESTS / "data" / "repeated_findings"
MANY = DATA / "chain_40_continuous.urdf"  # 39 continuous joints with lower/upper: 39 BK208
FEW = DATA / "chain_11_continuous.urdf"  # 10 of them: each shown


def _joint_lines(path: Path) -> list[int]:
    return [n for n, line in enumerate(path.read_text(encoding="utf-8").splitlines(), 1) if "<joint " in line]


@pytest.mark.parametrize(("lang", "more", "summary"), [
    ("en", "and 38 more BK208 like it in this file (lines {first} to {last}; j2, j3, j4, j5, j6, ...): "
           "--json lists each", "1 file checked: 0 errors, 39 warnings, 1 info."),
    ("fr", "et 38 autres BK208 semblables dans ce fichier (lignes {first} à {last} ; j2, j3, j4, j5, j6, ...) : "
           "--json les détaille un par un", "1 fichier vérifié : 0 erreur, 39 avertissements, 1 info."),
])
def test_a_finding_repeated_on_every_joint_is_shown_once_with_its_count(run_cli, lang, more, summary):
    code, out, _ = run_cli("--lang", lang, "validate", str(MANY))
    assert code == 0
    lines = out.splitlines()
    shown = [i for i, line in enumerate(lines) if line.startswith(f"{MANY}:") and " BK208 " in line]
    assert len(shown) == 1
    first = shown[0]
    joints = _joint_lines(MANY)
    assert lines[first].startswith(f"{MANY}:{joints[0]}: BK208 ")
    assert lines[first + 2].strip() == more.format(first=joints[1], last=joints[-1])
    assert lines[-1] == summary


def test_the_json_report_keeps_every_repeated_finding(run_cli):
    code, out, _ = run_cli("validate", str(MANY), "--format", "json")
    assert code == 0
    (report,) = json.loads(out)["files"]
    lines = [f["line"] for f in report["findings"] if f["code"] == "BK208"]
    assert lines == _joint_lines(MANY)
    assert json.loads(out)["summary"]["warnings"] == 39


def test_up_to_the_limit_each_finding_is_shown(run_cli):
    assert len(_joint_lines(FEW)) == REPEATED
    code, out, _ = run_cli("validate", str(FEW))
    assert code == 0
    assert [int(m) for m in re.findall(rf"^{re.escape(str(FEW))}:(\d+): BK208 ", out, re.M)] == _joint_lines(FEW)
    assert "more BK208" not in out


def test_an_inertial_repeated_on_every_link_is_judged_once_with_the_same_verdict():
    """gz-math's MassMatrix3::IsValid, asked once per distinct inertial: the verdict of a repeated
    inertial is the one computed for it (the oracle of the verdicts themselves is libsdformat, in
    tests/validate/test_gazebo.py)."""
    robot_findings = validate_path(str(MANY))
    assert [f.code for f in robot_findings if f.code.startswith("BK7")] == []
    _valid.cache_clear()
    from bras_kit.model.authoring import load

    robot = load(str(MANY))
    verdicts = {valid_mass_matrix(UrdfInertial.read(link.inertial)) for link in robot.links}
    assert verdicts == {True}
    info = _valid.cache_info()
    assert (info.misses, info.hits) == (1, len(robot.links) - 1)
    bad = UrdfInertial.read(robot.links[0].inertial)
    bad.inertia[0, 0] = -1.0
    assert valid_mass_matrix(bad) is False and _valid.cache_info().misses == 2


def test_a_launch_file_evaluation_does_not_load_the_message_definitions():
    """The stand-in's own packages (launch, launch_ros, xacro...) are imported without reading
    Jazzy's message store (rosbags', about 0.2 s): only a message package reads it."""
    import subprocess
    import sys

    code = ("import sys\nfrom bras_kit.ros.finder import install\ninstall()\n"
            "import launch, launch_ros.actions, ament_index_python.packages, launch.substitutions\n"
            "print('rosbags' in sys.modules)\nimport sensor_msgs.msg\nprint('rosbags' in sys.modules)\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True)
    assert done.stdout.split() == ["False", "True"]
