"""What the validator returns: findings as data (rule code, severity, where, the facts) and per-file results.

A :class:`Finding` holds no words. Where it is shown, :meth:`Finding.text` and
:meth:`Finding.hint_text` word it in the language of that place (``say`` of
:mod:`bras_kit.core.i18n`); :attr:`Finding.message` and :attr:`Finding.hint` are the
:class:`~bras_kit.core.message.Message` objects themselves (``str()`` gives the English).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from ..core.message import Message
from .registry import ERROR, INFO, TEXTS, WARNING, Hit, Rule, pick, text_message

SEVERITY_ORDER = {ERROR: 0, WARNING: 1, INFO: 2}
# the file could not be read at all: not well-formed, unsafe XML, xacro failure, missing file
UNREADABLE_CODES = frozenset({"BK100", "BK101", "BK102", "BK103"})


@dataclass(frozen=True)
class Finding:
    """One problem: ``path:line: code severity <element name="..."> message`` once worded.

    ``variant`` picks one of the rule's wordings; ``params`` are the facts that fill it in
    (numbers, names, the expected origin...), also read by programs and tests.
    """

    code: str
    severity: str
    element: str
    name: str | None
    line: int | None
    variant: str = ""
    params: Mapping[str, Any] = field(default_factory=dict, compare=False, repr=False)

    @property
    def message(self) -> Message:
        return text_message(self.code, pick(TEXTS[self.code].message, self.variant), self.params)

    @property
    def hint(self) -> Message | None:
        template = pick(TEXTS[self.code].hint, self.variant) if TEXTS[self.code].hint else ""
        return text_message(self.code, template, self.params) if template else None

    @property
    def data(self) -> dict[str, Any]:
        """The raw facts behind the wording (expected origin, excess...)."""
        return dict(self.params)

    def text(self, lang: str | None = None) -> str:
        """The message in ``lang`` (None: the library's language)."""
        from ..core.i18n import say

        return say(self.message, lang)

    def hint_text(self, lang: str | None = None) -> str:
        """The hint in ``lang``, or "" when the rule gives none."""
        from ..core.i18n import say

        hint = self.hint
        return say(hint, lang) if hint is not None else ""

    def as_dict(self, lang: str | None = None) -> dict[str, Any]:
        """The JSON form, ``message`` and ``hint`` worded in ``lang``."""
        return {
            "code": self.code,
            "severity": self.severity,
            "message": self.text(lang),
            "element": self.element,
            "name": self.name,
            "line": self.line,
            "hint": self.hint_text(lang),
        }


def finding(rule: Rule, found: Hit) -> Finding:
    """The finding of ``rule`` for one hit."""
    return Finding(rule.code, rule.severity, found.element, found.name, found.line, found.variant, dict(found.params))


# How a node's run ended (it raised, it used what the stand-in does not simulate, it published in a
# loop with no time passing): the cause of every later finding about what it published, so it is
# listed first, whatever its line (BK640 at the line that raised, before BK644 at the publisher's).
CAUSES = frozenset({"BK640", "BK641", "BK642"})


def sort_key(finding: Finding) -> tuple[int, int, int, str]:
    """A file's findings in reading order, causes first: by line, then severity, then code."""
    return (0 if finding.code in CAUSES else 1, finding.line or 0, SEVERITY_ORDER.get(finding.severity, 3),
            finding.code)


@dataclass
class FileResult:
    """The findings of one file, as shown by ``bras-kit validate``."""

    path: str
    findings: list[Finding]

    @property
    def readable(self) -> bool:
        """False when the file could not be read at all; its one finding says why."""
        return not any(f.code in UNREADABLE_CODES for f in self.findings)

    def count(self, severity: str) -> int:
        return sum(1 for f in self.findings if f.severity == severity)

    def ok(self, strict: bool = False) -> bool:
        """True when this file passes: readable, no error, and no warning when ``strict``."""
        failing = (ERROR, WARNING) if strict else (ERROR,)
        return self.readable and not any(f.severity in failing for f in self.findings)


def merge_results(results: list[FileResult], extra: list[FileResult]) -> list[FileResult]:
    """``extra``'s findings joined to those of the same file in ``results``, in reading order (a
    file only in ``extra`` comes after the others)."""
    by_path = {result.path: result for result in results}
    for result in extra:
        if result.path in by_path:
            by_path[result.path] = FileResult(result.path, sorted(by_path[result.path].findings + result.findings,
                                                                  key=sort_key))
        else:
            by_path[result.path] = result
    return list(by_path.values())
