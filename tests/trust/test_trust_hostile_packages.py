"""The hostile packages (tests/data/hostile_packages/): what a learner's setup.py and launch file
hand back to bras-kit's own process is checked before it acts, through every entry point.

Each case is laid over a copy of the tutorial's package in a fake workspace, beside a fake home
folder holding a private key, and run through ``build``, ``run``, ``launch``, ``validate --run``,
exercise 6 and ``grade --run-nodes``. Oracles: the files of the whole test folder (home, working
folder, workspace) compared kind by kind and byte for byte before and after, the install folder
aside (the command's own output; it must hold nothing of the secret), the line of each trick in the
corpus read by hand (tests/data/hostile_packages/README.md), and the finding worded in English and
in French without a byte of the secret.
"""

from __future__ import annotations

import json
import os
import re
import select
import shutil
import signal
import subprocess
import sys
import time
from pathlib import Path

import pytest
from paths import TESTS
from snapshots import snapshot

from bras_kit.cli import main
from bras_kit.trust.contain import available
from bras_kit.validate.package import validate_package

DATA = TESTS / "data"
CASES = DATA / "hostile_packages"
TUTORIAL = DATA / "launch" / "tutorial" / "bras_description"
SECRET = "-----BEGIN OPENSSH PRIVATE KEY----- bras-kit-trust-secret"

# case -> the findings it must give: (code, the learner's file, line), lines read by hand
EXPECTED: dict[str, set[tuple[str, str, int]]] = {
    "name_home": {("BK630", "setup.py", 8)},
    "name_dotdot": {("BK630", "setup.py", 8)},
    "name_slash": {("BK630", "setup.py", 8)},
    "source_absolute": {("BK630", "setup.py", 14)},
    "source_dotdot": {("BK630", "setup.py", 14)},
    "source_symlink_out": {("BK630", "setup.py", 14)},
    "source_symlink_loop": {("BK630", "setup.py", 14)},
    "source_fifo": {("BK630", "setup.py", 14)},
    "source_device": {("BK630", "setup.py", 14)},
    "target_absolute": {("BK630", "setup.py", 14)},
    "target_dotdot": {("BK630", "setup.py", 14)},
    "entry_point_code": {("BK630", "setup.py", 17)},
    "entry_point_name": {("BK630", "setup.py", 17)},
    "module_symlink_out": {("BK630", "setup.py", 10)},
    "setup_reaches": {("BK639", "setup.py", 8), ("BK639", "setup.py", 12)},
    "launch_reaches": {("BK639", "launch/affichage.launch.py", 9), ("BK639", "launch/affichage.launch.py", 13)},
    "rsp_dev_zero": {("BK632", "launch/affichage.launch.py", 8)},
    "rsp_secret": {("BK632", "launch/affichage.launch.py", 9)},
}
SETUP_CASES = [c for c in EXPECTED if c not in ("launch_reaches", "rsp_dev_zero", "rsp_secret")]
TMP_TARGETS = ("/tmp/x", "/tmp/pwned", "/pwned")


class World:
    """The test folder: home/ (with ~/.ssh/id_rsa), cwd/ (where bras-kit runs), ws/ (the workspace)."""

    def __init__(self, root: Path) -> None:
        self.root, self.home, self.cwd, self.ws = root, root / "home", root / "cwd", root / "ws"
        self.before: dict[str, tuple[str, int, str]] = {}

    def package(self, case: str) -> Path:
        """The tutorial's package with the case laid over it, and what git cannot hold."""
        folder = self.ws / "src" / "bras_description"
        shutil.copytree(TUTORIAL, folder)
        shutil.copytree(CASES / case, folder, dirs_exist_ok=True)
        secret = self.home / ".ssh" / "id_rsa"
        if case == "source_symlink_out":
            (folder / "urdf" / "lien.urdf").symlink_to(secret)
        elif case == "source_symlink_loop":
            (folder / "urdf" / "boucle.urdf").symlink_to("boucle.urdf")
        elif case == "source_fifo":
            os.mkfifo(folder / "urdf" / "tube.urdf")
        elif case == "module_symlink_out":
            (folder / "bras_description" / "vol.py").symlink_to(secret)
        self.before = self.snapshot()
        return folder

    def snapshot(self) -> dict[str, tuple[str, int, str]]:
        """Everything but what the commands write by design (install/, the grade report)."""
        kept = (str(self.ws / "install"), str(self.root / "report"), str(self.cwd / "install"))
        return {path: facts for path, facts in snapshot(self.root).items() if not path.startswith(kept)}

    def unchanged(self) -> None:
        after = self.snapshot()
        assert after == self.before, {k: after.get(k) for k in set(after) ^ set(self.before)}
        for path in TMP_TARGETS:
            assert not os.path.lexists(path), path
        for folder in (self.ws / "install", self.cwd / "install"):
            for path, facts in snapshot(folder).items() if folder.exists() else []:
                assert facts[0] != "link", path
                if facts[0] == "file":
                    assert SECRET.encode() not in Path(path).read_bytes(), path


@pytest.fixture
def world(tmp_path, monkeypatch) -> World:
    assert available().ok, available()
    w = World(tmp_path)
    (w.home / ".ssh").mkdir(parents=True)
    (w.home / ".ssh" / "id_rsa").write_text(SECRET)
    (w.home / "notes.txt").write_text("the learner's notes\n")
    w.cwd.mkdir()
    (w.cwd / "copies.txt").write_text("the teacher's folder\n")
    (w.ws / "src").mkdir(parents=True)
    (w.ws / "secret.txt").write_text(SECRET)  # what ../../secret.txt names from the package
    monkeypatch.setenv("HOME", str(w.home))
    monkeypatch.chdir(w.cwd)
    for path in TMP_TARGETS:
        assert not os.path.lexists(path), f"{path} is left from an earlier run: remove it"
    return w


def found(results) -> set[tuple[str, str, int]]:
    return {(f.code, str(f.params["file"]), f.line) for r in results for f in r.findings}


# ------------------------------------------------------------------ the library: validate PKG --run's reading


@pytest.mark.parametrize("case", sorted(EXPECTED))
def test_each_hostile_package_is_refused_at_its_line_and_changes_nothing(world, case):
    package = world.package(case)
    results = validate_package(str(package), launch=True)
    assert EXPECTED[case] <= found(results)
    for result in results:
        for finding in result.findings:
            english, french = finding.text("en"), finding.text("fr")
            assert SECRET not in english and SECRET not in french
            if (finding.code, str(finding.params["file"]), finding.line) in EXPECTED[case]:
                assert english != french, english  # worded in both languages
                assert "{" not in english and "{" not in french
    world.unchanged()


def test_the_name_refusal_says_catkins_words(world):
    results = validate_package(str(world.package("name_home")), launch=True)
    (finding,) = [f for r in results for f in r.findings if f.code == "BK630"]
    assert f'Package name "{world.home}/x" does not follow naming conventions' in finding.text("en")
    assert "n'est pas un nom que colcon accepte" in finding.text("fr")


def test_robot_state_publishers_file_argument_is_never_quoted(world):
    results = validate_package(str(world.package("rsp_secret")), launch=True)
    texts = [f.text(lang) for r in results for f in r.findings for lang in ("en", "fr")]
    assert any(str(world.home / ".ssh" / "id_rsa") in text for text in texts)  # the path, named
    assert not any("OPENSSH" in text for text in texts)  # never what it holds


# ------------------------------------------------------------------ the commands


@pytest.mark.parametrize("case", SETUP_CASES)
def test_bras_kit_build_refuses_each_hostile_setup_at_its_line(world, case, capsys):
    package = world.package(case)
    code = main(["build", str(package), "--lang", "en"])
    out = capsys.readouterr().out
    for rule, file, line in EXPECTED[case]:
        assert f"{file}:{line}:" in out and rule in out, out
    assert code == (0 if case == "setup_reaches" else 1)  # setup() itself was fine there
    assert SECRET not in out
    world.unchanged()


def test_bras_kit_build_in_french_names_the_line_too(world, capsys):
    package = world.package("name_dotdot")
    assert main(["build", str(package), "--lang", "fr"]) == 1
    out = capsys.readouterr().out
    assert "setup.py:8:" in out and "n'est pas un nom que colcon accepte" in out


def test_bras_kit_run_refuses_a_package_whose_name_is_a_path(world, capsys):
    package = world.package("name_home")
    assert main(["run", str(package), "animation", "--duration", "1", "--lang", "en"]) == 2
    err = capsys.readouterr().err
    assert "setup.py" in err and ":8" in err and "naming conventions" in err and "Traceback" not in err
    world.unchanged()


def test_bras_kit_run_refuses_a_data_file_linked_out(world, capsys):
    package = world.package("source_symlink_out")
    assert main(["run", str(package), "animation", "--duration", "1", "--lang", "en"]) == 2
    err = capsys.readouterr().err
    assert "urdf/lien.urdf" in err and "Traceback" not in err and SECRET not in err
    world.unchanged()


@pytest.mark.parametrize("lang", ["en", "fr"])
def test_bras_kit_run_names_what_setup_py_tried_at_its_lines(world, capsys, lang):
    """The build under `bras-kit run` is the one `bras-kit build` makes: what setup.py tried that its
    walls stopped is BK639 at its lines there too (errors: exit 1, as for the node's own BK659), and
    the node still runs (setup() itself was fine)."""
    package = world.package("setup_reaches")
    assert main(["run", str(package), "animation", "--duration", "1", "--lang", lang, "--json"]) == 1
    captured = capsys.readouterr()
    import json

    report = json.loads(captured.out)
    assert "20 messages" in captured.err, captured.err  # the node ran (20 Hz for 1 s)
    out = captured.out + captured.err
    assert all(f["code"] == "BK639" for r in report["files"] for f in r["findings"] if f["severity"] == "error")
    for rule, file, line in EXPECTED["setup_reaches"]:
        assert any(r["path"].endswith(file) and f["code"] == rule and f["line"] == line
                   for r in report["files"] for f in r["findings"]), report["files"]
    assert ("outside the folder it runs in" if lang == "en" else "hors du dossier") in out, out
    assert "Traceback" not in out
    world.unchanged()


@pytest.mark.slow
def test_a_live_run_names_what_setup_py_tried_before_its_node_runs(world, private_runtime):
    """Beside an open launch (here a page of the bus, which bras-kit launch opens), `bras-kit run`
    is live until Ctrl-C: what setup.py tried that its walls stopped is BK639 at its lines as soon
    as the package is built, while the node publishes, not when the run ends; Ctrl-C then ends it
    with exit 1, as a batch run with those findings ends. Oracles: the lines of the corpus, the
    node's messages reaching the page, the process still running when the findings are read."""
    from bras_kit.ros.bus import Bus

    package = world.package("setup_reaches")
    received: list[object] = []
    with Bus.listen() as page:
        page.on_joint_state(received.append)
        live = subprocess.Popen([sys.executable, "-m", "bras_kit", "run", str(package), "animation", "--quiet",
                                 "--lang", "en"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                                preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
        said, fd = b"", live.stdout.fileno()  # type: ignore[union-attr]
        try:
            end = time.monotonic() + 120
            while time.monotonic() < end and not re.search(rb"files? checked", said):
                if select.select([fd], [], [], 0.5)[0]:
                    chunk = os.read(fd, 65536)  # unbuffered: select sees all that is not read yet
                    said += chunk
                    if not chunk:
                        break
            running = live.poll() is None
            deadline = time.monotonic() + 60
            while len(received) < 10 and time.monotonic() < deadline:
                time.sleep(0.1)
        finally:
            live.send_signal(signal.SIGINT)
            out, err = live.communicate(timeout=60)
    shown = said.decode()
    assert running, shown + err
    assert len(received) >= 10, err  # the node was publishing, live, after the findings were shown
    for rule, file, line in EXPECTED["setup_reaches"]:
        assert f"{file}:{line}: {rule}" in shown, shown
    assert "outside the folder it runs in" in shown and SECRET not in shown + out + err
    assert "stopped by Ctrl-C" in err and "Traceback" not in shown + out + err
    assert live.returncode == 1, err
    world.unchanged()


@pytest.mark.parametrize("case", ["name_home", "rsp_dev_zero", "rsp_secret", "rviz_dev_zero", "launch_reaches"])
def test_bras_kit_launch_ends_and_refuses(world, case, capsys):
    """/dev/zero as the URDF file or RViz's configuration: the parent used to read it until its
    memory ran out; it is now never opened."""
    package = world.package(case)
    main(["launch", str(package), "--no-page", "--duration", "1", "--lang", "en"])
    captured = capsys.readouterr()
    out = captured.out + captured.err
    assert "Traceback" not in out and SECRET not in out
    for rule, file, line in EXPECTED.get(case, set()):
        assert f"{file}:{line}:" in out and rule in out, out
    world.unchanged()


@pytest.mark.parametrize("case", ["name_dotdot", "source_absolute", "setup_reaches", "launch_reaches", "rsp_dev_zero"])
def test_bras_kit_validate_run_reports_each_at_its_line(world, case, capsys):
    package = world.package(case)
    main(["validate", str(package), "--run", "--lang", "en"])
    out = capsys.readouterr().out
    for rule, file, line in EXPECTED[case]:
        assert f"{file}:{line}:" in out and rule in out, out
    assert SECRET not in out
    world.unchanged()


@pytest.mark.parametrize("case", ["name_home", "setup_reaches"])
def test_exercise_6_builds_the_package_through_the_same_walls(world, case):
    """Exercise 6 judges setup.py's data_files: it now runs setup.py (contained) as colcon does,
    so a hostile setup.py fails it at its line instead of passing unread."""
    from bras_kit.exercises import FAILED, copy_files, load_track
    from bras_kit.exercises.checks import run_checks

    track = load_track()
    exercise = track.exercise(6)
    folder = world.root / "exos"
    copy_files(exercise, folder)
    shutil.copy(TUTORIAL / "setup.py", folder / "bras_description" / "setup.py")
    assert run_checks(folder, exercise.checks, "en").state == "passed"  # the tutorial's setup.py passes
    package = world.package(case)  # the case's files over the exercise's package
    shutil.copytree(package, folder / "bras_description", dirs_exist_ok=True, symlinks=True)
    world.before = world.snapshot()
    outcome = run_checks(folder, exercise.checks, "en")
    assert outcome.state == FAILED
    (rule, file, line), *_ = sorted(EXPECTED[case])
    assert (outcome.file, outcome.line) == (f"bras_description/{file}", line)
    assert rule in str(outcome.reason)
    world.unchanged()


@pytest.mark.slow
def test_grade_run_nodes_reports_each_learner_at_their_line_and_changes_nothing(world):
    """One class, one learner per hostile case: before, `name=HOME + '/x'` wrote in the teacher's home
    folder and grade said "graded 2 of 2"."""
    cases = ["name_home", "name_dotdot", "source_absolute", "source_symlink_out", "setup_reaches", "launch_reaches",
             "rsp_dev_zero"]
    klass = world.root / "copies"
    for case in cases:
        package = world.package(case)
        shutil.move(str(package), klass / case)
    world.before = world.snapshot()
    code = main(["grade", str(klass), "-o", str(world.root / "report"), "--run-nodes", "--no-pictures",
                 "--jobs", "1", "--lang", "en"])
    assert code == 0
    learners = json.loads((world.root / "report" / "results.json").read_text())["learners"]
    got = {r["learner"]: {(f["code"], f["file"], f["line"]) for f in r["findings"]} for r in learners}
    for case in cases:
        assert EXPECTED[case] <= got[case], (case, got[case])
    assert SECRET not in (world.root / "report" / "results.json").read_text()
    assert SECRET not in (world.root / "report" / "grades.csv").read_text()
    world.unchanged()


def test_rviz_d_dev_zero_is_not_read_for_the_pages_fixed_frame(world):
    """bras-kit launch reads RViz's -d configuration for the page's fixed frame: /dev/zero there
    used to be read until memory ran out; it is refused by the one reader, and a real
    configuration of the package is still read."""
    from bras_kit.ros.evaluation import rviz_fixed_frame as _rviz_fixed_frame
    from bras_kit.validate.package import launch_package

    package = world.package("rviz_dev_zero")
    result = launch_package(str(package), str(world.ws / "install"))
    assert [n.arguments for n in result.plan.nodes if n.package == "rviz2"] == [["-d", "/dev/zero"]]
    assert _rviz_fixed_frame(result.plan) is None
    world.unchanged()
