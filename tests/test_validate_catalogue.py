"""The registry and its two languages stay consistent, and docs/rules.md is generated from them."""

from __future__ import annotations

import re
import string
from pathlib import Path

import pytest

from bras_kit.validate import RULES
from bras_kit.validate.catalogue import catalogue_markdown
from bras_kit.validate.i18n import default_language, rule_text, ui
from bras_kit.validate.registry import FAMILIES, SEVERITIES, select_rules

ROOT = Path(__file__).parent.parent
RULE_TESTS = (Path(__file__).parent / "test_validate_rules.py").read_text(encoding="utf-8")


def test_docs_rules_md_is_current():
    current = (ROOT / "docs" / "rules.md").read_text(encoding="utf-8")
    assert current == catalogue_markdown(), "regenerate: python -m bras_kit.validate.catalogue > docs/rules.md"


def test_codes_are_well_formed_and_names_unique():
    assert len([code for code in RULES if code < "BK6"]) == 65  # URDF and xacro rules
    assert len([code for code in RULES if "BK6" <= code < "BK64"]) == 15  # package rules
    assert len([code for code in RULES if code >= "BK64"]) == 12  # rules over a run of the node (bras-kit run)
    for code, rule in RULES.items():
        assert re.fullmatch(r"BK[1-6]\d\d", code) and rule.code == code
        assert rule.severity in SEVERITIES
        assert re.fullmatch(r"[a-z0-9]+(-[a-z0-9]+)*", rule.name)
    assert len({r.name for r in RULES.values()}) == len(RULES)
    assert {code[:3] for code in RULES} == set(FAMILIES)


def _fields(template: str) -> set[str]:
    return {name for _, name, _, _ in string.Formatter().parse(template) if name}


def _variants(template) -> dict[str, str]:
    return {"": template} if isinstance(template, str) else dict(template)


@pytest.mark.parametrize("code", sorted(RULES))
def test_both_languages_word_every_rule_alike(code):
    en, fr = rule_text(code, "en"), rule_text(code, "fr")
    for part in ("message", "hint"):
        en_variants, fr_variants = _variants(getattr(en, part)), _variants(getattr(fr, part))
        assert set(en_variants) == set(fr_variants), (code, part)
        for variant in en_variants:
            assert _fields(en_variants[variant]) == _fields(fr_variants[variant]), (code, part, variant)
    assert en.title != fr.title and en.explanation != fr.explanation
    assert len(en.explanation) > 120 and len(fr.explanation) > 120


def test_report_words_exist_in_both_languages():
    assert set(ui("en")) == set(ui("fr"))


# package rules (BK6xx): tests/test_validate_package.py::test_every_package_rule_is_triggered_by_a_defect
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
