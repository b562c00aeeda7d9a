"""Reports a learner reads in the first hour: the class table, the run's findings, the physics table."""

from __future__ import annotations
from paths import TESTS

import re
from pathlib import Path

import pytest

from bras_kit.model.authoring import load

DATA = TESTS / "data"
TUTORIAL = DATA / "tutorial_package"

# The tutorial's arm with the elbow written past the arm's end (z=0.9 on a 0.6 m arm): the
# tutorial's pitfall "segments mal positionnés", a warning (BK301), and nothing else wrong.
FLOATING_FOREARM = (TUTORIAL / "urdf" / "bras.urdf").read_text(encoding="utf-8").replace(
    '<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 0.9"/>')


def _grade(tmp_path: Path, lang: str) -> tuple[list[dict], object]:
    from bras_kit.grade import Options, find_submissions, grade_all, load_rubric

    folder = tmp_path / "class"
    folder.mkdir()
    (folder / "lea.urdf").write_text(FLOATING_FOREARM, encoding="utf-8")
    rubric = load_rubric()
    results, finished = grade_all(find_submissions(folder), rubric, Options(lang=lang), jobs=1)
    assert finished
    return results, rubric


def _first_problem_cell(page: str) -> str:
    row = re.search(r"<tr><td><a href='learners/[^']*'>lea</a></td><td>[^<]*</td><td>([^<]*)</td></tr>", page)
    assert row is not None, page
    return row.group(1)


@pytest.mark.parametrize(("lang", "header"), [("en", "first problem"), ("fr", "premier problème")])
def test_a_learner_with_only_warnings_sees_the_first_one_in_the_class_table(tmp_path: Path, lang: str,
                                                                           header: str) -> None:
    from bras_kit.core.i18n import say
    from bras_kit.grade.report import index_page

    results, rubric = _grade(tmp_path, lang)
    (lea,) = results
    assert lea["score"] < lea["max"]  # the warning cost points...
    assert {f["severity"] for f in lea["findings"]} <= {"warning", "info"}
    assert not any(f["severity"] == "error" for f in lea["findings"])  # ...with no error to show
    page = index_page(results, rubric, lambda m: say(m, lang), lang, True)
    assert f"<th>{header}</th>" in page
    assert _first_problem_cell(page).startswith("BK301 ")
    assert "0.9" in _first_problem_cell(page)


def test_an_error_comes_before_a_warning_in_the_class_table() -> None:
    from bras_kit.grade.report import first_problem

    result = {"findings": [{"code": "BK301", "severity": "warning", "message": "w"},
                           {"code": "BK505", "severity": "info", "message": "i"},
                           {"code": "BK104", "severity": "error", "message": "e"}], "first_error": "BK104 e"}
    assert first_problem(result) == "BK104 e"
    assert first_problem({"findings": [{"code": "BK505", "severity": "info", "message": "i"}]}) == ""
    assert first_problem({"findings": [], "first_error": "BK103 unreadable"}) == "BK103 unreadable"


def test_the_cause_is_listed_before_its_consequence_when_a_node_raises() -> None:
    """The node gives to_msg() an argument it does not take (rclpy/time.py: ``def to_msg(self)``),
    so the first tick raises a TypeError (line 20) before anything is published from the
    publisher of line 11."""
    from bras_kit.run import run_node
    from bras_kit.run.findings import run_findings

    recording = run_node(str(DATA / "run" / "nodes" / "raises_before_publishing.py"), duration=1.0)
    assert recording.ended == "error" and recording.failure is not None
    assert recording.failure.kind == "TypeError"
    findings = run_findings(recording, load(str(TUTORIAL / "urdf" / "bras.urdf")), lang="en")
    assert [(f.code, f.line) for f in findings] == [("BK640", 20), ("BK644", 11)]


@pytest.mark.parametrize(("lang", "words"), [
    ("en", ["joint", "mean error", "largest error", "peak torque", "effort limit", "time at limit", "torque needed"]),
    ("fr", ["articulation", "erreur moyenne", "plus grande erreur", "couple max", "limite d'effort",
            "temps en butée d'effort", "couple nécessaire"]),
])
def test_the_physics_table_is_headed_in_words(run_cli, lang: str, words: list[str]) -> None:
    code, out, _ = run_cli("simulate", "--inertials", "--duration", "0.5", "--lang", lang)
    assert code == 0
    header = next(line for line in out.splitlines() if line.startswith(words[0] + " "))
    assert re.split(r"\s{2,}", header.strip())[:len(words)] == words
    assert "." not in header  # no abbreviation such as err.moy


def test_one_misnamed_joint_is_spoken_of_in_the_singular() -> None:
    """The node names 'shoulder' for 'epaule': one unknown name, one joint never named."""
    from bras_kit.run import run_node
    from bras_kit.run.findings import run_findings

    recording = run_node(str(DATA / "run" / "nodes" / "stamp_zero_wrong_names.py"), duration=1.0)
    findings = {f.code: f for f in run_findings(recording, load(str(TUTORIAL / "urdf" / "bras.urdf")))}
    said = {code: f.text("fr") for code, f in findings.items() if code in ("BK646", "BK647")}
    assert "nomme 'shoulder', qui n'est pas une articulation mobile du robot" in said["BK646"]
    assert said["BK647"].endswith(": cette articulation ne bouge pas")
    assert "which is not a movable joint" in findings["BK646"].text("en")
    assert "that joint does not move" in findings["BK647"].text("en")


def test_two_misnamed_joints_keep_the_plural() -> None:
    from bras_kit.findings.data import finding
    from bras_kit.findings.registry import RULES, Hit
    from bras_kit.validate.package.run_rules import joint_state_unknown_names  # noqa: F401  (registers BK646)

    many = finding(RULES["BK646"], Hit("file", None, 3, {"file": "a.py", "names": ["a", "b"], "joints": ["c"]}, ""))
    assert "qui ne sont pas des articulations mobiles" in many.text("fr")
