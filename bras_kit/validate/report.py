"""Findings as text for people (``path:LINE: CODE severity <element> message``) or JSON for programs."""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass

from .findings import FileResult, Finding
from .i18n import DEFAULT_LANGUAGE, ui
from .registry import ERROR, INFO, WARNING

_COLOURS = {ERROR: "31", WARNING: "33", INFO: "36"}  # red, yellow, cyan


@dataclass(frozen=True)
class Totals:
    files: int
    unreadable: int
    errors: int
    warnings: int
    infos: int

    def as_dict(self) -> dict[str, int]:
        return dict(self.__dict__)


def totals(results: Sequence[FileResult]) -> Totals:
    return Totals(
        files=len(results),
        unreadable=sum(1 for r in results if not r.readable),
        errors=sum(r.count(ERROR) for r in results),
        warnings=sum(r.count(WARNING) for r in results),
        infos=sum(r.count(INFO) for r in results),
    )


def exit_code(results: Sequence[FileResult], strict: bool = False) -> int:
    """2 when a file could not be read, 1 when a file fails (errors; warnings too if strict), else 0."""
    if any(not r.readable for r in results):
        return 2
    return 0 if all(r.ok(strict) for r in results) else 1


def _count(key: str, n: int, lang: str) -> str:
    many = n > 1 if lang == "fr" else n != 1  # French: 0 and 1 take the singular
    return ui(lang)[f"{key}_{'many' if many else 'one'}"].format(n=n)


def element_text(finding: Finding) -> str:
    if finding.element in ("file", ""):
        return ""
    if finding.name is None:
        return f"<{finding.element}>"
    return f'<{finding.element} name="{finding.name}">'


def finding_text(path: str, finding: Finding, lang: str = DEFAULT_LANGUAGE, colour: bool = False) -> str:
    words = ui(lang)
    where = f"{path}:{finding.line}:" if finding.line else f"{path}:"
    severity = words[finding.severity]
    code = finding.code
    if colour:
        code = f"\033[1m{code}\033[0m"
        severity = f"\033[{_COLOURS[finding.severity]}m{severity}\033[0m"
    element = element_text(finding)
    head = " ".join(part for part in (where, code, severity, element, finding.message) if part)
    if finding.hint:
        return f"{head}\n  {words['hint']}{words['colon']}{finding.hint}"
    return head


def summary_text(results: Sequence[FileResult], lang: str = DEFAULT_LANGUAGE) -> str:
    t = totals(results)
    words = ui(lang)
    head = _count("checked", t.files, lang)
    if t.unreadable:
        head += f" ({_count('unreadable', t.unreadable, lang)})"
    if not (t.errors or t.warnings or t.infos):
        return head + words["colon"] + words["clean"] + "."
    counts = [_count("errors", t.errors, lang), _count("warnings", t.warnings, lang)]
    if t.infos:
        counts.append(_count("infos", t.infos, lang))
    return head + words["colon"] + ", ".join(counts) + "."


def format_text(results: Sequence[FileResult], lang: str = DEFAULT_LANGUAGE, colour: bool = False) -> str:
    blocks = [finding_text(r.path, f, lang, colour) for r in results for f in r.findings]
    return "\n".join(blocks + ([""] if blocks else []) + [summary_text(results, lang)]) + "\n"


def format_json(results: Sequence[FileResult], strict: bool = False) -> str:
    document = {
        "files": [
            {"path": r.path, "ok": r.ok(strict), "findings": [f.as_dict() for f in r.findings]}
            for r in results
        ],
        "summary": totals(results).as_dict(),
    }
    return json.dumps(document, ensure_ascii=False, indent=2) + "\n"
