"""RViz as a launch starts it: the configuration ``rviz2`` opens with, the description topics
robot_state_publisher publishes, and the transforms on tf while the launch runs. The page and the
terminal both read these, then :func:`bras_kit.ros.rviz.config.shown`."""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence
from typing import Any

from .config import RvizConfig, default_config, read_config

RVIZ_FILE_LIMIT = 1 << 20  # a .rviz past 1 MiB (or a device, a FIFO) is not read
RSP = "robot_state_publisher"
DESCRIPTION_TOPIC = "robot_description"  # robot_state_publisher.cpp (3.3.3): its publisher's relative name


def config_argument(arguments: Sequence[Any]) -> str | None:
    """The path given to rviz2 with ``-d`` / ``--display-config`` (rviz2's main.cpp options)."""
    for k, item in enumerate(arguments):
        if not isinstance(item, str):
            continue
        if item in ("-d", "--display-config") and k + 1 < len(arguments):
            following = arguments[k + 1]
            return following if isinstance(following, str) else None
        if item.startswith("-d") and len(item) > 2:
            return item[2:].strip()
    return None


def started_config(plan: Any) -> tuple[RvizConfig, str | None] | None:
    """(the configuration the launch's first rviz2 opens with, the ``-d`` file it read or None), or
    None when no rviz2 is started. No ``-d``, or a ``-d`` file that cannot be had: RViz's default
    (visualization_frame.cpp:345-349 and 674-676)."""
    from ...trust.learner_files import read_text

    for node in plan.nodes if plan is not None else []:
        if node.package != "rviz2":
            continue
        path = config_argument(node.arguments)
        if path is None:
            return default_config(), None
        # read through the one reader, inside the install tree the launch file came from: never
        # /dev/zero, a pipe, or a file elsewhere (docs/security.md)
        installed = plan.launch_file.rsplit(os.sep + "share" + os.sep, 1)[0]
        try:
            text = read_text(path, (installed,), limit=RVIZ_FILE_LIMIT)
        except (OSError, UnicodeDecodeError):
            return default_config(), None
        return read_config(text), path
    return None


def description_topics(plan: Any) -> set[str]:
    """Where each robot_state_publisher publishes the URDF, as rcl resolves its name."""
    return {n.resolve(DESCRIPTION_TOPIC) for n in (plan.nodes if plan is not None else []) if n.package == RSP}


def launch_transforms(robot: Any, joint_states: bool, positions: dict[str, float] | None = None,
                      stamp_ns: int = 10**9) -> list[Any]:
    """What tf holds while the launch runs: robot_state_publisher's static transforms, and the moving
    ones once a JointState naming the movable joints reaches it, stamped past rsp's first interval
    (robot_state_publisher.cpp:334-340) (``joint_states``: something publishes
    /joint_states, joint_state_publisher(_gui) or the learner's node)."""
    from .frames import JointStateIn, RobotStatePublisher

    if robot is None:
        return []
    rsp = RobotStatePublisher(robot)
    rsp.static()
    if joint_states:
        # joint_state_publisher publishes the movable joints that mimic none (joint_state_publisher.py)
        names = tuple(j.name for j in robot.joints if j.type not in ("fixed", None) and j.name and j.mimic is None)
        values = positions or {}
        rsp.on_joint_state(JointStateIn(stamp_ns, names, tuple(float(values.get(n, 0.0)) for n in names)))
    return list(rsp.transforms())


def names_of(transforms: Iterable[Any]) -> set[str]:
    return {t.parent for t in transforms} | {t.child for t in transforms}
