"""bras-kit grade on a generated class of 30 submissions: scores against hand-computed ones
(the default rubric: loads 4, no error 4, no BK3 warning 3, epaule+coude 2, wrist at the
forearm's tip 3, inertials 2, package without BK6 warning 2), unsafe archives refused, the
reports readable by a spreadsheet and a browser, the process pool and Dask agreeing."""

from __future__ import annotations

import csv
import io
import json
import shutil
import subprocess
import sys
import tarfile
import zipfile
from pathlib import Path

import pytest
from paths import REPO, TESTS

from bras_kit.model.authoring import arm_urdf
from bras_kit.scaffold.package import scaffold_package

HOSTILE = TESTS / "data" / "hostile"


def _write(path: Path, text: str) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text, encoding="utf-8")


def _zip_folder(folder: Path, archive: Path) -> None:
    with zipfile.ZipFile(archive, "w") as bundle:
        for file in sorted(folder.rglob("*")):
            if file.is_file():
                bundle.write(file, file.relative_to(folder.parent))


@pytest.fixture(scope="module")
def klass(tmp_path_factory) -> tuple[Path, dict[str, float]]:
    """The class folder and each learner's expected score, computed by hand from the rubric."""
    root = tmp_path_factory.mktemp("class")
    expected: dict[str, float] = {}
    plain, wrist, full = arm_urdf(), arm_urdf(wrist=True), arm_urdf(wrist=True, inertials=True)

    # right: the tutorial (4+4+3+2 = 13), + wrist (16), + inertials (18)
    for k in range(9):
        _write(root / f"arm{k}.urdf", arm_urdf(params={"bras_length": 0.5 + 0.05 * k}))
        expected[f"arm{k}"] = 13
    _write(root / "wrist.urdf", wrist)
    expected["wrist"] = 16
    _write(root / "wrist_inertials.urdf", full)
    expected["wrist_inertials"] = 18
    _write(root / "xacro_learner" / "bras.urdf.xacro",
           (REPO / "bras_kit" / "templates" / "robot" / "bras.urdf.xacro").read_text())
    expected["xacro_learner"] = 13  # the template with its defaults: the tutorial arm
    # whole packages: the package item needs no BK6 warning (+2)
    scaffold_package(root / "pkg_full", wrist=True, inertials=True)
    expected["pkg_full"] = 20
    scaffold_package(root / "pkg_plain")
    expected["pkg_plain"] = 15
    scaffold_package(root / "tmp_zip" / "bras_description", wrist=True, inertials=True)
    _zip_folder(root / "tmp_zip" / "bras_description", root / "pkg_zip.zip")
    expected["pkg_zip"] = 20
    with tarfile.open(root / "pkg_tar.tar.gz", "w:gz") as bundle:
        bundle.add(root / "tmp_zip" / "bras_description", arcname="bras_description")
    expected["pkg_tar"] = 20
    shutil.rmtree(root / "tmp_zip")
    # a package pitfall: setup.py no longer installs urdf/ (BK6xx) -> 20 - 2
    scaffold_package(root / "pkg_setup", wrist=True, inertials=True)
    setup = root / "pkg_setup" / "setup.py"
    setup.write_text(setup.read_text().replace("installed('urdf', '*.urdf', '*.xacro'),", ""))
    expected["pkg_setup"] = 4 + 0 + 3 + 2 + 3 + 2 + 0  # the BK6 finding is an error: no_errors 0 too

    # the tutorial's pitfalls
    _write(root / "coude_short.urdf", plain.replace('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 0.3"/>'))
    expected["coude_short"] = 10  # BK301 warning: pitfalls 0
    _write(root / "wrist_on_bras.urdf", wrist.replace('<parent link="avant_bras"/>', '<parent link="bras"/>'))
    expected["wrist_on_bras"] = 4 + 4 + 0 + 2 + 0  # BK301 (0.5 on a 0.6 m bras), wrist on the wrong parent
    _write(root / "wrist_short.urdf", wrist.replace('<origin xyz="0 0 0.5"/>', '<origin xyz="0 0 0.3"/>'))
    expected["wrist_short"] = 10  # not at the tip (wrist 0) and BK301 (pitfalls 0)
    _write(root / "massless.urdf", full.replace('<mass value="1.0"/>', '<mass value="0"/>'))
    expected["massless"] = 4 + 0 + 3 + 2 + 3 + 0  # loads, an error (BK500), pitfalls, arm, wrist, inertials
    _write(root / "no_coude.urdf", plain.replace('name="coude"', 'name="genou"'))
    expected["no_coude"] = 4 + 4 + 3 + 0  # the arm item needs coude

    # unreadable, hostile, unsafe, empty: zero, and the batch goes on
    _write(root / "broken.urdf", plain[: len(plain) // 2])
    expected["broken"] = 0
    shutil.copy(HOSTILE / "getattribute_escape.xacro", root / "hostile.xacro")
    expected["hostile"] = 0
    shutil.copy(HOSTILE / "macro_bomb.xacro", root / "bomb.xacro")
    expected["bomb"] = 0
    with zipfile.ZipFile(root / "zipslip.zip", "w") as bundle:
        bundle.writestr("../../evil.urdf", plain)
    expected["zipslip"] = 0
    info = tarfile.TarInfo("bras_description/urdf/bras.urdf")
    info.type, info.linkname = tarfile.SYMTYPE, "/etc/passwd"
    with tarfile.open(root / "tarlink.tar.gz", "w:gz") as bundle:
        bundle.addfile(info)
    expected["tarlink"] = 0
    (root / "empty").mkdir()
    expected["empty"] = 0
    _write(root / "notes.txt", "my robot is in my head")
    expected["notes.txt"] = 0
    # a 10 MB URDF (a huge comment): legal, slow to read, graded like the tutorial arm
    _write(root / "big.urdf", plain.replace("<robot", "<!-- " + "x" * (10 << 20) + " -->\n<robot", 1))
    expected["big"] = 13
    return root, expected


def _grade(klass_dir: Path, out: Path, *extra: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "bras_kit", "grade", str(klass_dir), "-o", str(out), *extra],
                          capture_output=True, text=True, timeout=600)


@pytest.fixture(scope="module")
def report(klass, tmp_path_factory):
    folder, _ = klass
    out = tmp_path_factory.mktemp("report") / "rapport"
    done = _grade(folder, out, "--jobs", "2", "--gradescope")
    assert done.returncode == 0, done.stderr
    assert "Traceback" not in done.stderr
    assert "grading [" not in done.stderr  # no progress bar when piped
    return out


@pytest.mark.slow
def test_scores_equal_the_hand_computed_ones(klass, report):
    _, expected = klass
    assert len(expected) == 30
    rows = list(csv.DictReader(io.StringIO((report / "grades.csv").read_text())))
    scores = {row["identifier"]: float(row["score"]) for row in rows}
    assert scores == expected
    for row in rows:  # the columns add up, and max is the rubric's total
        items = ("loads", "no_errors", "pitfalls", "arm", "wrist", "inertials", "package")
        assert sum(float(row[i]) for i in items) == float(row["score"])
        assert row["max"] == "20"
    unreadable = {row["identifier"] for row in rows if row["first_error"].startswith(("BK100", "BK102", "BK103"))}
    assert {"broken", "hostile", "bomb", "zipslip", "tarlink", "empty", "notes.txt"} <= unreadable


@pytest.mark.slow
def test_unsafe_archives_write_nothing_outside(klass, report):
    folder, _ = klass
    assert not (folder.parent / "evil.urdf").exists() and not (folder / "evil.urdf").exists()
    learners = {r["learner"]: r for r in json.loads((report / "results.json").read_text())["learners"]}
    assert "outside its folder" in learners["zipslip"]["first_error"]
    assert "not a plain file" in learners["tarlink"]["first_error"]
    assert not (Path.cwd() / "bras_kit_canary").exists()


@pytest.mark.slow
def test_html_pages_link_existing_pictures(klass, report):
    _, expected = klass
    index = (report / "index.html").read_text()
    for learner in expected:
        page = report / "learners" / (learner.replace(".", ".") + ".html")
        assert page.exists(), learner
        assert f"learners/{page.name}" in index
    learners = json.loads((report / "results.json").read_text())["learners"]
    drawn = [r for r in learners if r["picture"]]
    assert len(drawn) >= 20
    for result in drawn:
        picture = report / result["picture"]
        from PIL import Image

        assert Image.open(picture).size == (480, 360)
        page = (report / "learners" / f"{result['learner']}.html").read_text()
        assert f"../{result['picture']}" in page
    assert "<svg" in index and "BK301" in index  # the histogram and the rule counts


@pytest.mark.slow
def test_gradescope_shape(klass, report):
    data = json.loads((report / "gradescope" / "wrist.json").read_text())
    assert data["score"] == 16
    assert sum(t["score"] for t in data["tests"]) == 16
    assert sum(t["max_score"] for t in data["tests"]) == 20
    assert [t["output"] for t in data["tests"]] == ["", "", "", "", "", "not met: " + data["tests"][5]["name"], ""]
    short = json.loads((report / "gradescope" / "coude_short.json").read_text())
    pitfalls = next(t for t in short["tests"] if "BK3xx" in t["name"])
    assert pitfalls["score"] == 0 and pitfalls["output"].startswith("BK301 coude_short.urdf:")


@pytest.mark.slow
def test_findings_in_the_learners_language(klass, tmp_path):
    folder, _ = klass
    small = tmp_path / "classe"
    small.mkdir()
    shutil.copy(folder / "coude_short.urdf", small)
    out = tmp_path / "rapport"
    done = _grade(small, out, "--lang", "fr", "--no-pictures")
    assert done.returncode == 0, done.stderr
    learner = json.loads((out / "results.json").read_text())["learners"][0]
    message = next(f["message"] for f in learner["findings"] if f["code"] == "BK301")
    assert "articulation" in message


@pytest.mark.slow
def test_resume_regrades_only_what_changed(klass, tmp_path):
    folder, _ = klass
    small = tmp_path / "class"
    small.mkdir()
    for name in ("arm0.urdf", "wrist.urdf", "broken.urdf"):
        shutil.copy(folder / name, small)
    out = tmp_path / "out"
    assert _grade(small, out, "--no-pictures").returncode == 0
    first = {r["learner"]: r for r in json.loads((out / "results.json").read_text())["learners"]}
    (small / "broken.urdf").write_text(arm_urdf())
    assert _grade(small, out, "--no-pictures", "--resume").returncode == 0
    second = {r["learner"]: r for r in json.loads((out / "results.json").read_text())["learners"]}
    assert second["arm0"] == first["arm0"] and second["wrist"] == first["wrist"]  # reused as they were
    assert second["broken"]["score"] == 13 and first["broken"]["score"] == 0


def test_a_foreign_output_folder_is_refused(tmp_path, klass):
    folder, _ = klass
    out = tmp_path / "mine"
    out.mkdir()
    (out / "notes.txt").write_text("keep me")
    done = _grade(folder, out)
    assert done.returncode == 2 and "--force" in done.stderr
    assert (out / "notes.txt").read_text() == "keep me"


def test_explain_rubric_prints_the_default_rubric():
    done = subprocess.run([sys.executable, "-m", "bras_kit", "grade", "--explain-rubric"], capture_output=True, text=True)
    import yaml

    rubric = yaml.safe_load(done.stdout)
    assert sum(item["points"] for item in rubric["items"]) == 20


def test_a_bad_rubric_is_a_clear_error(tmp_path):
    rubric = tmp_path / "bareme.yaml"
    rubric.write_text("items:\n  - id: a\n    points: 2\n    check: magic\n")
    done = subprocess.run([sys.executable, "-m", "bras_kit", "grade", str(tmp_path), "--rubric", str(rubric)],
                          capture_output=True, text=True)
    assert done.returncode == 2 and "unknown check 'magic'" in done.stderr and "Traceback" not in done.stderr


def test_interrupted_batch_keeps_what_was_finished(klass, tmp_path):
    from bras_kit.grade import Options, find_submissions, grade_all, load_rubric

    folder, _ = klass
    submissions = [s for s in find_submissions(folder) if s.learner.startswith("arm")]
    seen = []

    def stop_after_two(result):
        seen.append(result["learner"])
        if len(seen) == 2:
            raise KeyboardInterrupt

    results, finished = grade_all(submissions, load_rubric(), Options(), jobs=1, on_result=stop_after_two)
    assert not finished
    assert [r["learner"] for r in results] == [s.learner for s in submissions if s.learner in seen]


@pytest.mark.slow
def test_dask_cluster_gives_the_same_report(klass, report, tmp_path):
    from distributed import LocalCluster

    folder, _ = klass
    with LocalCluster(n_workers=2, threads_per_worker=1, processes=True, host="127.0.0.1",
                      dashboard_address=None) as cluster:
        out = tmp_path / "dask"
        done = _grade(folder, out, "--scheduler", cluster.scheduler_address, "--gradescope")
        assert done.returncode == 0, done.stderr

    def comparable(path: Path):
        data = json.loads(path.read_text())
        for learner in data["learners"]:
            learner.pop("seconds")
            learner.pop("path")
            if learner["learner"] == "bomb":  # stopped by whichever limit comes first: the time
                learner["first_error"] = learner["first_error"].split()[0]  # budget or the size cap,
                for finding in learner["findings"]:  # so only its code is the same in both runs
                    finding.pop("message")
                    finding.pop("hint")
        return data

    assert comparable(out / "results.json") == comparable(report / "results.json")
    def grades(path: Path):
        rows = list(csv.DictReader(io.StringIO(path.read_text())))
        for row in rows:
            if row["identifier"] == "bomb":
                row["first_error"] = row["first_error"].split()[0]
        return rows

    assert grades(out / "grades.csv") == grades(report / "grades.csv")


def _dies_on_arm3(submission, rubric, options):
    """Stands in for grade() in forked pool workers: the worker grading arm3 dies outright."""
    import os

    from bras_kit.grade.worker import grade

    if submission.learner == "arm3":
        os._exit(9)
    return grade(submission, rubric, options)


def test_a_worker_that_dies_costs_only_its_submission(klass, monkeypatch):
    from bras_kit.grade import Options, find_submissions, grade_all, load_rubric, runner

    folder, expected = klass
    submissions = [s for s in find_submissions(folder) if s.learner.startswith("arm")]
    monkeypatch.setattr(runner, "grade", _dies_on_arm3)
    results, finished = grade_all(submissions, load_rubric(), Options(), jobs=2)
    assert finished
    scores = {r["learner"]: r["score"] for r in results}
    assert scores == {s.learner: (0 if s.learner == "arm3" else expected[s.learner]) for s in submissions}
    dead = next(r for r in results if r["learner"] == "arm3")
    assert "worker process died" in dead["first_error"]


@pytest.mark.slow
def test_gif_draws_each_arm_moving(klass, tmp_path):
    from PIL import Image

    folder, _ = klass
    small = tmp_path / "classe"
    small.mkdir()
    for name in ("wrist.urdf", "broken.urdf"):
        shutil.copy(folder / name, small)
    out = tmp_path / "rapport"
    done = _grade(small, out, "--gif", "--jobs", "1")
    assert done.returncode == 0, done.stderr
    learners = {r["learner"]: r for r in json.loads((out / "results.json").read_text())["learners"]}
    assert learners["wrist"]["animation"] == "pictures/wrist.gif" and learners["broken"]["animation"] is None
    gif = Image.open(out / "pictures" / "wrist.gif")
    assert gif.n_frames == 40 and gif.size == (320, 240)  # 4 s at 10 frames per second
    assert "../pictures/wrist.gif" in (out / "learners" / "wrist.html").read_text()


@pytest.mark.slow
def test_ctrl_c_writes_the_report_of_what_was_finished(tmp_path):
    import os
    import signal
    import time

    folder = tmp_path / "classe"
    folder.mkdir()
    # a class far longer than the time between the third picture and the signal: 200 tutorial
    # arms once took several seconds, and grading them was made fast enough to end first
    first, wrist = arm_urdf(), arm_urdf(wrist=True)
    for k in range(3000):
        (folder / f"eleve{k:04d}.urdf").write_text(first if k % 2 else wrist)
    expected = {f"eleve{k:04d}": 13 if k % 2 else 16 for k in range(3000)}
    out = tmp_path / "rapport"
    # SIGINT as a terminal leaves it: a test run started in the background (nohup, `cmd &` in a
    # script) inherits it ignored, and Python then never turns it into KeyboardInterrupt
    scratch = tmp_path / "tmp"  # the workers' unpacking folders: none is left behind
    scratch.mkdir()
    process = subprocess.Popen([sys.executable, "-m", "bras_kit", "grade", str(folder), "-o", str(out), "--jobs", "1"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True, start_new_session=True,
                               env={**os.environ, "TMPDIR": str(scratch)},
                               preexec_fn=lambda: signal.signal(signal.SIGINT, signal.SIG_DFL))
    deadline = time.monotonic() + 120
    # a third picture means the one worker has finished two learners (a picture is drawn before scoring)
    while time.monotonic() < deadline and len(list((out / "pictures").glob("*.png"))) < 3:
        time.sleep(0.05)
    os.killpg(process.pid, signal.SIGINT)  # as a terminal does: the whole group, workers included
    _, stderr = process.communicate(timeout=120)
    assert process.returncode == 130, stderr
    assert "interrupted" in stderr and "Traceback" not in stderr
    learners = json.loads((out / "results.json").read_text())["learners"]
    assert 2 <= len(learners) < len(expected)
    assert all(r["score"] == expected[r["learner"]] for r in learners)  # finished ones, none marked failed
    assert "interrupted" in (out / "index.html").read_text()
    assert [p.name for p in scratch.iterdir() if p.name.startswith("bras-kit-")] == []


def test_scheduler_without_dask_names_the_extra(tmp_path):
    (tmp_path / "alice.urdf").write_text(arm_urdf())
    code = ("import sys; sys.modules['distributed'] = None; from bras_kit.cli import main; "
            f"sys.exit(main(['grade', {str(tmp_path)!r}, '-o', {str(tmp_path / 'out')!r}, "
            "'--scheduler', 'tcp://127.0.0.1:8786']))")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 2 and "pip install 'bras-kit[cluster]'" in done.stderr
    assert "Traceback" not in done.stderr


def test_progress_bar_on_a_terminal_only():
    from bras_kit.grade.runner import Progress

    class Terminal(io.StringIO):
        def isatty(self) -> bool:
            return True

    shown, piped = Terminal(), io.StringIO()
    for stream in (shown, piped):
        progress = Progress(4, stream)
        for failed in (False, True, False):
            progress.update(failed)
        progress.close()
    assert piped.getvalue() == ""
    last = shown.getvalue().rstrip("\n").split("\r")[-1]
    assert "3/4" in last and "1 unreadable" in last and "/s" in last


def test_learners_whose_names_clash_once_made_safe_keep_their_own_pages():
    from bras_kit.grade.worker import _safe_name

    names = ["alice", "a b", "a_b", "a/b", "../x", "élève-3"]
    safe = [_safe_name(name) for name in names]
    assert len(set(safe)) == len(names)
    # plain lower-case ASCII names are kept as they are; others (é: a file system may store it
    # decomposed, or fold its case) get a digest of the exact name (tests/trust/test_gate_names.py)
    assert safe[0] == "alice" and safe[2] == "a_b" and safe[5].startswith("élève-3-")
    assert all("/" not in name and not name.startswith(".") for name in safe)


@pytest.mark.slow
def test_report_opens_from_disk_in_a_browser(klass, report, chromium):
    """Chromium, from file://, with no server: the index links every page, each page shows its picture."""
    from playwright.sync_api import sync_playwright

    _, expected = klass
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path=chromium, headless=True,
                                             args=["--no-sandbox", "--disable-background-networking"])
        page = browser.new_page()
        page.goto((report / "index.html").as_uri())
        links = page.eval_on_selector_all("a[href^='learners/']", "els => els.map(e => e.href)")
        assert len(links) == len(expected)
        assert page.eval_on_selector("svg", "e => e.querySelectorAll('rect').length") >= 1
        page.goto(next(link for link in links if link.endswith("/wrist.html")))
        size = page.eval_on_selector("img", "e => [e.complete, e.naturalWidth, e.naturalHeight]")
        assert size == [True, 480, 360]  # the picture loaded from disk
        assert "16 / 20" in page.inner_text("h1")
        page.click("text=class summary")
        assert page.url.endswith("/index.html")
        browser.close()


@pytest.mark.slow
def test_meshes_are_drawn_from_the_archive_and_never_from_outside(tmp_path):
    import trimesh

    base_cylinder = '<cylinder length="0.1" radius="0.15"/>'
    klass = tmp_path / "classe"
    klass.mkdir()
    package = tmp_path / "src" / "bras_description"
    (package / "meshes").mkdir(parents=True)
    (package / "package.xml").write_text("<package format='3'><name>bras_description</name></package>")
    trimesh.creation.box(extents=(0.3, 0.3, 0.1)).export(package / "meshes" / "socle.stl")
    _write(package / "urdf" / "bras.urdf",
           arm_urdf().replace(base_cylinder, '<mesh filename="package://bras_description/meshes/socle.stl"/>'))
    _zip_folder(package, klass / "maille.zip")
    outside = tmp_path / "secret.stl"
    trimesh.creation.box(extents=(0.3, 0.3, 0.1)).export(outside)
    _write(klass / "dehors.urdf", arm_urdf().replace(base_cylinder, f'<mesh filename="file://{outside}"/>'))
    _write(klass / "monte.urdf", arm_urdf().replace(base_cylinder, '<mesh filename="../secret.stl"/>'))
    out = tmp_path / "rapport"
    done = _grade(klass, out, "--jobs", "1")
    assert done.returncode == 0, done.stderr
    learners = {r["learner"]: r for r in json.loads((out / "results.json").read_text())["learners"]}
    assert learners["maille"]["picture"] == "pictures/maille.png"  # the mesh found while unpacked
    assert learners["dehors"]["picture"] is None and learners["monte"]["picture"] is None
    assert learners["dehors"]["status"] == learners["monte"]["status"] == "graded"  # still graded


def test_a_worker_the_pool_terminates_removes_the_submission_it_was_unpacking(tmp_path):
    """The pool ends the other workers with SIGTERM when one dies (grade/runner.py): the worker's
    finally blocks never run (it leaves with os._exit), so its handler removes the folder."""
    import signal

    unpacking = tmp_path / "bras-kit-grade-x"
    (unpacking / "unpacked" / "urdf").mkdir(parents=True)
    code = ("import os, signal, sys\n"
            "from bras_kit.grade import runner, worker\n"
            "runner._start_worker()\n"
            f"worker.workdir_in_use = {str(unpacking)!r}\n"
            "os.kill(os.getpid(), signal.SIGTERM)\n"
            "sys.exit(0)\n")
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120)
    assert done.returncode == 128 + signal.SIGTERM, done.stderr
    assert not unpacking.exists()
