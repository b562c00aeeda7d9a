"""bras-kit exercises: the track walked from init to the end with its reference solutions,
alternative correct solutions passing and plausible wrong ones failing with the hint that fits
(tests/data/exercises/<exercise>/<case>/: ``ok-*`` must pass, ``wrong-hN-*`` must fail with hint
N), half-written files as states, progress, reset, and the manifests' targets against the
closed-form forward kinematics of the two-link arm (computed here by hand, not by bras-kit)."""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from paths import REPO, TESTS

from bras_kit.core.errors import BrasKitError
from bras_kit.exercises import (
    BROKEN,
    FAILED,
    PASSED,
    check_exercise,
    copy_files,
    init_track,
    load_track,
    open_track,
    reveal_hint,
)
from bras_kit.exercises.checks import run_checks
from bras_kit.exercises.screen import exercise_lines

CASES = TESTS / "data" / "exercises"
TRACK = load_track()


def _overlay(case: Path, target: Path) -> None:
    for path in case.rglob("*"):
        if path.is_file():
            destination = target / path.relative_to(case)
            destination.parent.mkdir(parents=True, exist_ok=True)
            shutil.copyfile(path, destination)


def _screen(track, progress, exercise, outcome, lang="en") -> str:
    return "\n".join(exercise_lines(track, progress, exercise, outcome, lang, 200))


def _flat(text: str) -> str:
    return " ".join(text.split())


def test_track_follows_the_tutorial():
    titles = [e.title_in("en") for e in TRACK.exercises]
    assert len(titles) == 14
    assert titles[0] == "Describe the arm: the links" and titles[-1] == "Reach a point (FAQ)"
    for exercise in TRACK.exercises:
        for lang in ("en", "fr"):
            assert exercise.statement_in(lang) and exercise.title_in(lang)
            assert len(exercise.hints[lang]) == 3
            lesson = REPO / exercise.lesson_in(lang)
            assert lesson.is_file(), lesson


def test_reference_solutions_walk_the_track_from_init(tmp_path):
    """Each exercise fails from its starting files with its first hint on screen; its reference
    solution passes and moves the track on; at the end every exercise has passed."""
    init_track(tmp_path)
    track, progress = open_track(tmp_path)
    assert progress.current == "01-links"
    for exercise in track.exercises:
        assert progress.current == exercise.id
        outcome = check_exercise(track, progress, exercise, "en")
        assert outcome.state == FAILED and outcome.hint == 1, (exercise.id, outcome)
        assert _flat(exercise.hint_in("en", 1)) in _flat(_screen(track, progress, exercise, outcome))
        assert progress.current == exercise.id
        copy_files(exercise, tmp_path / exercise.id, "solution")
        outcome = check_exercise(track, progress, exercise, "en")
        assert outcome.state == PASSED, (exercise.id, outcome)
    assert progress.current == ""
    saved = json.loads((tmp_path / "progress.json").read_text())
    assert all(saved["exercises"][e.id]["passed"] for e in track.exercises)
    assert saved["exercises"]["01-links"]["checks"] == 2


def _cases():
    return sorted((exercise, case) for exercise in os.listdir(CASES) for case in os.listdir(CASES / exercise))


@pytest.mark.parametrize(("exercise_id", "case"), _cases())
def test_alternative_and_wrong_solutions(exercise_id, case, tmp_path):
    exercise = TRACK.exercise(exercise_id)
    copy_files(exercise, tmp_path)
    _overlay(CASES / exercise_id / case, tmp_path)
    outcome = run_checks(tmp_path, exercise.checks, "en")
    wrong = re.match(r"wrong-h(\d)-", case)
    if wrong is None:
        assert case.startswith("ok-")
        assert outcome.state == PASSED, outcome
        return
    assert outcome.state == FAILED, outcome
    assert outcome.hint == int(wrong.group(1)), outcome


def test_every_exercise_set_has_cases_of_both_kinds():
    for exercise in TRACK.exercises:
        names = os.listdir(CASES / exercise.id)
        assert any(n.startswith("ok-") for n in names) and any(n.startswith("wrong-") for n in names), exercise.id


def test_wrong_solution_shows_the_fitting_hint_in_french(tmp_path):
    init_track(tmp_path)
    track, progress = open_track(tmp_path)
    exercise = track.exercise(2)
    _overlay(CASES / "02-joints" / "wrong-h3-axis-x", tmp_path / exercise.id)
    outcome = check_exercise(track, progress, exercise, "fr")
    screen = _flat(_screen(track, progress, exercise, outcome, "fr"))
    assert _flat(exercise.hint_in("fr", 3)) in screen
    assert _flat(exercise.hint_in("fr", 1)) not in screen
    assert "avec epaule=0.5, coude=0.3, le point (0.000, 0.000, 0.500) de 'avant_bras' est en (0.517, -0.148, 0.996)" \
        in screen


# the closed form of the tutorial arm (shoulder 0.05 m above the floor, arm 0.6 m, forearm 0.5 m,
# both axes along y): a point z=d up the forearm at x = 0.6 sin a + d sin(a+b), z = 0.05 + 0.6 cos a + d cos(a+b)
def _closed_form(epaule: float, coude: float, d: float, arm: float = 0.6) -> tuple[float, float, float]:
    return (arm * math.sin(epaule) + d * math.sin(epaule + coude), 0.0,
            0.05 + arm * math.cos(epaule) + d * math.cos(epaule + coude))


@pytest.mark.parametrize("exercise", TRACK.exercises, ids=lambda e: e.id)
def test_manifest_targets_match_the_closed_form(exercise):
    lengths = {"avant_bras": 0.0, "poignet": 0.5}
    checked = 0
    for check in exercise.checks:
        if check["kind"] not in ("frame", "tip", "node_tip") or check.get("link", "avant_bras") not in lengths:
            continue
        pose = check.get("pose", {})
        if check["kind"] == "node_tip" and check.get("when") != "first":
            pose = {"10-fixed-pose": {"epaule": 0.6, "coude": 0.9},
                    "14-reach": {"epaule": 0.7, "coude": 1.2}}[exercise.id]
        arm = float(check.get("args", {}).get("longueur_bras", 0.6))
        d = lengths[check.get("link", "avant_bras")] + (0.5 if check["kind"] == "tip" else check.get("point", [0, 0, 0])[2])
        expected = _closed_form(pose.get("epaule", 0.0), pose.get("coude", 0.0), d, arm)
        assert math.dist(expected, check["at"]) <= min(float(check.get("tol", 0.002)), 0.002) / 2, (check, expected)
        checked += 1
    assert checked or exercise.id in {"04-limits", "06-data-files", "07-launch", "08-node-topic-names",
                                      "09-node-stamp-rate", "12-inertials"}


@pytest.mark.parametrize(("name", "text"), [
    ("half-written", '<?xml version="1.0"?>\n<robot name="bras">\n  <link name="base">\n    <visual>\n      <geom'),
    ("empty", ""),
    ("not-utf8", "\udcff"),
])
def test_half_written_urdf_is_a_state(tmp_path, name, text):
    exercise = TRACK.exercise(1)
    copy_files(exercise, tmp_path)
    (tmp_path / "bras.urdf").write_bytes(text.encode("utf-8", errors="surrogateescape"))
    outcome = run_checks(tmp_path, exercise.checks, "fr")
    assert outcome.state == BROKEN
    assert outcome.file == "bras.urdf" and outcome.reason


def test_half_written_node_is_a_state_with_its_line(tmp_path):
    exercise = TRACK.exercise(8)
    copy_files(exercise, tmp_path)
    text = (tmp_path / "animation.py").read_text()
    (tmp_path / "animation.py").write_text(text[: text.index("msg.position") + 20])
    outcome = run_checks(tmp_path, exercise.checks, "en")
    assert outcome.state == BROKEN
    assert outcome.file == "animation.py" and outcome.line == text[: text.index("msg.position")].count("\n") + 1


def test_deleted_file_is_a_state(tmp_path):
    exercise = TRACK.exercise(3)
    outcome = run_checks(tmp_path, exercise.checks, "en")
    assert outcome.state == BROKEN and "reset" in str(outcome.reason)


def test_no_hint_advises_force():
    for exercise in TRACK.exercises:
        for hints in exercise.hints.values():
            assert not any("--force" in hint for hint in hints)


def test_hints_come_one_at_a_time(tmp_path):
    init_track(tmp_path)
    track, progress = open_track(tmp_path)
    exercise = track.exercise(1)
    assert [reveal_hint(progress, exercise) for _ in range(4)] == [1, 2, 3, 3]
    assert json.loads((tmp_path / "progress.json").read_text())["exercises"]["01-links"]["hints"] == 3


def test_init_refuses_a_folder_with_a_track(tmp_path):
    init_track(tmp_path)
    with pytest.raises(BrasKitError, match="already holds an exercise track"):
        init_track(tmp_path)


def test_manifest_error_names_the_file(tmp_path):
    (tmp_path / "track.yaml").write_text("name: mine\nexercises: [one]\n")
    (tmp_path / "one").mkdir()
    (tmp_path / "one" / "exercise.yaml").write_text(
        "files: [a.urdf]\ntitle: {en: A}\nstatement: {en: S}\nhints: {en: [a, b, c]}\n"
        "checks:\n  - {kind: grep, file: a.urdf}\n")
    with pytest.raises(BrasKitError) as raised:
        load_track(tmp_path)
    assert raised.value.path == str(tmp_path / "one" / "exercise.yaml")
    assert "unknown check kind 'grep'" in str(raised.value)


def test_a_teachers_own_set(tmp_path, run_cli):
    """A set of one exercise in the same format, laid out with --set, checked like the built-in one."""
    source = tmp_path / "set"
    (source / "longer-arm" / "start").mkdir(parents=True)
    shutil.copyfile(TRACK.exercise(3).folder / "solution" / "bras.urdf", source / "longer-arm" / "start" / "bras.urdf")
    (source / "track.yaml").write_text("name: cours\nexercises: [longer-arm]\ntitle: {en: My class}\n")
    (source / "longer-arm" / "exercise.yaml").write_text(
        "files: [bras.urdf]\ntitle: {en: A longer forearm}\nstatement: {en: Make the forearm 0.7 m long.}\n"
        "hints: {en: [the box, its origin, size 0.7 and origin 0.35]}\n"
        "checks:\n  - {kind: tip, file: bras.urdf, at: [0, 0, 1.35], hint: 1}\n  - {kind: findings, file: bras.urdf}\n")
    learner = tmp_path / "learner"
    assert run_cli("exercises", "init", str(learner), "--track", str(source))[0] == 0
    code, out, _ = run_cli("exercises", "check", "-C", str(learner))
    assert code == 1 and "it must be at (0.000, 0.000, 1.350)" in _flat(out) and "hint 1/3: the box" in out
    urdf = learner / "longer-arm" / "bras.urdf"
    urdf.write_text(urdf.read_text().replace('<origin xyz="0 0 0.25"/>\n      <geometry><box size="0.06 0.06 0.5"/>',
                                             '<origin xyz="0 0 0.35"/>\n      <geometry><box size="0.06 0.06 0.7"/>'))
    code, out, _ = run_cli("exercises", "check", "-C", str(learner))
    assert code == 0, out


def test_cli_check_list_hint_in_french(tmp_path, run_cli):
    assert run_cli("exercises", "init", str(tmp_path / "exos"), "--lang", "fr")[0] == 0
    folder = str(tmp_path / "exos")
    code, out, _ = run_cli("exercises", "check", "-C", folder, "--lang", "fr")
    assert code == 1
    assert "exercice 1/14 : Décrire le bras : les segments" in out
    assert "indice 1/3 :" in out and "\x1b[" not in out
    code, out, _ = run_cli("exercises", "hint", "-C", folder, "--lang", "fr")
    assert code == 0 and "indice 1/3 :" in out and "indice 2/3 :" not in out
    code, out, _ = run_cli("exercises", "list", "-C", folder, "--lang", "fr")
    assert code == 0 and " 1. Décrire le bras : les segments" in out and "en cours" in out and "1/3 indice" in out
    shutil.copyfile(TRACK.exercise(1).folder / "solution" / "bras.urdf", tmp_path / "exos" / "01-links" / "bras.urdf")
    code, out, _ = run_cli("exercises", "check", "-C", folder, "--lang", "fr")
    assert code == 0 and "réussi" in out and "suite : exercice 2, Décrire le bras : les articulations" in out


def test_reset_asks_first_and_never_without_a_terminal(tmp_path, run_cli, monkeypatch):
    init_track(tmp_path)
    urdf = tmp_path / "01-links" / "bras.urdf"
    urdf.write_text("mine")
    monkeypatch.setattr(sys, "stdin", open(os.devnull))  # no terminal to ask in
    code, _, err = run_cli("exercises", "reset", "1", "-C", str(tmp_path))
    assert code == 2 and "asks first" in err and "--force" not in err
    assert urdf.read_text() == "mine"
    code, out, _ = run_cli("exercises", "reset", "1", "-C", str(tmp_path), "--force")
    assert code == 0 and urdf.read_text() == (TRACK.exercise(1).folder / "start" / "bras.urdf").read_text()


def test_watch_piped_prints_plain_screens_and_stops_on_interrupt(tmp_path):
    """Piped, watch mode prints each new state once, without escape codes, and Ctrl-C saves."""
    import signal
    import time

    init_track(tmp_path)
    process = subprocess.Popen([sys.executable, "-m", "bras_kit", "exercises", "--lang", "fr"], cwd=tmp_path,
                               stdin=subprocess.DEVNULL, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                               env={**os.environ, "COLUMNS": "60"})
    try:
        deadline = time.monotonic() + 60
        while time.monotonic() < deadline and "pas encore" not in (tmp_path / "progress.json").read_text() \
                and json.loads((tmp_path / "progress.json").read_text())["exercises"].get("01-links") is None:
            time.sleep(0.1)
        shutil.copyfile(TRACK.exercise(1).folder / "solution" / "bras.urdf", tmp_path / "01-links" / "bras.urdf")
        while time.monotonic() < deadline and json.loads((tmp_path / "progress.json").read_text())["current"] != \
                "02-joints":
            time.sleep(0.1)
        time.sleep(0.5)
    finally:
        process.send_signal(signal.SIGINT)
        out, err = process.communicate(timeout=30)
    assert process.returncode == 0, err
    assert "\x1b" not in out
    assert out.count("exercice 1/14 : Décrire le bras : les segments") == 1
    assert "exercice 1 réussi : Décrire le bras : les segments" in out
    assert "exercice 2/14 : Décrire le bras : les articulations" in out
    assert "progression est enregistrée" in out
