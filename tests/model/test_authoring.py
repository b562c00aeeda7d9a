"""The built-in arm: the tutorial's URDF number for number, its variants and its parameters."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest
from urdfdom_oracle import check_urdf

from bras_kit.core.errors import ParameterError
from bras_kit.kinematics.frames import fk, tf_tree
from bras_kit.model.authoring import arm, arm_urdf, load, parse_assignments, template_parameters


def visual(robot, link):
    (only,) = robot.link(link).visuals
    return only


# --- the default model is the tutorial's bras.urdf -------------------------------------------------

def test_robot_is_named_bras_with_three_links_and_two_joints(tutorial_robot):
    assert tutorial_robot.name == "bras"
    assert tutorial_robot.link_names == ["base", "bras", "avant_bras"]
    assert tutorial_robot.joint_names == ["epaule", "coude"]
    assert tutorial_robot.issues == []


def test_base_is_a_grey_cylinder(tutorial_robot):
    v = visual(tutorial_robot, "base")
    assert (v.geometry.kind, v.geometry.length, v.geometry.radius) == ("cylinder", 0.1, 0.15)
    assert v.origin.xyz == (0.0, 0.0, 0.0) and v.origin.rpy == (0.0, 0.0, 0.0)
    assert (v.material.name, v.material.rgba) == ("gris", (0.5, 0.5, 0.5, 1.0))


def test_bras_is_a_blue_box_raised_by_half_its_length(tutorial_robot):
    v = visual(tutorial_robot, "bras")
    assert (v.geometry.kind, v.geometry.size) == ("box", (0.08, 0.08, 0.6))
    assert v.origin.xyz == (0.0, 0.0, 0.3)
    assert (v.material.name, v.material.rgba) == ("bleu", (0.2, 0.4, 0.9, 1.0))


def test_avant_bras_is_an_orange_box_raised_by_half_its_length(tutorial_robot):
    v = visual(tutorial_robot, "avant_bras")
    assert (v.geometry.kind, v.geometry.size) == ("box", (0.06, 0.06, 0.5))
    assert v.origin.xyz == (0.0, 0.0, 0.25)
    assert (v.material.name, v.material.rgba) == ("orange", (0.95, 0.5, 0.1, 1.0))


@pytest.mark.parametrize("name,parent,child,z,lower,upper", [
    ("epaule", "base", "bras", 0.05, -1.57, 1.57),
    ("coude", "bras", "avant_bras", 0.6, -2.0, 2.0),
])
def test_joints_match_the_tutorial(tutorial_robot, name, parent, child, z, lower, upper):
    joint = tutorial_robot.joint(name)
    assert (joint.type, joint.parent, joint.child) == ("revolute", parent, child)
    assert joint.origin.xyz == (0.0, 0.0, z) and joint.origin.rpy == (0.0, 0.0, 0.0)
    assert joint.axis == (0.0, 1.0, 0.0)
    limit = joint.limit
    assert (limit.lower, limit.upper, limit.effort, limit.velocity) == (lower, upper, 10.0, 1.0)
    assert joint.mimic is None


def test_default_arm_has_no_inertials_nor_collisions(tutorial_robot):
    assert all(link.inertial is None and link.collisions == [] for link in tutorial_robot.links)


def test_arm_urdf_text_is_what_load_reads(tmp_path):
    path = tmp_path / "bras.urdf"
    path.write_text(arm_urdf())
    robot = load(path)
    assert robot.joint("coude").origin.xyz == (0.0, 0.0, 0.6)
    assert robot.path == str(path)
    assert load(None).link_names == ["base", "bras", "avant_bras"]


# --- the wrist (the tutorial's exercise) -------------------------------------------------------------

def test_wrist_adds_the_joint_poignet_moving_the_link_main(wrist_robot):
    # one name for a link and a joint is refused by Gazebo (BK700): the hand the wrist moves is "main"
    assert wrist_robot.link_names == ["base", "bras", "avant_bras", "main"]
    joint = wrist_robot.joint("poignet")
    assert (joint.type, joint.parent, joint.child, joint.axis) == ("revolute", "avant_bras", "main",
                                                                   (0.0, 1.0, 0.0))
    assert joint.origin.xyz == (0.0, 0.0, 0.5)
    assert (joint.limit.lower, joint.limit.upper) == (-1.57, 1.57)
    v = visual(wrist_robot, "main")
    assert v.geometry.size == (0.04, 0.04, 0.15) and v.origin.xyz == (0.0, 0.0, 0.075)


@pytest.mark.parametrize("forearm", [0.3, 0.5, 0.72, 1.1])
def test_wrist_joint_sits_at_forearm_tip(forearm):
    robot = arm(wrist=True, params={"avant_bras_length": forearm})
    assert robot.joint("poignet").origin.xyz == pytest.approx((0.0, 0.0, forearm), abs=1e-12)
    v = visual(robot, "avant_bras")
    assert v.origin.xyz[2] + v.geometry.size[2] / 2 == pytest.approx(forearm, abs=1e-12)
    # in a bent pose too: the wrist frame is the forearm frame moved by the forearm's length
    shoulder, elbow = 0.4, -0.9
    frames = fk(tf_tree(robot), {"epaule": shoulder, "coude": elbow, "poignet": 0.3})
    tip = np.array([0.6 * math.sin(shoulder) + forearm * math.sin(shoulder + elbow), 0.0,
                    0.05 + 0.6 * math.cos(shoulder) + forearm * math.cos(shoulder + elbow)])
    np.testing.assert_allclose(frames["main"][:3, 3], tip, atol=1e-12)


# --- inertials: solid-primitive formulas about the centre of the shape ------------------------------

def box_inertia(m, x, y, z):
    return {"ixx": m / 12 * (y * y + z * z), "iyy": m / 12 * (x * x + z * z),
            "izz": m / 12 * (x * x + y * y), "ixy": 0.0, "ixz": 0.0, "iyz": 0.0}


def cylinder_inertia(m, r, h):
    side = m / 12 * (3 * r * r + h * h)
    return {"ixx": side, "iyy": side, "izz": m * r * r / 2, "ixy": 0.0, "ixz": 0.0, "iyz": 0.0}


@pytest.mark.parametrize("link,mass,expected,centre", [
    ("base", 2.0, cylinder_inertia(2.0, 0.15, 0.1), 0.0),
    ("bras", 1.0, box_inertia(1.0, 0.08, 0.08, 0.6), 0.3),
    ("avant_bras", 0.5, box_inertia(0.5, 0.06, 0.06, 0.5), 0.25),
    ("main", 0.2, box_inertia(0.2, 0.04, 0.04, 0.15), 0.075),
])
def test_inertials_match_solid_formulas(link, mass, expected, centre):
    inertial = arm(wrist=True, inertials=True).link(link).inertial
    assert inertial.mass == mass
    assert inertial.origin.xyz == pytest.approx((0.0, 0.0, centre), abs=1e-12)
    for key, value in expected.items():
        assert inertial.inertia[key] == pytest.approx(value, abs=1e-12), key


def test_inertial_numbers_by_hand():
    robot = arm(inertials=True)
    base = robot.link("base").inertial.inertia
    assert base["ixx"] == pytest.approx(0.0775 / 6, abs=1e-12)   # 2/12 (3 * 0.15^2 + 0.1^2)
    assert base["izz"] == pytest.approx(0.0225, abs=1e-12)       # 2 * 0.15^2 / 2
    bras = robot.link("bras").inertial.inertia
    assert bras["ixx"] == pytest.approx(0.3664 / 12, abs=1e-12)  # 1/12 (0.08^2 + 0.6^2)
    assert bras["izz"] == pytest.approx(0.0128 / 12, abs=1e-12)  # 1/12 (2 * 0.08^2)


def test_inertial_follows_changed_sizes_and_mass():
    robot = arm(inertials=True, params={"bras_length": 0.8, "bras_width": 0.1, "bras_mass": 3})
    inertial = robot.link("bras").inertial
    assert inertial.mass == 3.0
    assert inertial.origin.xyz == pytest.approx((0.0, 0.0, 0.4), abs=1e-12)
    assert inertial.inertia["ixx"] == pytest.approx(3 / 12 * (0.01 + 0.64), abs=1e-12)
    assert inertial.inertia["izz"] == pytest.approx(3 / 12 * 0.02, abs=1e-12)


def test_inertial_origin_is_the_visual_centre():
    robot = arm(wrist=True, inertials=True)
    for link in robot.links:
        assert link.inertial.origin.xyz == pytest.approx(link.visuals[0].origin.xyz, abs=1e-12)


# --- parameters --------------------------------------------------------------------------------------

def test_longer_bras_moves_the_elbow_and_the_visual():
    robot = arm(params={"bras_length": 0.8})
    assert robot.joint("coude").origin.xyz == (0.0, 0.0, 0.8)
    v = visual(robot, "bras")
    assert v.origin.xyz == (0.0, 0.0, 0.4) and v.geometry.size == (0.08, 0.08, 0.8)


def test_taller_base_moves_the_shoulder():
    robot = arm(params={"base_length": 0.2})
    assert robot.joint("epaule").origin.xyz == (0.0, 0.0, 0.1)
    assert visual(robot, "base").geometry.length == 0.2


def test_limits_and_colour_can_be_set():
    robot = arm(params={"coude_lower": -0.5, "coude_upper": "0.75", "bras_color": "1 0 0 1"})
    assert (robot.joint("coude").limit.lower, robot.joint("coude").limit.upper) == (-0.5, 0.75)
    assert visual(robot, "bras").material.rgba == (1.0, 0.0, 0.0, 1.0)


def test_every_template_argument_is_listed():
    params = template_parameters()
    assert params["bras_length"].default == "0.6" and params["bras_length"].kind == "number"
    assert params["base_color"].kind == "colour"
    assert params["wrist"].kind == "flag"
    assert len([p for p in params.values() if p.kind != "flag"]) == 28


def test_unknown_parameter_lists_valid_names():
    with pytest.raises(ParameterError) as info:
        arm(params={"bras_lenght": 0.8})
    assert "unknown parameter 'bras_lenght'" in str(info.value.message)
    for name in template_parameters():
        if template_parameters()[name].kind != "flag":
            assert name in str(info.value.hint)


@pytest.mark.parametrize("value", ["abc", "nan", "inf", ""])
def test_non_numeric_value_is_refused(value):
    with pytest.raises(ParameterError, match="is not a number"):
        arm(params={"bras_length": value})


@pytest.mark.parametrize("value", ["1 0 0", "1 0 0 2", "red 0 0 1"])
def test_bad_colour_is_refused(value):
    with pytest.raises(ParameterError, match="is not a colour"):
        arm(params={"bras_color": value})


def test_assignment_without_equals_is_refused():
    assert parse_assignments(["a=1", " b = 2 "]) == {"a": "1", "b": "2"}
    with pytest.raises(ParameterError, match="is not NAME=VALUE"):
        parse_assignments(["bras_length"])


# --- the urdf command ----------------------------------------------------------------------------------

def test_urdf_command_prints_the_arm(run_cli):
    code, out, err = run_cli("urdf", "--wrist", "--param", "bras_length=0.8")
    assert code == 0, err
    assert '<joint name="poignet" type="revolute">' in out
    assert '<origin xyz="0 0 0.8"/>' in out


def test_urdf_command_lists_parameters(run_cli):
    code, out, _ = run_cli("urdf", "--list-params")
    assert code == 0
    assert [line.split()[0] for line in out.splitlines()] == list(template_parameters())


@pytest.mark.parametrize("argument,message", [
    ("nope=1", "unknown parameter 'nope'"),
    ("bras_length=abc", "bras_length='abc' is not a number"),
    ("bras_length", "is not NAME=VALUE"),
])
def test_urdf_command_bad_parameter_exits_2_without_traceback(run_cli, argument, message):
    code, out, err = run_cli("urdf", "--param", argument)
    assert code == 2 and out == ""
    assert err.startswith("bras-kit urdf: error: ") and message in err
    assert "Traceback" not in err


def test_urdf_command_unknown_parameter_lists_valid_names(run_cli):
    _, _, err = run_cli("urdf", "--param", "nope=1")
    assert "valid names: base_length, base_radius" in err and "poignet_velocity" in err


def test_urdf_output_is_not_overwritten_without_force(run_cli, tmp_path):
    out = tmp_path / "bras.urdf"
    out.write_text("my hand-made URDF")
    code, _, err = run_cli("urdf", "-o", str(out))
    assert code == 2
    assert "already exists" in err and "--force" in err
    assert out.read_text() == "my hand-made URDF"
    code, _, _ = run_cli("urdf", "-o", str(out), "--force")
    assert code == 0
    assert load(out).joint("coude").origin.xyz == (0.0, 0.0, 0.6)


def test_old_set_spelling_still_works_with_a_deprecation_note(run_cli):
    code, out, err = run_cli("urdf", "--set", "bras_length=0.8")
    assert code == 0 and 'xyz="0 0 0.8"' in out
    assert "--set is deprecated for template parameters: use --param" in err


def test_a_joint_given_as_template_parameter_points_to_set(run_cli):
    code, _, err = run_cli("urdf", "--param", "coude=1")
    assert code == 2 and "'coude' is a joint, not a template parameter" in err and "--set" in err


@pytest.mark.parametrize("argument,words", [
    ("bras_length=0", "bras_length=0: a length must be between 0.001 and 10 m"),
    ("bras_length=600", "bras_length=600: a length must be between 0.001 and 10 m"),
    ("base_radius=-0.1", "base_radius=-0.1: a radius must be between 0.001 and 10 m"),
    ("poignet_width=1e-9", "poignet_width=1e-9: a width must be between 0.001 and 10 m"),
    ("avant_bras_mass=0", "avant_bras_mass=0: a mass must be between 0.001 and 1000 kg"),
    ("coude_velocity=0", "coude_velocity=0: a velocity limit must be between 0.001 and 100 rad/s"),
    ("epaule_effort=-5", "epaule_effort=-5: an effort limit must be between 0.001 and 10000 N.m"),
    ("coude_lower=-7", "coude_lower=-7: a joint limit must be between -6.2832 and 6.2832 rad"),
    ("epaule_upper=-2", "epaule_lower=-1.57 is above epaule_upper=-2"),
])
def test_the_generator_refuses_what_its_validator_would_reject(run_cli, argument, words):
    code, out, err = run_cli("urdf", "--param", argument)
    assert code == 2 and out == "" and words in err
    assert "Traceback" not in err


def test_a_limit_in_degrees_is_pointed_out():
    with pytest.raises(ParameterError, match=r"epaule_upper=90: a joint limit must be between") as caught:
        arm(params={"epaule_upper": "90"})
    assert str(caught.value.hint) == "90 looks like degrees: write epaule_upper=90deg (1.5708 rad)"


@pytest.mark.parametrize("typed,radians", [("pi/2", math.pi / 2), ("90deg", math.pi / 2), ("1,2", 1.2),
                                           ("-0.5*pi", -math.pi / 2)])
def test_limits_take_what_learners_type_for_joint_values(typed, radians):
    assert arm(params={"coude_upper": typed}).joint("coude").limit.upper == pytest.approx(radians, abs=1e-15)


def test_a_size_takes_the_french_decimal_comma():
    assert arm(params={"bras_length": "0,8"}).joint("coude").origin.xyz == (0.0, 0.0, 0.8)


def test_range_errors_are_french_with_lang_fr(run_cli):
    code, _, err = run_cli("--lang", "fr", "urdf", "--param", "bras_length=0")
    assert code == 2
    assert "bras_length=0 : une longueur doit être comprise entre 0.001 et 10 m" in err
    assert "les dimensions sont en mètres" in err


def _number_parameters():
    return [p for p in template_parameters().values() if p.kind == "number"]


def _errors(robot):
    from bras_kit.validate import validate

    return [f"{f.code} {f.message}" for f in validate(robot) if f.severity == "error"]


@pytest.mark.parametrize("name", [p.name for p in _number_parameters()])
def test_each_parameter_at_its_bounds_gives_a_urdf_the_validator_accepts(name):
    from bras_kit.model.authoring import parameter_range

    allowed = parameter_range(name)
    assert allowed is not None, f"{name} has no range: a new kind of parameter needs one"
    other = "upper" if name.endswith("_lower") else "lower"
    for value in (allowed.lowest, allowed.highest):
        params = {name: repr(value)}
        if name.endswith(("_lower", "_upper")):  # keep the pair ordered
            params[f"{name.rsplit('_', 1)[0]}_{other}"] = repr(value)
        for options in ({"wrist": True}, {"wrist": True, "inertials": True}):
            assert _errors(arm(params=params, **options)) == [], (params, options)
    below, above = allowed.lowest - abs(allowed.lowest) * 0.5 - 1e-9, allowed.highest * 2 + 1
    for value in (below, above):
        with pytest.raises(ParameterError, match=f"^{name}=") as caught:
            arm(params={name: repr(value)})
        assert f"between {allowed.lowest:g} and {allowed.highest:g}" in str(caught.value)


EXTREMES = {
    "all smallest": {p.name: "0.001" for p in _number_parameters() if p.name.endswith(
        ("_length", "_width", "_radius", "_mass", "_effort", "_velocity"))},
    "all largest": {**{p.name: "10" for p in _number_parameters() if p.name.endswith(("_length", "_width", "_radius"))},
                    **{p.name: "1000" for p in _number_parameters() if p.name.endswith("_mass")}},
    "needles": {**{p.name: "10" for p in _number_parameters() if p.name.endswith("_length")},
                **{p.name: "0.001" for p in _number_parameters() if p.name.endswith(("_width", "_radius", "_mass"))}},
    "plates": {**{p.name: "0.001" for p in _number_parameters() if p.name.endswith("_length")},
               **{p.name: "10" for p in _number_parameters() if p.name.endswith(("_width", "_radius"))},
               **{p.name: "1000" for p in _number_parameters() if p.name.endswith("_mass")}},
    "full turns, still joints": {"epaule_lower": "-6.2832", "epaule_upper": "6.2832", "coude_lower": "0.5",
                                 "coude_upper": "0.5", "poignet_lower": "-90deg", "poignet_upper": "pi/2"},
}


@pytest.mark.parametrize("case", EXTREMES)
def test_accepted_combinations_pass_the_validator_and_check_urdf(case, tmp_path):
    text = arm_urdf(wrist=True, inertials=True, params=EXTREMES[case])
    assert _errors(arm(wrist=True, inertials=True, params=EXTREMES[case])) == []
    path = tmp_path / "bras.urdf"
    path.write_text(text)
    checked = check_urdf(path)
    assert checked.returncode == 0, checked.stdout + checked.stderr
    assert "Successfully Parsed XML" in checked.stdout


@pytest.mark.parametrize("argv,options", [
    (["--wrist", "--param", "bras_length=0.8"], "wrist, param bras_length=0.8"),
    (["--inertials", "--param", "bras_color=0.1 0.2 0.3 1"], "inertials, param bras_color=0.1 0.2 0.3 1"),
    (["--collisions"], "collisions"),
])
def test_urdf_header_names_each_option_whole_in_a_well_formed_comment(run_cli, argv, options):
    import xml.etree.ElementTree as ElementTree
    from xml.dom import minidom

    code, out, _ = run_cli("urdf", *argv)
    header = out.splitlines()[1]
    assert header == (f"<!-- Generated by bras-kit urdf with the options {options} (on the command line, "
                      "each starts with two dashes, which an XML comment cannot hold) -->")
    minidom.parseString(out)  # expat refuses "--" inside a comment
    ElementTree.fromstring(out)
    assert "- -" not in out


def test_urdf_header_and_template_comments_in_french(run_cli):
    code, out, _ = run_cli("urdf", "--lang", "fr", "--wrist")
    lines = out.splitlines()
    assert lines[1] == ("<!-- Généré par bras-kit urdf avec les options wrist (sur la ligne de commande, chacune "
                        "commence par deux tirets, qu'un commentaire XML ne peut pas contenir) -->")
    assert "l'option param de bras-kit urdf" in out and "Every number" not in out


def test_every_comment_of_the_template_has_french_words():
    """A comment added to the template in English only would reach a French package's xacro."""
    from babel.messages.pofile import read_po

    from bras_kit.core.i18n import LOCALE_DIR
    from bras_kit.core.resources import robot_template
    from bras_kit.model.authoring import _COMMENT, comment_id, localise_comments

    with (LOCALE_DIR / "fr" / "LC_MESSAGES" / "package.po").open("rb") as handle:
        french = {m.id: m.string for m in read_po(handle) if m.id}
    template = robot_template().read_text(encoding="utf-8")
    comments = [comment_id(found.group(1)) for found in _COMMENT.finditer(template)]
    assert len(comments) == 19  # the two inertia formulas (issue 52) included
    missing = [c for c in comments if not french.get(c)]
    assert missing == []
    translated = localise_comments(template, "fr")
    assert [comment_id(found.group(1)) for found in _COMMENT.finditer(translated)] == [french[c] for c in comments]
    assert all("--" not in french[c] for c in comments)
    assert expand_xacro_text(translated) == expand_xacro_text(template)


def expand_xacro_text(text):
    """The expansion without its comments: translating comments changes nothing else."""
    import re
    import tempfile

    from bras_kit.model.xacro import expand_xacro

    with tempfile.TemporaryDirectory() as folder:
        path = Path(folder) / "bras.urdf.xacro"
        path.write_text(text, encoding="utf-8")
        return re.sub(r"<!--.*?-->", "", expand_xacro(path, {"wrist": "true", "inertials": "true"}), flags=re.S)


def test_the_built_in_arm_is_cached_and_equals_xacros_expansion(tmp_path, monkeypatch):
    import xacro

    from bras_kit.core.resources import robot_template

    monkeypatch.setenv("XDG_CACHE_HOME", str(tmp_path))
    first = arm_urdf(wrist=True)
    files = list((tmp_path / "bras-kit").glob("arm-*.urdf"))
    assert len(files) == 1
    real = xacro.process_file(str(robot_template()), mappings={
        "wrist": "true", "inertials": "false", "collisions": "false", "base_inertial": "true"}).toprettyxml(indent="  ")
    assert files[0].read_text() == real  # what is kept is the real xacro's output
    assert arm_urdf(wrist=True) == first
    files[0].write_text("<?xml version='1.0'?>\n<robot")  # a cut-short cache is not trusted
    assert arm_urdf(wrist=True) == first
    files[0].unlink()
    victim = tmp_path / "victim.txt"
    victim.write_text("keep")
    files[0].symlink_to(victim)  # a link planted there is neither read nor written through
    assert arm_urdf(wrist=True) == first
    assert victim.read_text() == "keep"
