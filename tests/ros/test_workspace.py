"""The tutorial's commands typed where the tutorial types them: in the colcon workspace
(~/ros2_cellule_ws, packages in src/) or a folder below it, bras-kit build, launch PKG FILE and
run PKG EXE find the packages by name, build them all, and resolve launch includes and share
directories across packages.

Oracles: colcon's package discovery (colcon-recursive-crawl's recursive_crawl.py, lines 60-83:
a package stops the walk, hidden folders are skipped; colcon-core's COLCON_IGNORE and colcon-ros's
AMENT_IGNORE/CATKIN_IGNORE) and its topological order; ros2launch's get_share_file_path_from_package
(ros2launch/api/api.py, Jazzy lines 39-64: any file of that name in the share folder); the
workspace's own files (the joints of bras_description's URDF, read here with ElementTree; the
pilote node's 0.5 sin(t) at its 20 Hz ticks)."""

from __future__ import annotations

import math
import re
import shutil
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import pytest
from paths import TESTS

DATA = TESTS / "data"
TUTORIAL = DATA / "launch" / "tutorial" / "bras_description"
BRINGUP = DATA / "workspace" / "cellule_bringup"
ORDER = DATA / "workspace" / "ordre"


@pytest.fixture()
def workspace(tmp_path: Path) -> Path:
    """~/ros2_cellule_ws as the tutorial leaves it, plus a second package whose launch file
    includes bras_description's, and a package colcon is told to ignore."""
    root = tmp_path / "ros2_cellule_ws"
    shutil.copytree(TUTORIAL, root / "src" / "bras_description")
    shutil.copytree(BRINGUP, root / "src" / "cellule_bringup")
    shutil.copytree(TUTORIAL, root / "src" / "archives" / "bras_description")
    (root / "src" / "archives" / "COLCON_IGNORE").touch()
    return root


@pytest.fixture(autouse=True)
def private_runtime(tmp_path, monkeypatch):
    """A bus folder of this test's own, domain 0: no launch of another test is joined."""
    runtime = tmp_path / "runtime"
    runtime.mkdir(mode=0o700)
    monkeypatch.setenv("XDG_RUNTIME_DIR", str(runtime))
    monkeypatch.delenv("ROS_DOMAIN_ID", raising=False)
    return runtime


def _cli(cwd: Path, *argv: str, timeout: float = 300) -> subprocess.CompletedProcess:
    """bras-kit typed in a terminal at ``cwd``."""
    return subprocess.run([sys.executable, "-m", "bras_kit", *argv], cwd=cwd, capture_output=True, text=True,
                          timeout=timeout)


def _urdf_joints() -> list[str]:
    root = ET.parse(TUTORIAL / "urdf" / "bras.urdf").getroot()
    return [j.get("name") for j in root.iter("joint") if j.get("type") != "fixed"]


# ------------------------------------------------------------------ discovery, as colcon


def test_packages_are_found_as_colcon_finds_them_and_ordered_by_their_dependencies():
    from bras_kit.ros.workspace import find_workspace

    found = find_workspace(str(ORDER / "src" / "appli"))
    assert found is not None and found.root == str(ORDER)
    # appli depends on zeta_outils: built after it although its name comes first; vieux (COLCON_IGNORE),
    # garde (AMENT_IGNORE) and cache_pkg (a hidden folder) are not packages of the workspace
    assert found.names == ["zeta_outils", "appli"]
    assert found.package("appli").depends == ("rclpy", "zeta_outils")


def test_no_workspace_above_a_folder_without_src(tmp_path):
    from bras_kit.ros.workspace import find_workspace

    (tmp_path / "a" / "b").mkdir(parents=True)
    assert find_workspace(str(tmp_path / "a" / "b")) is None


# ------------------------------------------------------------------ bras-kit build


@pytest.mark.parametrize(("lang", "below", "said"), [
    ("en", "", "install tree: "),
    ("fr", "src/cellule_bringup/cellule_bringup", "arborescence d’installation : "),
])
def test_build_from_the_root_or_below_builds_every_package_in_dependency_order(workspace, lang, below, said):
    code = _cli(workspace / below, "build", "--lang", lang)
    assert code.returncode == 0, code.stdout + code.stderr
    lines = code.stdout.splitlines()
    assert [line for line in lines if line.startswith(("Starting", "Finished", "Summary"))] == [
        "Starting >>> bras_description", "Finished <<< bras_description",
        "Starting >>> cellule_bringup", "Finished <<< cellule_bringup", "Summary: 2 packages finished"]
    assert lines[-1] == said + str(workspace / "install")
    assert sorted(p.name for p in (workspace / "install").iterdir() if p.is_dir()) == ["bras_description",
                                                                                      "cellule_bringup"]
    assert (workspace / "install" / "cellule_bringup" / "share" / "cellule_bringup" / "launch" / "cellule.py").is_file()


def test_a_failed_build_claims_no_install_tree(workspace):
    setup = workspace / "src" / "cellule_bringup" / "setup.py"
    setup.write_text(setup.read_text().replace("glob('launch/*.py')", "['launch/absent.py']"))
    code = _cli(workspace, "build", "--lang", "en")
    assert code.returncode == 1
    assert "Finished <<< bras_description" in code.stdout
    assert "error: can't copy 'launch/absent.py': doesn't exist or not a regular file" in code.stdout
    assert code.stdout.splitlines()[-2:] == ["Summary: 1 package finished", "  1 package failed: cellule_bringup"]
    assert "install tree" not in code.stdout


@pytest.mark.parametrize(("lang", "command", "below", "said"), [
    ("en", ("build",), "", "have one name"),
    ("fr", ("build",), "src/bras_description/urdf", "portent le même nom"),
    ("en", ("launch", "bras_description", "affichage.launch.py", "--no-page"), "src", "have one name"),
    ("fr", ("run", "bras_description", "animation", "--duration", "1"), "", "portent le même nom"),
])
def test_two_packages_of_one_name_are_refused_as_colcon_refuses_them(workspace, lang, command, below, said):
    """A copy of bras_description kept in src/ beside it (colcon-core's get_packages: "Duplicate
    package names not supported", listing each folder; it builds none of them). With an empty
    COLCON_IGNORE in the copy, the workspace builds again."""
    shutil.copytree(TUTORIAL, workspace / "src" / "bras_description_copie")
    code = _cli(workspace / below, *command, "--lang", lang)
    assert code.returncode == 2, code.stdout + code.stderr
    assert said in code.stderr and "Traceback" not in code.stderr
    assert "bras_description (src/bras_description, src/bras_description_copie)" in code.stderr
    assert "COLCON_IGNORE" in code.stderr
    assert not (workspace / "install").exists()
    (workspace / "src" / "bras_description_copie" / "COLCON_IGNORE").touch()
    assert _cli(workspace / below, "build", "--lang", lang).returncode == 0


# ------------------------------------------------------------------ bras-kit launch PKG FILE


@pytest.mark.parametrize(("lang", "below", "started"), [
    ("en", "", "[INFO] started /robot_state_publisher"),
    ("fr", "src/cellule_bringup/launch", "[INFO] démarré /robot_state_publisher"),
])
def test_launch_by_name_includes_the_launch_file_of_the_other_package(workspace, lang, below, started):
    """cellule.py (not *.launch.py: ros2launch takes any file) includes bras_description's
    affichage.launch.py through get_package_share_directory, and starts pilote, which reads
    bras_description's URDF the same way: all of the workspace is built."""
    code = _cli(workspace / below, "launch", "cellule_bringup", "cellule.py", "--no-page", "--duration", "1",
                "--lang", lang)
    assert code.returncode == 0, code.stdout + code.stderr
    assert "ros2 launch cellule_bringup cellule.py" in code.stdout
    assert started in code.stdout  # robot_state_publisher comes from the included launch file
    assert re.search(r"/joint_states ?: 20 messages", code.stdout)  # pilote ran: bras_description's share found
    assert "PackageNotFoundError" not in code.stdout + code.stderr and "Traceback" not in code.stderr


def test_a_launch_file_found_twice_in_the_share_folder_is_refused_as_ros2_launch_refuses_it(workspace):
    package = workspace / "src" / "cellule_bringup"
    (package / "config").mkdir()
    shutil.copy(package / "launch" / "cellule.py", package / "config" / "cellule.py")
    setup = package / "setup.py"
    setup.write_text(setup.read_text().replace(
        "glob('launch/*.py')),", "glob('launch/*.py')),\n        (os.path.join('share', package_name, 'config'), "
        "['config/cellule.py']),"))
    code = _cli(workspace, "launch", "cellule_bringup", "cellule.py", "--no-page", "--lang", "en")
    assert code.returncode == 2
    assert "file 'cellule.py' was found more than once in the share directory of package 'cellule_bringup'" \
        in code.stderr


@pytest.mark.parametrize("lang", ["en", "fr"])
def test_an_unknown_package_lists_the_workspace_packages_and_the_hint_is_no_repeat(workspace, lang):
    code = _cli(workspace, "launch", "bras_descripton", "affichage.launch.py", "--lang", lang)
    assert code.returncode == 2
    assert "'bras_descripton'" in code.stderr and "bras_description, cellule_bringup" in code.stderr
    assert "bras-kit launch bras_descripton" not in code.stderr and "Traceback" not in code.stderr
    if lang == "fr":
        assert "introuvable" in code.stderr


@pytest.mark.parametrize("lang", ["en", "fr"])
def test_outside_a_workspace_the_hint_says_where_to_type_the_command(tmp_path, lang):
    here = tmp_path / "ros2_cellule_ws_elsewhere"
    here.mkdir()
    code = _cli(here, "launch", "bras_description", "affichage.launch.py", "--lang", lang)
    assert code.returncode == 2
    assert "cd ~/ros2_cellule_ws" in code.stderr
    assert "bras-kit launch bras_description" not in code.stderr and "Traceback" not in code.stderr


# ------------------------------------------------------------------ bras-kit run PKG EXE


@pytest.mark.parametrize(("lang", "below"), [("en", ""), ("fr", "src/bras_description/urdf")])
def test_run_by_name_finds_the_share_directory_of_the_other_package(workspace, lang, below, tmp_path):
    """pilote publishes the joints of bras_description's URDF, found with get_package_share_directory:
    bras_description is built beside it."""
    from bras_kit.motion.states_io import read_states

    out = tmp_path / "etats.csv"
    code = _cli(workspace / below, "run", "cellule_bringup", "pilote", "--duration", "1", "--quiet", "-o", str(out),
                "--lang", lang)
    assert code.returncode == 0, code.stdout + code.stderr
    states = read_states(str(out))
    assert states.names == _urdf_joints() == ["epaule", "coude"]
    assert len(states.times) == 20
    assert states.positions[:, 0] == pytest.approx(
        [0.5 * math.sin(0.05 * k) for k in range(1, 21)], abs=1e-9)


def test_run_by_name_from_the_root_uses_the_package_robot(workspace):
    code = _cli(workspace, "run", "bras_description", "animation", "--duration", "1", "--lang", "en")
    assert code.returncode == 0, code.stdout + code.stderr
    assert "built-in tutorial arm" not in code.stderr  # the package's own URDF, found by name
    assert "bras_description animation" in code.stderr


# ------------------------------------------------------------------ source install/setup.bash


@pytest.mark.parametrize("lang", ["en", "fr"])
def test_after_source_install_setup_bash_a_package_is_found_from_anywhere(workspace, tmp_path, lang):
    """The tutorial's `colcon build` then `source install/setup.bash`: bash itself sources the file
    bras-kit build wrote; from a folder outside the workspace, launch finds the package by name."""
    assert _cli(workspace, "build").returncode == 0
    elsewhere = tmp_path / "ailleurs"
    elsewhere.mkdir()
    script = (f"source {workspace}/install/setup.bash && source {workspace}/install/setup.bash && "
              f'echo "$AMENT_PREFIX_PATH" && cd {elsewhere} && {sys.executable} -m bras_kit launch cellule_bringup '
              f"cellule.py --no-page --duration 1 --lang {lang}")
    done = subprocess.run(["bash", "-c", script], capture_output=True, text=True, timeout=300)
    assert done.returncode == 0, done.stdout + done.stderr
    prefixes = done.stdout.splitlines()[0].split(":")
    assert prefixes[:2] == [str(workspace / "install" / "cellule_bringup"), str(workspace / "install" / "bras_description")]
    assert len(prefixes) == len(set(prefixes))  # sourced twice, each prefix once
    assert "ros2 launch cellule_bringup cellule.py" in done.stdout


def test_a_setup_bash_colcon_wrote_is_left_as_it_is(workspace):
    (workspace / "install").mkdir()
    colcon = "# generated from colcon_bash/shell/template/prefix_chain.bash.em\n"
    (workspace / "install" / "setup.bash").write_text(colcon)
    assert _cli(workspace, "build").returncode == 0
    assert (workspace / "install" / "setup.bash").read_text() == colcon


def test_a_setup_bash_planted_as_a_link_is_never_written_through(workspace, tmp_path):
    outside = tmp_path / "bashrc"
    (workspace / "install").mkdir()
    (workspace / "install" / "setup.bash").symlink_to(outside)  # dangling: writing through it would make it
    assert _cli(workspace, "build").returncode == 0
    assert not outside.exists() and (workspace / "install" / "setup.bash").is_symlink()
