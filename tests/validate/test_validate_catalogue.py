"""The registry and its two languages stay consistent, and docs/rules.md is generated from them."""

from __future__ import annotations

import re
from collections.abc import Mapping

import pytest
from paths import REPO, TESTS

from bras_kit.findings.registry import FAMILIES, SEVERITIES, TEXTS, select_rules
from bras_kit.validate import RULES, default_language
from bras_kit.validate.catalogue import catalogue_markdown, raw_text

ROOT = REPO
RULE_TESTS = "".join(path.read_text(encoding="utf-8") for path in
                     [TESTS / "validate" / "test_validate_rules.py", *TESTS.rglob("test_gazebo*.py"),
                      TESTS / "validate" / "test_validate_slips.py", *TESTS.rglob("test_live_*.py")])


def test_docs_rules_md_is_current():
    current = (ROOT / "docs" / "rules.md").read_text(encoding="utf-8")
    assert current == catalogue_markdown(), "regenerate: python -m bras_kit.validate.catalogue > docs/rules.md"


def test_codes_are_well_formed_and_names_unique():
    assert len([code for code in RULES if code < "BK6"]) == 69  # URDF and xacro rules
    assert len([code for code in RULES if "BK6" <= code < "BK64"]) == 32  # package rules (BK615: no rviz2 in the evaluated launch; BK630-BK635: built, launched; BK628-BK629: setup.cfg)
    assert len([code for code in RULES if "BK64" <= code < "BK7"]) == 16  # rules over a run of the node (bras-kit run; BK657-BK658: its record)
    assert len([code for code in RULES if "BK7" <= code < "BK8"]) == 12  # what Gazebo makes of the robot
    assert len([code for code in RULES if code >= "BK8"]) == 25  # the live ROS 2 graph (doctor --ros), BK840-BK845 judged by the rsp and RViz model, BK846 the running rviz2's Fixed Frame, BK847 the timeline
    for code, rule in RULES.items():
        assert re.fullmatch(r"BK[1-8]\d\d", code) and rule.code == code
        assert rule.severity in SEVERITIES
        assert re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", rule.name)
    assert len({r.name for r in RULES.values()}) == len(RULES)
    assert {code[:3] for code in RULES} == set(FAMILIES)


def _variants(template) -> dict[str, str]:
    return dict(template) if isinstance(template, Mapping) else {"": template}


def test_every_rule_has_its_words_and_no_words_lack_a_rule():
    assert set(TEXTS) == set(RULES)


@pytest.mark.parametrize("code", sorted(RULES))
def test_every_rule_is_worded_in_french_from_the_catalog(code):
    """The French comes from validate.po (msgctxt = code); fields are checked by test_i18n_catalogs."""
    words = TEXTS[code]
    assert words.message, code
    hints = _variants(words.hint).values() if words.hint else ()
    # (a rule's counted parts may read the same in French: "{positions} position")
    for english in (words.title, words.explanation, *_variants(words.message).values(), *hints):
        for n in (1, 2):  # a Plural in both its forms
            assert raw_text(code, english, "fr", n) != raw_text(code, english, "en", n), (code, english, n)
    assert len(words.explanation) > 120 and len(raw_text(code, words.explanation, "fr")) > 120


# package rules (BK6xx): tests/validate/test_validate_package.py::test_every_package_rule_is_triggered_by_a_defect
@pytest.mark.parametrize("code", sorted(code for code in RULES if not code.startswith("BK6")))
def test_every_rule_has_a_triggering_test(code):
    assert f'"{code}"' in RULE_TESTS, f"no test in test_validate_rules.py triggers {code}"


@pytest.mark.parametrize("environ, expected", [
    ({}, "en"),
    ({"LANG": "fr_FR.UTF-8"}, "fr"),
    ({"LANG": "fr_CA"}, "fr"),
    ({"LANG": "de_DE.UTF-8"}, "en"),
    ({"LANG": "fr_FR.UTF-8", "LC_ALL": "C"}, "en"),
    ({"LANG": "C", "LC_MESSAGES": "fr_BE.UTF-8"}, "fr"),
    ({"LC_ALL": "fr_FR.UTF-8", "LANG": "en_US.UTF-8"}, "fr"),
])
def test_default_language_from_the_locale(environ, expected):
    assert default_language(environ) == expected


def test_select_rules_by_prefix():
    assert [r.code for r in select_rules(["BK20"], ["BK205", "BK21"])] == [
        "BK200", "BK201", "BK202", "BK203", "BK204", "BK206", "BK207", "BK208", "BK209"]
    with pytest.raises(ValueError):
        select_rules(["XX"])
