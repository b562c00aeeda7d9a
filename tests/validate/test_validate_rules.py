"""One test per validator rule: a file that triggers it (exact message, line, hint) and a near miss
that does not. Files are the hand-written tutorial arm (tests/data/urdf/good/bras.urdf) with one
thing changed, written to tmp_path."""

from __future__ import annotations

import numpy as np
import pytest
from paths import TESTS
from urdfdom_oracle import check_urdf

from bras_kit.core.errors import ParameterError
from bras_kit.validate import validate, validate_path

DATA = TESTS / "data" / "urdf"
BRAS = (DATA / "good" / "bras.urdf").read_text(encoding="utf-8")
# lines of the reference file
LINE_ROBOT, LINE_BASE, LINE_BRAS, LINE_AVANT_BRAS = 4, 6, 13, 21
LINE_EPAULE, LINE_COUDE = 29, 37
LINE_COUDE_ORIGIN, LINE_COUDE_AXIS, LINE_COUDE_LIMIT = 40, 41, 42

COUDE_LIMIT = '<limit lower="-2.0" upper="2.0" effort="10" velocity="1.0"/>'
AVANT_BRAS_VISUAL_ORIGIN = '<origin xyz="0 0 0.25"/>'


def edited(*changes: tuple[str, str], text: str = BRAS) -> str:
    """The reference text with each (old, new) replaced once; ``old`` must be there."""
    for old, new in changes:
        assert old in text, old
        text = text.replace(old, new, 1)
    return text


def add_before_end(snippet: str, text: str = BRAS) -> str:
    return edited(("</robot>", snippet + "\n</robot>"), text=text)


@pytest.fixture
def check(tmp_path):
    def run(text: str, name: str = "robot.urdf", **options):
        path = tmp_path / name
        path.write_text(text, encoding="utf-8")
        return validate_path(str(path), **options)

    return run


def only(findings, code):
    hits = [f for f in findings if f.code == code]
    assert len(hits) == 1, [(f.code, f.text("en")) for f in findings]
    return hits[0]


def codes(findings) -> set[str]:
    return {f.code for f in findings}


# ====================================================================== baseline


def test_reference_arm_has_only_the_inertial_note(check):
    findings = check(BRAS)
    assert [(f.code, f.severity) for f in findings] == [("BK505", "info")]
    note = findings[0]
    assert note.text("en") == ("2 moving links have no <inertial> ('bras', 'avant_bras'): "
                            "fine for RViz, needed for physics simulation")
    assert (note.element, note.name, note.line) == ("link", "bras", LINE_BRAS)


@pytest.mark.parametrize("variant", [{}, {"wrist": True}, {"inertials": True}, {"wrist": True, "inertials": True}])
def test_tutorial_arm_variants_have_no_error_or_warning(variant):
    from bras_kit.model.authoring import arm

    findings = validate(arm(**variant))
    assert [f for f in findings if f.severity != "info"] == []


def test_tutorial_arm_with_changed_lengths_stays_clean():
    from bras_kit.model.authoring import arm

    robot = arm(wrist=True, inertials=True, params={"bras_length": 0.8, "avant_bras_length": 0.35})
    assert [f.code for f in validate(robot) if f.severity != "info"] == []


# ====================================================================== BK1xx loading


def test_not_well_formed_xml_names_the_line(check):
    findings = check(edited(('<box size="0.08 0.08 0.6"/>', '<box size="0.08 0.08 0.6">')))
    assert len(findings) == 1
    f = findings[0]
    assert (f.code, f.severity, f.line, f.element) == ("BK100", "error", 16, "file")
    assert f.text("en") == ("not well-formed XML: the tag <box> opened on line 16 is never closed: "
                            "the reader met </geometry> on line 16 while <box> was still open")
    assert "BK100" not in codes(check(BRAS))


def test_truncated_file_is_not_well_formed(check):
    f = only(check(BRAS[: BRAS.index("<joint name=\"coude\"")]), "BK100")
    assert f.text("en").startswith("not well-formed XML: the tag <robot name=\"bras\"> opened on line 4 is never closed")


def test_doctype_with_an_external_dtd_is_refused(check):
    text = BRAS.replace('<?xml version="1.0"?>\n', '<?xml version="1.0"?>\n<!DOCTYPE robot SYSTEM "robot.dtd">\n', 1)
    f = only(check(text), "BK101")
    assert (f.line, f.text("en")) == (2, "refused: the file declares a DTD (<!DOCTYPE ...>)")
    assert f.hint_text("en") == "delete the <!DOCTYPE ...> block: URDF files never need one"


def test_plain_doctype_naming_the_root_is_accepted_like_urdfdom_and_xacro(check):
    text = BRAS.replace('<?xml version="1.0"?>\n', '<?xml version="1.0"?>\n<!DOCTYPE robot>\n', 1)
    assert "BK101" not in codes(check(text))


def test_comment_mentioning_doctype_is_not_refused(check):
    assert "BK101" not in codes(check(edited(("<robot name=", "<!-- no <!DOCTYPE> here -->\n<robot name="))))


def test_entity_reference_is_refused(check):
    f = only(check(edited(('name="bras">', 'name="bras&eacute;">'))), "BK101")
    assert f.text("en") == "refused: the file uses an entity reference (&name;) that bras-kit does not expand"


def test_xacro_failure_is_reported_with_its_kind(check):
    text = '<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="${longueur}"/></robot>'
    f = only(check(text, "bras.urdf.xacro"), "BK102")
    assert f.text("en") == "xacro failed: NameError: name 'longueur' is not defined in the expression 'longueur'"
    assert f.hint_text("en") == "define the property with <xacro:property name=... value=...> before it is used"


def test_xacro_that_expands_is_not_a_failure(check):
    text = ('<robot name="b" xmlns:xacro="http://www.ros.org/wiki/xacro">'
            '<xacro:property name="longueur" value="0.6"/><link name="l${longueur}"/></robot>')
    findings = check(text, "bras.urdf.xacro")
    assert "BK102" not in codes(findings)
    assert codes(findings) == {"BK306", "BK307"}  # one link, nothing moves, nothing drawn


def test_missing_file_is_unreadable(tmp_path):
    missing = tmp_path / "absent.urdf"
    f = only(validate_path(str(missing)), "BK103")
    assert f.text("en") == f"no such file: {missing}"
    assert f.line is None


def test_folder_given_to_validate_path_is_unreadable(tmp_path):
    f = only(validate_path(str(tmp_path)), "BK103")
    assert f.text("en") == f"{tmp_path} is a folder, not a file"


def test_macro_only_xacro_is_a_library_note(check):
    text = ('<robot name="pieces" xmlns:xacro="http://www.ros.org/wiki/xacro">'
            '<xacro:macro name="segment" params="name"><link name="${name}"/></xacro:macro></robot>')
    findings = check(text, "pieces.xacro")
    assert [(f.code, f.severity) for f in findings] == [("BK124", "info")]


def test_xacro_without_macros_and_links_is_not_a_library(check):
    text = '<robot name="vide" xmlns:xacro="http://www.ros.org/wiki/xacro"></robot>'
    assert codes(check(text, "vide.xacro")) == {"BK106"}


# ====================================================================== BK1xx structure


def test_root_not_robot(check):
    f = only(check('<?xml version="1.0"?>\n<sdf version="1.6"><model name="bras"/></sdf>'), "BK104")
    assert (f.element, f.line, f.text("en")) == ("sdf", 2, "the outer element is <sdf>, not <robot>")
    assert codes(check('<sdf/>')) == {"BK104"}  # nothing else is reported about a non-robot
    assert "BK104" not in codes(check(BRAS))


def test_robot_without_name(check):
    f = only(check(edited(('<robot name="bras">', "<robot>"))), "BK105")
    assert (f.element, f.name, f.line, f.text("en")) == ("robot", None, LINE_ROBOT, "<robot> has no name attribute")
    assert "BK105" in codes(check(edited(('<robot name="bras">', '<robot name="  ">'))))
    assert "BK105" not in codes(check(edited(('<robot name="bras">', '<robot name="x">'))))


def test_robot_without_links(check):
    f = only(check('<robot name="vide">\n</robot>'), "BK106")
    assert (f.element, f.name, f.line, f.text("en")) == ("robot", "vide", 1, "the robot has no <link>")
    assert "BK106" not in codes(check('<robot name="un"><link name="base"/></robot>'))


def test_duplicate_link_name(check):
    findings = check(edited(('<link name="avant_bras">', '<link name="bras">')))
    f = only(findings, "BK107")
    assert (f.name, f.line, f.text("en")) == ("bras", LINE_AVANT_BRAS, "link 'bras' is defined twice (first on line 13)")


def test_link_and_joint_may_share_a_name(check):
    wrist = add_before_end(
        '<link name="poignet"><visual><origin xyz="0 0 0.075"/><geometry><box size="0.04 0.04 0.15"/>'
        '</geometry></visual></link>\n'
        '<joint name="poignet" type="revolute"><parent link="avant_bras"/><child link="poignet"/>'
        '<origin xyz="0 0 0.5"/><axis xyz="0 1 0"/>'
        '<limit lower="-1.57" upper="1.57" effort="5" velocity="1.5"/></joint>')
    findings = check(wrist)
    assert codes(findings) == {"BK505", "BK700"}  # BK700: fine for RViz, refused by Gazebo
    assert {f.severity for f in findings if f.code == "BK700"} == {"warning"}


def test_duplicate_joint_name(check):
    f = only(check(edited(('<joint name="coude"', '<joint name="epaule"'))), "BK108")
    assert (f.name, f.line, f.text("en")) == ("epaule", LINE_COUDE, "joint 'epaule' is defined twice (first on line 29)")


def test_duplicate_top_level_material(check):
    text = edited(("<link name=\"base\">", '<material name="gris"><color rgba="0.5 0.5 0.5 1"/></material>\n'
                   '<material name="gris"><color rgba="0.4 0.4 0.4 1"/></material>\n<link name="base">'))
    f = only(check(text), "BK109")
    assert (f.element, f.name, f.line) == ("material", "gris", 7)
    assert f.text("en") == "material 'gris' is defined twice at the top level (first on line 6)"


def test_same_inline_material_twice_with_same_colour_is_fine(check):
    text = edited(('<material name="orange"><color rgba="0.95 0.5 0.1 1"/>',
                   '<material name="bleu"><color rgba="0.2 0.4 0.9 1"/>'))
    assert not codes(check(text)) & {"BK109", "BK110"}


def test_material_redefined_with_another_colour(check):
    text = edited(('<material name="orange"><color rgba="0.95 0.5 0.1 1"/>',
                   '<material name="bleu"><color rgba="0.95 0.5 0.1 1"/>'))
    f = only(check(text), "BK110")
    assert (f.severity, f.element, f.name, f.line) == ("warning", "material", "bleu", 25)
    assert f.text("en") == ("material 'bleu' in link 'avant_bras' has colour 0.95 0.5 0.1 1, "
                         "but 'bleu' is already 0.2 0.4 0.9 1 (line 17), which wins")


def test_joint_parent_missing(check):
    f = only(check(edited(('<parent link="bras"/>', '<parent link="Bras"/>'))), "BK111")
    assert (f.name, f.line) == ("coude", LINE_COUDE)
    assert f.text("en") == "joint 'coude' has parent link 'Bras', which is not defined"
    assert f.hint_text("en") == "did you mean 'bras'? Link names must match exactly, case included"
    assert "BK111" not in codes(check(BRAS))


def test_joint_child_missing_without_close_name_lists_links(check):
    f = only(check(edited(('<child link="avant_bras"/>', '<child link="pince"/>'))), "BK112")
    assert f.text("en") == "joint 'coude' has child link 'pince', which is not defined"
    assert f.hint_text("en") == "define <link name=\"pince\"> or use one of the links: 'base', 'bras', 'avant_bras'"


def test_joint_parent_is_child(check):
    f = only(check(edited(('<parent link="bras"/>', '<parent link="avant_bras"/>'))), "BK113")
    assert f.text("en") == "joint 'coude' has 'avant_bras' as both parent and child"
    assert "BK113" not in codes(check(BRAS))


def test_link_with_two_parents(check):
    text = add_before_end('<joint name="renfort" type="fixed"><parent link="base"/>'
                          '<child link="avant_bras"/></joint>')
    f = only(check(text), "BK114")
    assert (f.name, f.line) == ("renfort", 45)
    assert f.text("en") == ("link 'avant_bras' is the child of joint 'coude' (line 37) "
                         "and again of joint 'renfort'")


def test_joint_cycle_names_the_loop(check):
    text = add_before_end('<joint name="retour" type="fixed"><parent link="avant_bras"/>'
                          '<child link="base"/></joint>')
    findings = check(text)
    f = only(findings, "BK115")
    assert (f.name, f.line) == ("retour", 45)
    assert f.text("en") == "the joints form a loop: base -> bras -> avant_bras -> base"
    assert f.hint_text("en") == ("break the loop: one of the joints 'epaule', 'coude', 'retour' points back up "
                      "the tree; make its child a new link")
    assert "BK116" not in codes(findings)


def test_several_roots_are_named(check):
    text = add_before_end('<link name="socle"/><link name="pince"/>'
                          '<joint name="serrage" type="fixed"><parent link="socle"/><child link="pince"/></joint>')
    f = only(check(text), "BK116")
    assert (f.name, f.line) == ("socle", 45)
    assert f.text("en") == "the robot has several root links: 'base', 'socle'"
    assert f.hint_text("en") == "attach 'socle' under another link with a joint (for instance a fixed joint from 'base')"


def test_link_disconnected(check):
    findings = check(add_before_end('<link name="poignet"/>'))
    f = only(findings, "BK117")
    assert (f.name, f.line, f.text("en")) == ("poignet", 45, "link 'poignet' is not connected by any joint")
    assert f.hint_text("en") == "add a joint with <child link=\"poignet\"/>, for instance from 'base', or remove the link"
    assert "BK116" not in codes(findings)  # an isolated link is reported once, as disconnected


def test_links_without_any_joint_take_the_first_as_root(check):
    findings = check('<robot name="r"><link name="a"/><link name="b"/></robot>')
    assert [(f.code, f.name) for f in findings if f.code == "BK117"] == [("BK117", "b")]


def test_joint_type_unknown(check):
    f = only(check(edited(('<joint name="coude" type="revolute">', '<joint name="coude" type="Revolute">'))),
             "BK118")
    assert f.text("en") == "joint 'coude' has type 'Revolute', which URDF does not know"
    assert f.hint_text("en") == 'did you mean type="revolute"? Types are lower case'
    f = only(check(edited(('<joint name="coude" type="revolute">', '<joint name="coude" type="hinge">'))), "BK118")
    assert f.hint_text("en") == "use one of: 'revolute', 'continuous', 'prismatic', 'fixed', 'floating', 'planar'"


def test_xacro_left_in_urdf(check):
    text = edited(('<robot name="bras">', '<robot name="bras" xmlns:xacro="http://www.ros.org/wiki/xacro">\n'
                   '  <xacro:property name="longueur" value="0.6"/>'),
                  ('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 ${longueur}"/>'))
    findings = check(text)
    f = only(findings, "BK119")
    assert (f.element, f.line) == ("xacro:property", 5)
    assert f.text("en") == "xacro markup in a plain URDF: <xacro:property> (and 1 more line)"  # one line: singular (issue 52)
    assert "BK123" in codes(findings)  # the unexpanded number is unreadable too
    assert "BK119" not in codes(check(text, "bras.urdf.xacro"))  # a .xacro is expanded first


def test_mimic_unknown_joint(check):
    text = edited(('<limit lower="-1.57" upper="1.57" effort="10" velocity="1.0"/>',
                   '<limit lower="-1.57" upper="1.57" effort="10" velocity="1.0"/><mimic joint="coud"/>'))
    f = only(check(text), "BK120")
    assert (f.name, f.line) == ("epaule", 34)
    assert f.text("en") == "joint 'epaule' mimics 'coud', which is not a joint of this robot"
    assert f.hint_text("en") == "did you mean 'coude'?"


def test_mimic_of_a_known_joint_is_fine(check):
    text = edited((COUDE_LIMIT, COUDE_LIMIT + '<mimic joint="epaule" multiplier="-1"/>'))
    assert not codes(check(text)) & {"BK120", "BK121"}


def test_mimic_cycle(check):
    text = edited(('<limit lower="-1.57" upper="1.57" effort="10" velocity="1.0"/>',
                   '<limit lower="-1.57" upper="1.57" effort="10" velocity="1.0"/><mimic joint="coude"/>'),
                  (COUDE_LIMIT, COUDE_LIMIT + '<mimic joint="epaule"/>'))
    f = only(check(text), "BK121")
    assert f.text("en") == "mimic joints follow each other in a loop: epaule -> coude -> epaule"


def test_missing_attribute(check):
    f = only(check(edited(('<joint name="coude" type="revolute">', '<joint name="coude">'))), "BK122")
    assert (f.element, f.name, f.line) == ("joint", "coude", LINE_COUDE)
    assert (f.text("en"), f.hint_text("en")) == ("<joint> has no 'type' attribute", 'write it, e.g. type="revolute"')


def test_missing_child_element(check):
    f = only(check(edited(('<child link="avant_bras"/>', ''))), "BK122")
    assert (f.text("en"), f.hint_text("en")) == ("<joint> has no <child>", 'write it, e.g. <child link="avant_bras"/>')


def test_missing_attribute_belongs_to_the_right_owner_when_names_are_shared(check):
    text = add_before_end(
        '<link name="poignet"><visual><origin xyz="0 0 0.075"/><geometry><box size="0.04 0.04 0.15"/>'
        '</geometry></visual></link>\n'
        '<joint name="poignet" type="revolute"><parent link="avant_bras"/><child link="poignet"/>\n'
        '<origin xyz="0 0 0.5"/><axis xyz="0 1 0"/><limit lower="-1.57" upper="1.57" effort="5"/></joint>')
    f = only(check(text), "BK201")
    assert (f.element, f.name, f.line) == ("joint", "poignet", 47)
    text = text.replace('<box size="0.04 0.04 0.15"/>', "<box/>")
    f = only(check(text), "BK122")
    assert (f.element, f.name, f.text("en")) == ("link", "poignet", "<box> has no 'size' attribute")


def test_number_unreadable(check):
    f = only(check(edited(('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0,6"/>'))), "BK123")
    assert (f.element, f.name, f.line) == ("joint", "coude", LINE_COUDE_ORIGIN)
    assert f.text("en") == '<origin> xyz="0 0,6" is not 3 numbers'
    assert f.hint_text("en") == 'write 3 numbers separated by spaces, e.g. xyz="0 0 0.6"'


def test_single_number_unreadable(check):
    f = only(check(edited(('upper="2.0" effort', 'upper="2,0" effort'))), "BK123")
    assert (f.text("en"), f.line) == ('<limit> upper="2,0" writes 2,0 with a decimal comma: URDF numbers take a point',
                                      LINE_COUDE_LIMIT)
    assert f.hint_text("en") == 'write upper="2.0"'


def test_single_number_with_a_unit_unreadable(check):
    f = only(check(edited(('upper="2.0" effort', 'upper="2rad" effort'))), "BK123")
    assert (f.text("en"), f.line) == ('<limit> upper="2rad" is not a number', LINE_COUDE_LIMIT)
    assert f.hint_text("en") == "write one number with a decimal point, e.g. 0.6 (not 0,6 and no unit)"


@pytest.mark.parametrize("digits", ["\u0661", "\uff11", "1_0"], ids=["arabic-indic", "full-width", "underscore"])
def test_number_python_reads_but_urdfdom_does_not_is_unreadable(check, digits):
    """float() accepts these; urdfdom (a C++ stream) reads only ASCII digits, sign, point, exponent."""
    f = only(check(edited(('upper="2.0" effort', f'upper="{digits}" effort'))), "BK123")
    assert (f.text("en"), f.line) == (f'<limit> upper="{digits}" is not a number', LINE_COUDE_LIMIT)


# ====================================================================== BK2xx joints


def test_revolute_without_limit(check):
    f = only(check(edited((COUDE_LIMIT, ""))), "BK200")
    assert (f.name, f.line, f.text("en")) == ("coude", LINE_COUDE, "revolute joint 'coude' has no <limit>")
    assert f.hint_text("en").startswith('add <limit lower="-1.57" upper="1.57" effort="10" velocity="1.0"/>')


def test_continuous_without_limit_is_fine(check):
    text = edited(('<joint name="coude" type="revolute">', '<joint name="coude" type="continuous">'),
                  (COUDE_LIMIT, ""))
    assert "BK200" not in codes(check(text))


def test_limit_without_effort(check):
    f = only(check(edited((COUDE_LIMIT, '<limit lower="-2.0" upper="2.0" velocity="1.0"/>'))), "BK201")
    assert (f.line, f.text("en")) == (LINE_COUDE_LIMIT, "joint 'coude': <limit> is missing 'effort'")
    assert f.hint_text("en").startswith('add effort="10" ')
    f = only(check(edited((COUDE_LIMIT, '<limit lower="-2.0" upper="2.0"/>'))), "BK201")
    assert f.text("en") == "joint 'coude': <limit> is missing 'effort', 'velocity'"
    assert "BK201" not in codes(check(BRAS))


def test_lower_above_upper(check):
    f = only(check(edited((COUDE_LIMIT, '<limit lower="2.0" upper="-2.0" effort="10" velocity="1.0"/>'))), "BK202")
    assert (f.severity, f.line) == ("error", LINE_COUDE_LIMIT)
    assert f.text("en") == "joint 'coude': lower limit 2 is above upper limit -2 rad"
    assert f.hint_text("en") == 'swap them: lower="-2" upper="2"'


def test_lower_equal_upper(check):
    f = only(check(edited((COUDE_LIMIT, '<limit lower="0.5" upper="0.5" effort="10" velocity="1.0"/>'))), "BK203")
    assert f.severity == "warning"
    assert f.text("en") == "joint 'coude': lower and upper are both 0.5 rad, so the joint cannot move"
    f = only(check(edited((COUDE_LIMIT, '<limit effort="10" velocity="1.0"/>'))), "BK203")
    assert f.text("en") == ("joint 'coude': <limit> gives neither lower nor upper, so both are 0 "
                         "and the joint cannot move")
    assert not codes(check(BRAS)) & {"BK202", "BK203"}


def test_zero_axis(check):
    f = only(check(edited(('<axis xyz="0 1 0"/>\n    <limit lower="-2.0"', '<axis xyz="0 0 0"/>\n    <limit lower="-2.0"'))),
             "BK204")
    assert (f.severity, f.line) == ("error", LINE_COUDE_AXIS)
    assert f.text("en") == "joint 'coude': <axis xyz=\"0 0 0\"> has no direction"


def test_non_unit_axis_is_normalised(check):
    f = only(check(edited(('<axis xyz="0 1 0"/>\n    <limit lower="-2.0"', '<axis xyz="0 2 0"/>\n    <limit lower="-2.0"'))),
             "BK205")
    assert f.severity == "warning"
    assert f.text("en") == "joint 'coude': axis 0 2 0 has length 2; it will be normalised to 0 1 0"
    assert f.hint_text("en") == 'write the unit vector: <axis xyz="0 1 0"/>'
    nearly_unit = check(edited(('<axis xyz="0 1 0"/>\n    <limit lower="-2.0"',
                                '<axis xyz="0 0.7071 0.7071"/>\n    <limit lower="-2.0"')))
    assert "BK205" not in codes(nearly_unit)


def test_axis_not_three_numbers(check):
    f = only(check(edited(('<axis xyz="0 1 0"/>\n    <limit lower="-2.0"', '<axis xyz="0 1"/>\n    <limit lower="-2.0"'))),
             "BK206")
    assert (f.name, f.line, f.text("en")) == ("coude", LINE_COUDE_AXIS, "joint 'coude': <axis xyz=\"0 1\"> is not three numbers")
    f = only(check(edited(('<axis xyz="0 1 0"/>\n    <limit lower="-2.0"', '<axis/>\n    <limit lower="-2.0"'))), "BK206")
    assert f.text("en") == "joint 'coude': <axis> has no xyz attribute"


def test_non_finite_number_anywhere(check):
    findings = check(edited(('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 nan"/>'),
                            ('<box size="0.06 0.06 0.5"/>', '<box size="0.06 0.06 inf"/>')))
    found = [(f.element, f.name, f.line, f.text("en")) for f in findings if f.code == "BK207"]
    assert found == [("link", "avant_bras", 24, '<box> size="0.06 0.06 inf" is not a finite number'),
                     ("joint", "coude", LINE_COUDE_ORIGIN, '<origin> xyz="0 0 nan" is not a finite number')]
    assert "BK207" not in codes(check(edited(('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 6e-1"/>'))))


def test_continuous_joint_with_bounds(check):
    f = only(check(edited(('<joint name="coude" type="revolute">', '<joint name="coude" type="continuous">'))),
             "BK208")
    assert f.text("en") == "joint 'coude' is continuous, so URDF readers ignore 'lower', 'upper' in its <limit>"
    text = edited(('<joint name="coude" type="revolute">', '<joint name="coude" type="continuous">'),
                  (COUDE_LIMIT, '<limit effort="10" velocity="1.0"/>'))
    assert "BK208" not in codes(check(text))


def test_effort_or_velocity_not_positive(check):
    findings = check(edited((COUDE_LIMIT, '<limit lower="-2.0" upper="2.0" effort="0" velocity="-1"/>')))
    assert [f.text("en") for f in findings if f.code == "BK209"] == [
        "joint 'coude': effort limit 0 is not positive",
        "joint 'coude': velocity limit -1 is not positive",
    ]
    assert "BK209" not in codes(check(BRAS))


def test_prismatic_travel_in_millimetres(check):
    text = edited(('<joint name="coude" type="revolute">', '<joint name="coude" type="prismatic">'),
                  (COUDE_LIMIT, '<limit lower="0" upper="200" effort="100" velocity="0.5"/>'))
    f = only(check(text), "BK210")
    assert f.text("en") == "prismatic joint 'coude' travels 200 m (0 to 200); limits are in metres"
    assert f.hint_text("en") == 'if you wrote millimetres, use lower="0" upper="0.2"'
    text = text.replace('upper="200"', 'upper="0.2"')
    assert "BK210" not in codes(check(text))


def test_revolute_limits_in_degrees(check):
    f = only(check(edited((COUDE_LIMIT, '<limit lower="-90" upper="90" effort="10" velocity="1.0"/>'))), "BK211")
    assert f.text("en") == "joint 'coude': limits -90..90 exceed a full turn; URDF angles are radians"
    assert f.hint_text("en") == 'in radians: lower="-1.5708" upper="1.5708"'
    full_turn = edited((COUDE_LIMIT, '<limit lower="-6.2832" upper="6.2832" effort="10" velocity="1.0"/>'))
    assert "BK211" not in codes(check(full_turn))


def test_axis_on_fixed_joint(check):
    f = only(check(edited(('<joint name="coude" type="revolute">', '<joint name="coude" type="fixed">'),
                          (COUDE_LIMIT, ""))), "BK212")
    assert (f.line, f.text("en")) == (LINE_COUDE_AXIS, "joint 'coude' is fixed, so its <axis> is ignored")
    f = only(check(edited(('<joint name="coude" type="revolute">', '<joint name="coude" type="fixed">'))), "BK212")
    assert f.text("en") == "joint 'coude' is fixed, so its <axis> and <limit> are ignored"
    bare = edited(('<joint name="coude" type="revolute">', '<joint name="coude" type="fixed">'),
                  (COUDE_LIMIT, ""), ('<axis xyz="0 1 0"/>\n    \n', ""))
    assert "BK212" not in codes(check(bare))


def test_moving_joint_without_axis_turns_about_x(check):
    f = only(check(edited(('<axis xyz="0 1 0"/>\n    <limit lower="-2.0"', '<limit lower="-2.0"'))), "BK213")
    assert (f.severity, f.text("en")) == ("info", "joint 'coude' has no <axis>: it turns about x (1 0 0), the URDF default")
    assert "BK213" not in codes(check(BRAS))


# ====================================================================== BK3xx tutorial pitfalls


def test_elbow_short_of_the_upper_arm_end(check):
    """The tutorial's "segments mal positionnés": coude at z 0.5 on a 0.6 m upper arm."""
    f = only(check(edited(('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 0.5"/>'))), "BK301")
    assert (f.severity, f.element, f.name, f.line) == ("warning", "joint", "coude", LINE_COUDE_ORIGIN)
    assert f.text("en") == ("joint 'coude' is at z=0.5, but the <box> of link 'bras' runs z 0..0.6: "
                         "the child hangs 0.1 m short of the segment's end")
    assert f.hint_text("en") == "put the joint at the end of 'bras': <origin xyz=\"0 0 0.6\"/>"
    assert f.data["expected"] == pytest.approx((0.0, 0.0, 0.6))


def test_elbow_past_the_upper_arm_end(check):
    f = only(check(edited(('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 0.7" rpy="0 0.1 0"/>'))), "BK301")
    assert f.text("en") == ("joint 'coude' is at z=0.7, 0.1 m past the end of link 'bras' (its <box> runs z 0..0.6): "
                         "the child floats in the air")
    assert f.hint_text("en") == "put the joint at the end of 'bras': <origin xyz=\"0 0 0.6\" rpy=\"0 0.1 0\"/>"


def test_segment_hung_above_the_base_is_a_warning_with_the_origin_on_the_base(check):
    # issue 19: the base is a flat cylinder (z -0.05..0.05); a shoulder at z=0.1 leaves the upper arm
    # (drawn from its joint up) 5 cm in the air: the origin to write is on the base's top face
    f = only(check(edited(('<origin xyz="0 0 0.05"/>', '<origin xyz="0 0 0.1"/>'))), "BK301")
    assert (f.name, f.variant, f.severity) == ("epaule", "detached", "warning")
    assert abs(f.data["distance"] - 0.05) < 1e-9
    assert f.hint_text("en") == "put the joint on the <cylinder> of 'base': <origin xyz=\"0 0 0.05\"/>"


def test_prismatic_carriage_mid_rail_is_not_a_segment_mistake(check):
    rail = ('<robot name="cartpole"><link name="rail"><visual><geometry><box size="4 0.05 0.05"/></geometry>'
            '</visual></link><link name="cart"><visual><geometry><box size="0.3 0.2 0.1"/></geometry></visual>'
            '</link><joint name="slider" type="prismatic"><parent link="rail"/><child link="cart"/>'
            '<origin xyz="0 0 0"/><axis xyz="1 0 0"/>'
            '<limit lower="-1.9" upper="1.9" effort="10" velocity="1"/></joint></robot>')
    assert "BK301" not in codes(check(rail))
    revolute = rail.replace('type="prismatic"', 'type="revolute"')  # a hinge mid-rail is the tutorial's mistake
    assert only(check(revolute), "BK301").severity == "warning"


def test_joint_far_past_the_tutorial_segment_is_a_warning_at_any_distance(check):
    # issue 19: 0.9 m past the end of the 0.6 m upper arm, the forearm floats; the old quarter-length window missed it
    f = only(check(edited(('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 1.5"/>'))), "BK301")
    assert (f.variant, round(f.data["distance"], 9)) == ("beyond", 0.9)
    assert f.hint_text("en") == "put the joint at the end of 'bras': <origin xyz=\"0 0 0.6\"/>"


def test_joint_within_tolerance_of_the_end_or_fixed_is_not_flagged(check):
    # 2 % of the 0.6 m segment is 12 mm: 5 mm off is rounding, not a mistake
    assert "BK301" not in codes(check(edited(('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 0.605"/>'))))
    # a shoulder inside the base cylinder is allowed (turntables sit inside their housing)
    assert "BK301" not in codes(check(edited(('<origin xyz="0 0 0.05"/>', '<origin xyz="0 0 0.0"/>'))))
    # fixed joints (sensor mounts) may sit anywhere on the segment
    camera = add_before_end('<link name="camera"/><joint name="camera_joint" type="fixed"><parent link="bras"/>'
                            '<child link="camera"/><origin xyz="0.04 0 0.3"/></joint>')
    assert "BK301" not in codes(check(camera))


def test_forearm_visual_leaves_a_gap_at_the_elbow(check):
    """The brief's example: visual origin z 0.3 for a 0.5 m box starts 5 cm after the joint."""
    f = only(check(edited((AVANT_BRAS_VISUAL_ORIGIN, '<origin xyz="0 0 0.3"/>'))), "BK302")
    assert (f.severity, f.element, f.name, f.line) == ("warning", "link", "avant_bras", 23)
    assert f.text("en") == ("the <box> of link 'avant_bras' starts 0.05 m after joint 'coude' (it runs z 0.05..0.55): "
                         "a gap shows between the segments")
    assert f.hint_text("en") == "start the visual at the joint: <origin xyz=\"0 0 0.25\"/> in the <visual> of 'avant_bras'"


def test_forearm_visual_overlaps_the_upper_arm(check):
    f = only(check(edited((AVANT_BRAS_VISUAL_ORIGIN, '<origin xyz="0 0 0.2"/>'))), "BK302")
    assert f.text("en") == ("the <box> of link 'avant_bras' reaches 0.05 m behind joint 'coude' (it runs z -0.05..0.45): "
                         "it overlaps the previous segment")


def test_forearm_visual_without_origin_is_centred_on_the_joint(check):
    f = only(check(edited((AVANT_BRAS_VISUAL_ORIGIN + "\n", ""))), "BK302")
    assert f.line == 22  # the <visual> itself: it has no <origin> line
    assert f.text("en") == ("the <box> of link 'avant_bras' is centred on joint 'coude' (it runs z -0.25..0.25): "
                         "half of it sticks out behind the joint")
    assert f.hint_text("en") == "start the visual at the joint: <origin xyz=\"0 0 0.25\"/> in the <visual> of 'avant_bras'"


def test_wrong_upper_arm_visual_is_reported_once(check):
    """bras drawn from -0.05: the visual is wrong, not the elbow at 0.6, so only BK302 fires."""
    findings = check(edited(('<origin xyz="0 0 0.3"/>', '<origin xyz="0 0 0.25"/>')))
    f = only(findings, "BK302")
    assert f.name == "bras"
    assert "BK301" not in codes(findings)


def test_pose_outside_limits(check):
    f = only(check(BRAS, pose={"coude": 2.5, "epaule": 1.0}), "BK303")
    assert (f.severity, f.name, f.line) == ("error", "coude", LINE_COUDE_LIMIT)
    assert f.text("en") == "joint 'coude' = 2.5 rad is 0.5 rad above its upper limit 2"
    assert f.hint_text("en") == "stay within -2..2 rad, or widen the <limit> if the mechanism allows it"
    f = only(check(BRAS, pose={"epaule": -2.0}), "BK303")
    assert f.text("en") == "joint 'epaule' = -2 rad is 0.43 rad below its lower limit -1.57"
    assert "BK303" not in codes(check(BRAS, pose={"coude": 2.0, "epaule": -1.57}))


def test_pose_naming_an_unknown_or_fixed_joint_is_a_usage_error(check):
    with pytest.raises(ParameterError, match="names joint 'coud'"):
        check(BRAS, pose={"coud": 1.0})
    fixed = edited(('<joint name="coude" type="revolute">', '<joint name="coude" type="fixed">'))
    with pytest.raises(ParameterError, match="sets joint 'coude', which is fixed"):
        check(fixed, pose={"coude": 1.0})


def test_motion_outside_limits(check):
    # coude = 2.4 sin t, sampled at 20 Hz for 2 s: first past 2 rad at t = 1.0 s (asin(2/2.4) = 0.985),
    # worst at t = 1.55 s where 2.4 sin(1.55) = 2.39948 (0.399 over)
    findings = check(BRAS, motion=["coude=2.4*sin(t)"], duration=2.0)
    f = only(findings, "BK304")
    assert (f.name, f.line) == ("coude", LINE_COUDE_LIMIT)
    assert f.text("en") == ("joint 'coude' goes past its upper limit 2 rad at t=1 s; "
                         "worst 0.399 rad over (2.399) at t=1.55 s")
    assert f.data["time"] == pytest.approx(1.0)
    assert f.data["worst_time"] == pytest.approx(1.55)


def test_motion_faster_than_velocity_limit(check):
    # d/dt 2.4 sin t = 2.4 cos t: 2.4 rad/s at t = 0, above the 1 rad/s limit until cos t < 1/2.4
    f = only(check(BRAS, motion=["coude=2.4*sin(t)"], duration=2.0), "BK305")
    assert f.severity == "warning"
    assert f.text("en") == ("joint 'coude' moves faster than its velocity limit 1 rad/s from t=0 s; "
                         "peak 2.4 rad/s at t=0 s")


def test_tutorial_motion_stays_within_limits(check):
    assert not codes(check(BRAS, motion=["tutorial"])) & {"BK304", "BK305"}


def test_states_are_checked_by_the_library(tutorial_robot):
    from bras_kit.motion import JointStates

    times = np.array([0.0, 0.05, 0.1])
    positions = np.array([[0.0, 0.0], [1.6, 0.0], [0.0, -2.5]])
    states = JointStates(times, ["epaule", "coude"], positions, np.zeros((3, 2)))
    found = [(f.code, f.name, f.data["time"], f.data["worst"]) for f in validate(tutorial_robot, states=states)
             if f.code == "BK304"]
    assert found == [("BK304", "epaule", 0.05, pytest.approx(0.03)), ("BK304", "coude", 0.1, pytest.approx(0.5))]


def test_no_movable_joint(check):
    text = edited(('<joint name="epaule" type="revolute">', '<joint name="epaule" type="fixed">'),
                  ('<joint name="coude" type="revolute">', '<joint name="coude" type="fixed">'))
    f = only(check(text), "BK306")
    assert (f.element, f.name, f.line) == ("robot", "bras", LINE_ROBOT)
    assert f.text("en") == "all 2 joints are fixed: the robot has nothing to move"
    assert "BK306" not in codes(check(BRAS))


def test_nothing_to_show(check):
    bare = '<robot name="nu"><link name="base"/><link name="bras"/>' \
           '<joint name="epaule" type="continuous"><parent link="base"/><child link="bras"/></joint></robot>'
    f = only(check(bare), "BK307")
    assert f.text("en") == "no link has a <visual>: RViz has nothing to draw"
    assert f.hint_text("en") == "give link 'base' a <visual> with a <geometry> (a box, cylinder or sphere is enough)"
    with_collision = bare.replace('<link name="bras"/>',
                                  '<link name="bras"><collision><geometry><sphere radius="0.1"/></geometry>'
                                  '</collision></link>')
    assert only(check(with_collision), "BK307").text("en") == (
        "no link has a <visual> (only <collision> shapes): RViz shows nothing by default")
    assert "BK307" not in codes(check(BRAS))


# ====================================================================== BK4xx geometry

BRAS_GEOMETRY = '<geometry><box size="0.08 0.08 0.6"/></geometry>'


def test_visual_without_geometry(check):
    f = only(check(edited((BRAS_GEOMETRY, ""))), "BK400")
    assert (f.element, f.name, f.line, f.text("en")) == ("link", "bras", 14, "a <visual> of link 'bras' has no <geometry>")


def test_empty_or_unknown_geometry(check):
    f = only(check(edited((BRAS_GEOMETRY, "<geometry/>"))), "BK400")
    assert (f.name, f.line, f.text("en")) == ("bras", 16, "<geometry> is empty")
    f = only(check(edited((BRAS_GEOMETRY, '<geometry><capsule radius="0.04" length="0.6"/></geometry>'))), "BK400")
    assert f.text("en") == "<geometry> holds <capsule>, which is not a URDF shape"
    assert "BK400" not in codes(check(BRAS))


def test_box_size_not_positive(check):
    f = only(check(edited(('<box size="0.08 0.08 0.6"/>', '<box size="0.08 0 0.6"/>'))), "BK401")
    assert (f.name, f.line, f.text("en")) == ("bras", 16, "link 'bras': <box> size 0.08 0 0.6 is not positive")


def test_cylinder_radius_negative_and_flat_mesh(check):
    f = only(check(edited(('radius="0.15"', 'radius="-0.15"'))), "BK401")
    assert f.text("en") == "link 'base': <cylinder> radius -0.15 is not positive"
    f = only(check(edited((BRAS_GEOMETRY, '<geometry><mesh filename="bras.stl" scale="1 0 1"/></geometry>'))),
             "BK401")
    assert f.text("en") == "link 'bras': <mesh> scale 1 0 1 has a zero component: the mesh is flat"
    mirrored = edited((BRAS_GEOMETRY, '<geometry><mesh filename="bras.stl" scale="1 -1 1"/></geometry>'))
    assert "BK401" not in codes(check(mirrored))


def test_mesh_file_missing_names_the_resolved_path(check, tmp_path):
    text = edited((BRAS_GEOMETRY, '<geometry><mesh filename="meshes/bras.stl"/></geometry>'))
    f = only(check(text), "BK402")
    assert (f.name, f.line) == ("bras", 16)
    assert f.text("en") == f"link 'bras': mesh 'meshes/bras.stl' not found (looked for {tmp_path / 'meshes' / 'bras.stl'})"
    (tmp_path / "meshes").mkdir()
    (tmp_path / "meshes" / "bras.stl").write_text("solid bras\nendsolid bras\n")
    assert "BK402" not in codes(check(text))


def test_package_mesh_resolved_through_package_path(check, tmp_path):
    text = edited((BRAS_GEOMETRY, '<geometry><mesh filename="package://bras_description/meshes/bras.stl"/></geometry>'))
    f = only(check(text), "BK403")
    assert f.severity == "warning"
    assert f.text("en") == ("link 'bras': package 'bras_description' of mesh "
                         "'package://bras_description/meshes/bras.stl' not found, so the file was not checked")
    package = tmp_path / "ws" / "bras_description"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text("<package/>")
    f = only(check(text, package_paths=[str(tmp_path / "ws")]), "BK402")
    assert f.data["path"] == str(package / "meshes" / "bras.stl")
    (package / "meshes" / "bras.stl").write_text("solid bras\nendsolid bras\n")
    assert not codes(check(text, package_paths=[str(tmp_path / "ws")])) & {"BK402", "BK403"}


def test_package_path_from_environment(check, tmp_path, monkeypatch):
    package = tmp_path / "ws" / "bras_description"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text("<package/>")
    (package / "meshes" / "bras.stl").write_text("solid bras\nendsolid bras\n")
    monkeypatch.setenv("BRAS_KIT_PACKAGE_PATH", str(tmp_path / "ws"))
    text = edited((BRAS_GEOMETRY, '<geometry><mesh filename="package://bras_description/meshes/bras.stl"/></geometry>'))
    assert not codes(check(text)) & {"BK402", "BK403"}


def test_mesh_url_is_not_fetched(check):
    text = edited((BRAS_GEOMETRY, '<geometry><mesh filename="https://example.org/bras.stl"/></geometry>'))
    f = only(check(text), "BK404")
    assert f.text("en") == "link 'bras': mesh 'https://example.org/bras.stl' is a URL; bras-kit does not download it"


def test_colour_written_as_bytes(check):
    f = only(check(edited(('rgba="0.2 0.4 0.9 1"', 'rgba="51 102 230 255"'))), "BK405")
    assert (f.element, f.name, f.line) == ("link", "bras", 17)
    assert f.text("en") == "material 'bleu': rgba 51 102 230 255 has components outside 0..1"
    assert f.hint_text("en") == 'colours are fractions of 1, not bytes: rgba="0.2 0.4 0.902 1"'
    f = only(check(edited(('rgba="0.2 0.4 0.9 1"', 'rgba="1.2 0.4 -0.1 1"'))), "BK405")
    assert f.hint_text("en") == 'each of r g b a goes from 0 to 1, e.g. rgba="1 0.4 0 1"'
    assert "BK405" not in codes(check(edited(('rgba="0.2 0.4 0.9 1"', 'rgba="0 0 1 1"'))))


def test_material_used_by_name_but_never_coloured(check):
    text = edited(('<material name="orange"><color rgba="0.95 0.5 0.1 1"/></material>', '<material name="violet"/>'))
    f = only(check(text), "BK406")
    assert (f.name, f.line, f.text("en")) == ("avant_bras", 25, "link 'avant_bras' uses material 'violet', "
                                                            "which has no colour anywhere in the file")
    reuse = edited(('<material name="orange"><color rgba="0.95 0.5 0.1 1"/></material>', '<material name="bleu"/>'))
    assert "BK406" not in codes(check(reuse))  # 'bleu' is given a colour in the upper arm


# ====================================================================== BK5xx inertia

# avant_bras as a uniform 0.5 kg box 0.06 x 0.06 x 0.5 centred at z 0.25:
# ixx = iyy = 0.5/12 (0.06² + 0.5²) = 0.0105667, izz = 0.5/12 (0.06² + 0.06²) = 0.0003
GOOD_INERTIAL = ('<inertial><origin xyz="0 0 0.25"/><mass value="0.5"/>'
                 '<inertia ixx="0.0105667" ixy="0" ixz="0" iyy="0.0105667" iyz="0" izz="0.0003"/></inertial>')


def with_forearm_inertial(inertial: str = GOOD_INERTIAL) -> str:
    return edited((AVANT_BRAS_VISUAL_ORIGIN + '\n      <geometry><box size="0.06 0.06 0.5"/></geometry>\n'
                   '      <material name="orange"><color rgba="0.95 0.5 0.1 1"/></material>\n    </visual>',
                   AVANT_BRAS_VISUAL_ORIGIN + '\n      <geometry><box size="0.06 0.06 0.5"/></geometry>\n'
                   '      <material name="orange"><color rgba="0.95 0.5 0.1 1"/></material>\n    </visual>\n    '
                   + inertial))


def test_consistent_inertial_gives_no_inertia_finding(check):
    findings = check(with_forearm_inertial())
    assert not codes(findings) & {"BK500", "BK501", "BK502", "BK503", "BK504"}
    assert only(findings, "BK505").text("en") == ("link 'bras' moves but has no <inertial>: "
                                               "fine for RViz, needed for physics simulation")


def test_mass_not_positive(check):
    f = only(check(with_forearm_inertial(GOOD_INERTIAL.replace('value="0.5"', 'value="0"'))), "BK500")
    assert (f.name, f.line, f.text("en")) == ("avant_bras", 27, "link 'avant_bras': mass 0 is not positive")


def test_inertia_all_zeros(check):
    zeros = ('<inertial><origin xyz="0 0 0.25"/><mass value="0.5"/>'
             '<inertia ixx="0" ixy="0" ixz="0" iyy="0" iyz="0" izz="0"/></inertial>')
    f = only(check(with_forearm_inertial(zeros)), "BK501")
    assert f.text("en") == "link 'avant_bras': the inertia is all zeros"


def test_inertia_not_positive_definite(check):
    skew = GOOD_INERTIAL.replace('ixy="0"', 'ixy="0.02"')  # |ixy| above sqrt(ixx iyy): a negative moment
    f = only(check(with_forearm_inertial(skew)), "BK501")
    # eigenvalues of [[0.0105667, 0.02], [0.02, 0.0105667]]: 0.0105667 -/+ 0.02
    assert f.text("en") == ("link 'avant_bras': the inertia is not positive definite "
                         "(principal moments -0.0094333 0.0003 0.0305667)")


def test_inertia_triangle_inequality(check):
    flat = GOOD_INERTIAL.replace('ixx="0.0105667"', 'ixx="0.001"').replace('iyy="0.0105667"', 'iyy="0.001"') \
        .replace('izz="0.0003"', 'izz="0.0021"')  # 5 % over: rounding size, a warning (gross: BK507 below)
    findings = check(with_forearm_inertial(flat))
    f = only(findings, "BK502")
    assert f.text("en") == ("link 'avant_bras': principal moments 0.001, 0.001, 0.0021: "
                         "the two smallest add up to less than the largest")
    assert "BK501" not in codes(findings)


def test_inertia_with_swapped_axes_is_far_from_the_shape(check):
    swapped = GOOD_INERTIAL.replace('ixx="0.0105667"', 'ixx="0.0003"').replace('izz="0.0003"', 'izz="0.0105667"')
    f = only(check(with_forearm_inertial(swapped)), "BK503")
    assert f.severity == "warning"
    # izz is 0.0105667 / 0.0003 = 35.2223 times too large, ixx 0.0105667 / 0.0003 = 35.2222 times too small
    # (the exact solid value is 0.01056666...): the larger spread, izz, is reported
    assert f.text("en") == ('link \'avant_bras\': izz = 0.0105667 is 35.2 times what a 0.5 kg '
                         '<box size="0.06 0.06 0.5"/> gives (0.0003)')
    assert f.hint_text("en") == ('for a uniform solid: <inertia ixx="0.0106" ixy="0" ixz="0" iyy="0.0106" iyz="0" '
                      'izz="0.0003"/>')


def test_inertia_within_a_factor_two_is_accepted(check):
    close = GOOD_INERTIAL.replace('ixx="0.0105667"', 'ixx="0.02"').replace('iyy="0.0105667"', 'iyy="0.02"')
    assert "BK503" not in codes(check(with_forearm_inertial(close)))


def test_inertia_of_an_upright_cylinder_matches(check):
    # base: 2 kg cylinder r 0.15 h 0.1 -> ixx = iyy = 2/12 (3 * 0.0225 + 0.01) = 0.0129167, izz = 0.0225
    base = ('<inertial><mass value="2.0"/><inertia ixx="0.0129167" ixy="0" ixz="0" iyy="0.0129167" iyz="0" '
            'izz="0.0225"/></inertial>')
    text = edited(('<material name="gris"><color rgba="0.5 0.5 0.5 1"/></material>\n    </visual>',
                   '<material name="gris"><color rgba="0.5 0.5 0.5 1"/></material>\n    </visual>' + base))
    assert "BK503" not in codes(check(text))


def test_inertia_of_a_lying_rod_written_as_if_upright(check):
    # 1 kg rod r 0.02 l 0.5 turned to lie along x: about x m r²/2 = 0.0002, across m(3r² + l²)/12 = 0.0209333
    rod = ('<robot name="tige"><link name="tige"><visual><origin rpy="0 1.5707963 0"/>'
           '<geometry><cylinder radius="0.02" length="0.5"/></geometry></visual>'
           '<inertial><mass value="1"/><inertia ixx="0.0209333" ixy="0" ixz="0" iyy="0.0209333" iyz="0" '
           'izz="0.00025"/></inertial></link></robot>')
    f = only(check(rod), "BK503")
    # izz is 0.0209333 / 0.00025 = 83.7 times too small; ixx, the rod's own axis (0.0002, under 1 % of
    # the largest moment), is too small for a meaningful ratio and is not compared
    assert f.text("en") == ('link \'tige\': izz = 0.00025 is 83.7 times smaller than what a 1 kg '
                         '<cylinder radius="0.02" length="0.5"/> gives (0.0209333)')
    assert f.hint_text("en") == ('for a uniform solid: <inertia ixx="0.0002" ixy="0" ixz="0" iyy="0.0209" iyz="0" '
                      'izz="0.0209"/>')
    upright = rod.replace('<origin rpy="0 1.5707963 0"/>', "").replace('izz="0.00025"', 'izz="0.0002"')
    assert "BK503" not in codes(check(upright))


def test_centre_of_mass_left_at_the_joint(check):
    at_joint = GOOD_INERTIAL.replace('<origin xyz="0 0 0.25"/>', "")
    f = only(check(with_forearm_inertial(at_joint)), "BK504")
    assert (f.name, f.line) == ("avant_bras", 27)
    assert f.text("en") == ("link 'avant_bras': the centre of mass at xyz 0 0 0 is near an end of its shape "
                         "(z 0..0.5), not at its middle 0 0 0.25")
    assert f.hint_text("en") == ("for a uniform segment, put the <inertial> origin at the middle of the shape: "
                      "<origin xyz=\"0 0 0.25\"/>")
    outside = GOOD_INERTIAL.replace('<origin xyz="0 0 0.25"/>', '<origin xyz="0.2 0 0.25"/>')
    assert only(check(with_forearm_inertial(outside)), "BK504").text("en") == (
        "link 'avant_bras': the centre of mass at xyz 0.2 0 0.25 lies outside its shape "
        "(x -0.03..0.03, y -0.03..0.03, z 0..0.5)")
    off_centre = GOOD_INERTIAL.replace('<origin xyz="0 0 0.25"/>', '<origin xyz="0 0 0.3"/>')
    assert "BK504" not in codes(check(with_forearm_inertial(off_centre)))


def test_root_link_inertia_is_noted(check):
    base = '<inertial><mass value="2.0"/><inertia ixx="0.0129" ixy="0" ixz="0" iyy="0.0129" iyz="0" izz="0.0225"/></inertial>'
    text = edited(('<link name="base">', '<link name="base">' + base))
    f = only(check(text), "BK506")
    assert (f.severity, f.name, f.line) == ("info", "base", 6)
    assert f.text("en") == "root link 'base' has an <inertial>: robot_state_publisher (KDL) ignores it and prints a warning"
    assert "BK506" not in codes(check(BRAS))


def test_every_moving_link_with_an_inertial_has_no_note(check):
    text = with_forearm_inertial()
    bras = GOOD_INERTIAL.replace("avant", "")
    text = edited(('<material name="bleu"><color rgba="0.2 0.4 0.9 1"/></material>\n    </visual>',
                   '<material name="bleu"><color rgba="0.2 0.4 0.9 1"/></material>\n    </visual>' + bras),
                  text=text)
    assert "BK505" not in codes(check(text, ignore=["BK503", "BK504"]))


# ====================================================================== selection and language


def test_select_and_ignore_by_prefix(check):
    text = edited(('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 0.5"/>'))
    assert codes(check(text)) == {"BK301", "BK505"}
    assert codes(check(text, select=["BK3"])) == {"BK301"}
    assert codes(check(text, ignore=["BK505"])) == {"BK301"}
    assert codes(check(text, select=["BK5"], ignore=["BK505"])) == set()
    with pytest.raises(ParameterError, match="no rule code starts with 'BK9'"):
        check(text, select=["BK9"])


def test_unreadable_file_is_reported_even_when_ignored(check):
    assert codes(check("<robot", ignore=["BK1"])) == {"BK100"}


def test_french_messages(check):
    f = only(check(edited(('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 0.5"/>'))), "BK301")
    assert f.text("fr") == ("l'articulation 'coude' est en z=0.5, mais le <box> du link 'bras' occupe z 0..0.6 : "
                         "l'enfant est accroché 0.1 m avant le bout du segment")
    assert f.hint_text("fr") == "placez l'articulation au bout de 'bras' : <origin xyz=\"0 0 0.6\"/>"


def test_missing_colour_of_a_top_level_material_belongs_to_the_material(check):
    text = edited(("<link name=\"base\">", '<material name="gris"><color/></material>\n<link name="base">'))
    f = only(check(text), "BK122")
    assert (f.element, f.name, f.line, f.text("en")) == ("material", "gris", 6, "<color> has no 'rgba' attribute")
    assert f.hint_text("en") == 'write it, e.g. rgba="0.2 0.4 0.9 1"'


def test_macro_library_note_can_be_ignored(check):
    text = ('<robot name="pieces" xmlns:xacro="http://www.ros.org/wiki/xacro">'
            '<xacro:macro name="segment" params="name"><link name="${name}"/></xacro:macro></robot>')
    assert check(text, "pieces.xacro", ignore=["BK124"]) == []


def test_joint_beside_its_parent_is_fine_when_the_shapes_touch(check):
    # a mobile base: the wheel axle sits 3.5 cm under a 0.4 x 0.1 x 0.1 plate; the 3.5 cm wheel touches it
    rover = ('<robot name="rover"><link name="plate"><visual><geometry><box size="0.4 0.1 0.1"/></geometry>'
             '</visual></link><link name="wheel"><visual><origin rpy="1.5707963 0 0"/><geometry>'
             '<cylinder length="0.1" radius="0.035"/></geometry></visual></link>'
             '<joint name="axle" type="continuous"><parent link="plate"/><child link="wheel"/>'
             '<origin xyz="0.13 0 -0.085"/><axis xyz="0 1 0"/></joint></robot>')
    assert "BK301" not in codes(check(rover))
    # two 1 m links side by side on one axle (like Gazebo's RRBot): the second beside the first
    side_by_side = BRAS.replace('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0.07 0.55"/>')
    assert "BK301" not in codes(check(side_by_side))
    small_wheel = rover.replace('radius="0.035"', 'radius="0.02"')  # now 1.5 cm of air under the plate
    assert "BK301" not in codes(check(small_wheel))  # beside the plate: not the tutorial's segment case


# ====================================================================== round 2: precision on real robots


def test_blank_line_before_the_xml_declaration_is_a_warning_and_the_file_is_read(check, tmp_path):
    text = "\n\n" + BRAS.lstrip()
    findings = check(text)
    f = only(findings, "BK125")
    assert (f.severity, f.line) == ("warning", 3)
    assert "BK100" not in codes(findings) and "BK301" not in codes(findings)  # the rest was checked
    # the outside oracle: urdfdom reads such a file too
    path = tmp_path / "robot.urdf"
    assert check_urdf(path).returncode == 0
    assert "BK125" not in codes(check(BRAS))


def test_latin1_file_is_an_encoding_error_with_the_fix(tmp_path):
    path = tmp_path / "latin1.urdf"
    path.write_bytes(BRAS.replace("<robot", "<!-- bras articulé -->\n<robot", 1).encode("latin-1"))
    f = only(validate_path(str(path)), "BK100")
    assert "0xe9" in f.text("en") and "Latin-1" in f.text("en") and "UTF-8" in f.hint_text("en")
    lines = BRAS.splitlines()
    assert f.line == lines.index(next(line for line in lines if line.startswith("<robot"))) + 1
    french = only(validate_path(str(path)), "BK100").text("fr")
    assert "n'est pas du texte UTF-8" in french and "0xe9" in french


def test_moving_leaf_link_without_visual_is_a_warning(check):
    tip = add_before_end('<link name="outil"/><joint name="rotation_outil" type="revolute"><parent link="avant_bras"/>'
                         '<child link="outil"/><origin xyz="0 0 0.5"/><axis xyz="0 0 1"/>'
                         '<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>')
    f = only(check(tip), "BK308")
    assert (f.severity, f.name) == ("warning", "outil")
    assert "rotation_outil" in f.text("en")
    fixed = tip.replace('type="revolute"><parent link="avant_bras"/><child link="outil"/>',
                        'type="fixed"><parent link="avant_bras"/><child link="outil"/>')
    assert "BK308" not in codes(check(fixed))  # a tool frame on a fixed joint is fine


def _with_inertials(text: str) -> str:
    inertial = ('<inertial><mass value="1"/><inertia ixx="0.01" ixy="0" ixz="0" iyy="0.01" iyz="0" '
                'izz="0.01"/></inertial>')
    for link in ("base", "bras", "avant_bras"):
        text = text.replace(f'<link name="{link}">', f'<link name="{link}">{inertial}', 1)
    return text


def test_massless_frame_link_behind_a_fixed_joint_is_legal(check):
    # like UR's tool0 or panda_hand_tcp: zero mass and inertia, fused into a heavy link
    frame = add_before_end('<link name="tool0"><inertial><mass value="0"/><inertia ixx="0" ixy="0" ixz="0" '
                           'iyy="0" iyz="0" izz="0"/></inertial></link><joint name="flange" type="fixed">'
                           '<parent link="avant_bras"/><child link="tool0"/><origin xyz="0 0 0.5"/></joint>',
                           text=_with_inertials(BRAS))
    assert not {"BK500", "BK501"} & codes(check(frame))
    # the same on a moving joint is a body with no mass: MuJoCo and Gazebo refuse it
    moving = frame.replace('<joint name="flange" type="fixed">', '<joint name="flange" type="revolute">'
                           '<axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/>')
    assert {"BK500", "BK501"} <= codes(check(moving))
    assert only(check(moving), "BK500").severity == "error"


def test_massless_root_link_is_legal(check):
    root = _with_inertials(BRAS).replace('<link name="base"><inertial><mass value="1"/>', '<link name="base">'
                                         '<inertial><mass value="0"/>', 1)
    assert "BK500" not in codes(check(root))


def test_negative_moment_of_inertia_is_an_error_even_on_a_frame_link(check):
    bad = add_before_end('<link name="tool0"><inertial><mass value="0.1"/><inertia ixx="-0.01" ixy="0" ixz="0" '
                         'iyy="0.01" iyz="0" izz="0.01"/></inertial></link><joint name="flange" type="fixed">'
                         '<parent link="avant_bras"/><child link="tool0"/><origin xyz="0 0 0.5"/></joint>',
                         text=_with_inertials(BRAS))
    assert only(check(bad), "BK501").severity == "error"


@pytest.mark.parametrize("lower,upper,flagged", [
    ("-9.42477796", "9.42477796", False),  # ANYmal's ±3π
    ("-6.98131701", "6.98131701", False),  # ABB IRB 140 axis 6: ±400° in radians
    ("-10", "10", True),  # whole numbers beyond one turn: degrees
    ("-90", "90", True),
    ("-13.0", "13.5", True),  # beyond two turns
])
def test_limit_in_degrees_spares_multi_turn_joints(check, lower, upper, flagged):
    text = edited((COUDE_LIMIT, f'<limit lower="{lower}" upper="{upper}" effort="10" velocity="1.0"/>'))
    assert ("BK211" in codes(check(text))) is flagged


def test_urdf_beside_its_xacro_is_checked_once_and_compared(run_cli, tmp_path):
    from bras_kit.scaffold.package import scaffold_package

    scaffold_package(str(tmp_path / "plain"))
    scaffold_package(str(tmp_path / "templated"), xacro=True)
    folder = tmp_path / "description"  # a folder of robot files, not a package
    folder.mkdir()
    urdf, xacro = folder / "bras.urdf", folder / "bras.urdf.xacro"
    urdf.write_text((tmp_path / "plain" / "urdf" / "bras.urdf").read_text(encoding="utf-8"), encoding="utf-8")
    xacro.write_text((tmp_path / "templated" / "urdf" / "bras.urdf.xacro").read_text(encoding="utf-8"),
                     encoding="utf-8")
    code, out, _ = run_cli("validate", str(folder), "--ignore", "BK505")
    assert code == 0
    from bras_kit.validate import compare_generated

    assert [f.code for f in compare_generated(str(urdf), str(xacro))] == ["BK126"]
    assert f"{urdf}: BK126 info this URDF was generated from {xacro}, which is checked instead" in out
    # no finding is reported twice: each line names one file, the xacro's findings only once
    assert out.count(" BK") == len({line for line in out.splitlines() if " BK" in line})
    # edited by hand: out of date, and the fix never overwrites the edited file
    urdf.write_text(urdf.read_text(encoding="utf-8").replace('size="0.08 0.08 0.6"', 'size="0.08 0.08 0.7"', 1),
                    encoding="utf-8")
    code, out, _ = run_cli("validate", str(folder), "--ignore", "BK505")
    assert f"{urdf}: BK127 warning this URDF differs from what {xacro} gives now" in out
    assert 'size="0.08 0.08 0.7" where the xacro file gives "0.08 0.08 0.6"' in out
    assert "--force" not in out
    assert [(f.code, f.severity) for f in compare_generated(str(urdf), str(xacro))] == [("BK127", "warning")]
    assert run_cli("validate", str(folder), "--ignore", "BK505", "--strict")[0] == 1
    # named explicitly, the URDF is checked as itself
    assert "BK126" not in run_cli("validate", str(urdf))[1]


def test_package_urdf_edited_the_tutorials_way_is_checked_as_written(run_cli, tmp_path):
    """A package made by bras-kit new, a xacro copied beside its URDF, then the tutorial's pitfall
    (coude at z=0.3): the URDF the package installs is what the launch file loads, so it is checked
    itself and the misplaced joint is reported there, with no advice to overwrite it."""
    from bras_kit.scaffold.package import scaffold_package

    package = tmp_path / "bras_description"
    scaffold_package(str(package))
    scaffold_package(str(tmp_path / "templated"), xacro=True)
    urdf, xacro = package / "urdf" / "bras.urdf", package / "urdf" / "bras.urdf.xacro"
    xacro.write_text((tmp_path / "templated" / "urdf" / "bras.urdf.xacro").read_text(encoding="utf-8"),
                     encoding="utf-8")
    text = urdf.read_text(encoding="utf-8")
    coude = text.index('<joint name="coude"')
    urdf.write_text(text[:coude] + text[coude:].replace('xyz="0 0 0.6"', 'xyz="0 0 0.3"', 1), encoding="utf-8")
    alone = run_cli("validate", str(urdf), "--ignore", "BK505")[1]
    out = run_cli("validate", str(package), "--ignore", "BK505")[1]
    assert f"{urdf}:51: BK301 warning <joint name=\"coude\"> joint 'coude' is at z=0.3" in out
    alone_codes = {line.split()[1] for line in alone.splitlines() if line.startswith(str(urdf) + ":")}
    assert alone_codes and alone_codes <= {line.split()[1] for line in out.splitlines()
                                           if line.startswith(str(urdf) + ":")}
    assert "BK127" not in out and "BK126" not in out and "--force" not in out


SAFETY = '<safety_controller soft_lower_limit="-1.9" soft_upper_limit="1.9" k_position="100" k_velocity="10"/>'


def test_safety_controller_number_that_is_not_a_number(check):
    text = edited((COUDE_LIMIT, COUDE_LIMIT + "\n    " + SAFETY.replace('upper_limit="1.9"', 'upper_limit="None"')))
    f = only(check(text), "BK230")
    assert (f.severity, f.element, f.name, f.line) == ("error", "joint", "coude", LINE_COUDE_LIMIT + 1)
    assert f.text("en") == "joint 'coude': <safety_controller soft_upper_limit=\"None\"> is not a number"
    assert "BK230" not in codes(check(edited((COUDE_LIMIT, COUDE_LIMIT + "\n    " + SAFETY))))


def test_safety_controller_without_k_velocity(check):
    f = only(check(edited((COUDE_LIMIT, COUDE_LIMIT + "\n    " + SAFETY.replace(' k_velocity="10"', "")))), "BK230")
    assert f.text("en") == "joint 'coude': <safety_controller> has no k_velocity attribute"


# ---------------------------------------------------------------- issue 19: inertia verdicts as a simulator sees them

PITFALLS = DATA / "pitfalls"


def test_gross_triangle_breach_on_a_moving_link_is_an_error_mujoco_agrees():
    import mujoco

    path = PITFALLS / "inertie_impossible.urdf"  # ixx + iyy = 0.02 < izz = 0.05 on the moving forearm
    (f,) = [f for f in validate_path(str(path)) if f.code in ("BK502", "BK507")]
    assert (f.code, f.severity, f.name) == ("BK507", "error", "avant_bras")
    assert f.data["ratio"] == pytest.approx(2.5)
    with pytest.raises(ValueError, match="A \\+ B >= C"):  # the oracle: MuJoCo refuses to load it
        mujoco.MjModel.from_xml_path(str(path))


def test_rounding_size_triangle_breach_stays_a_warning():
    (f,) = [f for f in validate_path(str(PITFALLS / "inertie_arrondie.urdf")) if f.code in ("BK502", "BK507")]
    assert (f.code, f.severity) == ("BK502", "warning")  # 0.021 against 0.02: 5 %, rounding


def test_negative_moment_of_a_massless_appendage_fused_into_a_valid_body_is_a_warning():
    findings = validate_path(str(PITFALLS / "antenne_fusionnee.urdf"))
    (f,) = [f for f in findings if f.code in ("BK501", "BK508")]
    assert (f.code, f.severity, f.name, f.data["body"]) == ("BK508", "warning", "antenne", "avant_bras")


@pytest.mark.parametrize("code,case", [("BK630", "missing_source"), ("BK631", "wrong_package"),
                                       ("BK632", "path_parameter"), ("BK633", "folders_in_module")])
def test_package_built_and_launched_finds_the_learner_case(code, case):
    """The full catalogue of cases (file, line, ROS's words) is in test_ros_launch.py."""
    from bras_kit.validate.package import validate_package

    folder = TESTS / "data" / "launch" / case / "bras_description"
    assert code in [f.code for r in validate_package(str(folder), select=[code], launch=True) for f in r.findings]
