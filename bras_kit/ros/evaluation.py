"""One evaluation of ``ros2 launch PKG FILE``, the one story the terminal and the page tell.

``bras-kit launch`` builds the package, evaluates its launch file and checks it once per save;
the terminal prints a :class:`LaunchEvaluation` and the page shows the same object, never a
reading of its own (the page used to load the package's source URDF and check it by itself: a
wrong Fixed Frame, a missing slider window or a file no longer installed read differently on
each side, issue 43). What the page draws is what RViz would draw from it:

- the robot robot_state_publisher loads from the install tree (none: nothing is drawn);
- nothing under a Fixed Frame (rviz2 ``-d`` file, Global Options) that is not a frame of the
  robot: RViz shows "Frame [X] does not exist" in its Global Status and an empty view;
- sliders only when joint_state_publisher(_gui) is started (joint_state_publisher_gui is
  that window; joint_state_publisher alone has none but publishes the joints, at 0).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..core.message import M, Message

if TYPE_CHECKING:
    from ..findings.data import FileResult, Finding
    from ..model.robot import Robot
    from .launched import Launched

JOINT_STATE_PUBLISHERS = ("joint_state_publisher", "joint_state_publisher_gui")
NO_RVIZ = M("The launch file starts no rviz2: no RViz window opens, nothing shows the robot (BK615). Add "
            "Node(package='rviz2', executable='rviz2') to the launch file, or run 'ros2 run rviz2 rviz2' in another "
            "terminal.")


@dataclass
class LaunchEvaluation:
    """A package built and launched once: what started, what robot_state_publisher loads, the
    RViz Fixed Frame, and every finding (package rules, the loaded robot's rules, the package's
    own nodes run in simulated time), each with the package file it is about."""

    root: str  # the package folder
    launched: Launched  # the build, the launch plan, the robot_description text
    robot: Robot | None = None  # parsed from robot_state_publisher's robot_description
    robot_file: str | None = None  # the package file that robot comes from (package-relative)
    robot_error: Message | None = None  # why robot_description does not read as a robot
    fixed_frame: str | None = None  # rviz2 -d's Global Options > Fixed Frame (None: no file read)
    sliders: bool = False  # joint_state_publisher(_gui) is started
    own_nodes: list[Any] = field(default_factory=list)  # the package's own PlannedNodes
    results: list[FileResult] = field(default_factory=list)  # every finding, by file
    checked: bool = False  # the results are in (the page may show the robot before)
    rviz: Any = None  # the RvizConfig rviz2 opens with (ros.rviz.started), None when no rviz2 is started
    rviz_file: str | None = None  # the -d file it was read from (None: RViz's default)
    # the learner's install/ of the package differs from these sources: ros2 launch would run the old files
    stale_install: Message | None = None

    @property
    def package(self) -> str:
        return self.launched.build.package

    def blank(self) -> Message | None:
        """Why RViz draws no robot from this launch (whatever its Fixed Frame), or None."""
        build, plan = self.launched.build, self.launched.plan
        if build.failure is not None:
            return M("colcon build failed: nothing is launched, so RViz shows no robot (see the findings)")
        if plan is None or plan.failure is not None:
            return M("ros2 launch stopped before starting any node: RViz shows no robot (see the findings)")
        if not any(node.package == "robot_state_publisher" for node in plan.nodes):
            return M("no robot_state_publisher is started: nothing publishes the robot, RViz shows none")
        if self.robot is None:
            return self.robot_error or M("robot_state_publisher got no robot_description: RViz shows no robot")
        if self.rviz is None:
            return NO_RVIZ
        return None

    @property
    def rviz_started(self) -> bool:
        """Whether the launch starts rviz2 (then the page is that RViz; else it draws nothing, BK615)."""
        return self.rviz is not None

    def frame_missing(self, frame: str | None) -> Message | None:
        """Why RViz draws nothing under Fixed Frame ``frame`` (None: it exists, or none is set)."""
        if frame is None or self.robot is None or frame in [link.name for link in self.robot.links]:
            return None
        plan = self.launched.plan
        if plan is not None and (plan.included or any(node.package == "tf2_ros" for node in plan.nodes)):
            return None  # a static transform or an included launch may publish that frame (as BK610 leaves it)
        return M("Fixed Frame [{frame}] does not exist: RViz draws nothing (frames of this robot: {links})",
                 frame=frame, links=", ".join(link.name for link in self.robot.links if link.name))

    def findings(self) -> list[tuple[str, Finding]]:
        """Every finding with its package-relative file, in the order the terminal prints them."""
        out = []
        root = os.path.abspath(self.root)
        for result in self.results:
            shown = os.path.relpath(os.path.abspath(result.path), root)
            out += [(result.path if shown.startswith("..") else shown, finding) for finding in result.findings]
        return out


def evaluate_launch(root: str, install_base: str, launch_file: str | None, arguments: dict[str, str],
                    package: Any, prefixes: tuple[str, ...] = ()) -> LaunchEvaluation:
    """Build ``root`` into ``install_base`` and evaluate ``launch_file`` as ``ros2 launch`` does;
    the robot robot_state_publisher loads, the Fixed Frame and the slider window read from that
    one plan. Findings come after (:func:`bras_kit.validate.package.launch_check.check_launch`)."""
    from .launched import launch_package

    launched = launch_package(root, install_base, launch_file, arguments, prefixes=prefixes)
    package.launched = launched  # the package rules read this build, not one of their own
    evaluation = LaunchEvaluation(root=root, launched=launched)
    plan = launched.plan
    if launched.build.failure is not None or plan is None:
        return evaluation
    from .rviz.started import started

    start = started(plan)  # the one reading of rviz2's start: the page's RViz and the RViz rules
    if start is not None:
        evaluation.rviz, evaluation.rviz_file = start.config, start.file
    evaluation.fixed_frame = rviz_fixed_frame(plan)
    evaluation.sliders = any(node.package in JOINT_STATE_PUBLISHERS for node in plan.nodes)
    evaluation.own_nodes = [node for node in plan.nodes if node.package == launched.build.package]
    if launched.description is not None and plan.failure is None:
        evaluation.robot, evaluation.robot_error = _robot(launched.description)
        evaluation.robot_file = package.description_source()
    return evaluation


def _robot(description: str) -> tuple[Robot | None, Message | None]:
    from ..core.errors import BrasKitError
    from ..model.robot import robot_from_xml
    from ..model.xmlio import parse_xml

    try:
        return robot_from_xml(parse_xml(description, "robot_description"), "robot_description", description), None
    except BrasKitError as exc:
        return None, M("robot_description does not read as a robot ({detail}): RViz shows none",
                       detail=exc.message)


def rviz_fixed_frame(plan: Any) -> str | None:
    """The Fixed Frame rviz2 starts with when the launch sets one (a ``-d`` file RViz reads, or
    ``-f``), as :func:`bras_kit.ros.rviz.started.started` reads it; None otherwise."""
    from .rviz.started import started

    start = started(plan)
    if start is None or (start.file is None and not start.fixed_frame):
        return None
    return start.config.fixed_frame
