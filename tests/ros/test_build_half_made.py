"""After a build that stopped half-way (colcon's half-made prefix, tests/ros/test_build_colcon_oracle.py),
the learner fixes the package and builds again: the half-made prefix is replaced, as a finished one
is; a folder that no build made is never removed."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path

import colcon_compare
import colcon_corpus
import pytest

PKG = colcon_corpus.PKG


def build(workspace: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "bras_kit", "build", str(workspace)], cwd=workspace,
                          capture_output=True, text=True, timeout=120)


@pytest.mark.parametrize(("variant", "fix"), [
    ("resource_marker_missing", (f"resource/{PKG}", "")),  # an ament_python package: colcon-ros's hook is left
    ("package_xml_missing", ("package.xml", colcon_corpus.package_xml())),  # a plain Python one: no hook at all
])
def test_a_half_made_prefix_is_replaced_by_the_next_build(variant, fix, tmp_path):
    workspace = colcon_compare.make_workspace(tmp_path, variant)
    first = build(workspace)
    assert first.returncode == 1, first.stdout + first.stderr
    prefix = workspace / "install" / PKG
    assert (prefix / "lib").is_dir() and not (prefix / "share/colcon-core").exists()
    (workspace / "src" / PKG / fix[0]).parent.mkdir(exist_ok=True)
    (workspace / "src" / PKG / fix[0]).write_text(fix[1])
    again = build(workspace)
    assert again.returncode == 0, again.stdout + again.stderr
    assert (prefix / "share/colcon-core/packages" / PKG).is_file()
    assert (prefix / "lib" / PKG / "publie").is_file()


def test_a_folder_no_build_made_is_left_alone(tmp_path):
    workspace = colcon_compare.make_workspace(tmp_path, "tutorial")
    mine = workspace / "install" / PKG / "notes.txt"
    mine.parent.mkdir(parents=True)
    mine.write_text("mes notes\n")
    done = build(workspace)
    assert done.returncode == 1 and "BK630" in done.stdout, done.stdout + done.stderr
    assert mine.read_text() == "mes notes\n"
