"""The documentation site: it builds strictly, every command has a page, and its examples run.

Runnable examples are ```console blocks whose commands start with ``$ bras-kit``. The lines
after a command are its output as shown: each must appear in what the command prints (a line
ending in ``...`` matches as a prefix; a line ``...`` stands for lines left out). A command
ending in ``# exit code N`` must exit with N, every other one with 0. Files the examples need
come from the fenced block right after an ``<!-- file: NAME -->`` comment. The commands of a
page run in order, in one temporary folder.
"""

from __future__ import annotations

import base64
import re
import shlex
import subprocess
import sys
from dataclasses import dataclass, field
from pathlib import Path

import pytest
import yaml
from paths import REPO

ROOT = REPO
DOCS = ROOT / "docs"
PAGES = sorted(DOCS.rglob("*.md"))

_FENCE = re.compile(r"^```(\S*)\s*$")
_FILE = re.compile(r"^<!--\s*file:\s*(\S+)\s*-->\s*$")
_EXIT = re.compile(r"#\s*exit code (\d+)\s*$")


@dataclass
class Command:
    line: int
    argv: list[str]
    exit_code: int
    output: list[str] = field(default_factory=list)


@dataclass
class File:
    line: int
    name: str
    text: str


def examples(page: Path) -> list[Command | File]:
    """Commands and files of a page, in the order they appear."""
    lines = page.read_text(encoding="utf-8").splitlines()
    steps: list[Command | File] = []
    i = 0
    pending_file = None
    while i < len(lines):
        marker = _FILE.match(lines[i])
        if marker:
            pending_file = marker.group(1)
            i += 1
            continue
        fence = _FENCE.match(lines[i])
        if not fence:
            i += 1
            continue
        start = i + 1
        end = next(k for k in range(start, len(lines)) if lines[k].strip() == "```")
        body = lines[start:end]
        if pending_file is not None:
            steps.append(File(start + 1, pending_file, "\n".join(body) + "\n"))
            pending_file = None
        elif fence.group(1) == "console":
            for offset, text in enumerate(body):
                if text.startswith("$ "):
                    assert text.startswith("$ bras-kit "), \
                        f"{page.name}:{start + offset + 1}: console blocks hold bras-kit commands only"
                    code = _EXIT.search(text)
                    argv = shlex.split(text[2:], comments=True)[1:]
                    steps.append(Command(start + offset + 1, argv, int(code.group(1)) if code else 0))
                elif steps and isinstance(steps[-1], Command) and text.strip():
                    steps[-1].output.append(text.rstrip())
        i = end + 1
    return steps


def _matches(expected: str, actual: str) -> bool:
    if expected.endswith("...") and expected != "...":
        return actual.startswith(expected[:-3])
    return actual == expected


def missing_output(expected: list[str], out: str, err: str) -> str | None:
    """The first shown line that the command did not print (stdout and stderr each in order)."""
    streams = {"out": out.splitlines(), "err": err.splitlines()}
    where = {"out": 0, "err": 0}
    for line in expected:
        if line == "...":
            continue
        for name, actual in streams.items():
            found = next((k for k in range(where[name], len(actual)) if _matches(line, actual[k].rstrip())), None)
            if found is not None:
                where[name] = found + 1
                break
        else:
            return line
    return None


RUNNABLE = [p for p in PAGES if any(isinstance(s, Command) for s in examples(p))]


def _page_id(page: Path) -> str:
    return page.relative_to(DOCS).as_posix()


@pytest.mark.notebook  # the site's build runs every lesson notebook (docs/hooks/lessons.py)
def test_site_builds_strictly(tmp_path: Path) -> None:
    result = subprocess.run([sys.executable, "-m", "mkdocs", "build", "--strict", "-q",
                             "-f", str(ROOT / "mkdocs.yml"), "-d", str(tmp_path / "site")],
                            capture_output=True, text=True, cwd=ROOT)
    assert result.returncode == 0, result.stderr
    site = tmp_path / "site"
    assert (site / "cli" / "validate" / "index.html").is_file()
    assert (site / "rules" / "index.html").is_file()
    # every lesson is published with its outputs: text printed by the code and its pictures
    for lang in ("fr", "en"):
        notebooks = sorted((ROOT / "lessons" / lang).rglob("*.ipynb"))
        assert len(notebooks) >= 10
        for notebook in notebooks:
            page = site / "lessons" / lang / notebook.relative_to(ROOT / "lessons" / lang).with_suffix("") / "index.html"
            assert page.is_file(), page
    see_it = site / "lessons" / "en" / "03-see-it"
    pictures = sorted(see_it.glob("out-*.png"))
    assert len(pictures) >= 3
    html = (see_it / "index.html").read_text(encoding="utf-8")
    assert "(360, 480, 3) uint8" in html  # the printed shape of the first rendered picture
    assert all(p.name in html for p in pictures)
    assert pictures[0].read_bytes().startswith(b"\x89PNG")


def _load_lessons_hook():
    import importlib.util

    spec = importlib.util.spec_from_file_location("lessons_hook", DOCS / "hooks" / "lessons.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def test_lesson_pages_keep_text_code_printed_output_and_pictures() -> None:
    hook = _load_lessons_hook()
    png = b"\x89PNG\r\n\x1a\nfake"
    notebook = {"cells": [
        {"cell_type": "markdown", "source": ["# Title\n", "Some *text*."]},
        {"cell_type": "code", "source": "print(1 + 1)\nimage", "outputs": [
            {"output_type": "stream", "name": "stdout", "text": ["2\n"]},
            {"output_type": "display_data", "data": {"image/png": base64.b64encode(png).decode(),
                                                     "text/plain": "<Figure>"}},
            {"output_type": "execute_result", "data": {"text/plain": "\x1b[31m42\x1b[0m"}},
        ]},
    ]}
    markdown, pictures = hook.to_markdown(notebook, "01-x")
    assert markdown.startswith("# Title\nSome *text*.\n\n```python")
    assert "```python\nprint(1 + 1)\nimage\n```" in markdown
    assert "```text\n2\n```" in markdown
    assert "![output of cell 1](01-x/out-01-1.png)" in markdown
    assert "```text\n42\n```" in markdown  # terminal colours removed
    assert pictures == {"01-x/out-01-1.png": png}


def test_a_failing_lesson_cell_fails_the_site_build() -> None:
    hook = _load_lessons_hook()
    notebook = {"cells": [{"cell_type": "code", "source": "1/0", "outputs": [
        {"output_type": "error", "ename": "ZeroDivisionError", "evalue": "", "traceback": []}]}]}
    with pytest.raises(RuntimeError, match="cell 0 failed: ZeroDivisionError"):
        hook.to_markdown(notebook, "broken")


def _nav_files(node: object) -> list[str]:
    if isinstance(node, str):
        return [node]
    if isinstance(node, dict):
        return [f for value in node.values() for f in _nav_files(value)]
    if isinstance(node, list):
        return [f for item in node for f in _nav_files(item)]
    return []


def test_every_cli_command_has_a_page_in_the_nav() -> None:
    from bras_kit.cli import COMMANDS

    nav = _nav_files(yaml.safe_load((ROOT / "mkdocs.yml").read_text(encoding="utf-8"))["nav"])
    for name in COMMANDS:
        page = DOCS / "cli" / f"{name}.md"
        assert page.is_file(), f"no page for 'bras-kit {name}'"
        assert f"cli/{name}.md" in nav
        assert page.read_text(encoding="utf-8").startswith(f"# bras-kit {name}\n")
        assert any(isinstance(s, Command) and s.argv[:1] == [name] for s in examples(page)), \
            f"cli/{name}.md has no runnable example of the command"
    assert set(nav) == {_page_id(p) for p in PAGES}, "every page is in the nav, and the nav has no missing page"


def _options(name: str) -> set[str]:
    from bras_kit.cli import build_parser

    parser = build_parser(name)
    sub = next(a for a in parser._actions if a.dest == "command").choices[name]  # type: ignore[union-attr]
    return {opt for action in sub._actions for opt in action.option_strings}


@pytest.mark.parametrize("name", sorted(p.stem for p in (DOCS / "cli").glob("*.md") if p.stem != "index"))
def test_options_documented_for_a_command_exist(name: str) -> None:
    """Every --option in a command page's option table is an option of that command."""
    known = _options(name)
    table = [line for line in (DOCS / "cli" / f"{name}.md").read_text(encoding="utf-8").splitlines()
             if line.startswith("| `")]
    documented = {opt for row in table for opt in re.findall(r"`(-[-\w]+)", row.split("|")[1])}
    assert documented, f"cli/{name}.md has no option table"
    assert documented <= known, f"not options of bras-kit {name}: {sorted(documented - known)}"


def test_example_parser_reads_commands_files_and_expected_codes(tmp_path: Path) -> None:
    page = tmp_path / "page.md"
    page.write_text(
        "<!-- file: a.urdf -->\n```xml\n<robot name='x'/>\n```\n\n"
        "```console\n$ bras-kit validate a.urdf --lang fr   # exit code 1\nline one\n...\n"
        "$ bras-kit tree \"my file.urdf\"\n```\n\n```bash\n$ pip install x\n```\n", encoding="utf-8")
    steps = examples(page)
    assert steps[0] == File(3, "a.urdf", "<robot name='x'/>\n")
    assert steps[1] == Command(7, ["validate", "a.urdf", "--lang", "fr"], 1, ["line one", "..."])
    assert steps[2] == Command(10, ["tree", "my file.urdf"], 0, [])
    assert len(steps) == 3
    assert missing_output(["b", "...", "wrote x..."], "a\nb\nwrote x.png\n", "") is None
    assert missing_output(["wrote x.png", "b"], "b\nwrote x.png\n", "") == "b"
    assert missing_output(["warn", "done"], "done\n", "warn\n") is None


@pytest.mark.slow
@pytest.mark.parametrize("page", RUNNABLE, ids=_page_id)
def test_examples_run(page: Path, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, run_cli) -> None:
    monkeypatch.chdir(tmp_path)
    for variable in ("LC_ALL", "LC_MESSAGES"):
        monkeypatch.delenv(variable, raising=False)
    monkeypatch.setenv("LANG", "C.UTF-8")  # the validator's default language follows the locale
    for step in examples(page):
        if isinstance(step, File):
            (tmp_path / step.name).write_text(step.text, encoding="utf-8")
            continue
        code, out, err = run_cli(*step.argv)
        where = f"{_page_id(page)}:{step.line}: bras-kit {shlex.join(step.argv)}"
        assert code == step.exit_code, f"{where} exited {code}, expected {step.exit_code}\n{out}\n{err}"
        missing = missing_output(step.output, out, err)
        assert missing is None, f"{where} did not print the line shown:\n  {missing}\nit printed:\n{out}\n{err}"


def test_pictures_used_by_the_docs_exist_and_stay_small() -> None:
    sys.path.insert(0, str(DOCS))
    try:
        from make_pictures import PICTURES
    finally:
        sys.path.remove(str(DOCS))
    text = "\n".join(p.read_text(encoding="utf-8") for p in PAGES)
    used = set(re.findall(r"img/([\w.-]+\.(?:png|gif))", text))
    assert used <= set(PICTURES), f"pictures no script makes: {sorted(used - set(PICTURES))}"
    sizes = {name: (DOCS / "img" / name).stat().st_size for name in PICTURES}
    assert max(sizes.values()) < 300_000 and sum(sizes.values()) < 1_000_000, sizes


@pytest.mark.slow
def test_make_pictures_draws_every_picture(tmp_path: Path) -> None:
    result = subprocess.run([sys.executable, str(DOCS / "make_pictures.py"), "--out", str(tmp_path)],
                            capture_output=True, text=True)
    assert result.returncode == 0, result.stderr
    from PIL import Image

    for name, size in {"poses.png": (960, 240), "wrist.png": (320, 320)}.items():
        with Image.open(tmp_path / name) as image:
            assert image.size == size
    with Image.open(tmp_path / "bras.gif") as gif:
        assert gif.size == (320, 240)
        assert gif.n_frames == 91  # 9 s at 10 frames a second, both ends included
    for name in ("frames.png", "angles.png", "reach.png"):
        assert (tmp_path / name).stat().st_size > 5_000
