"""What Gazebo makes of a URDF (BK7xx, bras-kit gazebo), judged by libsdformat 12 itself.

The oracle (tests/sdformat_oracle.py) calls libsdformat's ``cmdCheck`` and ``cmdPrint`` (what
``ign sdf -k`` / ``ign sdf -p`` run) on each file; the links and joints Gazebo keeps are read
from the SDF it prints. bras-kit's prediction (bras_kit.validate.urdf2sdf) never calls it.
CI installs Debian 12's ``libsdformat12-12``.
"""

from __future__ import annotations

import json
import re
from pathlib import Path

import numpy as np
import pytest
import sdformat_oracle as oracle
from paths import TESTS
from sdformat_oracle import REFUSAL_RULES

from bras_kit.core.errors import BrasKitError
from bras_kit.model.authoring import arm, arm_urdf, load
from bras_kit.validate import validate, validate_path
from bras_kit.validate.gazebo import TARGET_SEVERITY, gazebo_colour
from bras_kit.validate.urdf2sdf import gazebo_model

DATA = TESTS / "data"
GAZEBO = DATA / "gazebo"
FIXTURES = sorted(GAZEBO.glob("*.urdf"))
LEARNERS = sorted(p for p in (DATA / "urdf").rglob("*.urdf") if p.parent.name != "broken")
VARIANTS = {
    "tutorial": {},
    "wrist": {"wrist": True},
    "inertials": {"inertials": True},
    "wrist-inertials": {"wrist": True, "inertials": True},
    "root-without-inertial": {"wrist": True, "inertials": True, "root_inertial": False},
    "collisions": {"wrist": True, "collisions": True},
}


def _variant_file(tmp_path_factory, name: str) -> Path:
    path = tmp_path_factory.mktemp("variants") / f"{name}.urdf"
    path.write_text(arm_urdf(**VARIANTS[name]), encoding="utf-8")
    return path


def _agrees(path: Path) -> None:
    """Links, joints and verdict as libsdformat has them; a refused model is told why."""
    truth = oracle.verdict(str(path))
    try:
        robot = load(str(path))
    except BrasKitError:  # not XML: libsdformat cannot read it either, and validate says why
        assert not truth.valid
        assert {f.severity for f in validate_path(str(path))} == {"error"}
        return
    predicted = gazebo_model(robot)
    if predicted is None:  # not one tree: urdfdom, under libsdformat, refuses it; the BK1xx errors say why
        assert not truth.valid
        assert any(f.severity == "error" for f in validate_path(str(path)))
        return
    assert predicted.refused == (not truth.valid), truth.check_output
    if truth.sdf:  # the SDF is printed unless libsdformat cannot even read it back (a NaN pose)
        assert set(predicted.links) == set(truth.links)
        assert set(predicted.joints) == set(truth.joints)
        assert {j: predicted.joint_types[j] for j in predicted.joints} == truth.joint_types
    if predicted.refused:
        codes = {f.code for f in validate(robot, select=["BK7"], target="gazebo")}
        from bras_kit.validate.urdf2sdf import refusals

        for reason in refusals(predicted):
            assert codes & REFUSAL_RULES[reason["reason"]], (reason, codes)


@pytest.mark.parametrize("path", FIXTURES, ids=lambda p: p.stem)
def test_fixture_keeps_what_libsdformat_keeps(path):
    _agrees(path)


@pytest.mark.parametrize("path", LEARNERS, ids=lambda p: p.stem)
def test_learner_files_keep_what_libsdformat_keeps(path):
    _agrees(path)


@pytest.mark.parametrize("name", sorted(VARIANTS))
def test_arm_variants_keep_what_libsdformat_keeps(name, tmp_path_factory):
    _agrees(_variant_file(tmp_path_factory, name))


def test_tutorial_arm_done_right_passes_gazebos_reader(tmp_path_factory):
    path = _variant_file(tmp_path_factory, "wrist-inertials")
    truth = oracle.verdict(str(path))
    assert truth.valid and "Valid." in truth.check_output
    assert set(truth.links) == {"base", "bras", "avant_bras", "main"}
    assert set(truth.joints) == {"epaule", "coude", "poignet"}
    findings = validate(arm(wrist=True, inertials=True), target="gazebo")
    assert [f for f in findings if f.severity == "error"] == []
    assert not gazebo_model(arm(wrist=True, inertials=True)).refused


@pytest.mark.parametrize("xacro", [False, True], ids=["urdf", "xacro"])
def test_the_scaffolds_physics_package_passes_gazebos_reader_anchored(tmp_path, xacro):
    """bras-kit new --inertials --wrist: Gazebo keeps every link, holds the arm in place (the world
    joint is there in libsdformat's SDF), and bras-kit says so with nothing above info."""
    from bras_kit.model.xacro import expand_xacro
    from bras_kit.scaffold.package import scaffold_package

    scaffold_package(tmp_path / "bras_description", wrist=True, inertials=True, xacro=xacro)
    path = tmp_path / "bras_description" / "urdf" / "bras.urdf"
    if xacro:
        path.write_text(expand_xacro(path.with_suffix(".urdf.xacro"), {}), encoding="utf-8")
    truth = oracle.verdict(str(path))
    assert truth.valid and "Valid." in truth.check_output
    assert set(truth.links) == {"base", "bras", "avant_bras", "main"}
    assert truth.joint_types.get("ancrage") == "fixed"  # base to world: the model is anchored
    _agrees(path)
    robot = load(str(path))
    assert gazebo_model(robot).anchored
    assert [f.code for f in validate(robot, target="gazebo") if f.severity != "info"] == []


def test_the_wrist_as_the_tutorials_hint_writes_it_is_refused_and_named(tmp_path):
    truth = oracle.verdict(str(GAZEBO / "name_shared.urdf"))
    assert not truth.valid and truth.mentions("Joint with non-unique name [poignet]")
    found = [f for f in validate_path(str(GAZEBO / "name_shared.urdf")) if f.code == "BK700"]
    assert [(f.severity, f.element, f.name) for f in found] == [("warning", "joint", "poignet")]
    assert found[0].data["rename"] == "poignet_link"
    assert "Joint with non-unique name [poignet]" in found[0].text("en")
    assert "Joint with non-unique name [poignet]" in found[0].text("fr") and found[0].text("fr") != found[0].text("en")
    targeted = [f for f in validate_path(str(GAZEBO / "name_shared.urdf"), target="gazebo") if f.code == "BK700"]
    assert targeted[0].severity == "error"


# ------------------------------------------------------------------ one failing and one passing file per rule

PAIRS = [
    ("BK700", "name_shared.urdf", "arm_done_right.urdf", "warning"),
    ("BK701", "no_inertial_anywhere.urdf", "arm_done_right.urdf", "info"),
    ("BK702", "wrist_without_inertial.urdf", "arm_done_right.urdf", "warning"),
    ("BK702", "flange_without_inertial.urdf", "flange_with_inertial.urdf", "warning"),
    ("BK702", "tcp_preserved.urdf", "tcp_preserved_with_inertial.urdf", "warning"),
    ("BK703", "mass_1e-6.urdf", "mass_1e-5.urdf", "warning"),
    ("BK704", "tcp_merged.urdf", "tcp_preserved_with_inertial.urdf", "info"),
    ("BK705", "not_anchored.urdf", "arm_done_right.urdf", "info"),
    ("BK706", "no_collision.urdf", "arm_done_right.urdf", "info"),
    ("BK707", "package_mesh.urdf", "arm_done_right.urdf", "info"),
    ("BK708", "colours_saturated.urdf", "colours_dark.urdf", "info"),
    ("BK709", "floating_joint.urdf", "arm_done_right.urdf", "warning"),
    ("BK710", "zero_mass_frames.urdf", "zero_mass_frames_without_inertial.urdf", "warning"),
    ("BK711", "inertia_impossible.urdf", "arm_done_right.urdf", "warning"),
]


@pytest.mark.parametrize("code, failing, passing, severity", PAIRS, ids=[f"{p[0]}-{p[1]}" for p in PAIRS])
def test_rule_fails_and_passes(code, failing, passing, severity):
    """A warning is given in any case; a note about Gazebo only to a learner heading there (--target)."""
    target = "gazebo" if severity == "info" else None
    assert bool([f for f in validate_path(str(GAZEBO / failing)) if f.code == code]) == (target is None)
    bad = [f for f in validate_path(str(GAZEBO / failing), target=target) if f.code == code]
    assert [f.severity for f in bad] == [TARGET_SEVERITY["gazebo"][code] if target else severity]
    assert bad[0].text("en") and bad[0].text("fr") and bad[0].text("fr") != bad[0].text("en")
    assert bad[0].hint_text("fr") != bad[0].hint_text("en")
    assert [f for f in validate_path(str(GAZEBO / passing), target="gazebo") if f.code == code] == []
    targeted = [f for f in validate_path(str(GAZEBO / failing), target="gazebo") if f.code == code]
    assert [f.severity for f in targeted] == [TARGET_SEVERITY["gazebo"][code]]


def test_a_dropped_wrist_lists_what_goes_with_it():
    found = [f for f in validate_path(str(GAZEBO / "forearm_without_inertial.urdf")) if f.code == "BK702"]
    assert [(f.name, f.variant) for f in found] == [("avant_bras", "below")]
    assert found[0].data["lost_links"] == ["avant_bras", "main"]
    assert found[0].data["lost_joints"] == ["coude", "poignet"]
    truth = oracle.verdict(str(GAZEBO / "forearm_without_inertial.urdf"))
    assert truth.valid  # libsdformat says "Valid." and silently loses two links
    assert set(truth.links) == {"base", "bras"}


def test_mass_threshold_is_libsdformats():
    # ignition::math::equal(mass, 0.0): |mass| <= 1e-6 is no mass
    assert "main" not in oracle.verdict(str(GAZEBO / "mass_1e-6.urdf")).links
    assert "main" in oracle.verdict(str(GAZEBO / "mass_1e-5.urdf")).links
    assert "main" not in gazebo_model(load(str(GAZEBO / "mass_1e-6.urdf"))).links
    assert "main" in gazebo_model(load(str(GAZEBO / "mass_1e-5.urdf"))).links


def test_preserved_fixed_joints_keep_their_frame():
    merged = oracle.verdict(str(GAZEBO / "tcp_merged.urdf"))
    kept = oracle.verdict(str(GAZEBO / "tcp_preserved_with_inertial.urdf"))
    old = oracle.verdict(str(GAZEBO / "tcp_lumping_disabled.urdf"))
    assert "tcp" not in merged.links and "tcp" in kept.links and kept.joint_types["tcp_joint"] == "fixed"
    assert "tcp" not in old.links  # kept as a link, but without <inertial>: dropped (BK702 says so)
    predicted = gazebo_model(load(str(GAZEBO / "tcp_preserved_with_inertial.urdf")))
    assert "tcp" in predicted.links and predicted.preserved == {"tcp_joint"}


def test_colours_as_libsdformat_writes_them():
    truth = oracle.verdict(str(GAZEBO / "colours_saturated.urdf"))
    written = {"bras": (0.2, 0.4, 0.9, 1), "avant_bras": (0.95, 0.5, 0.1, 1), "main": (0.2, 0.8, 0.3, 1)}
    for link, rgba in written.items():
        np.testing.assert_allclose(truth.colours[f"{link}_visual"], gazebo_colour(rgba), atol=1e-12)


def test_rotated_inertials_are_merged_with_libsdformats_arithmetic(tmp_path):
    """A fixed link whose inertial frame is turned about two axes: libsdformat's merge applies the
    inverse rotation as three separate Euler steps; a body one moment short of valid tells whether the
    port of that arithmetic matches (the refusal depends on the merged moments)."""
    base = (GAZEBO / "arm_done_right.urdf").read_text()
    extra = """  <link name="plaque">
    <inertial><origin rpy="0.3 0.7 0" xyz="0.01 0 0.02"/><mass value="0.3"/>
      <inertia ixx="0.002" ixy="0" ixz="0" iyy="0.0005" iyz="0" izz="0.0015"/></inertial>
  </link>
  <joint name="plaque_joint" type="fixed">
    <parent link="main"/><child link="plaque"/><origin xyz="0 0.02 0.1" rpy="0 0.4 0.2"/>
  </joint>
</robot>"""
    path = tmp_path / "plaque.urdf"
    path.write_text(base.replace("</robot>", extra))
    _agrees(path)


# ------------------------------------------------------------------ bras-kit gazebo


def test_gazebo_command_json_lists_kept_merged_dropped(run_cli):
    code, out, _ = run_cli("gazebo", str(GAZEBO / "flange_without_inertial.urdf"), "--json")
    data = json.loads(out)
    assert code == 0 and data["loads"] is True
    truth = oracle.verdict(str(GAZEBO / "flange_without_inertial.urdf"))
    assert set(data["links"]) == set(truth.links)
    assert data["dropped"] == [{"link": "bride", "reason": "no-inertial", "mass": None, "merged_into": "main",
                                "lost_links": ["doigt"], "lost_joints": ["pince"]}]
    assert {"link": "bride", "into": "main", "joint": "bride_joint"} in data["merged"]
    assert {f["code"] for f in data["findings"]} >= {"BK702", "BK704"}


def test_gazebo_command_exit_status_says_whether_gazebo_loads_it(run_cli):
    assert run_cli("gazebo", "--wrist", "--inertials")[0] == 0
    code, out, _ = run_cli("gazebo", "--wrist")
    assert code == 1 and "Gazebo refuses model 'bras'" in out
    code, out, _ = run_cli("--lang", "fr", "gazebo", str(GAZEBO / "name_shared.urdf"))
    assert code == 1 and "Gazebo refuse le modèle 'bras'" in out and "BK700" in out


def test_gazebo_picture_marks_the_lost_parts_in_red(run_cli, tmp_path):
    from PIL import Image

    def red(path):
        image = np.asarray(Image.open(path).convert("RGB")).astype(int)
        return int(((image[..., 0] > 150) & (image[..., 1] < 80) & (image[..., 2] < 80)).sum())

    marked, only = tmp_path / "marked.png", tmp_path / "only.png"
    assert run_cli("gazebo", str(GAZEBO / "forearm_without_inertial.urdf"), "-o", str(marked))[0] == 0
    assert run_cli("gazebo", str(GAZEBO / "forearm_without_inertial.urdf"), "-o", str(only), "--only-kept")[0] == 0
    assert red(marked) > 500 and red(only) == 0


def test_gazebo_command_refuses_to_overwrite(run_cli, tmp_path):
    picture = tmp_path / "p.png"
    picture.write_bytes(b"mine")
    code, _, err = run_cli("gazebo", "-o", str(picture))
    assert code == 2 and picture.read_bytes() == b"mine"


@pytest.mark.parametrize("lang", ["en", "fr"])
def test_the_report_s_labels_share_one_column_in_each_language(run_cli, tmp_path, lang):
    """kept, joints, merged, dropped, anchored: the names after them start in one column, whatever
    the length of the label in the learner's language ('articulations :' is the longest)."""
    _, out, _ = run_cli("--lang", lang, "gazebo", str(GAZEBO / "tcp_merged.urdf"))
    _, more, _ = run_cli("--lang", lang, "gazebo", str(GAZEBO / "wrist_without_inertial.urdf"))
    lines = [line for line in (out + more).splitlines() if line.startswith("  ") and not line.startswith("   ")]
    labelled = [line for line in lines if re.match(r"  \S[^:]*:\s", line) and "BK" not in line
                and not line.lstrip().startswith(("hint", "correctif"))]
    assert len(labelled) >= 5, labelled
    columns = {re.match(r"  \S[^:]*:\s+", line).end() for line in labelled}
    assert len(columns) == 1, labelled
