"""bras-kit launch beside the learner's own install/ (issue 55): ros2 launch reads the workspace's
install tree, never the sources, so a file saved since the last ``colcon build`` is not used until
the learner builds again (the tutorial's "recompilez"). bras-kit launch builds the sources as they
are, and says when the learner's install/ is older; and ROS's errors name that install/, never
bras-kit's own temporary tree.

Oracle: the real colcon (tests/realcolcon.py) builds the learner's install/: the tree ros2 launch
would read. Unchanged sources must then say nothing (bras-kit's build and colcon's agree file for
file); a --symlink-install tree follows the sources by itself."""

from __future__ import annotations

import shutil
import subprocess
import sys
from pathlib import Path

import pytest
from paths import TESTS
from realcolcon import colcon_build

pytestmark = pytest.mark.slow

TUTORIAL = TESTS / "data" / "launch" / "tutorial" / "bras_description"
STALE = "ros2 launch would still use that old install until you run colcon build again"


def _workspace(tmp_path: Path) -> Path:
    workspace = tmp_path / "ros2_cellule_ws"
    shutil.copytree(TUTORIAL, workspace / "src" / "bras_description")
    return workspace


def _launch(workspace: Path) -> subprocess.CompletedProcess[str]:
    return subprocess.run([sys.executable, "-m", "bras_kit", "launch", "bras_description", "--no-page",
                           "--duration", "1"], cwd=workspace, capture_output=True, text=True, timeout=300)


# (colcon build's options, the file changed after it, whether ros2 launch would read an old copy)
CASES = {
    "unchanged": ((), None, False),
    "urdf_saved": ((), "urdf/bras.urdf", True),
    "node_saved": ((), "bras_description/animation.py", True),
    "launch_file_saved": ((), "launch/affichage.launch.py", True),
    "symlinked_urdf_saved": (("--symlink-install",), "urdf/bras.urdf", False),
}


@pytest.mark.parametrize("case", list(CASES))
def test_a_source_saved_since_colcon_build_is_said_to_be_unused_by_ros2_launch(tmp_path, case):
    options, changed, stale = CASES[case]
    workspace = _workspace(tmp_path)
    built = colcon_build(workspace, *options)
    assert built.returncode == 0, built.stdout + built.stderr
    if changed is not None:
        path = workspace / "src" / "bras_description" / changed
        path.write_text(path.read_text(encoding="utf-8") + "\n# saved after colcon build\n"
                        if path.suffix == ".py" else path.read_text(encoding="utf-8") + "\n<!-- saved -->\n",
                        encoding="utf-8")
    done = _launch(workspace)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "Traceback" not in done.stderr
    assert (STALE in done.stderr) is stale, done.stderr
    if stale:
        named = changed.split("/")[-1]
        line = next(t for t in done.stderr.splitlines() if STALE in t)
        assert str(workspace / "install" / "bras_description") in line and named in line, line


def test_no_colcon_build_yet_says_nothing_of_an_install(tmp_path):
    done = _launch(_workspace(tmp_path))
    assert done.returncode == 0 and STALE not in done.stderr, done.stderr


def test_the_forgotten_data_files_error_names_the_learners_install(tmp_path):
    """setup.py without the urdf/ entry: the launch file's open() fails as ros2 launch says it,
    naming <workspace>/install/bras_description/share/..., the path the learner's machine has."""
    workspace = _workspace(tmp_path)
    setup = workspace / "src" / "bras_description" / "setup.py"
    text = setup.read_text(encoding="utf-8")
    kept = [line for line in text.splitlines(keepends=True) if "'urdf'" not in line]
    setup.write_text("".join(kept), encoding="utf-8")
    done = _launch(workspace)
    said = done.stdout + done.stderr
    assert "No such file or directory" in said, said
    expected = str(workspace / "install" / "bras_description" / "share" / "bras_description" / "urdf" / "bras.urdf")
    assert expected in said, said
    assert "bras-kit-launch-" not in said, said
