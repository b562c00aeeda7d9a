"""Findings as text for people (``path:LINE: CODE severity <element> message``) or JSON for programs."""

from __future__ import annotations

import json
from collections.abc import Sequence
from dataclasses import dataclass

from ..core.i18n import say
from ..core.message import M, Message, Mn
from ..trust.inert import Shown, Styled, for_terminal, join, styled
from .data import FileResult, Finding
from .registry import ERROR, INFO, SEVERITY_WORDS, WARNING

_COLOURS = {ERROR: "red", WARNING: "yellow", INFO: "cyan"}


@dataclass(frozen=True)
class Totals:
    """How many files were checked, and how many findings of each severity."""

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


def _counts(kind: str, n: int) -> Message:
    if kind == "checked":
        return Mn("{n} file checked", "{n} files checked", n)
    if kind == "unreadable":
        return Mn("{n} could not be read", "{n} could not be read", n)
    if kind == "errors":
        return Mn("{n} error", "{n} errors", n)
    if kind == "warnings":
        return Mn("{n} warning", "{n} warnings", n)
    return Mn("{n} info", "{n} info", n)


def element_text(finding: Finding) -> str:
    if finding.element in ("file", ""):
        return ""
    if finding.name is None:
        return f"<{finding.element}>"
    return f'<{finding.element} name="{finding.name}">'


def finding_text(path: str, finding: Finding, lang: str | None = None) -> str:
    return str(_finding_shown(path, finding, lang, False))


def _finding_shown(path: str, finding: Finding, lang: str | None, colour: bool) -> Shown:
    where = f"{path}:{finding.line}:" if finding.line else f"{path}:"
    severity: Shown = say(SEVERITY_WORDS[finding.severity], lang)
    code: Shown = finding.code
    if colour:  # bras-kit's own styles, as Styled: only emit() writes them as colours
        code = styled(finding.code, "bold")
        severity = styled(str(severity), _COLOURS[finding.severity])
    element = for_terminal(element_text(finding))
    where = for_terminal(where)
    # a message may quote a learner's text (an exception's): its control characters are shown, not obeyed
    head = join(" ", [part for part in (where, code, severity, element, for_terminal(finding.text(lang))) if part])
    hint = finding.hint_text(lang)
    if hint:
        return head + "\n  " + say(M("hint: {hint}", hint=for_terminal(hint)), lang)
    return head


def summary_text(results: Sequence[FileResult], lang: str | None = None) -> str:
    t = totals(results)
    head = say(_counts("checked", t.files), lang)
    if t.unreadable:
        head += f" ({say(_counts('unreadable', t.unreadable), lang)})"
    if not (t.errors or t.warnings or t.infos):
        return say(M("{checked}: no problems found.", checked=head), lang)
    counts = [say(_counts("errors", t.errors), lang), say(_counts("warnings", t.warnings), lang)]
    if t.infos:
        counts.append(say(_counts("infos", t.infos), lang))
    return say(M("{checked}: {counts}.", checked=head, counts=", ".join(counts)), lang)


# more findings of one rule in one file than this (a generated robot: one per link or joint) are
# shown once, with their count and their first names; the JSON report keeps every one
REPEATED = 10
NAMES_SHOWN = 5


def format_text(results: Sequence[FileResult], lang: str | None = None) -> str:
    return str(_format_shown(results, lang, False))


def format_styled(results: Sequence[FileResult], lang: str | None = None) -> Styled:
    """:func:`format_text` with the codes in bold and the severities in colour, for a terminal
    (written by :func:`bras_kit.trust.inert.emit`)."""
    return Styled() + _format_shown(results, lang, True)


def _format_shown(results: Sequence[FileResult], lang: str | None, colour: bool) -> Shown:
    blocks = [block for r in results for block in _file_blocks(r, lang, colour)]
    return join("\n", blocks + ([""] if blocks else []) + [summary_text(results, lang)]) + "\n"


def _file_blocks(result: FileResult, lang: str | None, colour: bool) -> list[Shown]:
    by_code: dict[str, list[Finding]] = {}
    for found in result.findings:
        by_code.setdefault(found.code, []).append(found)
    blocks = []
    for found in result.findings:
        same = by_code[found.code]
        if len(same) <= REPEATED:
            blocks.append(_finding_shown(result.path, found, lang, colour))
        elif found is same[0]:
            blocks.append(_finding_shown(result.path, found, lang, colour) + "\n  " + repeated_text(same, lang))
    return blocks


def repeated_text(same: Sequence[Finding], lang: str | None = None) -> str:
    """The line under the first of many findings of one rule: how many more, where, which names."""
    rest = same[1:]
    names = [f.name for f in rest if f.name]
    shown = ", ".join(names[:NAMES_SHOWN]) + (", ..." if len(names) > NAMES_SHOWN else "")
    lines = [f.line for f in rest if f.line]
    if lines and shown:
        detail = say(M("lines {first} to {last}; {names}", first=min(lines), last=max(lines),
                       names=for_terminal(shown)), lang)
    else:
        detail = say(M("lines {first} to {last}", first=min(lines), last=max(lines)), lang) if lines \
            else for_terminal(shown)
    return say(Mn("and {n} more {code} like it in this file ({detail}): --json lists each",
                  "and {n} more {code} like it in this file ({detail}): --json lists each", len(rest),
                  code=same[0].code, detail=detail), lang)


def format_json(results: Sequence[FileResult], strict: bool = False, lang: str | None = None) -> str:
    """Findings for programs; ``message`` and ``hint`` worded in ``lang``."""
    document = {
        "files": [
            {"path": r.path, "ok": r.ok(strict), "findings": [f.as_dict(lang) for f in r.findings]}
            for r in results
        ],
        "summary": totals(results).as_dict(),
    }
    return json.dumps(document, ensure_ascii=False, indent=2) + "\n"
