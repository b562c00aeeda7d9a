"""Safe XML reading: lines kept, DTDs and entities refused before any expansion."""

from __future__ import annotations

import math

import pytest

from bras_kit.core.errors import XMLSafetyError, XMLSyntaxError
from bras_kit.model.robot import robot_from_xml
from bras_kit.model.xmlio import parse_xml, read_xml


def test_elements_remember_their_line():
    root = parse_xml('<robot name="r">\n  <link name="a"/>\n\n  <link name="b"/>\n</robot>')
    assert [(n.get("name"), n.line) for n in root.findall("link")] == [("a", 2), ("b", 4)]


def test_external_entity_is_refused_without_reading_the_file(tmp_path):
    secret = tmp_path / "secret.txt"
    secret.write_text("TOP-SECRET")
    text = f'<?xml version="1.0"?>\n<!DOCTYPE r [<!ENTITY x SYSTEM "file://{secret}">]>\n<robot name="&x;"/>'
    with pytest.raises(XMLSafetyError) as info:
        parse_xml(text)
    assert "TOP-SECRET" not in str(info.value)
    assert info.value.line == 2


def test_billion_laughs_is_refused():
    lol = '<!DOCTYPE lolz [<!ENTITY lol "lol">' + "".join(
        f'<!ENTITY lol{i} "{("&lol" + (str(i - 1) if i > 1 else "") + ";") * 10}">' for i in range(1, 10)
    ) + "]>"
    with pytest.raises(XMLSafetyError, match="DTD"):
        parse_xml(lol + "<robot>&lol9;</robot>")


def test_undefined_entity_reference_is_refused():
    with pytest.raises(XMLSafetyError, match="entit"):
        parse_xml('<robot name="&nope;"/>')


def test_unclosed_element_is_reported_at_its_opening_line_with_where_the_reader_stopped(tmp_path):
    path = tmp_path / "broken.urdf"
    path.write_text('<robot name="r">\n  <link name="a">\n</robot>\n')
    with pytest.raises(XMLSyntaxError) as info:
        read_xml(path)
    assert info.value.line == 2  # where <link name="a"> opens: the fix goes there
    assert str(path) in str(info.value)
    assert '<link name="a">' in str(info.value) and "line 3" in str(info.value)


def test_lenient_model_records_unreadable_numbers():
    root = parse_xml('<robot name="r"><link name="a"/><link name="b"/>'
                     '<joint name="j" type="revolute"><parent link="a"/><child link="b"/>'
                     '<origin xyz="0 0 abc"/><axis xyz="0 1"/><limit lower="nan" upper="1" effort="1" velocity="1"/>'
                     "</joint></robot>")
    robot = robot_from_xml(root)
    kinds = {(i.kind, i.attribute) for i in robot.issues}
    assert ("bad_number", "xyz") in kinds
    # unreadable, never defaulted: the axis is kept as not-a-number, with its issue (issue 38)
    axis = robot.joints[0].axis
    assert axis is not None and len(axis) == 3 and all(math.isnan(v) for v in axis)
    assert ("non_finite", "lower") in kinds


def test_named_material_colour_is_resolved():
    root = parse_xml('<robot name="r"><material name="red"><color rgba="1 0 0 1"/></material>'
                     '<link name="a"><visual><geometry><sphere radius="0.1"/></geometry>'
                     '<material name="red"/></visual></link></robot>')
    robot = robot_from_xml(root)
    assert robot.material_rgba(robot.links[0].visuals[0]) == (1.0, 0.0, 0.0, 1.0)
