"""A track keeps the language it was laid out in, and its lesson links open from its own folder
(issue 43: a track made with --lang fr answered in English when started with the command it
printed, and named its lessons from the clone's root)."""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
import time
import uuid

import pytest
from paths import REPO, TESTS

from bras_kit.exercises import init_track, load_track

TRACK = load_track()
FIRST = {"fr": "exercice 1/14 : Décrire le bras : les segments", "en": "exercise 1/14: Describe the arm: the links"}
LESSON = {"fr": "leçon :", "en": "lesson:"}
OTHER = {"fr": "en", "en": "fr"}


@pytest.fixture()
def english_machine(monkeypatch):
    """A machine whose locale is English and says nothing of bras-kit's language."""
    monkeypatch.delenv("BRAS_KIT_LANG", raising=False)
    for name in ("LANGUAGE", "LC_ALL", "LC_MESSAGES"):
        monkeypatch.delenv(name, raising=False)
    monkeypatch.setenv("LANG", "C.UTF-8")


def _lesson_shown(out: str, lang: str) -> str:
    line = next(line for line in out.splitlines() if line.startswith(LESSON[lang]))
    return line[len(LESSON[lang]):].strip()


@pytest.mark.parametrize("lang", ["fr", "en"])
def test_a_track_answers_in_the_language_it_was_made_in(run_cli, tmp_path, monkeypatch, english_machine, lang):
    monkeypatch.chdir(tmp_path)
    code, out, _ = run_cli("exercises", "init", "piste", "--lang", lang)
    assert code == 0
    assert json.loads((tmp_path / "piste" / "progress.json").read_text(encoding="utf-8"))["lang"] == lang
    # the environment now says the other language: the track keeps its own
    monkeypatch.setenv("BRAS_KIT_LANG", OTHER[lang])
    monkeypatch.chdir(tmp_path / "piste")
    code, out, _ = run_cli("exercises", "check")
    assert code == 1 and out.startswith(FIRST[lang])
    code, out, _ = run_cli("exercises", "list", "-C", str(tmp_path / "piste"))
    assert code == 0 and TRACK.title_in(lang) in out


def test_lang_on_the_command_line_still_chooses(run_cli, tmp_path, english_machine):
    init_track(tmp_path / "piste", lang="fr")
    code, out, _ = run_cli("exercises", "check", "-C", str(tmp_path / "piste"), "--lang", "en")
    assert code == 1 and out.startswith(FIRST["en"])


def test_a_track_made_before_the_language_was_kept_follows_the_environment(run_cli, tmp_path, english_machine,
                                                                          monkeypatch):
    init_track(tmp_path / "piste")
    progress = json.loads((tmp_path / "piste" / "progress.json").read_text(encoding="utf-8"))
    assert "lang" not in progress
    monkeypatch.setenv("BRAS_KIT_LANG", "fr")
    code, out, _ = run_cli("exercises", "check", "-C", str(tmp_path / "piste"))
    assert out.startswith(FIRST["fr"])


@pytest.mark.parametrize("lang", ["fr", "en"])
@pytest.mark.parametrize("where", ["inside", "beside"])
def test_lesson_links_open_from_the_tracks_own_folder(run_cli, tmp_path, monkeypatch, lang, where):
    """From the track's folder (where the learner was told to cd), the lesson path shown opens
    the exercise's lesson: the notebook of the source tree, in the track's language."""
    base = tmp_path if where == "beside" else tmp_path / "a" / "b"
    track = base / "piste"
    init_track(track, lang=lang)
    monkeypatch.chdir(track)
    _, out, _ = run_cli("exercises", "check")
    shown = _lesson_shown(out, lang)
    assert (track / shown).resolve() == (REPO / TRACK.exercise(1).lesson_in(lang)).resolve()
    assert (track / shown).is_file()


def test_a_sets_lesson_is_named_from_the_sets_folder(run_cli, tmp_path, monkeypatch):
    """A teacher's set names its lessons from its own folder, wherever the track is laid out."""
    teacher = tmp_path / "teacher" / "set"
    shutil.copytree(TESTS / "data" / "exercises_teacher_set", teacher)
    track = tmp_path / "class" / "piste"
    code, _, _ = run_cli("exercises", "init", str(track), "--track", str(teacher), "--lang", "en")
    assert code == 0
    monkeypatch.chdir(track)
    _, out, _ = run_cli("exercises", "check")
    assert (track / _lesson_shown(out, "en")).resolve() == (teacher / "notes" / "forearm.md").resolve()


def test_the_printed_command_starts_the_track_in_its_language_in_a_terminal(tmp_path):
    """As a learner types it: `bras-kit exercises init piste --lang fr` on an English machine, then
    the line it printed, in a real terminal (tmux)."""
    assert shutil.which("tmux"), "this test needs tmux: apt-get install tmux (system-packages.txt lists it)"
    env = {k: v for k, v in os.environ.items() if k not in ("BRAS_KIT_LANG", "LANGUAGE", "LC_ALL", "LC_MESSAGES",
                                                            "TMUX")}
    env.update(LANG="C.UTF-8", TERM="xterm-256color", PATH=os.path.dirname(sys.executable) + os.pathsep + env["PATH"])
    made = subprocess.run([sys.executable, "-m", "bras_kit", "exercises", "init", "piste", "--lang", "fr"],
                          cwd=tmp_path, env=env, capture_output=True, text=True, check=True)
    printed = made.stdout.splitlines()[-1]
    assert printed == "ensuite : cd piste && bras-kit exercises"
    command = printed.split(" : ", 1)[1]
    socket = f"bras-kit-test-{uuid.uuid4().hex[:8]}"
    subprocess.run(["tmux", "-L", socket, "-f", os.devnull, "new-session", "-d", "-s", "piste", "-x", "90", "-y", "50",
                    "-c", str(tmp_path), f"{command}; echo EXITED $?; sleep 120"], check=True, env=env)
    try:
        screen = ""
        deadline = time.monotonic() + 30
        while time.monotonic() < deadline:
            screen = subprocess.run(["tmux", "-L", socket, "capture-pane", "-p", "-J", "-t", "piste"],
                                    capture_output=True, text=True, check=True).stdout
            if "pas encore" in screen:
                break
            time.sleep(0.1)
        assert FIRST["fr"] in screen and "pas encore" in screen, screen
        shown = _lesson_shown("\n".join(line.strip() for line in screen.splitlines()), "fr")
        assert (tmp_path / "piste" / shown).is_file()
        subprocess.run(["tmux", "-L", socket, "send-keys", "-t", "piste", "q"], check=True)
    finally:
        subprocess.run(["tmux", "-L", socket, "kill-server"], capture_output=True)
