"""mkdocs hook: run every lesson notebook and publish it as a page with its outputs.

The notebooks are stored without outputs (so diffs stay readable); the site shows them as a
learner sees them after running them: text, code, printed results and pictures. Each notebook
runs in a fresh kernel in its own temporary folder, two at a time. A notebook that fails
fails the build, so the site never shows a lesson that does not run.
"""

from __future__ import annotations

import base64
import json
import os
import re
import tempfile
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any

ROOT = Path(__file__).resolve().parents[2]
LESSONS = ROOT / "lessons"
LANGUAGES = {"fr": "Leçons en français", "en": "Lessons in English"}
NAV_ENTRY = "lessons.md"
PICTURES = {"image/png": "png", "image/gif": "gif", "image/jpeg": "jpg"}
ANSI = re.compile(r"\x1b\[[0-9;]*[A-Za-z]")


def notebooks() -> list[tuple[str, Path]]:
    """(language, path) of every lesson and solution notebook, in reading order."""
    found = []
    for lang in LANGUAGES:
        folder = LESSONS / lang
        found += [(lang, p) for p in sorted(folder.glob("*.ipynb"))]
        found += [(lang, p) for p in sorted((folder / "solutions").glob("*.ipynb"))]
    return found


def page_uri(lang: str, path: Path) -> str:
    relative = path.relative_to(LESSONS / lang).with_suffix(".md")
    return f"lessons/{lang}/{relative.as_posix()}"


def title(path: Path) -> str:
    """The notebook's first Markdown heading."""
    cells = json.loads(path.read_text(encoding="utf-8"))["cells"]
    for cell in cells:
        if cell["cell_type"] == "markdown":
            for line in "".join(cell["source"]).splitlines():
                if line.startswith("#"):
                    return line.lstrip("#").strip()
    return path.stem


def kernel_environment() -> dict[str, str]:
    """The kernels' environment: this one, with Jupyter's inline plots (a headless
    MPLBACKEND=Agg, as CI sets, would make plt.show() draw nothing and the pages lose their figures)."""
    return {**os.environ, "MPLBACKEND": "module://matplotlib_inline.backend_inline"}


def executed_copy(path: str) -> Path | None:
    """Where a run of this notebook is kept for the rest of a test session (the folder named by
    BRAS_KIT_LESSONS_EXECUTED, which tests/conftest.py sets; None outside the tests), by the
    digest of its bytes: the site's build and tests/lessons/test_lessons.py run each lesson once."""
    import hashlib

    folder = os.environ.get("BRAS_KIT_LESSONS_EXECUTED")
    if not folder:
        return None
    return Path(folder) / (hashlib.sha256(Path(path).read_bytes()).hexdigest() + ".ipynb")


def execute(path: str) -> str:
    """Run one notebook in a fresh kernel and a temporary folder; return it as JSON text."""
    import nbformat
    from nbclient import NotebookClient

    kept = executed_copy(path)
    if kept is not None and kept.is_file():
        return kept.read_text(encoding="utf-8")
    notebook = nbformat.read(path, as_version=4)
    with tempfile.TemporaryDirectory() as folder:
        NotebookClient(notebook, timeout=180, kernel_name="python3",
                       extra_arguments=["--IPKernelApp.log_level=ERROR"],  # quiet kernel start-up notes
                       resources={"metadata": {"path": folder}}).execute(env=kernel_environment())
    text = nbformat.writes(notebook)
    if kept is not None:
        temporary = kept.with_suffix(f".{os.getpid()}.{id(notebook)}.tmp")
        temporary.write_text(text, encoding="utf-8")
        os.replace(temporary, kept)
    return text


def _text(value: Any) -> str:
    return ANSI.sub("", "".join(value) if isinstance(value, list) else str(value)).rstrip("\n")


def to_markdown(notebook: dict[str, Any], stem: str) -> tuple[str, dict[str, bytes]]:
    """Markdown for an executed notebook, and the pictures it refers to (name -> bytes)."""
    parts: list[str] = []
    pictures: dict[str, bytes] = {}
    for number, cell in enumerate(notebook["cells"]):
        source = _text(cell["source"])
        if cell["cell_type"] == "markdown":
            parts.append(source)
            continue
        if cell["cell_type"] != "code" or not source.strip():
            continue
        parts.append(f"```python\n{source}\n```")
        for k, output in enumerate(cell.get("outputs", [])):
            kind = output["output_type"]
            if kind == "stream":
                parts.append(f"```text\n{_text(output['text'])}\n```")
                continue
            if kind == "error":
                raise RuntimeError(f"{stem}: cell {number} failed: {output['ename']}")
            data = output.get("data", {})
            picture = next((m for m in PICTURES if m in data), None)
            if picture is not None:
                name = f"{stem}/out-{number:02d}-{k}.{PICTURES[picture]}"
                pictures[name] = base64.b64decode(_text(data[picture]))
                parts.append(f"![output of cell {number}]({name})")
            elif "image/svg+xml" in data:
                parts.append(_text(data["image/svg+xml"]))
            elif "application/vnd.jupyter.widget-view+json" in data:
                parts.append("*(interactive sliders: run the notebook to move them)*")
            elif "text/markdown" in data:
                parts.append(_text(data["text/markdown"]))
            elif "text/html" in data:
                parts.append(_text(data["text/html"]))
            elif "text/plain" in data:
                parts.append(f"```text\n{_text(data['text/plain'])}\n```")
    return "\n\n".join(parts) + "\n", pictures


def on_config(config: Any) -> Any:
    """Put every lesson page in the navigation, under the 'Lessons' entry."""
    sections: list[Any] = [{"Overview": NAV_ENTRY}]
    for lang, label in LANGUAGES.items():
        pages = [{title(path): page_uri(lang, path)} for code, path in notebooks() if code == lang]
        sections.append({label: pages})
    nav = config["nav"]
    for i, entry in enumerate(nav):
        if isinstance(entry, dict) and NAV_ENTRY in entry.values():
            nav[i] = {next(iter(entry)): sections}
    return config


def on_files(files: Any, config: Any) -> Any:
    """Run the notebooks and add their pages and pictures to the site."""
    from mkdocs.structure.files import File

    found = notebooks()
    with ThreadPoolExecutor(max_workers=2) as pool:
        executed = list(pool.map(execute, [str(path) for _, path in found]))
    for (lang, path), text in zip(found, executed):
        uri = page_uri(lang, path)
        markdown, pictures = to_markdown(json.loads(text), path.stem)
        files.append(File.generated(config, uri, content=markdown))
        folder = uri.rsplit("/", 1)[0]
        for name, data in pictures.items():
            files.append(File.generated(config, f"{folder}/{name}", content=data))
    return files
