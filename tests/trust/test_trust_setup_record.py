"""The checked form of setup()'s record (bras_kit.ros.setup_check) and the install tree laid out
from it (bras_kit.ros.build): each name and path the learner's setup.py hands back is checked
before bras-kit acts on it, and nothing is removed that the build did not make.

Oracles: catkin_pkg's package-name rule as colcon-ros applies it (catkin_pkg/package.py,
Package.validate: ``^[a-zA-Z0-9][a-zA-Z0-9_-]*$``, else 'Package name "X" does not follow naming
conventions'), REP 144's rules as the REP states them, setuptools' install_data layout (a plain
file to the prefix, a (folder, files) pair to prefix/folder), and the files on disk.
"""

from __future__ import annotations

import os
import shutil
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.ros.build import build_package
from bras_kit.ros.setup_check import (
    CheckedSetup,
    Refusal,
    check_setup,
    follows_rep144,
    name_problem,
)

TUTORIAL = TESTS / "data" / "launch" / "tutorial" / "bras_description"
LIB = "lib/python3.X/site-packages"


@pytest.fixture
def package(tmp_path) -> Path:
    root = tmp_path / "ws" / "src" / "bras_description"
    shutil.copytree(TUTORIAL, root)
    return root


def checked(root: Path, **setup) -> CheckedSetup | Refusal:
    return check_setup({"name": "bras_description", **setup}, str(root), manifest_name="bras_description",
                       setup_source=(root / "setup.py").read_text(), python_lib=LIB)


@pytest.mark.parametrize("name", ["bras_description", "bras-description", "Bras", "a", "2d_arm"])
def test_names_catkin_accepts_are_accepted(name):
    assert name_problem(name) is None


@pytest.mark.parametrize("name", ["", "../x", "bras/description", "/home/x/x", ".hidden", "-x", "a b", "bras.x",
                                  "x\n"])
def test_names_catkin_refuses_are_refused_in_its_words(name):
    words = name_problem(name)
    assert words in ("Package name must not be empty", f'Package name "{name}" does not follow naming conventions')


@pytest.mark.parametrize(("name", "rep144"), [("bras_description", True), ("bras__description", False),
                                              ("Bras", False), ("2d_arm", False), ("b", False),
                                              ("bras-description", False)])
def test_rep_144_is_lower_case_single_underscores_from_a_letter(name, rep144):
    assert follows_rep144(name) is rep144


def test_the_tutorials_setup_gives_the_layout_setuptools_gives(package):
    record = checked(package, packages=["bras_description"], data_files=[
        ["share/ament_index/resource_index/packages", ["resource/bras_description"]],
        ["share/bras_description", ["package.xml"]], "setup.cfg"],
        entry_points={"console_scripts": ["animation = bras_description.animation:main"]})
    assert isinstance(record, CheckedSetup)
    assert [(i.target, i.source) for i in record.installed] == [
        ("share/ament_index/resource_index/packages/bras_description", "resource/bras_description"),
        ("share/bras_description/package.xml", "package.xml"), ("setup.cfg", "setup.cfg")]
    assert {i.target for i in record.modules} == {f"{LIB}/bras_description/__init__.py",
                                                 f"{LIB}/bras_description/animation.py"}
    assert record.console_scripts == (("animation", "bras_description.animation", "main"),)


@pytest.mark.parametrize(("setup", "kind"), [
    ({"name": "../../x"}, "name"),
    ({"data_files": [["/etc", ["package.xml"]]]}, "outside"),
    ({"data_files": [["share/../..", ["package.xml"]]]}, "outside"),
    ({"data_files": [["share/x", ["/etc/passwd"]]]}, "source"),
    ({"data_files": [["share/x", ["../../etc/passwd"]]]}, "source"),
    ({"data_files": [["share/x", ["nope.urdf"]]]}, "missing_source"),
    ({"data_files": [["share/x", ["urdf"]]]}, "missing_source"),  # a folder: setuptools' "not a regular file"
    ({"data_files": "urdf/bras.urdf"}, "value"),
    ({"packages": ["../evil"]}, "module"),
    ({"packages": ["bras_description"], "package_dir": {"": "../.."}}, "source"),
    ({"scripts": ["/bin/sh"]}, "source"),
    ({"entry_points": {"console_scripts": ["x = os;import shutil:main"]}}, "entry_point"),
    ({"entry_points": {"console_scripts": ["../../x = bras_description.animation:main"]}}, "entry_point"),
    ({"entry_points": {"console_scripts": ["x = bras_description.animation"]}}, "entry_point"),
])
def test_each_untrusted_value_is_refused_with_its_kind(package, setup, kind):
    record = checked(package, **setup)
    assert isinstance(record, Refusal) and record.kind == kind


def test_a_refused_name_is_shown_at_its_line_of_setup_py(package):
    (package / "setup.py").write_text((package / "setup.py").read_text().replace(
        "    name=package_name,", "    name='../../x',"))
    record = checked(package, name="../../x")
    assert isinstance(record, Refusal) and (record.file, record.line) == ("setup.py", 8)


def test_a_name_missing_from_setup_is_package_xmls_and_checked_there(package):
    record = check_setup({"name": None}, str(package), manifest_name="bras/x", setup_source="", python_lib=LIB)
    assert isinstance(record, Refusal) and (record.kind, record.file) == ("name", "package.xml")


# ------------------------------------------------------------------ what the build removes


def test_a_previous_build_is_replaced(package, tmp_path):
    base = tmp_path / "ws" / "install"
    assert build_package(str(package), str(base)).failure is None
    (base / "bras_description" / "stale.txt").write_text("from the last build")
    assert build_package(str(package), str(base)).failure is None
    assert not (base / "bras_description" / "stale.txt").exists()


def test_a_folder_that_is_not_an_install_prefix_is_never_removed(package, tmp_path):
    base = tmp_path / "ws" / "install"
    (base / "bras_description").mkdir(parents=True)
    (base / "bras_description" / "thesis.tex").write_text("months of work")
    record = build_package(str(package), str(base))
    assert record.failure is not None and record.failure.kind == "prefix"
    assert (base / "bras_description" / "thesis.tex").read_text() == "months of work"


def test_a_prefix_that_is_a_link_is_never_followed_nor_removed(package, tmp_path):
    base, home = tmp_path / "ws" / "install", tmp_path / "home"
    (home / "share" / "colcon-core" / "packages").mkdir(parents=True)
    (home / "share" / "colcon-core" / "packages" / "bras_description").write_text("")  # looks like a prefix
    base.mkdir(parents=True)
    (base / "bras_description").symlink_to(home)
    record = build_package(str(package), str(base))
    assert record.failure is not None and record.failure.kind == "prefix"
    assert (home / "share" / "colcon-core" / "packages" / "bras_description").exists()
    assert os.listdir(home) == ["share"]


def test_a_file_and_a_folder_of_one_name_stop_the_build_as_data(package, tmp_path):
    (package / "setup.py").write_text(
        "from setuptools import setup\n"
        "setup(name='bras_description', data_files=[\n"
        "    ('share/x', ['package.xml']),\n"
        "    ('share/x/package.xml', ['setup.cfg']),\n"
        "])\n")
    record = build_package(str(package), str(tmp_path / "install"))
    assert record.failure is not None and record.failure.kind == "install"
    assert record.failure.colcon[-1] == "Failed   <<< bras_description [exited with code 1]"
    # the half-made prefix carries colcon's marker: the next build replaces it
    (package / "setup.py").write_text("from setuptools import setup\nsetup(name='bras_description')\n")
    assert build_package(str(package), str(tmp_path / "install")).failure is None


def test_a_console_script_is_written_from_checked_names_only(package, tmp_path):
    record = build_package(str(package), str(tmp_path / "install"))
    script = (tmp_path / "install" / "bras_description" / "lib" / "bras_description" / "animation").read_text()
    assert record.failure is None
    assert script.splitlines()[-2:] == ["from bras_description.animation import main", "sys.exit(main())"]
