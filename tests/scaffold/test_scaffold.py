"""bras-kit new: the tutorial's ROS 2 package, checked file by file, installed as colcon does,
and its node and launch file run against small stand-ins for rclpy and launch."""

from __future__ import annotations

import ast
import configparser
import importlib
import importlib.util
import math
import py_compile
import re
import subprocess
import sys
import types
from pathlib import Path

import numpy as np
import pytest
import yaml
from paths import REPO

from bras_kit.core.errors import OutputExistsError, ParameterError
from bras_kit.model.authoring import load
from bras_kit.model.xacro import expand_xacro
from bras_kit.model.xmlio import read_xml
from bras_kit.scaffold.package import plan_motion, render_package, scaffold_package

PKG = "bras_description"
EXPECTED_FILES = {
    "package.xml", "setup.py", "setup.cfg", "README.md", f"resource/{PKG}",
    f"{PKG}/__init__.py", f"{PKG}/motion.py", f"{PKG}/animation.py",
    "launch/affichage.launch.py", f"rviz/{PKG}.rviz", "test/test_motion.py",
    "urdf/bras.urdf",
}
EXEC_DEPENDS = {"robot_state_publisher", "joint_state_publisher_gui", "rviz2", "xacro", "rclpy",
                "sensor_msgs", "launch_ros"}
NARROW = {"epaule_lower": -0.3, "coude_upper": 0.5, "coude_velocity": 0.5,
          "poignet_lower": 0.2, "poignet_upper": 0.6}
VARIANTS = {
    "default": {},
    "wrist": {"wrist": True},
    "narrow": {"wrist": True, "params": NARROW},
}


@pytest.fixture(scope="module")
def packages(tmp_path_factory) -> dict[str, Path]:
    made = {}
    for key, options in VARIANTS.items():
        dest = tmp_path_factory.mktemp(key) / PKG
        scaffold_package(dest, **options)
        made[key] = dest
    return made


def load_module(path: Path, name: str) -> types.ModuleType:
    spec = importlib.util.spec_from_file_location(name, path)
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    return module


def motion_of(package: Path, name: str = PKG) -> types.ModuleType:
    return load_module(package / name / "motion.py", f"generated_motion_{abs(hash(package))}")


def without_comments(xml: str) -> str:
    return "\n".join(line for line in re.sub(r"<!--.*?-->", "", xml, flags=re.S).splitlines()
                     if line.strip())


# --- the files ---------------------------------------------------------------------------------------

def test_package_holds_the_tutorial_files(tmp_path):
    made = scaffold_package(tmp_path / "pkg")
    relative = {p.relative_to(tmp_path / "pkg").as_posix() for p in made}
    assert relative == EXPECTED_FILES
    on_disk = {p.relative_to(tmp_path / "pkg").as_posix()
               for p in (tmp_path / "pkg").rglob("*") if p.is_file()}
    assert on_disk == EXPECTED_FILES
    assert (tmp_path / "pkg" / "resource" / PKG).read_text() == ""


@pytest.mark.parametrize("variant", VARIANTS)
def test_every_generated_python_file_compiles(packages, tmp_path, variant):
    sources = sorted(packages[variant].rglob("*.py"))
    assert len(sources) == 6
    for source in sources:
        py_compile.compile(str(source), cfile=str(tmp_path / "out.pyc"), doraise=True)


def test_package_xml_is_format_3_ament_python_with_the_dependencies(packages):
    root = read_xml(packages["default"] / "package.xml")
    assert (root.tag, root.get("format")) == ("package", "3")
    assert root.find("name").text == PKG
    assert root.find("license").text == "Apache-2.0"
    assert "@" in root.find("maintainer").get("email")
    assert EXEC_DEPENDS <= {n.text for n in root.findall("exec_depend")}
    assert [n.text for n in root.findall("test_depend")] == [
        "ament_copyright", "ament_flake8", "ament_pep257", "python3-pytest"]
    assert root.find("export").find("build_type").text == "ament_python"


def test_setup_cfg_puts_scripts_where_ros2_run_looks(packages):
    config = configparser.ConfigParser(interpolation=None)
    config.read(packages["default"] / "setup.cfg")
    assert config["develop"]["script_dir"] == f"$base/lib/{PKG}"
    assert config["install"]["install_scripts"] == f"$base/lib/{PKG}"


def test_setup_py_declares_the_animation_entry_point(packages):
    tree = ast.parse((packages["default"] / "setup.py").read_text())
    call = next(n for n in ast.walk(tree) if isinstance(n, ast.Call) and getattr(n.func, "id", "") == "setup")
    keywords = {k.arg: k.value for k in call.keywords}
    assert ast.literal_eval(keywords["entry_points"]) == {
        "console_scripts": [f"animation = {PKG}.animation:main"]}
    assert ast.literal_eval(keywords["license"]) == "Apache-2.0"
    assert ast.literal_eval(keywords["version"]) == "0.0.0"


@pytest.mark.parametrize("variant", VARIANTS)
def test_rviz_config_shows_the_model_at_once(packages, variant):
    config = yaml.safe_load((packages[variant] / "rviz" / f"{PKG}.rviz").read_text())
    manager = config["Visualization Manager"]
    assert manager["Global Options"]["Fixed Frame"] == "base"
    displays = {d["Class"]: d for d in manager["Displays"]}
    model = displays["rviz_default_plugins/RobotModel"]
    assert model["Description Source"] == "Topic"
    assert model["Description Topic"]["Value"] == "/robot_description"
    # robot_state_publisher publishes the description once, latched: RViz must ask for it
    assert model["Description Topic"]["Durability Policy"] == "Transient Local"
    assert displays["rviz_default_plugins/TF"]["Enabled"] is True
    assert displays["rviz_default_plugins/Grid"]["Enabled"] is True
    assert all(d["Enabled"] is True for d in manager["Displays"])


def test_rviz_camera_looks_at_the_middle_of_the_arm(packages):
    config = yaml.safe_load((packages["default"] / "rviz" / f"{PKG}.rviz").read_text())
    view = config["Visualization Manager"]["Views"]["Current"]
    # arm top at rest: 0.05 (shoulder) + 0.6 (bras) + 0.5 (avant_bras) = 1.15 m
    assert view["Focal Point"]["Z"] == pytest.approx(0.575)
    assert view["Distance"] == pytest.approx(2.53)


def test_package_holds_one_robot_description_the_tutorial_urdf_or_with_xacro_the_template(tmp_path):
    plain = {p.relative_to(tmp_path / "a").as_posix() for p in scaffold_package(tmp_path / "a")}
    templated = {p.relative_to(tmp_path / "b").as_posix() for p in scaffold_package(tmp_path / "b", xacro=True)}
    assert plain - templated == {"urdf/bras.urdf"}
    assert templated - plain == {"urdf/bras.urdf.xacro"}


@pytest.mark.parametrize("variant", VARIANTS)
def test_xacro_package_expands_to_the_plain_package_urdf(packages, tmp_path, variant):
    options = VARIANTS[variant]
    scaffold_package(tmp_path / PKG, xacro=True, **options)
    urdf = (packages[variant] / "urdf" / "bras.urdf").read_text()
    expanded = expand_xacro(tmp_path / PKG / "urdf" / "bras.urdf.xacro")
    assert without_comments(expanded) == without_comments(urdf)


def test_packaged_xacro_defaults_to_the_chosen_variant(tmp_path):
    scaffold_package(tmp_path / "narrow", xacro=True, **VARIANTS["narrow"])
    text = (tmp_path / "narrow" / "urdf" / "bras.urdf.xacro").read_text()
    assert '<xacro:arg name="wrist" default="true"/>' in text
    assert '<xacro:arg name="inertials" default="false"/>' in text
    assert '<xacro:arg name="coude_upper" default="0.5"/>' in text
    scaffold_package(tmp_path / "default", xacro=True)
    default = (tmp_path / "default" / "urdf" / "bras.urdf.xacro").read_text()
    assert '<xacro:arg name="wrist" default="false"/>' in default


def test_xacro_package_launch_file_runs_xacro_and_launches_clean(tmp_path):
    from bras_kit.ros.launched import launch_package

    scaffold_package(tmp_path / PKG, xacro=True)
    result = launch_package(str(tmp_path / PKG), str(tmp_path / "install"))
    assert result.plan is not None and result.plan.failure is None and result.problems == []
    assert result.description is not None
    assert '<joint name="coude" type="revolute">' in result.description


def test_urdf_follows_the_variant(packages):
    assert load(packages["default"] / "urdf" / "bras.urdf").joint_names == ["epaule", "coude"]
    narrow = load(packages["narrow"] / "urdf" / "bras.urdf")
    assert narrow.joint_names == ["epaule", "coude", "poignet"]
    assert narrow.joint("coude").limit.upper == 0.5


# --- the motion: the tutorial's waves, inside the limits ------------------------------------------

def test_default_motion_is_the_tutorials(packages):
    motion = motion_of(packages["default"])
    assert motion.JOINT_NAMES == ["epaule", "coude"]
    assert motion.WAVES == {"epaule": (0.0, 0.8, 1.0, 0.0), "coude": (0.0, 1.2, 0.7, 0.0)}
    for t in (0.0, 0.05, 1.0, 2.5, 17.3):
        assert motion.joint_positions(t) == [0.8 * math.sin(t), 1.2 * math.sin(0.7 * t)]
        assert motion.joint_velocities(t) == pytest.approx([0.8 * math.cos(t), 0.84 * math.cos(0.7 * t)])


def test_wrist_has_its_own_frequency(packages):
    motion = motion_of(packages["wrist"])
    assert motion.JOINT_NAMES == ["epaule", "coude", "poignet"]
    centre, amplitude, frequency, phase = motion.WAVES["poignet"]
    assert (centre, amplitude, frequency, phase) == (0.0, 1.0, 1.3, 0.0)  # 1.0 sin 1.3t
    assert frequency not in (1.0, 0.7)


def test_narrowed_limits_recentre_and_shrink_the_waves(packages):
    # epaule -0.3..1.57: centre 0.635, 0.8 fits in 0.9 * 0.935; coude -2..0.5 at 0.5 rad/s:
    # centre -0.75, amplitude 0.9 * 0.5 / 0.7 = 0.642857...; poignet 0.2..0.6: 0.4 +- 0.9 * 0.2
    assert motion_of(packages["narrow"]).WAVES == {
        "epaule": (0.635, 0.8, 1.0, 0.0),
        "coude": (-0.75, 0.642857, 0.7, 0.0),
        "poignet": (0.4, 0.18, 1.3, 0.0),
    }


def test_tutorial_waves_would_leave_the_narrowed_limits():
    """Why the waves are recomputed: the tutorial's coude wave passes coude_upper=0.5."""
    assert max(1.2 * math.sin(0.7 * k / 20) for k in range(1201)) > 0.5


@pytest.mark.parametrize("variant", VARIANTS)
def test_motion_stays_inside_limits_for_a_minute_at_20_hz(packages, variant):
    motion = motion_of(packages[variant])
    robot = load(packages[variant] / "urdf" / "bras.urdf")
    assert motion.JOINT_NAMES == [j.name for j in robot.movable_joints()]
    for name, (lower, upper, velocity) in motion.LIMITS.items():
        limit = robot.joint(name).limit
        assert (lower, upper, velocity) == (limit.lower, limit.upper, limit.velocity)
    for step in range(60 * 20 + 1):
        t = step / 20
        for joint, q, dq in zip(robot.movable_joints(), motion.joint_positions(t),
                                motion.joint_velocities(t)):
            assert joint.limit.lower <= q <= joint.limit.upper, (joint.name, t, q)
            assert abs(dq) <= joint.limit.velocity, (joint.name, t, dq)


def test_motion_keeps_a_margin_from_each_limit(packages):
    motion = motion_of(packages["narrow"])
    for name, (centre, amplitude, _, _) in motion.WAVES.items():
        lower, upper, _ = motion.LIMITS[name]
        margin = 0.1 * (upper - lower) / 2
        assert centre - amplitude >= lower + margin - 1e-9
        assert centre + amplitude <= upper - margin + 1e-9


def test_equal_limits_give_a_still_joint():
    from bras_kit.model.authoring import arm

    waves = plan_motion(arm(params={"coude_lower": 0.3, "coude_upper": 0.3}))
    assert (waves[1].joint, waves[1].centre, waves[1].amplitude) == ("coude", 0.3, 0.0)


def test_inverted_limits_are_refused_and_nothing_is_written(run_cli, tmp_path):
    from bras_kit.model.authoring import arm

    with pytest.raises(ParameterError, match="coude_lower=1 is above coude_upper=-1"):
        arm(params={"coude_lower": 1, "coude_upper": -1})  # refused before any URDF is written
    code, _, err = run_cli("new", str(tmp_path / "p"), "--param", "coude_lower=1", "--param", "coude_upper=-1")
    assert code == 2 and "coude" in err
    assert not (tmp_path / "p").exists()


@pytest.mark.slow
@pytest.mark.parametrize("lang,limits_test", [("en", "test_limits_match_the_urdf"),
                                               ("fr", "test_limites_recopiees_de_l_urdf")])
def test_package_own_test_passes_and_catches_a_changed_limit(tmp_path, lang, limits_test):
    package = tmp_path / PKG
    scaffold_package(package, wrist=True, lang=lang)
    command = [sys.executable, "-m", "pytest", "-q", "-p", "no:cacheprovider", "test"]
    passed = subprocess.run(command, cwd=package, capture_output=True, text=True, timeout=300)
    assert passed.returncode == 0, passed.stdout + passed.stderr
    assert "2 passed" in passed.stdout
    urdf = package / "urdf" / "bras.urdf"
    urdf.write_text(urdf.read_text().replace('lower="-2.0" upper="2.0"', 'lower="-2.0" upper="0.3"'))
    failed = subprocess.run(command, cwd=package, capture_output=True, text=True, timeout=300)
    assert failed.returncode == 1
    assert limits_test in failed.stdout and "1 failed, 1 passed" in failed.stdout


# --- the animation node, on a stand-in for rclpy ---------------------------------------------------

class FakeTime:
    def __init__(self, nanoseconds: int) -> None:
        self.nanoseconds = nanoseconds

    def __sub__(self, other: FakeTime) -> FakeTime:
        return FakeTime(self.nanoseconds - other.nanoseconds)

    def to_msg(self) -> tuple[int, int]:
        return divmod(self.nanoseconds, 1_000_000_000)


class FakeRos:
    """Just enough of rclpy and sensor_msgs to run the node: a clock that the spin advances."""

    TICKS = 40

    def __init__(self) -> None:
        self.clock_ns = 1_700_000_000_000_000_000
        self.published: list = []
        self.publishers: list = []
        self.timers: list = []
        self.nodes: list = []
        self.calls: list[str] = []

    def modules(self) -> dict[str, types.ModuleType]:
        ros = self

        class Node:
            def __init__(self, name: str) -> None:
                ros.nodes.append(name)

            def create_publisher(self, message_type, topic, depth):
                ros.publishers.append((message_type.__name__, topic, depth))
                return types.SimpleNamespace(publish=ros.published.append)

            def create_timer(self, period, callback):
                ros.timers.append((period, callback))

            def get_clock(self):
                return types.SimpleNamespace(now=lambda: FakeTime(ros.clock_ns))

            def destroy_node(self):
                ros.calls.append("destroy_node")

        def spin(node):
            ((period, callback),) = ros.timers
            for _ in range(ros.TICKS):
                ros.clock_ns += round(period * 1e9)
                callback()

        class JointState:
            def __init__(self) -> None:
                self.header = types.SimpleNamespace(stamp=None, frame_id="")
                self.name: list[str] = []
                self.position: list[float] = []
                self.velocity: list[float] = []

        rclpy = types.ModuleType("rclpy")
        rclpy.init = lambda args=None: ros.calls.append("init")
        rclpy.spin = spin
        rclpy.ok = lambda: True
        rclpy.shutdown = lambda: ros.calls.append("shutdown")
        node_module = types.ModuleType("rclpy.node")
        node_module.Node = Node
        executors = types.ModuleType("rclpy.executors")
        executors.ExternalShutdownException = type("ExternalShutdownException", (Exception,), {})
        sensor_msgs = types.ModuleType("sensor_msgs")
        msg = types.ModuleType("sensor_msgs.msg")
        msg.JointState = JointState
        return {"rclpy": rclpy, "rclpy.node": node_module, "rclpy.executors": executors,
                "sensor_msgs": sensor_msgs, "sensor_msgs.msg": msg}


@pytest.fixture
def generated_import(monkeypatch):
    """Import a generated package by name from its folder; forget it afterwards."""
    names: list[str] = []

    def importer(package_dir: Path, module: str) -> types.ModuleType:
        monkeypatch.syspath_prepend(str(package_dir))
        names.append(module.split(".")[0])
        return importlib.import_module(module)

    yield importer
    for key in list(sys.modules):
        if key.split(".")[0] in names:
            del sys.modules[key]


@pytest.mark.parametrize("wrist,lang", [(False, "en"), (True, "en"), (True, "fr")], ids=["default", "wrist", "fr"])
def test_animation_node_publishes_joint_states_at_20_hz(tmp_path, monkeypatch, generated_import, wrist, lang):
    name = f"bk_anim_{lang}_wrist" if wrist else f"bk_anim_{lang}"
    scaffold_package(tmp_path / name, name=name, wrist=wrist, lang=lang)
    ros = FakeRos()
    for module_name, module in ros.modules().items():
        monkeypatch.setitem(sys.modules, module_name, module)
    start = ros.clock_ns
    animation = generated_import(tmp_path / name, f"{name}.animation")
    motion = sys.modules[f"{name}.motion"]
    animation.main()

    assert ros.nodes == ["animation_bras"]
    assert ros.publishers == [("JointState", "joint_states", 10)]
    assert [period for period, _ in ros.timers] == [0.05]
    assert ros.calls == ["init", "destroy_node", "shutdown"]
    assert len(ros.published) == FakeRos.TICKS
    names = ["epaule", "coude"] + (["poignet"] if wrist else [])
    for tick, state in enumerate(ros.published, 1):
        elapsed = tick * 50_000_000
        assert state.name == names
        assert state.header.stamp == divmod(start + elapsed, 1_000_000_000)
        assert state.position == motion.joint_positions(elapsed / 1e9)
        assert state.velocity == motion.joint_velocities(elapsed / 1e9)
        t = tick * 0.05
        assert state.position[:2] == pytest.approx([0.8 * math.sin(t), 1.2 * math.sin(0.7 * t)], abs=1e-12)


# --- installing as colcon does ------------------------------------------------------------------------

def colcon_like_install(source: Path, work: Path) -> tuple[subprocess.CompletedProcess, Path]:
    """What colcon's ament_python build runs: setup.py egg_info, build and install into a prefix."""
    build, prefix = work / "build", work / "install"
    build.mkdir(parents=True)
    result = subprocess.run(
        [sys.executable, "setup.py", "egg_info", "--egg-base", str(build), "build", "--build-base",
         str(build), "install", "--prefix", str(prefix), "--record", str(build / "install.log"),
         "--single-version-externally-managed"],
        cwd=source, capture_output=True, text=True, timeout=300)
    return result, prefix


@pytest.mark.slow
@pytest.mark.parametrize("name,wrist", [(PKG, False), (PKG, True), ("mon_bras", False)],
                         ids=["default", "wrist", "other-name"])
def test_package_installs_like_colcon_build(tmp_path, name, wrist):
    source = tmp_path / "src" / name
    scaffold_package(source, name=name, wrist=wrist)
    result, prefix = colcon_like_install(source, tmp_path)
    assert result.returncode == 0, result.stdout + result.stderr
    share = prefix / "share" / name
    installed = {p.relative_to(prefix).as_posix() for p in prefix.rglob("*") if p.is_file()}
    assert {
        f"share/{name}/package.xml",
        f"share/{name}/urdf/bras.urdf",
        f"share/{name}/launch/affichage.launch.py",
        f"share/{name}/rviz/{name}.rviz",
        f"share/ament_index/resource_index/packages/{name}",
        f"lib/{name}/animation",
    } <= installed
    assert (share / "urdf" / "bras.urdf").read_text() == (source / "urdf" / "bras.urdf").read_text()
    (site,) = prefix.glob(f"lib/python*/site-packages/{name}")
    assert {p.name for p in site.glob("*.py")} == {"__init__.py", "motion.py", "animation.py"}
    assert (prefix / "lib" / name / "animation").read_text().startswith("#!")
    (entry_points,) = prefix.glob("lib/python*/site-packages/*.egg-info/entry_points.txt")
    config = configparser.ConfigParser()
    config.read(entry_points)
    assert dict(config["console_scripts"]) == {"animation": f"{name}.animation:main"}
    assert not any("test_motion" in path for path in installed)


@pytest.mark.slow
@pytest.mark.parametrize("lang", ["en", "fr"])
def test_installed_launch_file_finds_the_installed_files(tmp_path, monkeypatch, lang):
    source = tmp_path / "src" / PKG
    scaffold_package(source, lang=lang)
    result, prefix = colcon_like_install(source, tmp_path)
    assert result.returncode == 0, result.stderr
    share = prefix / "share" / PKG

    def node(**kwargs):
        return ("Node", kwargs)

    def package_share(name: str) -> str:
        if name != PKG:
            raise LookupError(name)
        return str(share)

    fakes = {
        "ament_index_python": types.ModuleType("ament_index_python"),
        "ament_index_python.packages": types.SimpleNamespace(get_package_share_directory=package_share),
        "launch": types.SimpleNamespace(LaunchDescription=lambda entities: list(entities)),
        "launch.actions": types.SimpleNamespace(
            DeclareLaunchArgument=lambda name, **kw: ("Argument", name, kw)),
        "launch.conditions": types.SimpleNamespace(IfCondition=lambda v: ("if", v),
                                                   UnlessCondition=lambda v: ("unless", v)),
        "launch.substitutions": types.SimpleNamespace(LaunchConfiguration=lambda n: ("config", n)),
        "launch_ros": types.ModuleType("launch_ros"),
        "launch_ros.actions": types.SimpleNamespace(Node=node),
    }
    for module_name, module in fakes.items():
        monkeypatch.setitem(sys.modules, module_name, module)
    launch_file = load_module(share / "launch" / "affichage.launch.py", f"generated_launch_{lang}")
    entities = launch_file.generate_launch_description()

    arguments = [e for e in entities if e[0] == "Argument"]
    assert [(a[1], a[2]["default_value"]) for a in arguments] == [("animation", "false")]
    nodes = {(e[1]["package"], e[1]["executable"]): e[1] for e in entities if e[0] == "Node"}
    assert set(nodes) == {("robot_state_publisher", "robot_state_publisher"),
                          ("joint_state_publisher_gui", "joint_state_publisher_gui"),
                          (PKG, "animation"), ("rviz2", "rviz2")}
    description = nodes["robot_state_publisher", "robot_state_publisher"]["parameters"][0]
    assert description["robot_description"] == (share / "urdf" / "bras.urdf").read_text()
    flag, config = nodes["rviz2", "rviz2"]["arguments"]
    assert flag == "-d" and Path(config) == share / "rviz" / f"{PKG}.rviz" and Path(config).is_file()
    animation = ("config", "animation")
    assert nodes["joint_state_publisher_gui", "joint_state_publisher_gui"]["condition"] == ("unless", animation)
    assert nodes[PKG, "animation"]["condition"] == ("if", animation)
    assert (prefix / "lib" / PKG / "animation").is_file()


@pytest.mark.slow
@pytest.mark.parametrize("lang,message", [
    ("en", f"{PKG}: no *.urdf or *.xacro file in urdf/"),
    ("fr", f"{PKG} : aucun fichier *.urdf ou *.xacro dans urdf/ (lancez colcon depuis l'espace de travail"),
])
def test_build_stops_with_a_message_when_urdf_folder_is_empty(tmp_path, lang, message):
    """The tutorial's 'file not found' pitfall becomes an error at build time."""
    source = tmp_path / "src" / PKG
    scaffold_package(source, lang=lang)
    for path in (source / "urdf").iterdir():
        path.unlink()
    result, prefix = colcon_like_install(source, tmp_path)
    assert result.returncode != 0
    assert message in result.stderr
    assert not (prefix / "share" / PKG).exists()


# --- the new command -------------------------------------------------------------------------------------

def test_new_defaults_to_bras_description_in_the_current_folder(run_cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli("new")
    assert code == 0, err
    assert {p.relative_to(tmp_path / PKG).as_posix()
            for p in (tmp_path / PKG).rglob("*") if p.is_file()} == EXPECTED_FILES
    assert EXPECTED_FILES <= {line.strip() for line in out.splitlines() if line.startswith("  ")}


def test_new_with_a_name_uses_it_everywhere(run_cli, tmp_path):
    code, _, err = run_cli("new", str(tmp_path / "ws"), "--name", "mon_bras", "--wrist")
    assert code == 0, err
    root = tmp_path / "ws"
    assert (root / "resource" / "mon_bras").is_file()
    assert (root / "rviz" / "mon_bras.rviz").is_file()
    assert "package_name = 'mon_bras'" in (root / "setup.py").read_text()
    assert "'animation = mon_bras.animation:main'" in (root / "setup.py").read_text()
    assert read_xml(root / "package.xml").find("name").text == "mon_bras"
    assert "from mon_bras.motion import" in (root / "mon_bras" / "animation.py").read_text()
    assert "PACKAGE = 'mon_bras'" in (root / "launch" / "affichage.launch.py").read_text()
    assert "ros2 launch mon_bras affichage.launch.py" in (root / "README.md").read_text()
    assert not (root / PKG).exists()


def test_new_takes_template_parameters(run_cli, tmp_path):
    code, _, err = run_cli("new", str(tmp_path / "p"), "--param", "bras_length=0.8", "--inertials")
    assert code == 0, err
    robot = load(tmp_path / "p" / "urdf" / "bras.urdf")
    assert robot.joint("coude").origin.xyz == (0.0, 0.0, 0.8)
    assert robot.link("bras").inertial is not None
    assert "bras-kit new --inertials --param bras_length=0.8" in (tmp_path / "p" / "README.md").read_text()


@pytest.mark.parametrize("name", ["Bras", "2bras", "bras-description", "bras description", "_bras", "class"])
def test_new_refuses_an_invalid_package_name(run_cli, tmp_path, monkeypatch, name):
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli("new", "--name", name)
    assert code == 2 and out == ""
    assert f"'{name}'" in err and "Traceback" not in err
    assert list(tmp_path.iterdir()) == []


def test_new_with_an_unknown_parameter_writes_nothing(run_cli, tmp_path):
    code, _, err = run_cli("new", str(tmp_path / "p"), "--param", "bras_lenght=0.8")
    assert code == 2 and "valid names" in err
    assert not (tmp_path / "p").exists()


def test_new_refuses_a_non_empty_folder_without_force(run_cli, tmp_path):
    dest = tmp_path / "p"
    dest.mkdir()
    (dest / "setup.py").write_text("# my own setup.py\n")
    code, _, err = run_cli("new", str(dest))
    assert code == 2
    assert "already exists and is not empty" in err and "--force" in err
    assert (dest / "setup.py").read_text() == "# my own setup.py\n"
    assert sorted(p.name for p in dest.iterdir()) == ["setup.py"]
    with pytest.raises(OutputExistsError):
        scaffold_package(dest)


def test_new_with_force_rewrites_its_files_and_keeps_the_others(run_cli, tmp_path):
    dest = tmp_path / "p"
    dest.mkdir()
    (dest / "setup.py").write_text("# my own setup.py\n")
    (dest / "NOTES.txt").write_text("mine")
    code, _, err = run_cli("new", str(dest), "--force")
    assert code == 0, err
    assert "package_name = 'bras_description'" in (dest / "setup.py").read_text()
    assert (dest / "NOTES.txt").read_text() == "mine"


def test_new_accepts_an_existing_empty_folder(tmp_path):
    (tmp_path / "empty").mkdir()
    assert len(scaffold_package(tmp_path / "empty")) == len(EXPECTED_FILES)


def test_new_refuses_a_file_as_folder(run_cli, tmp_path):
    (tmp_path / "file").write_text("x")
    code, _, err = run_cli("new", str(tmp_path / "file"), "--force")
    assert code == 2 and "is not a folder" in err


def test_render_package_checks_the_name_before_anything():
    with pytest.raises(ParameterError, match="not a valid ROS package name"):
        render_package("Bras")


def test_the_scaffolded_node_moves_like_the_cli_and_lesson_6(tmp_path):
    """One wrist motion: the package's motion.py, bras-kit's tutorial motion and lesson 6."""
    import importlib.util

    from bras_kit.model.authoring import arm
    from bras_kit.motion import TUTORIAL_FORMULAS, tutorial_motion

    scaffold_package(tmp_path / "p", wrist=True)
    spec = importlib.util.spec_from_file_location("motion_wrist", tmp_path / "p" / "bras_description" / "motion.py")
    module = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(module)
    motion = tutorial_motion(arm(wrist=True))
    times = [0.0, 0.4, 1.7, 3.3, 8.25]
    expected = motion.positions(np.array(times))
    for k, t in enumerate(times):
        assert module.joint_positions(t) == pytest.approx(list(expected[k]), abs=1e-12)
    # by hand: epaule 0.8 sin t, coude 1.2 sin 0.7t, poignet 1.0 sin 1.3t
    assert module.joint_positions(1.7) == pytest.approx([0.8 * math.sin(1.7), 1.2 * math.sin(1.19), math.sin(2.21)])
    lesson = (REPO / "lessons" / "lesson_src" / "l06_wrist.py").read_text()
    written = "[" + ", ".join(f'"{name}={formula}"' for name, formula in TUTORIAL_FORMULAS.items()) + "]"
    assert written in lesson
