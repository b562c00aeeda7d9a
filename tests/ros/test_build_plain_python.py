"""A package.xml catkin_pkg refuses: colcon builds the folder as a plain Python package without a word
(tests/ros/test_build_colcon_oracle.py shows the tree it makes); bras-kit build says so, and why."""

from __future__ import annotations

import subprocess
import sys

import colcon_compare
import pytest


@pytest.mark.parametrize(("lang", "said"), [("en", "as a plain Python package"), ("fr", "simple paquet Python")])
def test_a_refused_package_xml_is_named_with_catkin_pkgs_words(lang, said, tmp_path):
    workspace = colcon_compare.make_workspace(tmp_path, "invalid_maintainer_email")
    done = subprocess.run([sys.executable, "-m", "bras_kit", "build", str(workspace), "--lang", lang],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stdout + done.stderr
    assert said in done.stdout and 'Invalid email "eleve@ecole" for person "Élève"' in done.stdout
    assert "Finished <<< bras_description" in done.stdout


def test_an_accepted_package_xml_gets_no_such_note(tmp_path):
    workspace = colcon_compare.make_workspace(tmp_path, "tutorial")
    done = subprocess.run([sys.executable, "-m", "bras_kit", "build", str(workspace)], capture_output=True,
                          text=True, timeout=120)
    assert done.returncode == 0 and "catkin_pkg" not in done.stdout, done.stdout
