"""Property: whatever is done to the tutorial URDF, the validator returns findings (or raises a
BrasKitError for bad options), never a traceback, and the findings print as text and JSON."""

from __future__ import annotations

import json
import re
import tempfile
from pathlib import Path

import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from paths import TESTS

from bras_kit.core.errors import BrasKitError
from bras_kit.findings.data import FileResult
from bras_kit.findings.report import format_json, format_text
from bras_kit.validate import Finding, validate_path

DATA = TESTS / "data" / "urdf"
BRAS = (DATA / "good" / "bras.urdf").read_text(encoding="utf-8")


def _inertial_arm() -> str:
    from bras_kit.model.authoring import arm_urdf

    return arm_urdf(wrist=True, inertials=True)


BASES = [BRAS, _inertial_arm()]
NUMBER = re.compile(r"-?\d+(?:\.\d+)?(?:e-?\d+)?")
NAME = re.compile(r'(?:name|link|joint)="([^"]*)"')
TAG = re.compile(r"<(box|cylinder|sphere|mesh|visual|collision|inertial|limit|axis|origin|mimic|parent|child)\b")

ODD_NUMBERS = st.one_of(
    st.sampled_from(["nan", "inf", "-inf", "1e309", "-0", "0", "1e-320", "abc", "0,5", "", "1 2", "-1e308",
                     "1e308", "0x10", "${x}", "$(arg a)", "1_000", " ", "-"]),
    st.floats(allow_nan=True, allow_infinity=True).map(repr),
    st.integers(-10**6, 10**6).map(str),
)
ODD_NAMES = st.one_of(
    st.sampled_from(["", "base", "bras", "avant_bras", "coude", "epaule", "poignet", "Bras", " ", "a b"]),
    st.text(alphabet=st.characters(blacklist_characters='"<&'), max_size=8),
)
SNIPPETS = st.one_of(
    st.sampled_from([
        '<link name="x"/>', '<link name="bras"/>', '<link/>', "<joint/>", '<material name="bleu"/>',
        '<joint name="j" type="revolute"><parent link="bras"/><child link="bras"/></joint>',
        '<joint name="k" type="fixed"><parent link="avant_bras"/><child link="base"/></joint>',
        '<mimic joint="epaule"/>', '<mimic joint="coude"/>', '<mimic/>', "<!DOCTYPE x>", "&amp;", "&x;",
        '<xacro:if value="1">', "]]>", '<axis xyz="0 0 0"/>', '<inertial><mass value="-1"/></inertial>',
        "<inertial/>", '<inertia ixx="1" ixy="2" ixz="3" iyy="1" iyz="0" izz="1"/>', "<geometry/>",
        '<visual><geometry><mesh filename="package://nulle_part/x.stl" scale="0 1 1"/></geometry></visual>',
        '<visual><geometry><mesh filename="https://example.org/x.stl"/></geometry></visual>',
        '<limit lower="2" upper="-2"/>', '<color rgba="255 0 0 1"/>', "<robot>", "</robot>", "<!--", "-->",
    ]),
    st.text(max_size=30),
)


@st.composite
def mutated(draw) -> tuple[str, str]:
    text = draw(st.sampled_from(BASES))
    for _ in range(draw(st.integers(1, 4))):
        kind = draw(st.sampled_from(["number", "name", "remove", "insert", "truncate", "tag", "duplicate"]))
        if kind == "number":
            matches = list(NUMBER.finditer(text))
            if matches:
                m = draw(st.sampled_from(matches))
                text = text[:m.start()] + draw(ODD_NUMBERS) + text[m.end():]
        elif kind == "name":
            matches = list(NAME.finditer(text))
            if matches:
                m = draw(st.sampled_from(matches))
                text = text[:m.start(1)] + draw(ODD_NAMES) + text[m.end(1):]
        elif kind == "remove":
            lines = text.splitlines(keepends=True)
            if lines:
                del lines[draw(st.integers(0, len(lines) - 1))]
                text = "".join(lines)
        elif kind == "insert":
            at = draw(st.integers(0, len(text)))
            text = text[:at] + draw(SNIPPETS) + text[at:]
        elif kind == "truncate":
            text = text[: draw(st.integers(0, len(text)))]
        elif kind == "tag":
            matches = list(TAG.finditer(text))
            if matches:
                m = draw(st.sampled_from(matches))
                text = text[:m.start(1)] + draw(st.sampled_from(["box", "sphere", "mesh", "capsule", "link",
                                                                 "limit", "axis"])) + text[m.end(1):]
        else:
            lines = text.splitlines(keepends=True)
            if lines:
                i = draw(st.integers(0, len(lines) - 1))
                lines.insert(i, lines[i])
                text = "".join(lines)
    suffix = draw(st.sampled_from([".urdf", ".urdf", ".urdf", ".xacro"]))
    return text, suffix


@pytest.fixture(scope="module")
def folder():
    with tempfile.TemporaryDirectory(prefix="bras-kit-fuzz-") as name:
        yield Path(name)


@settings(max_examples=200, deadline=None, suppress_health_check=[HealthCheck.function_scoped_fixture,
                                                                   HealthCheck.too_slow])
@given(case=mutated(), lang=st.sampled_from(["en", "fr"]),
       pose=st.one_of(st.none(), st.fixed_dictionaries({"coude": st.floats(-10, 10)})))
def test_mutated_tutorial_urdf_never_crashes(folder, case, lang, pose):
    text, suffix = case
    path = folder / f"robot{suffix}"
    # surrogatepass: a lone surrogate from the generator becomes bytes that are not valid UTF-8,
    # which the validator must report like any other unreadable file
    path.write_bytes(text.encode("utf-8", errors="surrogatepass"))
    try:
        findings = validate_path(str(path), lang=lang, pose=pose)
    except BrasKitError:
        return  # a clean error (e.g. --pose naming a joint the mutated robot lost)
    assert all(isinstance(f, Finding) for f in findings)
    result = [FileResult(str(path), findings)]
    assert format_text(result, lang).endswith(".\n")
    assert json.loads(format_json(result))["files"][0]["path"] == str(path)
