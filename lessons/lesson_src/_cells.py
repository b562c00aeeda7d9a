"""The pieces a lesson is made of: cells with French and English text."""

from __future__ import annotations

import functools
import re
import textwrap
from dataclasses import dataclass, field
from pathlib import Path


@dataclass
class Cell:
    kind: str  # "markdown" or "code"
    fr: str
    en: str
    hidden: bool = False  # a collapsed solution cell (source_hidden)
    shared: bool = False  # a code cell written once; its French comments come from the lessons' catalog


@dataclass
class Lesson:
    number: str  # "01"; solutions use "06-solution"
    slug: dict[str, str]
    title: dict[str, str]
    cells: list[Cell] = field(default_factory=list)
    folder: str = ""  # "" or "solutions"

    def filename(self, lang: str) -> str:
        return f"{self.number}-{self.slug[lang]}.ipynb"


def md(fr: str, en: str) -> Cell:
    return Cell("markdown", _dedent(fr), _dedent(en))


def code(src: str, en: str | None = None, *, hidden: bool = False) -> Cell:
    """A code cell; ``en`` only when the English cell differs (printed words).

    A cell given once is shared; its comments are English and become French through the
    lessons' catalog, :data:`CATALOG` (a comment missing there stays English: the build script
    says so).
    """
    if en is not None:
        return Cell("code", _dedent(src), _dedent(en), hidden=hidden)
    text = _dedent(src)
    return Cell("code", french_comments(text), text, hidden=hidden, shared=True)


# The French words of the shared code cells' comments: the lessons' gettext catalog
# (lessons/locale/fr/LC_MESSAGES/lessons.po, one entry per English comment; a translator edits
# it with any PO editor, and the build script lists the comments it does not hold yet).
CATALOG = Path(__file__).resolve().parent.parent / "locale" / "fr" / "LC_MESSAGES" / "lessons.po"


@functools.cache
def _french() -> dict[str, str]:
    from babel.messages.pofile import read_po

    with CATALOG.open("rb") as handle:
        return {str(m.id): str(m.string) for m in read_po(handle) if m.id and m.string}


def french_comment(english: str) -> str | None:
    """The French of a shared cell's comment, or None when the catalog does not hold it."""
    return _french().get(english)


_COMMENT = re.compile(r"(#\s*)(.+)$")


def french_comments(text: str) -> str:
    """``text`` with each ``# comment`` found in the lessons' catalog (:data:`CATALOG`) in French."""
    out = []
    for line in text.split("\n"):
        match = _COMMENT.search(line)
        if match and not _in_string(line, match.start()) and french_comment(match.group(2).strip()) is not None:
            line = line[:match.start(2)] + str(french_comment(match.group(2).strip()))
        out.append(line)
    return "\n".join(out)


def untranslated_comments(text: str) -> list[str]:
    """Comments of a shared cell that the lessons' catalog (:data:`CATALOG`) does not translate."""
    found = []
    for line in text.split("\n"):
        match = _COMMENT.search(line)
        if match and not _in_string(line, match.start()) and french_comment(match.group(2).strip()) is None:
            found.append(match.group(2).strip())
    return found


def _in_string(line: str, index: int) -> bool:
    """Whether position ``index`` of ``line`` is inside a quoted string (good enough for comments)."""
    quote = None
    for char in line[:index]:
        if quote is None and char in "\"'":
            quote = char
        elif char == quote:
            quote = None
    return quote is not None


def _dedent(text: str) -> str:
    return textwrap.dedent(text).strip("\n")


