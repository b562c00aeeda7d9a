"""A package built as colcon builds it and its launch files evaluated as ``ros2 launch`` would: the
reading under ``bras-kit launch`` and ``bras-kit validate PKG_DIR`` (whose rules, BK630-BK635,
live in :mod:`bras_kit.validate.package.launch_rules`). It imports no rule and no numpy: the worker
of :mod:`bras_kit.ros.ahead` runs it beside the rules.
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field

from ..trust import scratch
from .build import BuildRecord, build_package
from .launching import (
    MAX_LAUNCH_NODES,
    LaunchPlan,
    PlannedNode,
    StartProblem,
    begin_plan,
    plan_launch,
    preload_planning,
    robot_state_publisher_start,
    ros_arguments_start,
)


@dataclass
class Launched:
    """A package built, one of its launch files evaluated, and what robot_state_publisher would read."""

    build: BuildRecord
    launch_file: str = ""  # package-relative source of the launch file
    plan: LaunchPlan | None = None
    description: str | None = None  # the URDF robot_state_publisher loads
    problems: list[tuple[PlannedNode, StartProblem]] = field(default_factory=list)
    others: dict[str, Launched] = field(default_factory=dict)  # the other launch files, by source
    start_problems: list[tuple[PlannedNode, StartProblem]] = field(default_factory=list)  # BK634: rcl's arguments


def launch_sources(build: BuildRecord) -> list[str]:
    return sorted(i.source for i in build.installed
                  if i.target.startswith(f"share/{build.package}/") and
                  i.source.endswith((".launch.py", "_launch.py", ".launch.xml", ".launch.yaml", ".launch.yml")))


def share_files_named(build: BuildRecord, name: str) -> list[str]:
    """The package files installed under share/PKG/ with the name ``name``, whatever it ends with:
    ros2launch looks for the name in every folder of the share directory and takes any file
    (ros2launch/api/api.py, get_share_file_path_from_package, Jazzy lines 39-64; more than one is
    its MultipleLaunchFilesError)."""
    wanted = os.path.basename(name)
    return sorted(i.source for i in build.installed
                  if i.target.startswith(f"share/{build.package}/") and os.path.basename(i.target) == wanted)


def _read_plans() -> None:
    """What this process needs to read a launch file's evaluation (the nodes' --ros-args), imported
    while setup.py's child runs rather than after the launch file's."""
    from . import names  # noqa: F401


def launch_package(root: str, install_base: str, launch_file: str | None = None,
                   arguments: dict[str, str] | None = None, *, prefixes: tuple[str, ...] = (),
                   ahead: bool = False) -> Launched:
    """Build ``root`` into ``install_base`` and evaluate ``launch_file`` (a file's name anywhere in
    the package's share folder, default: the first installed launch file) as ``ros2 launch PKG
    FILE`` would; ``prefixes``: the other packages of the workspace, built. ``ahead``: the launch
    file's child is forked and walled in while setup.py runs (:func:`.launching.begin_plan`; for an
    ``install_base`` of bras-kit's own that holds nothing else)."""
    early = begin_plan(install_base, list(prefixes), learner_roots=(root,)) if ahead else None
    try:
        # the launch file's child imports what it needs itself, or this process does while setup.py runs
        build = build_package(root, install_base, meanwhile=_read_plans if early is not None else preload_planning)
        result = Launched(build)
        if build.failure is not None:
            return result
        sources = launch_sources(build)
        if launch_file is not None:
            chosen = share_files_named(build, launch_file)
            result.launch_file = chosen[0] if len(chosen) == 1 else launch_file
        elif sources:
            result.launch_file = sources[0]
        if not result.launch_file:
            return result
        target = next((i.target for i in build.installed if i.source == result.launch_file), None)
        if target is None:
            return result
        path, chosen_prefixes = os.path.join(build.prefix, target), [build.prefix, *prefixes]
        if early is not None:
            told, early = early, None
            plan = told.plan(path, chosen_prefixes, arguments)
        else:
            plan = plan_launch(path, chosen_prefixes, arguments, learner_roots=(root,))
    finally:
        if early is not None:
            early.cancel()
    result.plan = plan
    described: dict[tuple[str, tuple[str, ...]], tuple[str | None, list[StartProblem]]] = {}  # one parse each
    for node in plan.nodes[:MAX_LAUNCH_NODES]:  # the child's bound, held here too
        result.start_problems += [(node, p) for p in ros_arguments_start(node)]
        if node.package == "robot_state_publisher":
            key = (str(node.parameters.get("robot_description", "")), tuple(node.arguments[:1]))
            if key not in described:
                described[key] = robot_state_publisher_start(node, roots=(build.prefix, *prefixes, root))
            text, problems = described[key]
            result.problems += [(node, p) for p in problems]
            if text is not None and result.description is None:
                result.description = text
    return result


def evaluate_package(root: str) -> Launched | None:
    """``root`` built in a temporary install tree, its first launch file evaluated, then each other one
    (None: no package.xml)."""
    if not os.path.isfile(os.path.join(root, "package.xml")):
        return None
    with scratch.folder("bras-kit-build-") as base:
        first = launch_package(root, os.path.join(base, "install"), ahead=True)
        if first.plan is not None:
            for other in launch_sources(first.build):
                if other != first.launch_file:
                    first.others[other] = launch_package(root, os.path.join(base, "install"), other)
    return first
