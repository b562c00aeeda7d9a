"""Write the lesson notebooks (French and English) from one description.

Each lesson is a list of cells; a cell carries its French and English text, so both languages
always have the same cells in the same order. Run it after editing a lesson::

    python lessons/build_lessons.py          # rewrite lessons/fr and lessons/en
    python lessons/build_lessons.py --check  # exit 1 if the stored notebooks are out of date

Notebooks are written without outputs and with stable cell ids, so diffs stay readable.
In code cells, ``@LANG@`` becomes ``fr`` or ``en`` (the validator speaks both).
"""

from __future__ import annotations

import argparse
import sys
from pathlib import Path

import nbformat

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE))

from lesson_src import LESSONS  # noqa: E402  (the lessons themselves, one module each)
from lesson_src._cells import Cell, Lesson, untranslated_comments  # noqa: E402

LANGS = ("fr", "en")


def notebook(lesson: Lesson, lang: str) -> nbformat.NotebookNode:
    nb = nbformat.v4.new_notebook()
    nb.metadata = {
        "kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
        "language_info": {"name": "python"},
    }
    title = f"# {lesson.title[lang]}"
    cells = [Cell("markdown", title, title), *lesson.cells]
    for i, cell in enumerate(cells):
        text = getattr(cell, lang).replace("@LANG@", lang)
        cell_id = f"{lesson.number}-{i:02d}"
        if cell.kind == "markdown":
            nb.cells.append(nbformat.v4.new_markdown_cell(text, id=cell_id))
        else:
            new = nbformat.v4.new_code_cell(text, id=cell_id)
            if cell.hidden:
                new.metadata["jupyter"] = {"source_hidden": True}
                new.metadata["tags"] = ["solution"]
            nb.cells.append(new)
    nbformat.validate(nb)
    return nb


def render_all() -> dict[Path, str]:
    """Every notebook's path (relative to lessons/) and its JSON text."""
    out = {}
    for lesson in LESSONS:
        for lang in LANGS:
            path = Path(lang, lesson.folder, lesson.filename(lang)) if lesson.folder else Path(lang, lesson.filename(lang))
            out[path] = nbformat.writes(notebook(lesson, lang)) + "\n"
    return out


def untranslated() -> list[str]:
    """English comments of shared code cells that have no French words yet."""
    return [f"lesson {lesson.number}: no French for the comment {comment!r} (add it to lessons/locale/fr/LC_MESSAGES/lessons.po)"
            for lesson in LESSONS for cell in lesson.cells if cell.shared
            for comment in untranslated_comments(cell.en)]


def main(argv: list[str] | None = None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true", help="only check the notebooks are current")
    args = parser.parse_args(argv)
    wanted = render_all()
    stale = []
    for rel, text in wanted.items():
        path = HERE / rel
        current = path.read_text(encoding="utf-8") if path.exists() else None
        if current != text:
            stale.append(rel)
            if not args.check:
                path.parent.mkdir(parents=True, exist_ok=True)
                path.write_text(text, encoding="utf-8")
    extra = [p.relative_to(HERE) for lang in LANGS for p in (HERE / lang).rglob("*.ipynb")
             if p.relative_to(HERE) not in wanted and ".ipynb_checkpoints" not in p.parts]
    problems = untranslated()
    problems += [f"not made by build_lessons.py: lessons/{rel}" for rel in extra]
    if args.check:
        problems += [f"out of date: lessons/{rel} (run python lessons/build_lessons.py)" for rel in stale]
    else:
        for rel in stale:
            print(f"wrote lessons/{rel}")
    for problem in problems:
        print(problem)
    return 1 if problems else 0


if __name__ == "__main__":
    raise SystemExit(main())
