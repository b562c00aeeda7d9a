"""bras_kit.launcher: ``ros2 launch`` without the CLI (issue 54: the launch's orchestration left
cli/launch.py, so a notebook can launch). The launch a notebook makes is the command's: the
same nodes started, the same findings, and its words go where the caller says, never to the
process's own streams behind its back.

Oracles: what Jazzy's ros2 launch starts for the tutorial's launch file (the node names of
tests/run_cases.py's table, as the real launch answers them), the command's own JSON report in
another process, and the real colcon for the learner's install/."""

from __future__ import annotations

import io
import json
import shutil
import subprocess
import sys

import pytest
from paths import TESTS

TUTORIAL = TESTS / "data" / "launch" / "tutorial" / "bras_description"


def _package(tmp_path):
    package = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL, package)
    return package


def test_a_notebook_launches_the_tutorial_package_as_the_command_does(tmp_path, capsys):
    from bras_kit.launcher import Reporter, launch

    package = _package(tmp_path)
    out, err = io.StringIO(), io.StringIO()
    seen = []

    def evaluated(evaluation, package_paths):
        seen.append((evaluation.checked, evaluation.robot is not None, package_paths))

    launched = launch(str(package), "affichage.launch.py", duration=1, reporter=Reporter("en", out, err),
                      on_evaluated=evaluated)
    # ros2 launch on Jazzy starts the three nodes of the tutorial's launch file, under these names
    assert [n.full_name for n in launched.plan.nodes] == ["/robot_state_publisher", "/joint_state_publisher_gui",
                                                         "/rviz2"]
    assert [link.name for link in launched.evaluation.robot.links] == ["base", "bras", "avant_bras"]
    # the page is handed the evaluation once, with its robot, before the checks are in
    assert len(seen) == 1 and seen[0][:2] == (False, True)
    assert seen[0][2][0].endswith("/install/bras_description/share")  # the meshes, as robot_state_publisher finds them
    assert launched.evaluation.checked and launched.started
    assert out.getvalue().startswith("ros2 launch bras_description affichage.launch.py\n")
    assert "[INFO] started /robot_state_publisher" in out.getvalue()
    captured = capsys.readouterr()
    assert captured.out == "" and captured.err == ""  # nothing behind the caller's back
    # the findings are the command's, as its JSON report gives them from another process
    done = subprocess.run([sys.executable, "-m", "bras_kit", "launch", str(package), "affichage.launch.py",
                           "--no-page", "--json", "--duration", "1"], capture_output=True, text=True, timeout=300)
    assert done.returncode in (0, 1), done.stderr
    report = json.loads(done.stdout)
    command = sorted((f["code"], f.get("line")) for r in report["files"] for f in r["findings"])
    mine = sorted((f.code, f.line) for r in launched.results for f in r.findings)
    assert mine == command
    assert "BK613" in [code for code, _ in mine]  # rviz2 with no configuration: RViz opens empty


def test_a_launch_file_the_package_does_not_install_is_refused_as_ros2_launch_refuses_it(tmp_path):
    from bras_kit.core.errors import ParameterError
    from bras_kit.launcher import Reporter, launch

    with pytest.raises(ParameterError) as refused:
        launch(str(_package(tmp_path)), "absent.launch.py", duration=1, reporter=Reporter("en", io.StringIO(),
                                                                                         io.StringIO()))
    # ros2launch/api/api.py's words (Jazzy), naming the install/ the learner would have
    assert "file 'absent.launch.py' was not found in the share directory of package 'bras_description'" \
        in str(refused.value)
    assert "bras-kit-launch-" not in str(refused.value)


@pytest.mark.slow
def test_the_stale_install_is_part_of_the_evaluation_a_page_reads(tmp_path, monkeypatch):
    """The warning the terminal gives (tests/view/test_launch_stale_install.py) is also the
    evaluation's, so a page says it where the learner looks."""
    from realcolcon import colcon_build

    from bras_kit.launcher import Reporter, launch

    workspace = tmp_path / "ros2_cellule_ws"
    shutil.copytree(TUTORIAL, workspace / "src" / "bras_description")
    built = colcon_build(workspace)
    assert built.returncode == 0, built.stdout + built.stderr
    monkeypatch.chdir(workspace)
    err = io.StringIO()
    current = launch("bras_description", duration=1, reporter=Reporter("en", io.StringIO(), err))
    assert current.evaluation.stale_install is None and "colcon build again" not in err.getvalue()
    urdf = workspace / "src" / "bras_description" / "urdf" / "bras.urdf"
    urdf.write_text(urdf.read_text(encoding="utf-8") + "\n<!-- saved -->\n", encoding="utf-8")
    stale = launch("bras_description", duration=1, reporter=Reporter("en", io.StringIO(), err))
    assert stale.evaluation.stale_install is not None
    assert "share/bras_description/urdf/bras.urdf" in str(stale.evaluation.stale_install)
    assert str(stale.evaluation.stale_install) in err.getvalue()
