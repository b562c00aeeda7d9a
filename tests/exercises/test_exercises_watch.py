"""Watch mode in a real terminal (tmux, driven with send-keys and read with capture-pane), in
French and in English: the first exercise on screen with its first hint, a half-written file
shown as a state (the watcher goes on), the save that completes it passing and moving on, the
next hint on a key, the list, and q to quit. The latency from a save to the new screen is
printed (speed is measured, not asserted; the watcher polls every 0.2 s)."""

from __future__ import annotations

import os
import subprocess
import sys
import time
import uuid
from pathlib import Path

import pytest
import system

from bras_kit.exercises import init_track, load_track

pytestmark = pytest.mark.slow


@pytest.fixture(autouse=True)
def tmux_is_installed() -> None:
    # the watch mode is judged in a real terminal: without tmux it skips, naming the package (fails in CI)
    system.program("tmux", "tmux")

TRACK = load_track()
WIDTH = 72
WORDS = {
    "fr": {"first": "exercice 1/14 : Décrire le bras : les segments", "not_yet": "pas encore", "hint1": "indice 1/3 :",
           "hint2": "indice 2/3 :", "broken": "illisible", "passed": "exercice 1 réussi : Décrire le bras : les segments",
           "second": "exercice 2/14 : Décrire le bras : les articulations", "list": "à faire", "back": "appuyez sur une touche"},
    "en": {"first": "exercise 1/14: Describe the arm: the links", "not_yet": "not yet", "hint1": "hint 1/3:",
           "hint2": "hint 2/3:", "broken": "cannot be read", "passed": "exercise 1 passed: Describe the arm: the links",
           "second": "exercise 2/14: Describe the arm: the joints", "list": "to do", "back": "press any key"},
}


class Terminal:
    def __init__(self, folder: Path, lang: str) -> None:
        self.socket = f"bras-kit-test-{uuid.uuid4().hex[:8]}"
        command = f"{sys.executable} -m bras_kit exercises --lang {lang}; echo EXITED $?; sleep 120"
        env = {**os.environ, "TERM": "xterm-256color"}
        env.pop("TMUX", None)
        subprocess.run(["tmux", "-L", self.socket, "-f", os.devnull, "new-session", "-d", "-s", "exos",
                        "-x", str(WIDTH), "-y", "60", "-c", str(folder), command], check=True, env=env)

    def screen(self, joined: bool = True) -> str:
        args = ["tmux", "-L", self.socket, "capture-pane", "-p", "-t", "exos"] + (["-J"] if joined else [])
        return subprocess.run(args, capture_output=True, text=True, check=True).stdout

    def wait_for(self, text: str, timeout: float = 30.0) -> float:
        start = time.monotonic()
        while time.monotonic() - start < timeout:
            if text in " ".join(self.screen().split()):
                return time.monotonic() - start
            time.sleep(0.05)
        raise AssertionError(f"{text!r} never shown; the screen:\n{self.screen()}")

    def keys(self, *keys: str) -> None:
        subprocess.run(["tmux", "-L", self.socket, "send-keys", "-t", "exos", *keys], check=True)

    def close(self) -> None:
        subprocess.run(["tmux", "-L", self.socket, "kill-server"], capture_output=True)


@pytest.mark.parametrize("lang", ["fr", "en"])
def test_watch_mode_in_a_terminal(tmp_path, lang):
    words = WORDS[lang]
    init_track(tmp_path)
    exercise = TRACK.exercise(1)
    solution = (exercise.folder / "solution" / "bras.urdf").read_text()
    urdf = tmp_path / "01-links" / "bras.urdf"
    terminal = Terminal(tmp_path, lang)
    try:
        terminal.wait_for(words["first"])
        terminal.wait_for(words["not_yet"])
        terminal.wait_for(" ".join(exercise.hint_in(lang, 1).split()[:6]))
        assert words["hint1"] in terminal.screen()
        # the screen fits the terminal: no line is longer than it (tmux would have wrapped it)
        assert terminal.screen(joined=False) == terminal.screen(joined=True)
        assert all(len(line) <= WIDTH for line in terminal.screen().splitlines())

        urdf.write_text(solution[: len(solution) // 2])  # an editor caught mid-save
        broken = terminal.wait_for(words["broken"])
        assert "Traceback" not in terminal.screen()

        urdf.write_text(solution)
        passed = terminal.wait_for(words["second"])
        terminal.wait_for(words["passed"])
        print(f"\n{lang}: half-written file shown {broken:.2f} s after the write, pass {passed:.2f} s after the save")

        terminal.keys("h")
        terminal.wait_for(words["hint2"])
        terminal.keys("l")
        terminal.wait_for(words["back"])
        terminal.wait_for(words["list"])
        terminal.keys("x")
        terminal.wait_for(words["second"])
        terminal.keys("q")
        terminal.wait_for("EXITED 0")
        assert "Traceback" not in terminal.screen()
    finally:
        terminal.close()
    progress = (tmp_path / "progress.json").read_text()
    assert '"current": "02-joints"' in progress and '"hints": 2' in progress
