"""The lesson notebooks: stored clean, the same in both languages, and every one runs top to bottom."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path

import nbformat
import pytest

LESSONS = Path(__file__).resolve().parent.parent / "lessons"
LANGS = ("fr", "en")


def _notebooks(lang: str) -> list[Path]:
    return sorted(p for p in (LESSONS / lang).rglob("*.ipynb") if ".ipynb_checkpoints" not in p.parts)


def _key(path: Path) -> str:
    """Pairs a French notebook with its English twin: folder + number (``07``, ``solutions/07``)."""
    rel = path.relative_to(LESSONS / path.relative_to(LESSONS).parts[0])
    return str(rel.parent / rel.name.split("-")[0])


def _id(path: Path) -> str:
    return str(path.relative_to(LESSONS))


ALL = [p for lang in LANGS for p in _notebooks(lang)]


def test_every_lesson_exists_in_both_languages() -> None:
    fr = {_key(p) for p in _notebooks("fr")}
    en = {_key(p) for p in _notebooks("en")}
    assert fr == en
    lessons = {k for k in fr if "/" not in k}
    assert lessons == {f"{n:02d}" for n in range(1, 12)}
    assert {k for k in fr if k.startswith("solutions/")} >= {"solutions/06", "solutions/07"}


@pytest.mark.parametrize("path", ALL, ids=_id)
def test_notebook_is_stored_without_outputs(path: Path) -> None:
    nb = nbformat.read(path, as_version=4)
    for cell in nb.cells:
        if cell.cell_type == "code":
            assert cell.outputs == [], f"{path.name}: cell {cell.id} has stored outputs"
            assert cell.execution_count is None, f"{path.name}: cell {cell.id} has an execution count"


@pytest.mark.parametrize("path", _notebooks("fr"), ids=_id)
def test_french_and_english_notebooks_have_the_same_cells(path: Path) -> None:
    twin = next(p for p in _notebooks("en") if _key(p) == _key(path))
    fr, en = nbformat.read(path, as_version=4), nbformat.read(twin, as_version=4)
    assert [c.cell_type for c in fr.cells] == [c.cell_type for c in en.cells]
    hidden = [[bool(c.metadata.get("jupyter", {}).get("source_hidden")) for c in nb.cells] for nb in (fr, en)]
    assert hidden[0] == hidden[1]


@pytest.mark.parametrize("path", _notebooks("fr"), ids=_id)
def test_french_notebooks_are_written_in_french(path: Path) -> None:
    twin = next(p for p in _notebooks("en") if _key(p) == _key(path))
    fr, en = nbformat.read(path, as_version=4), nbformat.read(twin, as_version=4)
    pairs = [(a.source, b.source) for a, b in zip(fr.cells, en.cells) if a.cell_type == "markdown"]
    same = [a for a, b in pairs if a == b]
    assert len(same) * 4 <= len(pairs), f"{len(same)} of {len(pairs)} text cells are not translated"


def test_notebook_code_passes_ruff() -> None:
    result = subprocess.run([sys.executable, "-m", "ruff", "check", "--no-cache", "--output-format", "concise",
                             *map(str, ALL)], capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr


def test_notebooks_match_their_build_script() -> None:
    result = subprocess.run([sys.executable, str(LESSONS / "build_lessons.py"), "--check"],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stdout + result.stderr


@pytest.mark.slow
@pytest.mark.parametrize("path", ALL, ids=_id)
def test_notebook_runs_top_to_bottom(path: Path, tmp_path: Path) -> None:
    from nbclient import NotebookClient

    nb = nbformat.read(path, as_version=4)
    client = NotebookClient(nb, timeout=120, kernel_name="python3", resources={"metadata": {"path": str(tmp_path)}})
    client.execute()  # raises CellExecutionError, with the failing cell and traceback, on any error
    ran = [c for c in nb.cells if c.cell_type == "code"]
    assert ran and all(c.execution_count is not None for c in ran)


def test_french_lessons_speak_the_tutorials_french() -> None:
    """Segments, articulations, repères: no English word left in the French lessons' text
    (code spans, code blocks and XML tags aside; RViz's own setting names are kept)."""
    import re

    english = re.compile(r"\b(links?|joints?|frames?|the|and|of|error|warning|wrote)\b", re.IGNORECASE)
    found = []
    for path in sorted((LESSONS / "fr").rglob("*.ipynb")):
        for cell in json.loads(path.read_text(encoding="utf-8"))["cells"]:
            if cell["cell_type"] != "markdown":
                continue
            text = "".join(cell["source"])
            text = re.sub(r"```.*?```", "", text, flags=re.S)
            text = re.sub(r"`[^`]*`|<[^>]+>|\*\*Fixed Frame\*\*|Fixed Frame", "", text)
            found += [f"{path.name}: {m.group(0)}" for m in english.finditer(text)]
    assert not found, found
