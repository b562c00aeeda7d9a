"""Paste accidents of a first hour: each named by its character (or name) and its fix, at its line.

Oracles: the files in tests/data/paste/ are refused by Python's own XML reader too (so they
are really broken), the lines and columns are counted by hand, the code points are Unicode's,
and the fix each message gives, applied to the file, makes it readable. For xacro, the real
xacro package ignores an argument no file declares (xacro/__init__.py, ``process_doc`` sets
``substitution_args_context['arg']`` to the mappings as given, and only ``<xacro:arg>`` and
``$(arg)`` ever read it).
"""

from __future__ import annotations
from paths import TESTS

import xml.etree.ElementTree as ElementTree
from pathlib import Path

import pytest

from bras_kit.core.errors import ParameterError, XMLSyntaxError
from bras_kit.core.i18n import say, say_error
from bras_kit.model.xacro import expand_xacro
from bras_kit.model.xmlio import read_xml

PASTE = TESTS / "data" / "paste"


@pytest.mark.parametrize(("name", "line", "column", "code"), [
    ("curly_quotes.urdf", 5, 15, "U+201C"),  # '  <joint name=' is 14 characters
    ("nbsp_in_tag.urdf", 7, 11, "U+00A0"),  # '    <child' is 10 characters
    ("bom_after_blank_line.urdf", 2, 1, "U+FEFF"),
])
def test_a_pasted_character_is_named_at_its_line_and_column(name: str, line: int, column: int, code: str) -> None:
    path = PASTE / name
    with pytest.raises(ElementTree.ParseError):
        ElementTree.parse(path)
    with pytest.raises(XMLSyntaxError) as caught:
        read_xml(path)
    error = caught.value
    assert error.line == line
    text = say_error(error, "en")
    assert f"({code}) at column {column}" in text
    assert error.fix is not None and say(error.fix, "en") in text
    french = say_error(error, "fr")
    assert f"({code}) en colonne {column}" in french and "column" not in french


def test_the_curly_quote_fix_makes_the_file_readable() -> None:
    path = PASTE / "curly_quotes.urdf"
    with pytest.raises(XMLSyntaxError) as caught:
        read_xml(path)
    fix = say(caught.value.fix, "en")
    assert fix.startswith('replace \u201c \u201d on this line with ",')
    fixed = path.read_text(encoding="utf-8").replace("\u201c", '"').replace("\u201d", '"')
    joint = ElementTree.fromstring(fixed.encode()).find("joint")
    assert joint is not None and joint.get("name") == "coude"


def test_a_tab_before_the_declaration_is_named_by_the_validator() -> None:
    from bras_kit.validate import validate_path

    path = PASTE / "tab_before_declaration.urdf"
    with pytest.raises(ElementTree.ParseError):  # Python's reader refuses it; urdfdom reads it
        ElementTree.parse(path)
    found = [f for f in validate_path(path) if f.code == "BK125"]
    assert len(found) == 1 and found[0].line == 1
    assert "a tab (U+0009)" in say(found[0].message, "en")
    assert "tabulation (U+0009)" in say(found[0].message, "fr")
    assert "delete the tab at the start of line 1" in say(found[0].hint, "en")


def test_a_misspelt_xacro_argument_gets_the_nearest_declared_name() -> None:
    with pytest.raises(ParameterError) as caught:
        expand_xacro(PASTE / "arm.urdf.xacro", {"bras_lenght": "0.8"}, sandbox=False)
    text = say_error(caught.value, "en")
    assert "unknown xacro argument 'bras_lenght'" in text
    assert "did you mean bras_length?" in text
    assert "avant_bras_length, bras_length" in text  # every declared name, for the learner to pick
    assert "vouliez-vous dire bras_length ?" in say_error(caught.value, "fr")


def test_a_declared_argument_is_taken_even_when_no_expression_reads_it() -> None:
    text = expand_xacro(PASTE / "arm.urdf.xacro", {"bras_length": "0.8", "avant_bras_length": "0.4"}, sandbox=False)
    origin = ElementTree.fromstring(text).find("joint/origin")
    assert origin is not None and origin.get("xyz") == "0 0 0.8"


def test_the_xacro_command_refuses_a_misspelt_argument(run_cli) -> None:
    code, out, err = run_cli("xacro", str(PASTE / "arm.urdf.xacro"), "bras_lenght:=0.8")
    assert code == 2 and out == ""
    assert "did you mean bras_length?" in err and "Traceback" not in err
