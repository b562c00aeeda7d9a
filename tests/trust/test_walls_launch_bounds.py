"""Every launch has a bound on its nodes and on its log: past it the evaluation stops there, and
the learner gets BK631 (too_many_nodes, log_flood) at the line, in English and French.

Categories: many nodes (robot_state_publishers each given the URDF, plain nodes, nodes added by
an OpaqueFunction), a LogInfo flood (many short lines, one huge line, lines in a learner's
loop that catches every Exception). Oracles: the counts written in the launch files here, the
tutorial's launch file (3 nodes, no log) which stays clean, and the clock."""

from __future__ import annotations

import os
import shutil
import time

import pytest
from paths import DATA as DATA_DIR

from bras_kit.ros.launched import launch_package
from bras_kit.validate.package import validate_package

TUTORIAL = os.path.join(DATA_DIR, "launch", "tutorial", "bras_description")
HEAD = ("import os\nfrom launch import LaunchDescription\nfrom launch.actions import LogInfo, OpaqueFunction\n"
        "from launch_ros.actions import Node\nfrom ament_index_python.packages import get_package_share_directory\n\n"
        "def generate_launch_description():\n"
        "    chemin = get_package_share_directory('bras_description')\n"
        "    with open(os.path.join(chemin, 'urdf', 'bras.urdf')) as f:\n"
        "        description = f.read()\n")

CASES = {
    "rsp": HEAD + "    return LaunchDescription([Node(package='robot_state_publisher', executable='robot_state_publisher',"
                  " name=f'rsp{k}', parameters=[{'robot_description': description}]) for k in range(600)])\n",
    "plain": HEAD + "    return LaunchDescription([Node(package='bras_description', executable='animation', name=f'n{k}')"
                    " for k in range(100_000)])\n",
    "opaque": HEAD + "    def more(context):\n        return [Node(package='rviz2', executable='rviz2', name=f'r{k}')"
                     " for k in range(1000)]\n    return LaunchDescription([OpaqueFunction(function=more)])\n",
    "short_lines": HEAD + "    return LaunchDescription([LogInfo(msg='x') for k in range(200_000)])\n",
    "huge_line": HEAD + "    return LaunchDescription([LogInfo(msg='x' * (50 << 20))])\n",
    "caught": HEAD + "    actions = []\n    for k in range(50_000):\n        try:\n"
                     "            actions.append(LogInfo(msg='y' * 100))\n        except Exception:\n"
                     "            pass\n    return LaunchDescription(actions)\n",
}
VARIANT = {"rsp": "too_many_nodes", "plain": "too_many_nodes", "opaque": "too_many_nodes",
           "short_lines": "log_flood", "huge_line": "log_flood", "caught": "log_flood"}


def package_with(tmp_path, text: str) -> str:
    root = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL, root)
    (root / "launch" / "affichage.launch.py").write_text(text, encoding="utf-8")
    return str(root)


@pytest.mark.parametrize("case", sorted(CASES))
def test_a_launch_past_its_bound_stops_there_quickly(tmp_path, case):
    root = package_with(tmp_path, CASES[case])
    start = time.monotonic()
    result = launch_package(root, str(tmp_path / "install"), "affichage.launch.py")
    seconds = time.monotonic() - start
    assert result.plan is not None and result.plan.failure is not None, result.plan
    assert result.plan.failure.type == "Bound"
    assert len(result.plan.nodes) <= 256 and len(result.plan.logs) <= 10_000
    assert sum(len(entry[1]) for entry in result.plan.logs) <= 1 << 20
    assert seconds < 35, seconds  # under the launch child's 40 s wall clock, which no case reaches


@pytest.mark.parametrize("case", ["rsp", "huge_line"])
def test_the_bound_is_bk631_in_english_and_french(tmp_path, case):
    root = package_with(tmp_path, CASES[case])
    results = validate_package(root, select=["BK631"], launch=True)
    found = [f for r in results for f in r.findings if f.code == "BK631"]
    assert [f.variant for f in found] == [VARIANT[case]], [f.text("en") for f in found]
    english, french = found[0].text("en"), found[0].text("fr")
    if case == "rsp":
        assert "more than 256 nodes" in english and "plus de 256 nœuds" in french
    else:
        assert "more than 10,000 lines or 1 MiB" in english and "1 Mio" in french


def test_the_tutorial_launch_is_within_its_bounds(tmp_path):
    result = launch_package(TUTORIAL, str(tmp_path / "install"), "affichage.launch.py")
    assert result.plan is not None and result.plan.failure is None and len(result.plan.nodes) == 3
    assert result.description is not None
