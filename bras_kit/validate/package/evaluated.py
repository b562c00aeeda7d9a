"""The package's launch files as ``ros2 launch`` evaluated them, for the rules that judge a launch
as a whole: which files stand on their own (a file another one includes is judged with it), which
topics robot_state_publisher really publishes (rcl's names: namespaces, remappings, ``~/``), which
``.rviz`` files RViz is given. Only when the launch files were evaluated (``validate --launch``,
``bras-kit launch``); the rules fall back to reading the Python launch files otherwise.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any

from ...ros.launched import Launched, evaluate_package
from ...ros.package import JOINT_STATE_PUBLISHERS, Package, relative

RSP = "robot_state_publisher"
DESCRIPTION_TOPIC = "robot_description"  # robot_state_publisher.cpp: create_publisher(..., "robot_description", ...)


def evaluations(pkg: Package) -> list[Any] | None:
    """The evaluated launch files that did not stop (``Launched``), or None if none was evaluated."""
    top = pkg.launched
    if top is None and pkg.evaluate:
        top = launched(pkg)
    if top is None or top.plan is None:
        return None
    results = [top, *top.others.values()]
    return [r for r in results if r.plan is not None and r.plan.failure is None]


def standing_alone(results: list[Any]) -> list[Any]:
    """The files no other evaluated file includes: an included file is part of the launch that includes it."""
    included = {os.path.realpath(f) for r in results for f in r.plan.included}
    return [r for r in results if os.path.realpath(r.plan.launch_file) not in included]


def launched(pkg: Package) -> Launched | None:
    """The package built and its launch files evaluated (kept on the Package; begun ahead in a
    worker where the CLI did, see :attr:`Package.ahead`)."""
    if pkg.launched is not None:
        return pkg.launched
    result = pkg.ahead(pkg.root) if pkg.ahead is not None else None
    if result is None:
        result = evaluate_package(pkg.root)
    pkg.launched = result
    return result


def place(result: Launched, file: str, line: int) -> tuple[str, int]:
    """A file of the install tree (or the package) as the package file it came from."""
    if not file:
        return result.launch_file, 0
    source = result.build.source_of(file)
    if source is not None:
        return source, line
    if file.startswith(result.build.root + os.sep):
        return relative(result.build.root, file), line
    return result.launch_file, 0


def description_topics(result: Any) -> set[str]:
    """Where each robot_state_publisher the launch starts publishes the URDF (rcl_node_resolve_name)."""
    return {n.resolve(DESCRIPTION_TOPIC) for n in result.plan.nodes if n.package == RSP}


JOINT_STATES = "joint_states"  # robot_state_publisher subscribes to it, joint_state_publisher(_gui) publishes it


def joint_state_topics(result: Any, publisher_of: Any) -> tuple[set[str], list[tuple[str, str | None]]]:
    """(the topics robot_state_publisher listens on, [(who, the topic it publishes JointState on)])
    as rcl resolves each node's name: its namespace, its -r rules. ``who``'s topic is None when it
    cannot be known (a process bras-kit does not know, a topic that is not written literally)."""
    listens = {n.resolve(JOINT_STATES) for n in result.plan.nodes if n.package == RSP}
    sources: list[tuple[str, str | None]] = []
    for node in result.plan.nodes:
        if node.package in JOINT_STATE_PUBLISHERS:
            sources.append((node.full_name, node.resolve(JOINT_STATES)))
        elif node.package == result.build.package:
            publisher = publisher_of(node.executable)
            if publisher is not None:
                topic = publisher.topic
                sources.append((node.full_name, node.resolve(topic) if isinstance(topic, str) and topic else None))
    sources += [(" ".join(p["cmd"][:1]), None) for p in result.plan.processes]
    return listens, sources


def joint_state_sources(result: Any, publishes: Any) -> bool:
    """Whether something the launch starts may publish /joint_states: a joint_state_publisher, one of
    the package's own nodes that ``publishes`` says publishes JointState, or a process bras-kit does not know."""
    for node in result.plan.nodes:
        if node.package in JOINT_STATE_PUBLISHERS:
            return True
        if node.package == result.build.package and publishes(node.executable):
            return True
    return bool(result.plan.processes)


@dataclass(frozen=True)
class RvizUse:
    """An .rviz file of the package that an evaluated launch gives to rviz2 -d, and where."""

    source: str  # the .rviz file of the package (relative)
    launch: str  # the launch file that gives it (relative)
    line: int
    node: Any  # the rviz2 PlannedNode
    result: Any  # the Launched it belongs to


def rviz_uses(pkg: Package, results: list[Any]) -> Iterator[RvizUse]:
    """Each ``rviz2 -d FILE`` of the evaluated launches whose FILE is installed from this package."""
    for result in results:
        for node in result.plan.nodes:
            if node.package != "rviz2":
                continue
            config = _config(node.arguments)
            if config is None:
                continue
            source = result.build.source_of(os.path.normpath(config))  # a doubled slash is the same file
            if source is None or not os.path.isfile(os.path.join(pkg.root, source)):
                continue
            launch, line = place(result, node.file, node.line)
            yield RvizUse(source, launch, line, node, result)


def rviz_config(node: Any) -> str | None:
    """The path rviz2 is given with ``-d`` (rviz_common's --display-config), if any."""
    return _config(node.arguments)


def _config(arguments: list[str]) -> str | None:
    from ...ros.rviz.started import config_argument

    return config_argument(arguments)  # rviz2's own reading of its command line, the page's
