"""RViz as a launch starts it: the configuration ``rviz2`` opens with, the description topics
robot_state_publisher publishes, and the transforms on tf while the launch runs. The page and the
terminal both read these, then :func:`bras_kit.ros.rviz.config.shown`."""

from __future__ import annotations

import os
from collections.abc import Iterable, Sequence
from dataclasses import dataclass, replace
from typing import Any

from .config import RvizConfig, default_config, read_config, with_fixed_frame

RVIZ_FILE_LIMIT = 1 << 20  # a .rviz past 1 MiB (or a device, a FIFO) is not read
RSP = "robot_state_publisher"
DESCRIPTION_TOPIC = "robot_description"  # robot_state_publisher.cpp (3.3.3): its publisher's relative name


def option_value(arguments: Sequence[Any], short: str, long: str) -> str | None:
    """The value rviz2 takes for one of its options, as Qt's QCommandLineParser reads its command
    line (rviz_common visualizer_app.cpp:84-103): ``-d FILE``, ``-dFILE``, ``--display-config FILE``
    or ``--display-config=FILE``; given twice, the last (QCommandLineParser::value)."""
    value = None
    for k, item in enumerate(arguments):
        if not isinstance(item, str):
            continue
        following = arguments[k + 1] if k + 1 < len(arguments) else None
        if item in (f"-{short}", f"--{long}"):
            value = following if isinstance(following, str) else value
        elif item.startswith(f"--{long}="):
            value = item.split("=", 1)[1]
        elif item.startswith(f"-{short}") and not item.startswith("--") and len(item) > 2:
            value = item[2:].strip()  # a short option's value written against it
    return value


def config_argument(arguments: Sequence[Any]) -> str | None:
    """The path given to rviz2 with ``-d`` / ``--display-config``."""
    return option_value(arguments, "d", "display-config")


def fixed_frame_argument(arguments: Sequence[Any]) -> str | None:
    """The frame given to rviz2 with ``-f`` / ``--fixed-frame``: set after the configuration is
    loaded, so it wins over the file's (visualizer_app.cpp:165-168)."""
    return option_value(arguments, "f", "fixed-frame")


@dataclass(frozen=True)
class Started:
    """The launch's first rviz2 and the configuration it opens with. ``given`` is the ``-d`` path
    as the launch gives it (None: no ``-d``); ``read`` whether RViz reads it (else RViz opens its
    default, visualization_frame.cpp:345-349 without -d, 674-676 for a file it cannot load)."""

    config: RvizConfig
    node: Any  # the rviz2 PlannedNode (its file and line: where the launch starts it)
    given: str | None = None
    read: bool = False
    fixed_frame: str | None = None  # -f FRAME, which wins over the file's Fixed Frame

    @property
    def file(self) -> str | None:
        """The file the configuration was read from (None: RViz's default)."""
        return self.given if self.read else None


def started(plan: Any) -> Started | None:
    """How the launch's first rviz2 starts, or None when no rviz2 is started."""
    from ...trust.learner_files import read_text

    for node in plan.nodes if plan is not None else []:
        if node.package != "rviz2":
            continue
        path = config_argument(node.arguments)
        frame = fixed_frame_argument(node.arguments)
        if path is None:
            start = Started(default_config(), node)
        else:
            # read through the one reader, inside the install tree the launch file came from: never
            # /dev/zero, a pipe, or a file elsewhere (docs/security.md)
            installed = plan.launch_file.rsplit(os.sep + "share" + os.sep, 1)[0]
            try:
                start = Started(read_config(read_text(path, (installed,), limit=RVIZ_FILE_LIMIT)), node, path, True)
            except (OSError, UnicodeDecodeError):
                start = Started(default_config(), node, path)
        if frame:  # visualizer_app.cpp:165-168: only a frame that is not empty
            start = replace(start, config=with_fixed_frame(start.config, frame), fixed_frame=frame)
        return start
    return None


def started_config(plan: Any) -> tuple[RvizConfig, str | None] | None:
    """(the configuration the launch's first rviz2 opens with, the ``-d`` file it read or None), or
    None when no rviz2 is started."""
    start = started(plan)
    return None if start is None else (start.config, start.file)


def description_topics(plan: Any) -> set[str]:
    """Where each robot_state_publisher publishes the URDF, as rcl resolves its name."""
    return {n.resolve(DESCRIPTION_TOPIC) for n in (plan.nodes if plan is not None else []) if n.package == RSP}


def launch_transforms(robot: Any, joint_states: bool, positions: dict[str, float] | None = None,
                      stamp_ns: int = 10**9, names: Iterable[str] | None = None) -> list[Any]:
    """What tf holds while the launch runs: robot_state_publisher's static transforms, and the moving
    ones once a JointState reaches it, stamped past rsp's first interval
    (robot_state_publisher.cpp:334-340) (``joint_states``: something publishes /joint_states).
    joint_state_publisher(_gui) names every movable joint; a learner's node names those it sends
    (``names``): rsp publishes a transform for each joint the message names and the URDF knows, and
    none for the others (robot_state_publisher.cpp:326-366), so a joint never sent (``coud`` for
    ``coude``) leaves its child link, and the links below it, with no transform."""
    from .frames import JointStateIn, RobotStatePublisher

    if robot is None:
        return []
    rsp = RobotStatePublisher(robot)
    rsp.static()
    if joint_states:
        if names is None:  # joint_state_publisher: the movable joints that mimic none (joint_state_publisher.py)
            sent = tuple(j.name for j in robot.joints if j.type not in ("fixed", None) and j.name and j.mimic is None)
        else:
            sent = tuple(dict.fromkeys(n for n in names if isinstance(n, str)))
        values = positions or {}
        if sent or names is None:  # a node that sent no joint of the robot leaves rsp as it was
            rsp.on_joint_state(JointStateIn(stamp_ns, sent, tuple(float(values.get(n, 0.0)) for n in sent)))
    return list(rsp.transforms())


def names_of(transforms: Iterable[Any]) -> set[str]:
    return {t.parent for t in transforms} | {t.child for t in transforms}
