"""The rule catalogue, generated from the registry: ``bras-kit explain`` and ``docs/rules.md``.

Regenerate the documentation with::

    python -m bras_kit.validate.catalogue > docs/rules.md

(a test fails when the file is not current).
"""

from __future__ import annotations

import difflib
from collections.abc import Mapping

from ..core.errors import ParameterError
from ..core.i18n import catalog, current_language, say
from ..core.message import M
from ..findings.registry import (
    FAMILIES,
    FAMILY_TITLES,
    SEVERITY_WORDS,
    Plural,
    Rule,
    Template,
    Text,
    sorted_rules,
)
from . import RULES


def find_rule(code_or_name: str) -> Rule:
    """A rule by code (``BK301``, any case) or name (``joint-not-at-segment-end``)."""
    key = code_or_name.strip()
    if key.upper() in RULES:
        return RULES[key.upper()]
    by_name = {r.name: r for r in RULES.values()}
    if key.lower() in by_name:
        return by_name[key.lower()]
    close = [by_name[n].code for n in difflib.get_close_matches(key.lower(), list(by_name), n=1)]
    raise ParameterError(
        M("unknown rule '{rule}'", rule=code_or_name),
        hint=M("did you mean {code} ({name})? run 'bras-kit explain' with no code to list every rule",
               code=close[0], name=RULES[close[0]].name) if close
        else M("run 'bras-kit explain' with no code to list every rule"),
    )


def raw_text(code: str, english: Text, lang: str | None = None, n: int = 2) -> str:
    """One of rule ``code``'s texts in ``lang`` as written in the catalog (fields not filled in);
    a :class:`Plural` in its form for ``n`` things."""
    lang = lang or current_language()
    if isinstance(english, Plural):
        if lang == "en":
            return english.singular if n == 1 else english.plural
        return catalog(lang, "validate").npgettext(code, english.singular, english.plural, n)
    return english if lang == "en" else catalog(lang, "validate").pgettext(code, english)


def explain_text(rule: Rule, lang: str | None = None) -> str:
    """What ``bras-kit explain CODE`` prints, in ``lang``."""
    title = raw_text(rule.code, rule.texts.title, lang)
    head = f"{rule.code} {rule.name} ({say(SEVERITY_WORDS[rule.severity], lang)})"
    body = [head, title[0].upper() + title[1:] + ".", "",
            raw_text(rule.code, rule.texts.explanation, lang).replace("`", ""), "",
            say(M("Family: {family}", family=FAMILY_TITLES[rule.family]), lang)]
    if not rule.reported_by_loader:
        body.append(say(M("Skip it with: bras-kit validate --ignore {code}", code=rule.code), lang))
    return "\n".join(body) + "\n"


def rule_list_text(lang: str | None = None) -> str:
    """Every rule, family by family: what ``bras-kit explain`` prints without a code."""
    lines = []
    for prefix, family in FAMILIES.items():
        lines.append(f"{prefix}xx {say(FAMILY_TITLES[family], lang)}")
        for r in sorted_rules():
            if r.code.startswith(prefix):
                severity = say(SEVERITY_WORDS[r.severity], lang)
                lines.append(f"  {r.code}  {severity:<13} {r.name:<32} {raw_text(r.code, r.texts.title, lang)}")
        lines.append("")
    return "\n".join(lines)


# ---------------------------------------------------------------- docs/rules.md


def _md(text: str) -> str:
    """Markdown with ``<tags>`` outside `code spans` escaped, so that they show instead of vanishing as HTML."""
    parts = text.split("`")
    return "`".join(part.replace("<", "&lt;") if i % 2 == 0 else part for i, part in enumerate(parts))


def _templates(label: str, code: str, template: Template, lang: str) -> list[str]:
    def lines(name: str, text: Text) -> list[str]:
        if isinstance(text, Plural):  # both forms, as the catalog words them for one and for several
            one, several = raw_text(code, text, lang, 1), raw_text(code, text, lang, 2)
            return [f"- {name}, singular (counting {{{text.n}}}): `{one}`", f"- {name}, plural: `{several}`"]
        return [f"- {name}: `{raw_text(code, text, lang)}`"] if text else []

    if isinstance(template, (str, Plural)):
        return lines(label, template)
    return [line for variant, value in template.items() for line in lines(f"{label} ({variant or 'otherwise'})", value)]


def _parts(code: str, parts: Mapping[str, Plural], lang: str) -> list[str]:
    return [line for name, part in parts.items() for line in _templates(f"part {{{name}}}", code, part, lang)]


def _section(rule: Rule, lang: str) -> list[str]:
    texts = rule.texts
    language = "English" if lang == "en" else "Français"
    return [
        f"**{language}**: {_md(raw_text(rule.code, texts.title, lang))}",
        "",
        *_templates("message", rule.code, texts.message, lang),
        *_templates("hint", rule.code, texts.hint, lang),
        *_parts(rule.code, texts.parts, lang),
        "",
        _md(raw_text(rule.code, texts.explanation, lang)),
        "",
    ]


INTRO = """\
# Validator rules

<!-- Generated by `python -m bras_kit.validate.catalogue > docs/rules.md`; do not edit by hand. -->

`bras-kit validate` checks URDF and xacro files against the rules below and prints one line per
finding, `path:LINE: CODE severity <element name="..."> message`, followed by a hint. The same
text, in English or French, is shown by `bras-kit explain CODE`.

- **error**: the file is wrong; ROS tools refuse it or show something else than intended.
- **warning**: probably a mistake; the file still loads.
- **info**: advice (for example what physics simulation will need later).

Exit status: 0 when no file has an error (warnings and infos allowed), 1 when one has (with
`--strict`, warnings too), 2 when a file could not be read at all or the command line is wrong.

A file that cannot be read at all (BK100 not well-formed, BK101 unsafe XML, BK102 xacro failure,
BK103 missing or unreadable) is reported as a finding, with its line when known, *and* makes the
command exit with 2: scripts can tell "this input is broken" from "this robot has defects", and
editors still get a line to jump to. Other files on the same command line are still checked.
`--select` and `--ignore` take codes or prefixes (`BK3`, `BK301`); they never hide BK100-BK103.
For `.xacro` files, lines point at the element with the same name in the xacro source when it is
written there literally, and are left out otherwise.

Given a ROS 2 package folder (one holding `package.xml` and `setup.py`, such as the one
`bras-kit new` makes), `bras-kit validate PKGDIR` also applies the BK6xx rules to the package
itself: `setup.py`, `package.xml`, the launch files, the `.rviz` configuration and the Python
nodes, each finding at its file and line. Those files are read, never run.
"""


def catalogue_markdown() -> str:
    parts = [INTRO, "| Code | Name | Severity | Finds |", "|---|---|---|---|"]
    for r in sorted_rules():
        parts.append(f"| [{r.code}](#{r.code.lower()}) | {r.name} | {r.severity} | {_md(r.texts.title)} |")
    parts.append("")
    for prefix, family in FAMILIES.items():
        parts += [f"## {prefix}xx: {say(FAMILY_TITLES[family], 'en')}", ""]
        for r in sorted_rules():
            if r.code.startswith(prefix):
                parts += [f"### {r.code}", "", f"`{r.name}`, {r.severity}", ""]
                parts += _section(r, "en") + _section(r, "fr")
    return "\n".join(parts).rstrip() + "\n"


if __name__ == "__main__":
    import sys

    sys.stdout.write(catalogue_markdown())
