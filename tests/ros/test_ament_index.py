"""The ament_index_python stand-in (bras_kit/ros/standin/ament_index_python) against
ament/ament_index 1.8.1 (Jazzy), cited by file and line: what a learner's launch file or node
gets from it on an install tree laid out here by hand (share/ament_index/resource_index/packages/PKG
marks an installed package, as colcon's ament_python build writes it)."""

from __future__ import annotations

import warnings
from pathlib import Path

import pytest

from bras_kit.ros.standin import ament_index_python as index
from bras_kit.ros.standin.ament_index_python import packages


def _install(prefix: Path, *names: str, share: bool = True) -> Path:
    for name in names:
        marker = prefix / "share" / "ament_index" / "resource_index" / "packages" / name
        marker.parent.mkdir(parents=True, exist_ok=True)
        marker.write_text("")
        if share:
            (prefix / "share" / name).mkdir(parents=True, exist_ok=True)
    return prefix


@pytest.fixture()
def prefixes(tmp_path, monkeypatch):
    first = _install(tmp_path / "install" / "bras_description", "bras_description")
    second = _install(tmp_path / "opt" / "ros", "bras_description", "robot_state_publisher")
    missing = tmp_path / "not_built"
    monkeypatch.setenv("AMENT_PREFIX_PATH", f"{first}:{missing}::{second}")
    return first, second, missing


def test_the_first_prefix_of_ament_prefix_path_that_lists_the_package_wins(prefixes):
    first, second, _ = prefixes
    # resources.py:81-91: the prefixes in order, the first holding the marker
    assert index.get_package_prefix("bras_description") == str(first)
    assert index.get_package_share_directory("bras_description") == str(first / "share" / "bras_description")
    assert index.get_package_share_path("robot_state_publisher") == second / "share" / "robot_state_publisher"
    assert index.get_packages_with_prefixes() == {"bras_description": str(first),
                                                  "robot_state_publisher": str(second)}


def test_an_unknown_package_is_a_key_error_naming_the_existing_prefixes(prefixes):
    first, second, _ = prefixes
    # packages.py:27 (a KeyError), 60-63; search_paths.py:33-34 (folders that do not exist are left out)
    with pytest.raises(KeyError) as raised:
        index.get_package_share_directory("bras_descripton")
    assert type(raised.value) is index.PackageNotFoundError
    assert raised.value.args[0] == f"package 'bras_descripton' not found, searching: {[str(first), str(second)]}"


@pytest.mark.parametrize("name", ["b", "bras description", "_bras", "bras/description", "brás"])
def test_a_name_outside_rep_127_is_a_value_error(prefixes, name):
    # packages.py:56-58: [a-zA-Z0-9][a-zA-Z0-9_-]+, ASCII only
    with pytest.raises(ValueError, match=f"^'{name}' is not a valid package name$"):
        index.get_package_prefix(name)


def test_a_missing_share_folder_is_a_warning_not_an_error(tmp_path, monkeypatch):
    prefix = _install(tmp_path / "install", "bras_description", share=False)
    monkeypatch.setenv("AMENT_PREFIX_PATH", str(prefix))
    share = prefix / "share" / "bras_description"
    # packages.py:83-84 and 104-105
    with pytest.warns(UserWarning, match=r"^Share directory for bras_description \(.*\) does not exist\.$"):
        assert index.get_package_share_directory("bras_description") == str(share)
    with pytest.warns(UserWarning, match=r"^Share path for bras_description \(.*\) does not exist\.$"):
        index.get_package_share_path("bras_description")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert packages.get_package_share_directory("bras_description", print_warning=False) == str(share)


@pytest.mark.parametrize("value", [None, ""])
def test_no_ament_prefix_path_is_an_environment_error(monkeypatch, value):
    if value is None:
        monkeypatch.delenv("AMENT_PREFIX_PATH", raising=False)
    else:
        monkeypatch.setenv("AMENT_PREFIX_PATH", value)
    # search_paths.py:29-31 (EnvironmentError is OSError)
    with pytest.raises(OSError, match="^Environment variable 'AMENT_PREFIX_PATH' is not set or empty$"):
        index.get_package_prefix("bras_description")


def test_resources_leave_out_folders_and_dot_files_and_refuse_separators(prefixes):
    first, _, _ = prefixes
    packages_folder = first / "share" / "ament_index" / "resource_index" / "packages"
    (packages_folder / ".hidden").write_text("")
    (packages_folder / "a_folder").mkdir()
    (packages_folder.parent / ".cache").mkdir()
    (packages_folder / "bras_description").write_text("the marker's text")
    # resources.py:113-121 and 134-140
    assert set(index.get_resources("packages")) == {"bras_description", "robot_state_publisher"}
    assert index.get_resource_types() == {"packages"}
    assert index.get_resource("packages", "bras_description") == ("the marker's text", str(first))
    assert index.has_resource("packages", "nothing") is False
    with pytest.raises(LookupError, match="^Could not find the resource 'nothing' of type 'packages'$"):
        index.get_resource("packages", "nothing")
    # resources.py:74-80
    with pytest.raises(index.InvalidResourceNameError, match="^Resource name 'a/b' is invalid$"):
        index.get_resource("packages", "a/b")
    with pytest.raises(index.InvalidResourceTypeNameError, match=r"^Resource type 'p\\q' is invalid$"):
        index.get_resources("p\\q")
