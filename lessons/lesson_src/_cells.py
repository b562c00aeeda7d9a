"""The pieces a lesson is made of: cells with French and English text."""

from __future__ import annotations

import textwrap
from dataclasses import dataclass, field


@dataclass
class Cell:
    kind: str  # "markdown" or "code"
    fr: str
    en: str
    hidden: bool = False  # a collapsed solution cell (source_hidden)


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
    """A code cell; ``en`` only when the English cell differs (comments, printed words)."""
    return Cell("code", _dedent(src), _dedent(en if en is not None else src), hidden=hidden)


def _dedent(text: str) -> str:
    return textwrap.dedent(text).strip("\n")


