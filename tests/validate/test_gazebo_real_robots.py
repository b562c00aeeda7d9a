"""What Gazebo keeps of the real-robot corpus (tests/validate/test_real_robots.py's files), judged by libsdformat 12.

For every robot the corpus holds, bras-kit's prediction of the SDF model (links and joints
kept, and whether the model is refused) is compared with what libsdformat's ``cmdCheck`` and
``cmdPrint`` do with the same URDF (xacro files expanded first). Every refused model must get
a finding naming why: a BK7xx rule for what the conversion refuses, an error for what urdfdom
refuses before it (a joint naming a missing link...). The figures measured are printed.
"""

from __future__ import annotations

import pytest
import sdformat_oracle as oracle
from robot_corpus import ROOTS, TREES
from sdformat_oracle import REFUSAL_RULES

from bras_kit.core.errors import BrasKitError
from bras_kit.model.authoring import load
from bras_kit.validate import validate
from bras_kit.validate.urdf2sdf import gazebo_model, refusals

pytestmark = pytest.mark.slow


@pytest.fixture(scope="module")
def corpus(tmp_path_factory):
    oracle.require()
    folder = tmp_path_factory.mktemp("expanded")
    robots = {}
    for package, tree in TREES.items():
        for path in sorted([*tree.rglob("*.urdf"), *tree.rglob("*.xacro")]):
            try:
                robot = load(str(path), package_paths=ROOTS)
            except BrasKitError:
                continue  # BK100-BK103: test_real_robots checks those
            if not robot.links or not robot.source_text:
                continue  # a xacro macro library
            name = f"{package}/{path.relative_to(tree)}"
            expanded = folder / (name.replace("/", "__") + ".urdf")
            expanded.write_text(robot.source_text, encoding="utf-8")
            robots[name] = (robot, expanded)
    truths = oracle.verdicts([str(expanded) for _, expanded in robots.values()])
    return {name: (robot, truths[str(expanded)]) for name, (robot, expanded) in robots.items()}


def test_bras_kit_keeps_the_links_and_joints_libsdformat_keeps(corpus):
    files = links = same_links = refused = urdfdom = 0
    mismatches = []
    for name, (robot, truth) in corpus.items():
        predicted = gazebo_model(robot)
        if predicted is None:  # urdfdom refuses it (not one tree)
            if truth.valid:
                mismatches.append((name, "bras-kit says not one tree, libsdformat accepts it"))
            continue
        files += 1
        refused += not truth.valid
        if truth.urdfdom_refused:  # urdfdom's own checks (a malformed origin...): the URDF rules' errors say why
            urdfdom += 1
            if not any(f.severity == "error" for f in validate(robot, package_paths=ROOTS)):
                mismatches.append((name, "urdfdom refuses it, bras-kit has no error"))
            continue
        if predicted.refused != (not truth.valid):
            mismatches.append((name, f"refused {predicted.refused}, libsdformat valid {truth.valid}"))
        if truth.sdf:
            links += len(robot.links)
            same_links += sum((link.name in predicted.links) == (link.name in truth.links) for link in robot.links)
            if set(predicted.links) != set(truth.links) or set(predicted.joints) != set(truth.joints):
                mismatches.append((name, sorted(set(predicted.links) ^ set(truth.links))))
    print(f"\nGazebo agreement: {files} files, {refused} refused by libsdformat ({urdfdom} by urdfdom), "
          f"links kept/dropped matching {same_links}/{links}")
    assert files > 100 and links > 2000
    assert mismatches == []


def test_every_model_libsdformat_refuses_gets_a_finding_naming_why(corpus):
    unexplained = []
    for name, (robot, truth) in corpus.items():
        if truth.valid:
            continue
        findings = validate(robot, package_paths=ROOTS, target="gazebo")
        predicted = gazebo_model(robot)
        reasons = refusals(predicted) if predicted is not None else []
        codes = {f.code for f in findings}
        explained = all(codes & REFUSAL_RULES[r["reason"]] for r in reasons) if reasons \
            else any(f.severity == "error" for f in findings)  # urdfdom's refusals: the URDF rules' errors
        if not explained:
            unexplained.append((name, truth.check_output[-200:]))
    assert unexplained == []


def test_no_real_robot_gets_a_gazebo_error_without_the_target(corpus):
    """BK7xx never makes an error on its own: only --target gazebo does (real robots keep 0 false errors)."""
    for _, (robot, _) in list(corpus.items())[:40]:
        assert not [f for f in validate(robot, select=["BK7"]) if f.severity == "error"]
