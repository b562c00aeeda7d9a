"""Words for findings, in English or French.

Each language module (``messages_en``, ``messages_fr``) holds, per rule code, a
:class:`RuleText`: a short title, the one-line message and the hint as ``str.format``
templates, and the long explanation shown by ``bras-kit explain``. A template may be a dict
of variants (``{"gap": ..., "overlap": ...}``), chosen by the rule's :class:`Hit`. Both
languages use the same placeholders (a test checks it), so any finding can be worded in
either language from the same facts.
"""

from __future__ import annotations

import importlib
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

from .findings import Finding
from .registry import Hit, Rule
from .solids import number

LANGUAGES = ("en", "fr")
DEFAULT_LANGUAGE = "en"
MAX_LISTED = 8  # names shown in a list before "... (+N)"

Template = str | Mapping[str, str]


@dataclass(frozen=True)
class RuleText:
    title: str
    message: Template
    hint: Template
    explanation: str


def default_language(environ: Mapping[str, str] | None = None) -> str:
    """``BRAS_KIT_LANG``, else ``fr`` when the locale says French (LC_ALL, LC_MESSAGES, LANG), else ``en``."""
    from ..i18n import resolve_language

    return resolve_language(None, environ)


def check_language(lang: str) -> str:
    if lang not in LANGUAGES:
        from ..errors import ParameterError

        raise ParameterError(f"unknown language '{lang}'", hint="use --lang en or --lang fr")
    return lang


def _module(lang: str):  # type: ignore[no-untyped-def]
    return importlib.import_module(f"{__package__}.messages_{check_language(lang)}")


def rule_text(code: str, lang: str = DEFAULT_LANGUAGE) -> RuleText:
    return _module(lang).RULE_TEXTS[code]  # type: ignore[no-any-return]


def ui(lang: str = DEFAULT_LANGUAGE) -> Mapping[str, str]:
    """Words of the report itself (summary, severity names, "hint")."""
    return _module(lang).UI  # type: ignore[no-any-return]


def pick(template: Template, variant: str) -> str:
    if isinstance(template, str):
        return template
    return template.get(variant) or template[""]


def format_value(value: Any) -> str:
    """Numbers as in a URDF (``0.6``), vectors space-separated, name lists quoted and capped."""
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, (int, float)):
        return number(float(value)) if isinstance(value, float) else str(value)
    if isinstance(value, (tuple, list)):
        if all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in value) and value:
            return " ".join(format_value(v) for v in value)
        shown = [f"'{v}'" for v in value[:MAX_LISTED]]
        if len(value) > MAX_LISTED:
            shown.append(f"... (+{len(value) - MAX_LISTED})")
        return ", ".join(shown)
    return "?" if value is None else str(value)


def word(rule: Rule, found: Hit, lang: str = DEFAULT_LANGUAGE) -> Finding:
    """The finding for ``found``, worded in ``lang``."""
    text = rule_text(rule.code, lang)
    params = {key: format_value(value) for key, value in found.params.items()}
    message = pick(text.message, found.variant).format(**params)
    hint = pick(text.hint, found.variant).format(**params) if text.hint else ""
    return Finding(rule.code, rule.severity, message, found.element, found.name, found.line, hint,
                   dict(found.params))
