"""Learners' slips the reader accepts (bras_kit/validate/slips.py): degrees, grams, a comment closed with '->'.

Each defect has a failing and a passing file in tests/data/urdf/slips/; the expected values are
worked out by hand in the comments.
"""

from __future__ import annotations

import math

from paths import TESTS

from bras_kit.validate import validate_path

SLIPS = TESTS / "data" / "urdf" / "slips"


def _only(findings, code):
    found = [f for f in findings if f.code == code]
    assert len(found) == 1, [(f.code, f.text("en")) for f in findings]
    return found[0]


def test_wrist_rpy_written_in_degrees():
    f = _only(validate_path(str(SLIPS / "rpy_degrees.urdf")), "BK214")
    assert (f.severity, f.element, f.name) == ("error", "joint", "poignet")
    # 90 rad = 14 turns + 2.0354 rad = 116.6 degrees; 90 degrees = pi/2 = 1.5708 rad
    assert f.data["effective"] == "116.6" and math.isclose(math.remainder(90, 2 * math.pi), 2.0354, abs_tol=1e-4)
    assert f.data["origin"] == '<origin xyz="0 0 0.5" rpy="0 1.5708 0"/>'
    assert "rpy=\"0 90 0\"" in f.text("fr") and f.text("fr") != f.text("en")
    assert f.line == (SLIPS / "rpy_degrees.urdf").read_text().splitlines().index(
        '    <origin xyz="0 0 0.5" rpy="0 90 0"/>') + 1


def test_wrist_rpy_in_radians_passes():
    assert [f for f in validate_path(str(SLIPS / "rpy_radians.urdf")) if f.code == "BK214"] == []


def test_forearm_mass_written_in_grams():
    f = _only(validate_path(str(SLIPS / "mass_grams.urdf")), "BK509")
    # 500 kg / (0.06 x 0.06 x 0.5 m3 = 0.0018 m3) = 277,778 kg/m3; 500 g = 0.5 kg
    assert (f.severity, f.name, f.data["density"], f.data["kilograms"]) == ("warning", "avant_bras", "277,778", "0.5")
    assert f.text("fr") != f.text("en") and "0.5" in f.hint_text("fr")


def test_forearm_mass_in_kilograms_passes():
    assert [f for f in validate_path(str(SLIPS / "mass_kilograms.urdf")) if f.code == "BK509"] == []


def test_comment_closed_with_an_arrow_names_what_it_swallows_at_its_line():
    text = (SLIPS / "comment_arrow.urdf").read_text()
    comment_line = text.splitlines().index("  <!-- avant-bras : un pavé de 0,5 m ->") + 1
    f = _only(validate_path(str(SLIPS / "comment_arrow.urdf")), "BK100")
    assert (f.severity, f.line, f.variant) == ("error", comment_line, "comment")
    assert '<link name="avant_bras">' in f.text("en") and '<link name="avant_bras">' in f.text("fr")
    assert f.hint_text("en") == f"close the comment on line {comment_line} with '-->' (two dashes)"


def test_comment_closed_with_an_arrow_and_never_closed_runs_to_the_end_of_the_file(tmp_path):
    """No '-->' after the arrow: the comment runs to the end of the file (no line to name)."""
    text = (SLIPS / "comment_arrow.urdf").read_text().replace("  <!-- les articulations -->\n", "")
    assert text.count("-->") == 0
    path = tmp_path / "bras.urdf"
    path.write_text(text)
    comment_line = text.splitlines().index("  <!-- avant-bras : un pavé de 0,5 m ->") + 1
    f = _only(validate_path(str(path)), "BK100")
    assert (f.line, f.variant) == (comment_line, "comment_unclosed")
    for lang in ("en", "fr"):
        assert '<joint name="coude">' in f.text(lang) and "line 0" not in f.text(lang) and "ligne 0" not in f.text(lang)
    assert "end of the file" in f.text("en") and "fin du fichier" in f.text("fr")


def test_check_urdf_reports_the_link_the_comment_swallowed():
    """urdfdom (TinyXML2) reads the comment to the next '-->': the forearm is missing for it too."""
    from urdfdom_oracle import check_urdf

    done = check_urdf(SLIPS / "comment_arrow.urdf")
    assert "child link [avant_bras] of joint [coude] not found" in done.stdout + done.stderr


def test_comment_closed_properly_passes():
    assert validate_path(str(SLIPS / "comment_closed.urdf"), ignore=["BK7"]) == []
