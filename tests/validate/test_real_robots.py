"""The validator on every robot description shipped in real PyPI packages.

example-robot-data and rtb-data are in the dev extra; tests/data/real_robots/pybullet_data holds
the files of pybullet's pybullet_data whose defects those two lack (pybullet has no wheel past
CPython 3.11: see tests/data/real_robots/README.md). Every .urdf and .xacro in them is validated and compared with tests/data/real_robots.tsv, a table
of the files that do not pass cleanly, each with the reviewed reason. urdfdom's check_urdf
is the outside oracle for "a legal robot": no file it accepts may get an error that the
table does not record as a real defect.
"""

from __future__ import annotations

import subprocess
from pathlib import Path

import pytest
import system
from paths import TESTS
from robot_corpus import ROOTS, TREES

from bras_kit.validate import validate_path

pytestmark = pytest.mark.slow

TABLE = TESTS / "data" / "real_robots.tsv"
UNREADABLE = {"BK100", "BK101", "BK102", "BK103"}


def _expected() -> dict[tuple[str, str], tuple[int, str, str]]:
    table = {}
    for line in TABLE.read_text().splitlines():
        if line and not line.startswith("#"):
            package, name, code, codes, reason = line.split("\t")
            table[(package, name)] = (int(code), codes, reason)
    return table


def _verdict(path: Path) -> tuple[int, str]:
    findings = validate_path(str(path), package_paths=ROOTS)
    errors = sorted({f.code for f in findings if f.severity == "error"})
    code = 2 if UNREADABLE & set(errors) else (1 if errors else 0)
    return code, ",".join(errors)


@pytest.fixture(scope="module")
def verdicts() -> dict[tuple[str, str], tuple[int, str]]:
    out = {}
    for package, tree in TREES.items():
        for path in sorted([*tree.rglob("*.urdf"), *tree.rglob("*.xacro")]):
            out[(package, str(path.relative_to(tree)))] = _verdict(path)
    return out


def test_the_corpus_holds_the_three_sources_and_every_reviewed_defect(verdicts):
    assert set(TREES) == {"example-robot-data", "rtb-data", "pybullet_data"}
    assert len(verdicts) > 150
    table_codes = {c for _, codes, _ in _expected().values() for c in codes.split(",") if c}
    seen = {c for _, codes in verdicts.values() for c in codes.split(",") if c}
    assert table_codes <= seen
    assert {"BK118", "BK119", "BK123", "BK201", "BK202", "BK400", "BK401"} <= seen  # pybullet_data's own


def test_every_real_robot_gets_the_reviewed_verdict(verdicts):
    expected = _expected()
    differences = []
    for key, (code, codes) in verdicts.items():
        want_code, want_codes, _ = expected.get(key, (0, "", ""))
        if (code, codes) != (want_code, want_codes):
            differences.append((key, f"got exit {code} {codes or '-'}", f"table says {want_code} {want_codes or '-'}"))
    assert not differences, differences[:20]
    assert set(expected) <= set(verdicts), "the table names files that are no longer shipped"


def test_no_unreviewed_error_on_a_robot_check_urdf_accepts(verdicts):
    check_urdf = system.program("check_urdf", "liburdfdom-tools")
    expected = _expected()
    accepted_with_errors = []
    for (package, name), (code, _) in verdicts.items():
        if not name.endswith(".urdf") or code == 0:
            continue
        path = TREES[package] / name
        if subprocess.run([check_urdf, str(path)], capture_output=True).returncode == 0:
            accepted_with_errors.append((package, name))
    assert accepted_with_errors, "the oracle agrees with every verdict: the test would not notice a change"
    for key in accepted_with_errors:
        assert expected[key][2], f"{key}: an error on a robot urdfdom accepts needs a reviewed reason"
