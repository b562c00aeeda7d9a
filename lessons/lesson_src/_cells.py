"""The pieces a lesson is made of: cells with French and English text."""

from __future__ import annotations

import re
import textwrap
from dataclasses import dataclass, field


@dataclass
class Cell:
    kind: str  # "markdown" or "code"
    fr: str
    en: str
    hidden: bool = False  # a collapsed solution cell (source_hidden)
    shared: bool = False  # a code cell written once; its French comments come from FR_COMMENTS


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

    A cell given once is shared; its comments are English and become French through
    :data:`FR_COMMENTS` (a comment missing there stays English: the build script says so).
    """
    if en is not None:
        return Cell("code", _dedent(src), _dedent(en), hidden=hidden)
    text = _dedent(src)
    return Cell("code", french_comments(text), text, hidden=hidden, shared=True)


# English comment of a shared code cell -> its French words.
FR_COMMENTS = {
    "1.0: radians": "1.0 : radians",
    "joint epaule": "articulation epaule",
    "joint coude": "articulation coude",
    "the library's messages and picture words in this notebook's language":
        "messages, titres et axes de la bibliothèque dans la langue du carnet",
    "+ 0.0 turns -0.0 into 0.0": "+ 0.0 change -0.0 en 0.0",
    "the error's words, in the library's language": "les mots de l'erreur, dans la langue de la bibliothèque",
    "run this cell when you are done with the 3D view": "exécutez cette cellule quand vous avez fini avec la vue 3D",
    "--no-build-isolation: use the installed setuptools, no download":
        "--no-build-isolation : le setuptools installé, sans téléchargement",
    "tidy up the temporary folder": "ranger le dossier temporaire",
    "20 Hz, like the node's 0.05 s timer": "20 Hz, comme le minuteur de 0,05 s du nœud",
    "ixx = iyy = 0.030533, izz = 0.0010667": "ixx = iyy = 0.030533, izz = 0.0010667",
    "repaired: the generated arm": "réparé : le bras généré",
}

_COMMENT = re.compile(r"(#\s*)(.+)$")


def french_comments(text: str) -> str:
    """``text`` with each ``# comment`` found in :data:`FR_COMMENTS` in French."""
    out = []
    for line in text.split("\n"):
        match = _COMMENT.search(line)
        if match and not _in_string(line, match.start()) and match.group(2).strip() in FR_COMMENTS:
            line = line[:match.start(2)] + FR_COMMENTS[match.group(2).strip()]
        out.append(line)
    return "\n".join(out)


def untranslated_comments(text: str) -> list[str]:
    """Comments of a shared cell that :data:`FR_COMMENTS` does not translate."""
    found = []
    for line in text.split("\n"):
        match = _COMMENT.search(line)
        if match and not _in_string(line, match.start()) and match.group(2).strip() not in FR_COMMENTS:
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


