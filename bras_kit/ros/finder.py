"""The stand-in's import hook: which module names are ROS's, and where a child process takes them.

A child that runs a node or a launch file installs it first (:func:`install`): ROS names then
come from ``standin/`` or from Jazzy's message definitions, never from a real ROS install. Kept
apart from the node runner (:mod:`.child`) so that a launch file's child imports only this.
"""

from __future__ import annotations

import importlib.machinery
import os
import sys
from typing import Any

STANDIN = os.path.join(os.path.dirname(os.path.abspath(__file__)), "standin")
SIMULATED = ("rclpy", "tf2_ros", "_bras_sim", "_messages")
# the stand-in's own packages (folders of standin/), none of them a message package
STANDIN_PACKAGES = frozenset(name for name in os.listdir(STANDIN) if os.path.isdir(os.path.join(STANDIN, name))
                             and not name.startswith(("_", ".")))
# other ROS 2 Python packages a node may import: refused with a clear message, never taken
# from a real install (the stand-in's rclpy cannot drive them)
ROS_PACKAGES = ("launch", "launch_ros", "ament_index_python", "tf2_py", "tf_transformations",
                "rosidl_runtime_py", "rclpy_message_converter", "message_filters", "rosbag2_py",
                "rcl_interfaces", "action_msgs", "robot_state_publisher", "urdf_parser_py", "xacro")
# how interface packages are named: a name like these is looked at, not taken for one (a learner's
# test_from_std_msgs.py or bras_msgs is the learner's own module)
ROS_SUFFIXES = ("_msgs", "_srvs", "_interfaces", "_actions")
# Python packages of ROS 2 Jazzy (rosdistro's jazzy/distribution.yaml) whose interfaces bras-kit
# holds no definitions of: a node importing one uses what bras-kit run does not simulate
JAZZY_UNSIMULATED = frozenset((
    "ackermann_msgs", "action_tutorials_interfaces", "composition_interfaces", "control_msgs",
    "controller_manager_msgs", "example_interfaces", "gazebo_msgs", "geographic_msgs", "map_msgs",
    "moveit_msgs", "nav2_msgs", "octomap_msgs", "pcl_msgs", "pendulum_msgs", "ros_gz_interfaces",
    "sensor_msgs_py", "test_msgs", "tf2_geometry_msgs", "tf2_sensor_msgs", "turtlesim", "vision_msgs",
))
# a module rosidl_generator_py made: its package folder holds the C type support it loads
# (``<package>_s__rosidl_typesupport_c.cpython-312-x86_64-linux-gnu.so``)
TYPESUPPORT = "__rosidl_typesupport_"
ROS_INSTALL = "/opt/ros/"


def is_ros_name(top: str) -> bool:
    """A name the hook looks at: ROS's own, or named like an interface package (which it may not be)."""
    return top in SIMULATED or top in ROS_PACKAGES or top.endswith(ROS_SUFFIXES) or top in JAZZY_UNSIMULATED


def _interface_package(top: str) -> bool:
    """An interface package of Jazzy whose definitions bras-kit holds (std_msgs, sensor_msgs...)."""
    import _messages

    return top in _messages.packages()


def _generated_by_ros(spec: Any) -> bool:
    """A module found on sys.path that a ROS install or rosidl made, not the learner's own code."""
    folders = list(spec.submodule_search_locations or ()) or [os.path.dirname(spec.origin or "")]
    for folder in folders:
        if os.path.abspath(folder).startswith(ROS_INSTALL):
            return True
        try:
            if any(TYPESUPPORT in name for name in os.listdir(folder)):
                return True
        except OSError:
            continue
    return False


def _not_an_interface_of_ours(fullname: str, top: str) -> Any:
    """A name like an interface package's that bras-kit holds no definitions of. The learner's own
    module of that name (bras_msgs, test_from_std_msgs.py) is imported as Python imports it; a
    package a ROS install generated, or one of Jazzy's, is not simulated; anything else does not
    exist, and Python says so as on Jazzy (ModuleNotFoundError: No module named 'x_msgs')."""
    if "." in fullname and top in sys.modules:
        return None  # a submodule of the learner's own module
    found = importlib.machinery.PathFinder.find_spec(fullname)
    if found is not None and not _generated_by_ros(found):
        return None  # Python's own finders, after this one, take it
    if found is not None or top in JAZZY_UNSIMULATED:
        import _bras_sim

        raise _bras_sim.NotSimulated(fullname)
    return None


def _message_spec(fullname: str) -> Any:
    """Message packages (sensor_msgs, rcl_interfaces, tf2_msgs...) come from Jazzy's definitions."""
    import _messages

    return _messages.find_spec(fullname)


class StandinFinder:
    """First on sys.meta_path in the child: ROS names come from the stand-in folder or stop.
    (A finder needs only ``find_spec``: not deriving from ``importlib.abc.MetaPathFinder`` spares
    every child importing ``importlib.resources``, tempfile and shutil with it, 6 ms.)"""

    def find_spec(self, fullname: str, path: Any = None, target: Any = None) -> Any:
        top = fullname.partition(".")[0]
        if not is_ros_name(top):
            return None
        if top not in SIMULATED and top not in ROS_PACKAGES and top not in STANDIN_PACKAGES \
                and not _interface_package(top):
            return _not_an_interface_of_ours(fullname, top)
        if top not in SIMULATED and top not in STANDIN_PACKAGES:
            # only a message package reads Jazzy's definitions (rosbags' whole store, about 0.2 s):
            # launch, launch_ros, xacro... are the stand-in's own folders
            spec = _message_spec(fullname)
            if spec is not None:
                return spec
            if "." in fullname and _message_spec(fullname.rpartition(".")[0]) is not None:
                # `from std_msgs.msg import JointState` looks for a submodule last (importlib
                # _handle_fromlist): none, and Python raises the ImportError Jazzy raises
                return None
        search = [STANDIN] if path is None or "." not in fullname else path
        spec = importlib.machinery.PathFinder.find_spec(fullname, search)
        if spec is None:
            import _bras_sim

            raise _bras_sim.NotSimulated(fullname)
        return spec


def install() -> None:
    """The hook first on ``sys.meta_path``, every ROS module imported before it forgotten (the real
    xacro, if imported, is set aside: the stand-in's xacro imports it when it expands)."""
    for name in list(sys.modules):
        if is_ros_name(name.partition(".")[0]):
            del sys.modules[name]
    sys.meta_path.insert(0, StandinFinder())
