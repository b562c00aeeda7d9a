"""What the learner sees, as lines of text fitted to a width: the exercise, its state, its hints.

Colours only when asked (a terminal that is not NO_COLOR); otherwise plain text, readable when
piped or written to a file.
"""

from __future__ import annotations

import os
import textwrap
from collections.abc import Sequence
from dataclasses import dataclass

from ..core.i18n import say
from ..core.message import M, Message, Mn
from ..trust.inert import Shown, for_terminal, styled
from .checks import BROKEN, PASSED, Outcome
from .manifest import Exercise, Track, lesson_link
from .progress import Progress

MIN_WIDTH, MAX_WIDTH = 40, 100
@dataclass(frozen=True)
class Style:
    colour: bool = False

    def __call__(self, text: str, name: str) -> Shown:
        """``text`` in the style ``name`` (a :class:`~bras_kit.trust.inert.Styled`, which only
        :func:`~bras_kit.trust.inert.emit` writes as colour), or the plain text without colours."""
        return styled(text, name) if self.colour else text


def wants_colour(stream: object) -> bool:
    isatty = getattr(stream, "isatty", None)
    return bool(isatty and isatty()) and not os.environ.get("NO_COLOR") and os.environ.get("TERM") != "dumb"


def fitted(width: int) -> int:
    return max(MIN_WIDTH, min(MAX_WIDTH, width))


def _wrap(text: str, width: int, indent: str = "") -> list[str]:
    out: list[str] = []
    for paragraph in text.split("\n\n"):
        flat = " ".join(paragraph.split())
        out.extend(textwrap.wrap(flat, width, initial_indent=indent, subsequent_indent=indent,
                                 break_long_words=True, break_on_hyphens=False) or [""])
    return out


def _labelled(label: str, text: str, width: int, shown: Shown | None = None) -> list[Shown]:
    """``label text`` with the text wrapped under itself; ``shown`` is the label as printed
    (coloured), ``label`` its plain text (its width)."""
    lines = _wrap(text, max(20, width - len(label) - 1)) if text else [""]
    pad = " " * (len(label) + 1)
    return [((shown or label) + " " + lines[0]).rstrip(), *(pad + line for line in lines[1:])]


def state_word(outcome: Outcome | None, style: Style, lang: str) -> Shown:
    if outcome is None:
        return style(say(M("checking..."), lang), "dim")
    if outcome.state == PASSED:
        return style(say(M("passed"), lang), "green")
    if outcome.state == BROKEN:
        return style(say(M("cannot be read"), lang), "yellow")
    return style(say(M("not yet"), lang), "red")


def _reason(outcome: Outcome, lang: str) -> str:
    where = outcome.file + (f":{outcome.line}" if outcome.file and outcome.line else "")
    text = say(outcome.reason, lang) if isinstance(outcome.reason, Message) else str(outcome.reason or "")
    return f"{where}: {text}" if where else text


def hints_to_show(outcome: Outcome | None, seen: int) -> list[int]:
    """The hints shown: those asked for, and the one that fits a failure (the first at least)."""
    if outcome is not None and outcome.state == PASSED:
        return []
    shown = set(range(1, seen + 1))
    if outcome is not None and outcome.state != BROKEN:
        shown.add(outcome.hint)
    return sorted(shown)


def exercise_lines(track: Track, progress: Progress, exercise: Exercise, outcome: Outcome | None, lang: str,
                   width: int, style: Style = Style()) -> list[Shown]:
    width = fitted(width)
    rule = style("─" * width, "dim")
    passed = sum(progress.passed(e.id) for e in track.exercises)
    head = say(M("exercise {number}/{total}: {title}", number=exercise.number, total=len(track.exercises),
                 title=exercise.title_in(lang)), lang)
    heading = _wrap(head, width)
    lines: list[Shown] = [style(heading[0], "bold"), *heading[1:], rule]
    lines += _wrap(exercise.statement_in(lang), width)
    lines.append("")
    files = ", ".join(os.path.join(exercise.id, name) for name in exercise.files)
    lines += _labelled(say(M("files:"), lang), files, width)
    if exercise.lesson_in(lang):
        lines += _labelled(say(M("lesson:"), lang), lesson_link(track, exercise, lang, progress.folder), width)
    lines.append(rule)
    # the reason and the detail may quote the learner's file (a syntax error's line): text, not commands
    reason = for_terminal(_reason(outcome, lang)) if outcome and outcome.reason else ""
    dash = " —" if reason else ""
    lines += _labelled(str(state_word(outcome, Style(), lang)) + dash, reason, width,
                       state_word(outcome, style, lang) + dash)
    if outcome is not None and outcome.detail:
        detail = say(outcome.detail, lang) if isinstance(outcome.detail, Message) else str(outcome.detail)
        lines += _wrap(for_terminal(detail), width, "  ")
    if outcome is not None and outcome.state == BROKEN:
        lines += _wrap(say(M("finish writing the file and save it: it is checked again at once"), lang), width, "  ")
    lines += hint_lines(exercise, hints_to_show(outcome, progress.hints_seen(exercise.id)), lang, width, style)
    lines.append(rule)
    lines += _wrap(say(M("{passed}/{total} exercises passed", passed=passed, total=len(track.exercises)), lang), width)
    return lines


def keys_line(lang: str, width: int) -> str:
    return say(M("h: next hint   c: check again   l: list   q: quit"), lang)[:fitted(width)]


def list_lines(track: Track, progress: Progress, lang: str, width: int, style: Style = Style()) -> list[Shown]:
    width = fitted(width)
    lines = [style(track.title_in(lang), "bold")]
    mark: Shown
    for exercise in track.exercises:
        if progress.passed(exercise.id):
            mark = style(say(M("passed"), lang), "green")
        elif exercise.id == progress.current:
            mark = style(say(M("current"), lang), "yellow")
        else:
            mark = say(M("to do"), lang)
        seen = progress.hints_seen(exercise.id)
        used = say(Mn("{n}/3 hint", "{n}/3 hints", seen), lang) if seen else ""
        lines.append(_row(f"{exercise.number:2d}. {exercise.title_in(lang)}", mark, used, width))
    passed = sum(progress.passed(e.id) for e in track.exercises)
    lines.append(say(M("{passed}/{total} exercises passed", passed=passed, total=len(track.exercises)), lang))
    return lines


def _row(title: str, mark: Shown, used: str, width: int) -> Shown:
    room = max(10, width - 24)
    if len(title) > room:
        title = title[:room - 1] + "…"
    return (f"{title:<{room}} " + mark + f" {used}").rstrip()


def done_lines(track: Track, lang: str, width: int, style: Style = Style()) -> list[Shown]:
    return [style(say(M("every exercise of '{track}' passed: well done!", track=track.title_in(lang)), lang), "green"),
            *_wrap(say(M("the files stay yours: bras-kit view, run and validate work on them as on any other"),
                       lang), fitted(width))]


def hint_lines(exercise: Exercise, numbers: Sequence[int], lang: str, width: int,
               style: Style = Style()) -> list[Shown]:
    lines: list[Shown] = []
    for number in numbers:
        label = say(M("hint {n}/3:", n=number), lang)
        lines += _labelled(label, exercise.hint_in(lang, number), fitted(width), style(label, "yellow"))
    return lines
