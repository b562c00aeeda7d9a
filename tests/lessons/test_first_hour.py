"""The first hour of a learner: the getting-started pages (English and French) and the first screen.

The pages walk the French tutorial's steps 1 to 7 and its FAQ; every ``bras-kit`` command they
show, in a console block or a bash block, runs here in order in one temporary folder, and must
exit as the page says (0 unless ``# exit code N``). ``bras-kit view`` without ``--export``
serves until Ctrl-C: it is started as a learner would start it, its page is fetched, then it is
interrupted, and it must stop cleanly.
"""

from __future__ import annotations
from paths import REPO

import os
import re
import shlex
import signal
import subprocess
import sys
import time
import urllib.request
from dataclasses import dataclass
from pathlib import Path

import pytest
from pages import free_port as _free_port

ROOT = REPO
PAGES = {"en": ROOT / "docs" / "getting-started.md", "fr": ROOT / "docs" / "getting-started.fr.md"}
_FENCE = re.compile(r"^```(\S*)\s*$")
_FILE = re.compile(r"^<!--\s*file:\s*(\S+)\s*-->\s*$")
_EXIT = re.compile(r"#\s*exit code (\d+)\s*$")


@dataclass
class Step:
    line: int
    argv: list[str] | None  # a command, or None for a file to write
    exit_code: int = 0
    name: str = ""
    text: str = ""


def steps(page: Path) -> list[Step]:
    """The files and ``bras-kit`` commands of a page's fenced blocks, in order."""
    lines = page.read_text(encoding="utf-8").splitlines()
    out: list[Step] = []
    pending = None
    i = 0
    while i < len(lines):
        if marker := _FILE.match(lines[i]):
            pending = marker.group(1)
        elif fence := _FENCE.match(lines[i]):
            end = next(k for k in range(i + 1, len(lines)) if lines[k].strip() == "```")
            body = lines[i + 1:end]
            if pending is not None:
                out.append(Step(i + 2, None, name=pending, text="\n".join(body) + "\n"))
                pending = None
            elif fence.group(1) in ("console", "bash"):
                for k, text in enumerate(body):
                    # a console block shows commands after "$ " (the other lines are their output)
                    command = text[2:] if text.startswith("$ ") else text if fence.group(1) == "bash" else ""
                    if command.startswith("bras-kit "):
                        code = _EXIT.search(command)
                        argv = shlex.split(command, comments=True)[1:]
                        out.append(Step(i + 2 + k, argv, int(code.group(1)) if code else 0))
            i = end
        i += 1
    return out


def _commands(lang: str) -> list[list[str]]:
    found = [s.argv for s in steps(PAGES[lang]) if s.argv is not None]
    if lang == "fr":  # the French page asks for French answers
        assert all(a[:2] == ["--lang", "fr"] or a[-2:] == ["--lang", "fr"] for a in found), found
        found = [[w for k, w in enumerate(a) if w != "--lang" and (k == 0 or a[k - 1] != "--lang")] for a in found]
    return found


def test_both_pages_walk_the_same_commands() -> None:
    english = _commands("en")
    assert english == _commands("fr")
    names = {argv[0] for argv in english}
    # the tutorial's ROS 2 steps each have their bras-kit counterpart on the page
    assert {"doctor", "new", "urdf", "validate", "tree", "explain", "view", "render", "run", "fk", "frames",
            "motion", "xacro", "simulate", "reach", "demo"} <= names


@pytest.mark.parametrize(("lang", "step_word", "faq"), [("en", "Step", "FAQ"), ("fr", "Étape", "FAQ")])
def test_each_step_of_the_tutorial_has_its_section(lang: str, step_word: str, faq: str) -> None:
    headings = [line for line in PAGES[lang].read_text(encoding="utf-8").splitlines() if line.startswith("#")]
    for number in range(1, 8):
        assert any(h.startswith(f"### {step_word} {number} ") for h in headings), (lang, number)
    assert f"## {faq}" in headings


def test_the_readme_opens_on_the_getting_started_in_both_languages() -> None:
    first_lines = "\n".join((ROOT / "README.md").read_text(encoding="utf-8").splitlines()[:12])
    assert "docs/getting-started.md" in first_lines and "docs/getting-started.fr.md" in first_lines


def test_the_getting_started_says_jupyterlab_comes_with_dev() -> None:
    text = PAGES["en"].read_text(encoding="utf-8")
    assert "not part of `[dev]`" not in text
    assert "JupyterLab comes with `[dev]`" in text


def _serve_then_interrupt(argv: list[str], folder: Path, where: str) -> None:
    """Start a serving ``bras-kit view`` or ``launch``, fetch its page, press Ctrl-C: it must exit 0."""
    env = dict(os.environ, BRAS_KIT_LANG="", LANG="C.UTF-8")
    process = subprocess.Popen([sys.executable, "-m", "bras_kit", *argv, "--port", str(_free_port())], cwd=folder,
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, env=env)
    try:
        assert process.stdout is not None
        deadline = time.monotonic() + 120
        url = None
        while url is None and time.monotonic() < deadline:
            line = process.stdout.readline()
            if not line:
                break
            found = re.search(r"http://\S+", line)
            url = found.group() if found else None
        assert url, f"{where}: no address printed\n{process.stderr.read() if process.poll() is not None else ''}"
        with urllib.request.urlopen(url, timeout=30) as page:
            assert page.status == 200
    finally:
        process.send_signal(signal.SIGINT)
        try:
            _, err = process.communicate(timeout=60)
        except subprocess.TimeoutExpired:
            process.kill()
            raise
    assert process.returncode == 0, f"{where}: Ctrl-C ended it with {process.returncode}\n{err}"
    assert "Traceback" not in err and "Warning" not in err, err


@pytest.mark.slow
@pytest.mark.parametrize("lang", sorted(PAGES))
def test_every_command_of_the_page_runs(lang: str, tmp_path: Path, monkeypatch: pytest.MonkeyPatch, run_cli) -> None:
    monkeypatch.chdir(tmp_path)
    for variable in ("LC_ALL", "LC_MESSAGES", "BRAS_KIT_LANG"):
        monkeypatch.delenv(variable, raising=False)
    monkeypatch.setenv("LANG", "C.UTF-8")
    page = PAGES[lang]
    for step in steps(page):
        where = f"{page.name}:{step.line}"
        if step.argv is None:
            (tmp_path / step.name).write_text(step.text, encoding="utf-8")
            continue
        serving = step.argv[0] == "view" and "--export" not in step.argv
        if serving or (step.argv[0] == "launch" and "--duration" not in step.argv):  # until Ctrl-C, as typed
            _serve_then_interrupt(step.argv, tmp_path, where)
            continue
        code, out, err = run_cli(*step.argv)
        assert code == step.exit_code, f"{where}: bras-kit {shlex.join(step.argv)} exited {code}\n{out}\n{err}"


def test_help_groups_commands_in_the_order_a_learner_meets_them(run_cli) -> None:
    code, out, _ = run_cli("--help")
    assert code == 0
    titles = ["start here:", "describe the arm:", "check it:", "see it:", "package, build and launch it:",
              "move it and run your node:", "physics and reach:", "teach and grade:"]
    places = [out.index(f"\n{title}\n") for title in titles]
    assert places == sorted(places)
    for first, then in [("urdf", "validate"), ("validate", "view"), ("view", "new"), ("new", "run"),
                        ("run", "simulate"), ("simulate", "grade")]:
        assert out.index(f"\n  {first} ") < out.index(f"\n  {then} ")
    assert "--set" not in out  # deprecated for urdf: --param is the spelling to learn


def test_help_in_french_has_french_titles_and_spaced_colons(run_cli) -> None:
    code, out, _ = run_cli("--lang", "fr", "--help")
    assert code == 0
    assert "\ndécrire le bras :\n" in out and "\noptions :\n" in out and "utilisation : bras-kit" in out
    assert "describe the arm" not in out


def test_a_command_in_no_group_is_listed_last_under_other_commands(run_cli, monkeypatch) -> None:
    from bras_kit import cli

    monkeypatch.setitem(cli.COMMANDS, "fly", "fly the arm around")
    monkeypatch.setattr(cli, "_command_module", lambda name: pytest.fail("no module is imported for --help"))
    code, out, _ = run_cli("--help")
    assert code == 0
    assert out.index("\nother commands:\n  fly ") > out.index("\nteach and grade:\n")


def test_the_demo_ends_on_three_things_to_try(run_cli, tmp_path: Path) -> None:
    code, out, _ = run_cli("demo", str(tmp_path / "demo"), "--duration", "0.5", "--lang", "fr")
    assert code == 0
    tail = out.splitlines()[-4:]
    assert tail[0] == "à essayer ensuite :"
    assert [line.split()[:2] for line in tail[1:]] == [["bras-kit", "view"], ["jupyter", "lab"], ["bras-kit", "exercises"]]
    assert tail[2].split()[2] == "lessons/fr"
