""""RViz reste vide" (BK610-BK615): the ``.rviz`` configuration the launch file gives RViz, as
rviz2 loads it (:mod:`bras_kit.ros.rviz`).

Registered on import (:mod:`bras_kit.validate.package`); every hit carries ``file``.
"""

from __future__ import annotations

import os
from collections.abc import Iterator
from typing import Any

from ...findings.registry import ERROR, INFO, Hit
from ...ros.package import (
    Package,
)
from ...ros.staticpy import ShareFile, known
from .rules import (
    ROBOT_DESCRIPTION,
    _at,
    _config_argument,
    _included,
    _rviz_files,
    _rviz_starts,
    package_rule,
)

# ---------------------------------------------------------------- "RViz reste vide"








def _description_topic_mismatches(pkg: Package, source: str, value: str) -> list[tuple[str, list[str], str]] | None:
    """(the topic RViz subscribes to, the topics robot_state_publisher publishes, the launch file)
    for each evaluated launch that gives ``source`` to RViz beside a robot_state_publisher, as rcl
    resolves both names (namespace, remappings, ``~/``: bras_kit/ros/names.py). None when no
    evaluated launch tells (then the root topic /robot_description is the reference)."""
    from .evaluated import description_topics, evaluations, rviz_uses

    told = False
    out = []
    for use in rviz_uses(pkg, evaluations(pkg) or []):
        published = description_topics(use.result)
        if use.source != source or not published:
            continue
        told = True
        heard = use.node.resolve(value)
        if heard not in published:
            out.append((heard, sorted(published), use.launch))
    return out if told else None


def _rviz_lines(lines: list[str], key: str, start: int = 0) -> int | None:
    for k in range(start, len(lines)):
        if lines[k].strip().startswith(key):
            return k + 1
    return None


@package_rule("BK610", "rviz-fixed-frame-not-a-link", ERROR)
def rviz_fixed_frame_not_a_link(pkg: Package) -> Iterator[Hit]:
    from ...ros.rviz.config import fixed_frame_of

    robot = pkg.robot
    if robot is None:
        return
    links = [link.name for link in robot.links if link.name]
    if any(launch.includes for launch in pkg.launch_files):
        return  # other frames may be published (static transforms, included launch files)
    root = _root(robot) or (links[0] if links else "base")
    forced: set[str | None] = set()  # the .rviz files whose Fixed Frame rviz2's -f replaces
    said = set()
    for result, start in _rviz_started(pkg):
        if not start.fixed_frame:
            continue
        if start.file is not None:
            forced.add(result.build.source_of(os.path.normpath(start.file)))
        file, line = _place(result, start.node.file, start.node.line)
        if start.config.fixed_frame not in links and (file, line) not in said:
            said.add((file, line))
            yield _at(file, line or None, "argument", frame=start.config.fixed_frame, links=links, root=root)
    for source, _, _ in _rviz_files(pkg):
        if source in forced:
            continue
        parsed = pkg.rviz(source)
        if parsed is None:
            continue
        data, lines = parsed
        # the Fixed Frame as RViz takes it from the file (the page reads it the same way)
        frame, set_in_file = fixed_frame_of(data)
        if frame in links:
            continue
        if not set_in_file:
            yield _at(source, _rviz_lines(lines, "Global Options:"), "missing", frame=frame, root=root)
        else:
            yield _at(source, _rviz_lines(lines, "Fixed Frame:"), frame=str(frame), links=links, root=root)


def _rviz_started(pkg: Package) -> Iterator[tuple[Any, Any]]:
    """(evaluated launch, how its rviz2 starts: ros.rviz.started) for each evaluated launch with rviz2."""
    from ...ros.rviz.started import started
    from .evaluated import evaluations

    for result in evaluations(pkg) or []:
        start = started(result.plan)
        if start is not None:
            yield result, start


def _place(result: Any, file: str, line: int) -> tuple[str, int]:
    from .evaluated import place

    return place(result, file, line)


def _root(robot: Any) -> str | None:
    children = {j.child for j in robot.joints}
    return next((link.name for link in robot.links if link.name and link.name not in children), None)


@package_rule("BK611", "rviz-robot-model-not-shown", ERROR)
def rviz_robot_model_not_shown(pkg: Package) -> Iterator[Hit]:
    for source, _, _ in _rviz_files(pkg):
        parsed = pkg.rviz(source)
        if parsed is None:
            continue
        _, lines = parsed
        # the page's reading, RViz's (bras_kit.ros.rviz.config): every scalar a string, a display
        # unchecked unless Value/Enabled say so and Enabled read last (display.cpp:277-291), an
        # unknown Description Source read as Topic (enum_property.cpp:65-73)
        from ...ros.rviz.config import read_config

        models = [d for d in read_config("\n".join(lines)).displays if d.kind.endswith("/RobotModel")]
        if not models:
            yield _at(source, _rviz_lines(lines, "Displays:"), "missing")
            continue
        model = models[0]
        start = (_rviz_lines(lines, "Class: rviz_default_plugins/RobotModel") or 1) - 1
        if not model.enabled:
            yield _at(source, start + 1, "disabled")
        if model.description_source != "Topic":
            continue
        value = model.description_topic
        line = _rviz_lines(lines, "Description Topic:", start) or start + 1
        mismatches = _description_topic_mismatches(pkg, source, str(value)) if isinstance(value, str) and value \
            else None
        if mismatches is None:
            if value != ROBOT_DESCRIPTION:
                yield _at(source, line, "topic", topic=str(value if value is not None else ""))
            continue
        for heard, published, launch in dict.fromkeys((h, tuple(p), lf) for h, p, lf in mismatches):
            plain = list(published) == [ROBOT_DESCRIPTION]
            yield _at(source, line, "topic" if plain and heard == value else "namespace", topic=heard,
                      published=", ".join(published), launch=launch)


@package_rule("BK612", "rviz-no-tf-display", INFO)
def rviz_no_tf_display(pkg: Package) -> Iterator[Hit]:
    for source, _, _ in _rviz_files(pkg):
        parsed = pkg.rviz(source)
        if parsed is None:
            continue
        _, lines = parsed
        from ...ros.rviz.config import TF, read_config

        if not any(d.kind == TF for d in read_config("\n".join(lines)).displays):  # RViz's reading (the page's)
            yield _at(source, _rviz_lines(lines, "Displays:"))


@package_rule("BK613", "rviz-without-configuration", INFO)
def rviz_without_configuration(pkg: Package) -> Iterator[Hit]:
    """RViz opens its default configuration: the launch's rviz2 as :mod:`bras_kit.ros.rviz.started`
    starts it (the page's RViz is that same start), or, with no evaluation, as the Python launch
    files read."""
    from .evaluated import evaluations

    results = evaluations(pkg)
    if results is None:
        yield from _rviz_default_in_sources(pkg)
        return
    yield from _rviz_default_started(pkg)


def _rviz_default_started(pkg: Package) -> Iterator[Hit]:
    said = set()
    for result, start in _rviz_started(pkg):
        if start.read:
            continue
        file, line = _place(result, start.node.file, start.node.line)
        if (file, line) in said:
            continue  # an included launch file's rviz2, said once
        said.add((file, line))
        if start.given is None:  # no -d (visualization_frame.cpp:345-349): the default, empty
            configs = pkg.files("rviz", (".rviz",))
            yield _at(file, line or None, "unused" if configs else "", config=configs[0] if configs else "",
                      package=pkg.name)
            continue
        # a -d RViz cannot load: it logs so and opens its default (visualization_frame.cpp:674-676)
        share = os.path.join(result.build.prefix, "share", pkg.name) + os.sep
        config = os.path.normpath(start.given)
        if not config.startswith(share) or result.build.source_of(config) is not None:
            continue  # another package's file, a folder of the learner's, or installed yet unreadable
        inside = config[len(share):]
        variant = "not_installed" if os.path.isfile(os.path.join(pkg.root, inside)) else "missing"
        yield _at(file, line or None, variant, config=inside, package=pkg.name)


def _rviz_default_in_sources(pkg: Package) -> Iterator[Hit]:
    """BK613 read from the Python launch files, when no launch was evaluated (``validate`` without
    ``--launch``): -d to a file of the package's share folder, or no -d."""
    installed = pkg.installed()
    for path, node in _rviz_starts(pkg):
        target = _config_argument(node)
        if isinstance(target, ShareFile) and target.package == pkg.name and target.relative.endswith(".rviz"):
            if not os.path.isfile(os.path.join(pkg.root, target.relative)):
                yield _at(path, node.line, "missing", config=target.relative, package=pkg.name)
            elif installed is not None and target.relative not in installed:
                yield _at(path, node.line, "not_installed", config=target.relative, package=pkg.name)
            continue
        if not known(node.arguments) or target is not None:
            continue
        configs = pkg.files("rviz", (".rviz",))
        yield _at(path, node.line, "unused" if configs else "", config=configs[0] if configs else "",
                  package=pkg.name)


@package_rule("BK615", "rviz-not-started", INFO)
def rviz_not_started(pkg: Package) -> Iterator[Hit]:
    """robot_state_publisher started, no rviz2 (ros.rviz.started finds none: the page opens no RViz)."""
    from ...ros.rviz.started import started
    from .evaluated import evaluations, standing_alone

    for result in standing_alone(evaluations(pkg) or []):
        rsp = [n for n in result.plan.nodes if n.package == "robot_state_publisher"]
        if not rsp or started(result.plan) is not None or _included(pkg, result.launch_file):
            continue
        if result.plan.included or result.plan.processes:
            continue  # an included launch file, or a process bras-kit does not know, may start RViz
        file, line = _place(result, rsp[0].file, rsp[0].line)
        yield _at(file, line or None)
