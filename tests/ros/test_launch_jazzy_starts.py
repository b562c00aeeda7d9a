"""Launch files that start on ROS 2 Jazzy start here too (issue 52, item 2): no error and no warning
from ``bras-kit validate PKG`` for the styles learners copy, and a path is compared as the system
resolves it, never as text.

Every file is tests/data/launch/jazzy_starts/bras_description/launch/<case> (a few more, kept aside
while the rules were changed, in jazzy_starts/unseen/). Each one's first comment says what it does;
why each starts on Jazzy, from the Jazzy sources: ``os.path.join`` (and ``PathJoinSubstitution``,
whose ``perform`` is ``os.path.join`` of its parts: launch 3.4.3
substitutions/path_join_substitution.py) gives the system a path whose './', '..' and doubled
slashes it resolves (path_resolution(7)); ``os.path.join(get_package_share_directory(PKG))`` of one
part is that part; xacro.process_file reads the installed file wherever the install tree is;
rviz_common's VisualizationFrame::loadDisplayConfig (visualization_frame.cpp:675) logs a file it
cannot load and loads its default configuration; ParameterValue(..., value_type=str) and
launch_xml's ``type="str"`` keep the xacro output as text (the words of the rest are in
tests/data/launch/fidelity/JAZZY.md, obtained from the real sources).
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from paths import TESTS

from bras_kit.validate.package import validate_package

CORPUS = TESTS / "data" / "launch" / "jazzy_starts"
PACKAGE = CORPUS / "bras_description"
# a file that includes another is checked with it, as ros2 launch reads them
INCLUDES = {"include_rsp.launch.py": ["rsp.launch.py"], "include_find_package_share.launch.py": ["rsp.launch.py"]}
INCLUDED = {name for names in INCLUDES.values() for name in names}
SEEN = sorted(n for n in os.listdir(PACKAGE / "launch") if n not in INCLUDED)
UNSEEN = sorted(os.listdir(CORPUS / "unseen"))


def package_with(tmp_path: Path, name: str, folder: Path = PACKAGE / "launch") -> Path:
    """A copy of the corpus package holding the launch file ``name`` (and the files it includes) only."""
    dest = tmp_path / "bras_description"
    shutil.copytree(PACKAGE, dest, ignore=shutil.ignore_patterns("launch"))
    (dest / "launch").mkdir()
    shutil.copy(folder / name, dest / "launch" / name)
    for included in INCLUDES.get(name, []):
        shutil.copy(PACKAGE / "launch" / included, dest / "launch" / included)
    return dest


def errors_and_warnings(root: Path) -> list[tuple[str, str, str, int | None, str]]:
    return [(f.code, f.severity, os.path.relpath(r.path, root), f.line, f.text("en"))
            for r in validate_package(str(root), launch=True) for f in r.findings
            if f.severity in ("error", "warning")]


@pytest.mark.parametrize("name", SEEN)
def test_a_launch_file_that_starts_on_jazzy_gets_no_error_and_no_warning(tmp_path, name):
    assert errors_and_warnings(package_with(tmp_path, name)) == []


@pytest.mark.parametrize("name", UNSEEN)
def test_a_launch_file_that_starts_on_jazzy_unseen_cases(tmp_path, name):
    assert errors_and_warnings(package_with(tmp_path, name, CORPUS / "unseen")) == []


def test_the_issues_launch_file_passes_the_command_line(tmp_path):
    """xacro.process_file(os.path.join(get_package_share_directory(...), 'urdf', 'bras.urdf')) and a -d
    to a configuration the package does not have: exit 0, RViz's defaults said as advice. Run as on a
    machine with no $XDG_RUNTIME_DIR nor $TMPDIR (a container, a CI runner): the package is then built
    in /dev/shm where it has room (bras_kit.trust.scratch), whose installed URDF xacro refused to read."""
    root = package_with(tmp_path, "xacro_process_file.launch.py")
    env = {k: v for k, v in os.environ.items() if k not in ("XDG_RUNTIME_DIR", "TMPDIR", "TEMP", "TMP")}
    done = subprocess.run([sys.executable, "-m", "bras_kit", "validate", str(root), "--format", "json"],
                          capture_output=True, text=True, encoding="utf-8", timeout=300, env=env)
    assert done.returncode == 0, done.stdout[-2000:] + done.stderr[-2000:]
    found = [(f["code"], f["severity"]) for r in json.loads(done.stdout)["files"] for f in r["findings"]]
    assert ("BK613", "info") in found
    assert not [f for f in found if f[1] in ("error", "warning")]


def test_a_share_folder_joined_alone_then_joined_again_is_the_same_folder(tmp_path):
    """os.path.join(get_package_share_directory(PKG)) then os.path.join(that, 'urdf', ...): the issue's
    'share/bras_description//urdf/bras.urdf' was this path read as text."""
    from bras_kit.ros.package import share_targets
    from bras_kit.validate.package import Package

    root = package_with(tmp_path, "xacro_pretty.launch.py")
    opened = [share.relative for _, share, _ in share_targets(Package(str(root)))]
    assert opened == ["urdf/bras.urdf.xacro"]


@pytest.mark.parametrize(("parts", "expected"), [
    (["urdf", "bras.urdf"], "urdf/bras.urdf"),
    (["urdf/", "bras.urdf"], "urdf/bras.urdf"),
    (["./urdf", "bras.urdf"], "urdf/bras.urdf"),
    (["urdf//bras.urdf"], "urdf/bras.urdf"),
    (["launch", "..", "urdf", "bras.urdf"], "urdf/bras.urdf"),
    (["launch/../urdf/./bras.urdf"], "urdf/bras.urdf"),
    (["urdf", "", "bras.urdf"], "urdf/bras.urdf"),
])
def test_share_paths_are_normalised_as_the_system_resolves_them(tmp_path, parts, expected):
    """Oracle: os.path.join over a real share folder, resolved by the file system (os.path.realpath)."""
    from bras_kit.ros.staticpy import Share, ShareFile, join_paths

    share = tmp_path / "share" / "bras_description"
    (share / "urdf").mkdir(parents=True)
    (share / "launch").mkdir()
    (share / "urdf" / "bras.urdf").write_text("<robot/>", encoding="utf-8")
    real = os.path.realpath(os.path.join(str(share), *parts))
    assert os.path.relpath(real, share).replace(os.sep, "/") == expected
    assert join_paths([Share("bras_description"), *parts]) == ShareFile("bras_description", expected)


@pytest.mark.parametrize("parts", [["..", "autre", "urdf", "x.urdf"], ["urdf", "..", "..", "x.urdf"]])
def test_a_path_that_leaves_the_share_folder_is_not_judged(parts):
    """Where '..' out of share/PKG lands depends on how the workspace was installed (merged or not)."""
    from bras_kit.ros.staticpy import UNKNOWN, Share, join_paths

    assert join_paths([Share("bras_description"), *parts]) is UNKNOWN


def test_an_absolute_part_drops_the_share_folder_as_os_path_join_does():
    from bras_kit.ros.staticpy import Share, join_paths

    assert join_paths([Share("bras_description"), "/urdf/bras.urdf"]) == os.path.join("/x", "/urdf/bras.urdf")


def test_an_rviz_configuration_the_package_holds_but_does_not_install_is_advice(tmp_path):
    """RViz given -d a file that is not installed opens its defaults, and the launch starts: BK613
    (info) says what RViz will show and which data_files entry is missing; no BK602 error."""
    root = package_with(tmp_path, "open_read.launch.py")
    setup = root / "setup.py"
    text = setup.read_text(encoding="utf-8")
    line = "        (os.path.join('share', package_name, 'rviz'), glob('rviz/*')),\n"
    assert text.count(line) == 1
    setup.write_text(text.replace(line, ""), encoding="utf-8")
    assert errors_and_warnings(root) == []
    (finding,) = [f for r in validate_package(str(root), launch=True) for f in r.findings if f.code == "BK613"]
    assert (finding.severity, finding.variant) == ("info", "not_installed")
    assert "rviz/bras.rviz, which setup.py does not install" in finding.text("en")
    assert "que setup.py n'installe pas" in finding.text("fr")
    assert finding.hint_text("en") == "add rviz/bras.rviz to data_files in setup.py, then run colcon build again"


def test_a_file_in_the_in_memory_scratch_folder_is_readable_by_xacro(tmp_path):
    """bras-kit builds a package to evaluate it in /dev/shm where it can: the installed URDF there is a
    regular file, which xacro.process_file in the launch file must read (it was refused as a system file)."""
    from bras_kit.model.xacro_files import check_readable_file

    shm = Path("/dev/shm")
    assert shm.is_dir()
    fd, path = __import__("tempfile").mkstemp(suffix=".urdf", dir=shm)
    try:
        os.write(fd, b"<robot name='bras'/>")
        os.close(fd)
        check_readable_file(path)  # raises on a refused file
    finally:
        os.unlink(path)


def test_a_device_is_still_refused(tmp_path):
    from bras_kit.core.errors import BrasKitError
    from bras_kit.model.xacro_files import check_readable_file

    for path in ("/dev/null", "/proc/self/status"):
        with pytest.raises(BrasKitError):
            check_readable_file(path)


def test_a_file_missing_behind_a_doubled_slash_is_named_as_a_package_path(tmp_path):
    """Jazzy fails on a file that is nowhere (FileNotFoundError), doubled slash or not: BK631 names
    it as the package path to check, urdf/absente.urdf, not '/urdf/absente.urdf'."""
    launch = tmp_path / "absente.launch.py"
    launch.write_text((PACKAGE / "launch" / "trailing_slashes.launch.py").read_text(encoding="utf-8")
                      .replace("os.path.join(share, 'urdf/', 'bras.urdf')", "share + '/urdf/absente.urdf'"),
                      encoding="utf-8")
    root = package_with(tmp_path, "absente.launch.py", tmp_path)
    (finding,) = [f for r in validate_package(str(root), launch=True) for f in r.findings if f.code == "BK631"]
    assert finding.variant == "no_file" and finding.data["path"] == "urdf/absente.urdf"
