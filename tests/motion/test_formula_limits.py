"""BK623 follows a node's formula with Python floats (bras_kit.motion.formula_limits), so that
``validate PKG_DIR`` needs no numpy (issue 43). Its oracle is the numpy path it stands for:
``check_limits(robot, sample(motion_from_specs(robot, ["JOINT=FORMULA"]), duration))``, which
the motion tests check against the tutorial's node and finite differences."""

from __future__ import annotations

import math
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.core.errors import BrasKitError
from bras_kit.model.authoring import arm, arm_urdf
from bras_kit.model.robot import robot_from_xml
from bras_kit.model.xmlio import parse_xml
from bras_kit.motion import check_limits, motion_from_specs, sample
from bras_kit.motion.formula_limits import formula_position_violations

TUTORIAL = TESTS / "data" / "package_tutorial"
SECONDS = 60.0  # BK623's span (validate/package/rules.py MOTION_SECONDS)

FORMULAS = [
    "0.8*sin(t)", "1.2*sin(0.7*t)", "0.0 + 0.8 * sin(1.0 * t + 0.0)", "3*sin(t)", "-3*cos(0.3*t) + 1",
    "1.57*sin(t)", "1.5700000001*sin(pi/2 + 2*pi*t)", "2*t - 5", "0.1*t", "clip(5*sin(t), -1.6, 1.6)",
    "min(t, 1.6)", "max(-t, -2.1)", "floor(t) % 3 - 1", "deg(100)*sin(t)", "sqrt(t)", "atan2(t, 1)*2",
    "exp(-t)*4", "(t - 30)**2 / 500", "0", "1.57", "-1.58",
]


def _numpy_path(robot, joint: str, formula: str):
    states = sample(motion_from_specs(robot, [f"{joint}={formula}"]), duration=SECONDS)
    return [v for v in check_limits(robot, states) if v.kind == "position" and v.joint == joint]


def _same(got, expected) -> None:
    assert [(v.joint, v.kind, v.side, v.bound, v.samples, v.unit) for v in got] == \
        [(v.joint, v.kind, v.side, v.bound, v.samples, v.unit) for v in expected]
    for a, b in zip(got, expected):
        assert a.time == b.time  # k / rate: the same first sample past the limit
        assert math.isclose(a.value, b.value, rel_tol=1e-12, abs_tol=1e-12)
        assert math.isclose(a.excess, b.excess, rel_tol=1e-9, abs_tol=1e-12)


@pytest.mark.parametrize("formula", FORMULAS)
@pytest.mark.parametrize("joint", ["epaule", "coude"])
def test_a_formula_followed_in_floats_finds_what_the_motion_module_finds(joint, formula):
    robot = arm()
    _same(formula_position_violations(robot, joint, formula, SECONDS), _numpy_path(robot, joint, formula))


def test_a_prismatic_joint_and_the_wrist_are_followed_as_the_motion_module_follows_them():
    text = arm_urdf(wrist=True).replace('type="revolute"', 'type="prismatic"', 1)
    robot = robot_from_xml(parse_xml(text, "bras.urdf"), "bras.urdf", text)
    for joint in ("epaule", "poignet"):
        for formula in ("0.5*t", "3*sin(t)", "-0.2"):
            got, expected = formula_position_violations(robot, joint, formula, SECONDS), _numpy_path(robot, joint, formula)
            _same(got, expected)
    assert {v.unit for v in formula_position_violations(robot, "epaule", "3*sin(t)", SECONDS)} == {"m"}


REFUSED = [
    ("doigt", "sin(t)"),  # no such joint
    ("epaule", "log(t)"),  # not a number at 0
    ("epaule", "sin(t"),  # not a formula
    ("epaule", "__import__('os')"),  # not allowed
    ("epaule", "t.csv"),  # read as a waypoint file
]


@pytest.mark.parametrize(("joint", "formula"), REFUSED)
def test_what_the_motion_module_refuses_is_refused_alike(joint, formula):
    robot = arm()
    with pytest.raises(BrasKitError) as expected:
        _numpy_path(robot, joint, formula)
    with pytest.raises(BrasKitError) as got:
        formula_position_violations(robot, joint, formula, SECONDS)
    assert type(got.value) is type(expected.value)


def test_a_fixed_joint_a_mimic_joint_and_a_robot_that_is_no_tree_are_refused_alike():
    text = arm_urdf(wrist=True)
    fixed = text.replace('<joint name="coude" type="revolute">', '<joint name="coude" type="fixed">')
    mimic = text.replace('<joint name="poignet" type="revolute">',
                         '<joint name="poignet" type="revolute"><mimic joint="coude"/>')
    two_roots = text.replace('<child link="bras"/>', '<child link="base"/>', 1)
    for variant, joint in ((fixed, "coude"), (mimic, "poignet"), (two_roots, "coude")):
        assert variant != text
        robot = robot_from_xml(parse_xml(variant, "bras.urdf"), "bras.urdf", variant)
        with pytest.raises(BrasKitError) as expected:
            _numpy_path(robot, joint, "sin(t)")
        with pytest.raises(BrasKitError) as got:
            formula_position_violations(robot, joint, "sin(t)", SECONDS)
        assert type(got.value) is type(expected.value)


def _validate_in_a_fresh_process(package: Path) -> tuple[str, bool]:
    """``bras-kit validate PKG_DIR`` as the command runs it; its output, and whether numpy was imported."""
    code = ("import sys\nfrom bras_kit.cli import main\ncode = main(['validate', sys.argv[1]])\n"
            "print('NUMPY', 'numpy' in sys.modules)\n")
    done = subprocess.run([sys.executable, "-c", code, str(package)], capture_output=True, text=True, timeout=120,
                          env={**os.environ, "BRAS_KIT_LANG": "en"})
    assert "Traceback" not in done.stderr, done.stderr
    return done.stdout, "NUMPY True" in done.stdout


def test_validating_the_tutorial_package_needs_no_numpy_and_still_follows_its_formulas(tmp_path):
    """The tutorial's package: its formulas followed (in floats), no finding, no numpy imported.
    With an amplitude past epaule's limit, BK623 names it, still without numpy."""
    out, imported = _validate_in_a_fresh_process(TUTORIAL)
    assert "0 errors" in out and not imported, out
    package = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL, package)
    node = package / "bras_description" / "animation.py"
    text = node.read_text(encoding="utf-8")
    assert "0.8 * math.sin(self.t)" in text
    node.write_text(text.replace("0.8 * math.sin(self.t)", "3 * math.sin(self.t)"), encoding="utf-8")
    out, imported = _validate_in_a_fresh_process(package)
    assert "BK623" in out and "epaule" in out and not imported, out
