"""bras-kit build and launch: the tutorial's package and learner cases (tests/data/launch/<case>/).

Oracles: the install layout colcon + setuptools make from the tutorial's data_files (listed by
hand below), the words of distutils' copy_file, launch/launch_ros (Jazzy) and
robot_state_publisher.cpp cited in bras_kit/ros/, and the URDF file's own text.
"""

from __future__ import annotations

import os
import sys

import pytest
from paths import DATA as DATA_DIR

from bras_kit.ros.build import build_package
from bras_kit.ros.launched import launch_package
from bras_kit.validate.package import Package, validate_package

DATA = os.path.join(DATA_DIR, "launch")


def case(name: str) -> str:
    return os.path.join(DATA, name, "bras_description")


def test_tutorial_package_installs_as_colcon_lays_it_out(tmp_path):
    record = build_package(case("tutorial"), str(tmp_path / "install"))
    assert record.failure is None
    prefix = tmp_path / "install" / "bras_description"
    for target in ("share/ament_index/resource_index/packages/bras_description",
                   "share/bras_description/package.xml", "share/bras_description/urdf/bras.urdf",
                   "share/bras_description/launch/affichage.launch.py", "lib/bras_description/animation",
                   # setuptools' install_lib: lib/pythonX.Y of the Python that runs the build (3.12 on Jazzy)
                   f"lib/python{sys.version_info[0]}.{sys.version_info[1]}/site-packages/bras_description/animation.py"):
        assert (prefix / target).is_file(), target
    assert record.scripts == [("animation", "bras_description.animation", "main")]


def test_tutorial_launch_starts_its_three_nodes_and_feeds_the_urdf(tmp_path):
    result = launch_package(case("tutorial"), str(tmp_path / "install"), "affichage.launch.py")
    assert result.plan is not None and result.plan.failure is None
    assert [(n.package, n.executable, n.line) for n in result.plan.nodes] == [
        ("robot_state_publisher", "robot_state_publisher", 13),
        ("joint_state_publisher_gui", "joint_state_publisher_gui", 15), ("rviz2", "rviz2", 16)]
    with open(os.path.join(case("tutorial"), "urdf", "bras.urdf"), encoding="utf-8") as handle:
        assert result.description == handle.read()
    assert result.problems == []


def test_tutorial_package_has_nothing_above_info():
    results = validate_package(case("tutorial"), select=["BK6"], launch=True)
    assert [f.code for r in results for f in r.findings if f.severity != "info"] == []


def test_docs_style_launch_runs_xacro_and_obeys_conditions(tmp_path):
    result = launch_package(case("styles"), str(tmp_path / "install"), "docs_style.launch.py")
    assert result.plan is not None and result.plan.failure is None
    assert [n.executable for n in result.plan.nodes] == ["robot_state_publisher", "joint_state_publisher_gui",
                                                         "rviz2"]
    assert result.description is not None and "${" not in result.description
    assert '<box size="0.08 0.08 0.6"/>' in result.description.replace("\n", "")  # ${longueur_bras} = 0.6


def test_argument_given_on_the_command_line_flips_the_condition(tmp_path):
    result = launch_package(case("styles"), str(tmp_path / "install"), "docs_style.launch.py", {"gui": "false"})
    assert result.plan is not None
    assert "joint_state_publisher" in [n.executable for n in result.plan.nodes]
    assert "joint_state_publisher_gui" not in [n.executable for n in result.plan.nodes]


def test_group_namespace_include_timer_and_opaque_function(tmp_path):
    result = launch_package(case("styles"), str(tmp_path / "install"), "namespaced.launch.py")
    assert result.plan is not None and result.plan.failure is None
    nodes = [(n.full_name, n.delay) for n in result.plan.nodes]
    assert nodes == [("/bras/robot_state_publisher", 0.0), ("/robot_state_publisher", 0.0),
                     ("/joint_state_publisher", 0.0), ("/rviz2", 0.0), ("/animation_bras", 2.0)]
    assert result.problems == []


@pytest.mark.parametrize(("name", "code", "variant", "file", "line", "ros"), [
    ("wrong_package", "BK631", "package", "launch/affichage.launch.py", 7,
     "package 'bras_descripton' not found, searching:"),
    ("relative_path", "BK631", "relative", "launch/affichage.launch.py", 8,
     "[Errno 2] No such file or directory: 'urdf/bras.urdf'"),
    ("path_parameter", "BK632", "path", "launch/affichage.launch.py", 13,
     "Unable to initialize urdf::model from robot description"),
    ("xacro_read_raw", "BK632", "xacro", "launch/affichage.launch.py", 13,
     "Unable to initialize urdf::model from robot description"),
    ("executable_with_py", "BK631", "executable_py", "launch/affichage.launch.py", 15,
     "executable 'animation.py' not found on the libexec directory"),
    ("marker_missing", "BK603", "file", "resource/bras_description", None,
     "resource/bras_description is missing: ros2 cannot find the package bras_description"),
    ("missing_source", "BK630", "missing_source", "setup.py", 13,
     "error: can't copy 'README.md': doesn't exist or not a regular file"),
    ("setup_raises", "BK630", "setup_raised", "setup.py", 13, "NameError: name 'glob' is not defined"),
    ("ament_cmake", "BK630", "ament_cmake", "package.xml", 18, "<build_type>ament_cmake</build_type>"),
    ("missing_slash", "BK601", "slash", "setup.py", 14,
     "setup.py installs 'urdf/bras.urdf' into share/bras_descriptionurdf, not share/bras_description/urdf"),
    ("folders_in_module", "BK633", "", "bras_description/launch", None, "glob('launch/*')"),
])
def test_learner_mistake_is_found_where_it_is(name, code, variant, file, line, ros):
    package = Package(case(name))
    found = [(r.path, f) for r in validate_package(case(name), select=[code], package=package, launch=True) for f in r.findings]
    assert found, name
    path, finding = found[0]
    assert path == os.path.join(case(name), file)
    assert (finding.code, finding.variant, finding.line) == (code, variant, line)
    assert ros in finding.text()


def test_missing_marker_stops_bras_kit_build_with_colcons_words(tmp_path, capsys, monkeypatch):
    from bras_kit.cli import main

    monkeypatch.chdir(tmp_path)
    assert main(["build", case("marker_missing")]) == 1
    out = capsys.readouterr().out
    assert "error: can't copy 'resource/bras_description': doesn't exist or not a regular file" in out
    assert "Failed   <<< bras_description [exited with code 1]" in out
    assert "hint: create the empty file resource/bras_description" in out
    # what colcon leaves when setuptools stops at the first data_files entry (tests/ros/test_build_colcon_oracle.py
    # checks it file for file): the modules, the entry's folder, colcon-ros's first hook; no marker, no script
    prefix = tmp_path / "install" / "bras_description"
    assert (prefix / "share/ament_index/resource_index/packages").is_dir()
    assert not (prefix / "share/ament_index/resource_index/packages/bras_description").exists()
    assert (prefix / "share/bras_description/hook/ament_prefix_path.dsv").is_file()
    assert not (prefix / "share/colcon-core").exists() and not (prefix / "lib/bras_description").exists()


def test_executable_with_py_no_longer_advises_a_py_entry_point():
    texts = [f.hint_text() for r in validate_package(case("executable_with_py"), select=["BK6"], launch=True) for f in r.findings]
    assert not any("animation.py = " in t for t in texts)
    assert any("executable='animation'" in t for t in texts)


def test_cli_launch_no_browser_runs_the_learner_node(tmp_path, capsys):
    from bras_kit.cli import main

    folder = case("styles")
    code = main(["launch", folder, "namespaced.launch.py", "--no-page", "--duration", "2"])
    out = capsys.readouterr().out
    assert code == 0
    assert "/animation_bras" in out
    assert "/joint_states: 40 messages at 20 Hz" in out  # the node's 0.05 s timer for 2 s


NODE_READING_ITS_SHARE = '''\
import os
import xml.etree.ElementTree as ElementTree

import rclpy
from ament_index_python.packages import get_package_share_directory
from rclpy.node import Node
from sensor_msgs.msg import JointState


class Lecteur(Node):
    def __init__(self):
        super().__init__('lecteur')
        urdf = os.path.join(get_package_share_directory('bras_description'), 'urdf', 'bras.urdf')
        self.names = [j.get('name') for j in ElementTree.parse(urdf).getroot().findall('joint')]
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.create_timer(0.1, self.tick)

    def tick(self):
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = self.names
        msg.position = [0.0] * len(self.names)
        self.pub.publish(msg)


def main():
    rclpy.init()
    rclpy.spin(Lecteur())
'''


def test_run_builds_the_package_so_its_node_finds_its_share_folder(tmp_path):
    import shutil

    from bras_kit.run import joint_states, run_node

    package = tmp_path / "bras_description"
    shutil.copytree(case("tutorial"), package)
    (package / "bras_description" / "animation.py").write_text(NODE_READING_ITS_SHARE, encoding="utf-8")
    recording = run_node(str(package), "animation", duration=0.5)
    assert recording.failure is None
    states = joint_states(recording)
    assert len(states) == 5 and states.names == ["epaule", "coude"]  # from the installed bras.urdf


def test_run_of_a_package_that_does_not_build_says_colcons_words():
    from bras_kit.core.errors import BrasKitError
    from bras_kit.run import run_node

    with pytest.raises(BrasKitError) as caught:
        run_node(case("missing_source"), "animation", duration=0.5)
    assert "error: can't copy 'README.md': doesn't exist or not a regular file" in str(caught.value)


@pytest.mark.parametrize(("file", "nodes"), [
    ("display.launch.xml", ["/robot_state_publisher", "/joint_state_publisher_gui", "/outils/rviz2"]),
    ("display.launch.yaml", ["/robot_state_publisher", "/joint_state_publisher", "/rviz2"]),
])
def test_xml_and_yaml_launch_files_run_as_ros2_launch_runs_them(tmp_path, file, nodes):
    result = launch_package(case("styles"), str(tmp_path / "install"), file)
    assert result.plan is not None and result.plan.failure is None
    assert [n.full_name for n in result.plan.nodes] == nodes
    assert result.problems == [] and result.description is not None
    assert '<joint name="epaule" type="revolute">' in result.description  # xacro ran: $(command 'xacro ...')


def test_copied_styles_namespace_include_cat_and_file_argument_start_clean(tmp_path):
    """An included robot launch file in a namespace, Command(['cat ', path]), robot_state_publisher's
    file argument: each starts on Jazzy, so nothing above info (no "RViz stays empty", no
    "nothing publishes /joint_states" for the included file alone)."""
    results = validate_package(case("copied_styles"), select=["BK6"], launch=True)
    assert [(f.code, f.line) for r in results for f in r.findings if f.severity != "info"] == []
    result = launch_package(case("copied_styles"), str(tmp_path / "install"), "affichage.launch.py")
    assert result.plan is not None
    assert [n.full_name for n in result.plan.nodes] == ["/bras/robot_state_publisher", "/joint_state_publisher_gui",
                                                        "/rviz2"]
    fallback = launch_package(case("copied_styles"), str(tmp_path / "install2"), "fallback.launch.py")
    assert [p.kind for _, p in fallback.problems] == ["file_fallback"]  # robot_state_publisher's own warning
    assert fallback.description is not None


def test_rviz_started_with_a_configuration_gives_the_viewer_its_fixed_frame(tmp_path):
    from bras_kit.ros.evaluation import rviz_fixed_frame as _rviz_fixed_frame
    from bras_kit.scaffold.package import scaffold_package

    scaffold_package(tmp_path / "bras_description")
    rviz = tmp_path / "bras_description" / "rviz" / "bras_description.rviz"
    rviz.write_text(rviz.read_text(encoding="utf-8").replace("Fixed Frame: base", "Fixed Frame: bras"),
                    encoding="utf-8")
    result = launch_package(str(tmp_path / "bras_description"), str(tmp_path / "install"))
    assert _rviz_fixed_frame(result.plan) == "bras"
    assert _rviz_fixed_frame(launch_package(case("tutorial"), str(tmp_path / "i2")).plan) is None  # rviz2 alone


def test_unknown_launch_file_gets_ros2_launchs_words(capsys):
    from bras_kit.cli import main

    assert main(["launch", case("tutorial"), "nope.launch.py", "--no-page"]) == 2
    err = capsys.readouterr().err
    assert "file 'nope.launch.py' was not found in the share directory of package 'bras_description'" in err
    assert "'affichage.launch.py'" in err


def test_log_info_is_printed_as_ros2_launch_prints_it(tmp_path, capsys):
    """launch 3.4 (Jazzy) actions/log_info.py:40,58-62 logs the performed message on the
    'launch.user' logger at INFO; logging/__init__.py:225-226, the screen's default format
    '[{levelname}] [{name}]: {msg}'."""
    import shutil

    from bras_kit.cli import main

    package = tmp_path / "bras_description"
    shutil.copytree(case("styles"), package)
    (package / "launch" / "said.launch.py").write_text(
        "from launch import LaunchDescription\n"
        "from launch.actions import DeclareLaunchArgument, LogInfo\n"
        "from launch.substitutions import LaunchConfiguration\n\n\n"
        "def generate_launch_description():\n"
        "    return LaunchDescription([DeclareLaunchArgument('bras', default_value='gauche'),\n"
        "                              LogInfo(msg=['bras: ', LaunchConfiguration('bras')])])\n")
    code = main(["launch", str(package), "said.launch.py", "bras:=droit", "--no-page", "--duration", "1"])
    out = capsys.readouterr().out
    assert "[INFO] [launch.user]: bras: droit\n" in out, out
    assert code == 0
