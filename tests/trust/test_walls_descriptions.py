"""A robot description has a size and a count of links and joints bras-kit will parse and hold;
past them it is the learner's finding, never a swollen process.

Categories: robot_description given as a parameter's text (past 8 MiB; past 20,000 links and
joints in a few MiB: short elements), as a file named on robot_state_publisher's command line
(past the reader's 8 MiB), the package's own robot file read by the package rules, and a robot
file in a class graded by ``grade``. Oracles: the sizes and counts of the texts made here, and
the tutorial's arm (5 kB, 3 links), which passes each bound unchanged."""

from __future__ import annotations

import csv
import os
import shutil
import subprocess
import sys
import time

import pytest
from paths import TESTS

from bras_kit.ros.launching import (
    MAX_DESCRIPTION_CHARS,
    MAX_DESCRIPTION_ELEMENTS,
    PlannedNode,
    robot_state_publisher_start,
)

TUTORIAL_URDF = TESTS / "data" / "tutorial_package" / "urdf" / "bras.urdf"


def chain(links: int, padding: str = "") -> str:
    """A URDF chain of ``links`` links after ``base``, each with ``padding`` in a comment."""
    parts = ['<?xml version="1.0"?>\n<robot name="big">\n  <link name="base"/>\n']
    for k in range(links):
        parent = "base" if k == 0 else f"l{k - 1}"
        parts.append(f'  <link name="l{k}"/><!--{padding}-->\n  <joint name="j{k}" type="fixed">'
                     f'<parent link="{parent}"/><child link="l{k}"/></joint>\n')
    parts.append("</robot>\n")
    return "".join(parts)


def rsp(description: str = "", arguments: tuple[str, ...] = ()) -> PlannedNode:
    return PlannedNode("robot_state_publisher", "robot_state_publisher", None, None,
                       {"robot_description": description} if description else {}, [], [], list(arguments), 0.0,
                       "/x/launch/a.launch.py", 3)


def test_the_tutorial_arm_passes_every_bound():
    text = TUTORIAL_URDF.read_text(encoding="utf-8")
    loaded, problems = robot_state_publisher_start(rsp(text))
    assert loaded == text and problems == []


def test_a_description_past_the_size_bound_is_not_parsed():
    text = chain(10, padding="x" * (MAX_DESCRIPTION_CHARS // 10))
    assert len(text) > MAX_DESCRIPTION_CHARS
    start = time.monotonic()
    loaded, problems = robot_state_publisher_start(rsp(text))
    assert loaded is None and [p.kind for p in problems] == ["too_large"]
    assert problems[0].detail == str(round(len(text) / (1 << 20), 1))
    assert time.monotonic() - start < 1


def test_a_description_of_more_links_and_joints_than_held_is_not_parsed():
    text = chain(MAX_DESCRIPTION_ELEMENTS // 2 + 1)  # links + joints: one past the bound
    assert len(text) < MAX_DESCRIPTION_CHARS
    loaded, problems = robot_state_publisher_start(rsp(text))
    assert loaded is None and [p.kind for p in problems] == ["too_many"]
    loaded, problems = robot_state_publisher_start(rsp(chain(MAX_DESCRIPTION_ELEMENTS // 2 - 1)))
    assert loaded is not None and problems == []


def test_a_urdf_file_past_the_readers_bound_is_too_large(tmp_path):
    (tmp_path / "big.urdf").write_text(chain(10, padding="x" * (MAX_DESCRIPTION_CHARS // 10)), encoding="utf-8")
    loaded, problems = robot_state_publisher_start(rsp(arguments=("big.urdf",)), roots=(str(tmp_path),))
    assert loaded is None and [p.kind for p in problems] == ["file_fallback", "too_large"]


def test_the_finding_has_its_words_in_english_and_french():
    import bras_kit.validate.package  # noqa: F401 - registers the package rules and their words
    from bras_kit.findings.data import finding
    from bras_kit.findings.registry import RULES, hit

    for variant, detail, english, french in (("too_large", "59.4", "59.4 MiB of text, more than the 8 MiB",
                                              "59.4 Mio de texte, plus que les 8 Mio"),
                                             ("too_many", "20000", "more than 20000 links and joints",
                                              "plus de 20000 links et joints")):
        found = finding(RULES["BK632"], hit("file", None, 3, variant, file="a.launch.py", detail=detail, ros="",
                                            launch=""))
        assert english in found.text("en") and "neither checked nor shown" in found.text("en")
        assert french in found.text("fr") and "ni vérifié ni affiché" in found.text("fr")


def test_the_package_rules_do_not_parse_a_robot_file_past_the_bound(tmp_path):
    from bras_kit.scaffold.package import scaffold_package
    from bras_kit.validate.package import validate_package

    scaffold_package(tmp_path / "pkg")
    (tmp_path / "pkg" / "urdf" / "bras.urdf").write_text(chain(10, padding="x" * (MAX_DESCRIPTION_CHARS // 10)),
                                                          encoding="utf-8")
    start = time.monotonic()
    results = validate_package(str(tmp_path / "pkg"), select=["BK600"])
    found = [(f.code, f.text("en")) for r in results for f in r.findings]
    assert any(code == "BK600" and "more than the 8 MiB bras-kit reads" in text for code, text in found), found
    assert time.monotonic() - start < 30


def test_a_class_with_a_60_mb_robot_is_graded_small_and_fast(tmp_path):
    """Before: the check of that learner's 60 MB file was stopped at its 40 s wall clock, the
    grading process at 608 MB; now its file is refused by its size (37 MB, 3 s), and a file of
    40,000 links and joints by their count."""
    klass = tmp_path / "class"
    klass.mkdir()
    shutil.copy(TUTORIAL_URDF, klass / "alice.urdf")
    (klass / "zoe.urdf").write_text(chain(40, padding="x" * ((60 << 20) // 40)), encoding="utf-8")
    (klass / "yann.urdf").write_text(chain(MAX_DESCRIPTION_ELEMENTS), encoding="utf-8")  # 2.7 MB, 40,000 elements
    code = ("import resource, subprocess, sys\n"
            "p = subprocess.run(sys.argv[1:], capture_output=True, text=True, timeout=200)\n"
            "sys.stdout.write(p.stdout); sys.stderr.write(p.stderr)\n"
            "print('MAXRSS', resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n")
    start = time.monotonic()
    done = subprocess.run([sys.executable, "-c", code, sys.executable, "-m", "bras_kit", "grade", str(klass), "-o",
                           str(tmp_path / "out"), "--no-pictures", "--jobs", "1"], capture_output=True, text=True,
                          timeout=250, env={**os.environ, "BRAS_KIT_LANG": "en"})
    seconds, peak = time.monotonic() - start, int(done.stdout.rsplit("MAXRSS", 1)[1]) / 1024
    with open(tmp_path / "out" / "grades.csv", encoding="utf-8", newline="") as handle:
        rows = {row[0]: row for row in csv.reader(handle)}
    assert float(rows["alice"][1]) > 0
    assert "zoe.urdf holds 60 MiB, more than the 32 MiB" in rows["zoe"][-1]
    assert "more than 20000 links and joints" in rows["yann"][-1]
    assert peak < 300 and seconds < 30, (peak, seconds)


@pytest.mark.parametrize("links", [1, 2, 100])
def test_small_robots_are_held_as_before(links):
    loaded, problems = robot_state_publisher_start(rsp(chain(links)))
    assert loaded is not None and problems == []


def test_a_launch_giving_robot_state_publisher_60_mb_is_bk632_small_and_fast(tmp_path):
    """A launch file making a 60 MB robot_description in Python: launch_ros would yaml.dump the
    text (PyYAML's emitter: about 40 s for 60 MB), which stopped the launch file's child at its
    40 s wall clock with BK631 'wall limit'; past bras-kit's bound the text is now kept as it is,
    and robot_state_publisher's counterpart says BK632 too_large without parsing it. Peak memory
    is the kernel's ru_maxrss of bras-kit and the children it waited for."""
    package = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL_URDF.parent.parent, package)
    (package / "launch" / "affichage.launch.py").write_text(
        "from launch import LaunchDescription\nfrom launch_ros.actions import Node\n\n\n"
        "def generate_launch_description():\n"
        "    text = '<robot name=\"r\"><link name=\"base\"/><!--' + 'x' * (60 << 20) + '--></robot>'\n"
        "    return LaunchDescription([Node(package='robot_state_publisher', executable='robot_state_publisher',\n"
        "                                   parameters=[{'robot_description': text}])])\n", encoding="utf-8")
    code = ("import resource, subprocess, sys\n"
            "p = subprocess.run(sys.argv[1:], capture_output=True, text=True, timeout=200)\n"
            "sys.stdout.write(p.stdout); sys.stderr.write(p.stderr)\n"
            "print('MAXRSS', resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss)\n")
    start = time.monotonic()
    done = subprocess.run([sys.executable, "-c", code, sys.executable, "-m", "bras_kit", "launch", str(package),
                           "--no-page", "--duration", "1"], capture_output=True, text=True, timeout=250,
                          env={**os.environ, "BRAS_KIT_LANG": "en"}, cwd=tmp_path)
    seconds, peak = time.monotonic() - start, int(done.stdout.rsplit("MAXRSS", 1)[1]) / 1024
    assert "BK632" in done.stdout and "60.0 MiB of text, more than the 8 MiB" in done.stdout, done.stdout
    assert "wall limit" not in done.stdout
    assert seconds < 25 and peak < 450, (seconds, peak)
