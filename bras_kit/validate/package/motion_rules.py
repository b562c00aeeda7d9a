""""Le robot apparaît mais ne bouge pas" (BK614, BK620-BK623): who publishes ``/joint_states``,
with which names and within which limits, and whether ``ros2 run`` can find the node.

Registered on import (:mod:`bras_kit.validate.package`); every hit carries ``file``.
"""

from __future__ import annotations

from collections.abc import Iterator
from typing import Any

from ...findings.registry import ERROR, Hit
from ...ros.launch_source import NodeCall
from ...ros.package import (
    JOINT_STATE_PUBLISHERS,
    SETUP_PY,
    Package,
)
from .rules import (
    MOTION_SECONDS,
    _at,
    _included,
    _misplaced,
    _module_file,
    _module_written,
    _not_written,
    _on_joint_states,
    _publisher_for,
    package_rule,
)

# ---------------------------------------------------------------- "le robot ne bouge pas"




def _own_executables(pkg: Package) -> list[tuple[str, NodeCall]]:
    return [(launch.path, node) for launch in pkg.launch_files for node in launch.nodes
            if node.package == pkg.name]




@package_rule("BK620", "no-joint-state-source", ERROR)
def no_joint_state_source(pkg: Package) -> Iterator[Hit]:
    from .evaluated import (
        evaluations,
        joint_state_sources,
        joint_state_topics,
        place,
        standing_alone,
    )

    results = evaluations(pkg) or []
    movable = [j.name for j in pkg.robot.movable_joints()] if pkg.robot is not None else []
    heard = [p for p in pkg.publishers if _on_joint_states(p.topic)]  # BK624 speaks of the others
    # evaluated: each launch as ros2 launch runs it, an included file judged with the file that includes it
    for result in standing_alone(results):
        if _included(pkg, result.launch_file):
            continue  # judged with the file that includes it (BK631 when that one stops)
        rsp = [n for n in result.plan.nodes if n.package == "robot_state_publisher"]
        if not rsp:
            continue
        file, line = place(result, rsp[0].file, rsp[0].line)
        if not joint_state_sources(result, lambda executable: _publisher_for(pkg, executable) is not None):
            yield _at(file, line or None, "nodes" if heard else "", joints=movable or ["?"],
                      node=heard[0].module if heard else "")
            continue
        # rcl's names: the sliders at the root beside a namespaced robot_state_publisher are not heard
        listens, sources = joint_state_topics(result, lambda executable: _publisher_for(pkg, executable))
        in_code = {n.full_name for n in result.plan.nodes if n.package == pkg.name
                   and (p := _publisher_for(pkg, n.executable)) is not None and not _on_joint_states(p.topic)}
        if all(who in in_code for who, _ in sources):
            continue  # BK624 names the topic written in the node
        if sources and all(topic is not None and topic not in listens for _, topic in sources):
            yield _at(file, line or None, "topic", joints=movable or ["?"], listens=", ".join(sorted(listens)),
                      sources=", ".join(f"{who} -> {topic}" for who, topic in sources))
    evaluated = {r.launch_file for r in results}
    for launch in pkg.launch_files:  # the Python launch files no evaluation judged
        if launch.path in evaluated:
            continue
        nodes = launch.nodes
        starts_rsp = any(n.package == "robot_state_publisher" for n in nodes)
        if not starts_rsp or launch.includes or _included(pkg, launch.path):
            continue  # another launch file or process may publish the joint states
        if any(n.package in JOINT_STATE_PUBLISHERS or not isinstance(n.package, str) for n in nodes):
            continue
        own = [n for n in nodes if n.package == pkg.name]
        if any(not isinstance(n.executable, str) or _publisher_for(pkg, n.executable) is not None for n in own):
            continue
        line = next(n.line for n in nodes if n.package == "robot_state_publisher")
        yield _at(launch.path, line, "nodes" if heard else "", joints=movable or ["?"],
                  node=heard[0].module if heard else "")


@package_rule("BK621", "joint-state-names-mismatch", ERROR)
def joint_state_names_mismatch(pkg: Package) -> Iterator[Hit]:
    robot = pkg.robot
    if robot is None:
        return
    movable = [j.name for j in robot.movable_joints() if j.name]
    for publisher in pkg.publishers:
        if publisher.names is None:
            continue
        unknown = [n for n in publisher.names if n not in movable]
        missing = [n for n in movable if n not in publisher.names]
        line = publisher.names_line or publisher.line
        if unknown:
            yield _at(publisher.path, line, "unknown_one" if len(unknown) == 1 else "unknown", names=unknown,
                      joints=movable)
        if missing:
            yield _at(publisher.path, line, "missing_one" if len(missing) == 1 else "missing", names=missing,
                      published=publisher.names or ["-"])


@package_rule("BK622", "node-entry-point-missing", ERROR)
def node_entry_point_missing(pkg: Package) -> Iterator[Hit]:
    setup = pkg.setup
    if setup is None or setup.scripts is None:
        return
    scripts = {s.name: s for s in setup.scripts}
    for path, node in _own_executables(pkg):
        if isinstance(node.executable, str) and node.executable.endswith(".py") and node.executable[:-3] in scripts:
            continue  # BK631: the executable is the console_scripts name, without .py
        if isinstance(node.executable, str) and node.executable not in scripts:
            yield _at(path, node.line, "launch", executable=node.executable, package=pkg.name,
                      entry=_entry_text(node.executable, f"{pkg.name}.{node.executable}"))
    listed = {s.module for s in setup.scripts}
    misplaced = {script.module: _misplaced(pkg, script.module) for script in setup.scripts
                 if not _module_written(pkg, script.module)}
    for publisher in pkg.publishers:
        if any(publisher.path in files for files in misplaced.values()):
            continue  # the node an entry names, in the wrong folder: said below
        if publisher.has_main and publisher.module not in listed:
            executable = publisher.module.rsplit(".", 1)[-1]
            yield _at(SETUP_PY, setup.scripts_line, "node", module=publisher.module, node_file=publisher.path,
                      package=pkg.name, executable=executable, entry=_entry_text(executable, publisher.module))
    for script in setup.scripts:
        if _not_written(pkg, script.module):
            continue  # BK608: the node is the learner's next step
        if misplaced.get(script.module):
            yield _at(SETUP_PY, script.line, "elsewhere", executable=script.name, module=script.module,
                      node_file=_module_file(script.module), found=misplaced[script.module],
                      moved=misplaced[script.module][0], package=pkg.name)
            continue
        tree = pkg.module_tree(script.module)
        if tree is None:
            yield _at(SETUP_PY, script.line, "module", executable=script.name, module=script.module)
        elif script.function and not any(getattr(n, "name", None) == script.function for n in tree.body):
            yield _at(SETUP_PY, script.line, "function", executable=script.name, module=script.module,
                      function=script.function)


def _entry_text(executable: str, module: str) -> str:
    return f"'{executable} = {module}:main'"


@package_rule("BK623", "node-motion-outside-limits", ERROR)
def node_motion_outside_limits(pkg: Package) -> Iterator[Hit]:
    robot = pkg.robot
    if robot is None:
        return
    movable = {j.name for j in robot.movable_joints()}
    for publisher in pkg.publishers:
        if publisher.degrees:
            continue  # BK626 names the cause: the node's angles are in degrees
        formulas = {joint: text for joint, text in publisher.formulas.items() if joint in movable}
        for joint, text, violation in _violations(robot, formulas):
            yield _at(publisher.path, publisher.formulas_line or publisher.line, violation.side,
                      joint=joint, formula=text, value=round(violation.value, 3), time=round(violation.time, 2),
                      bound=violation.bound, unit=violation.unit)


def _violations(robot: Any, formulas: dict[str, str]) -> Iterator[tuple[str, str, Any]]:
    """Position limit violations of each formula, as the motion module's sampling and checks find
    them (followed with Python floats: validating a package needs no numpy, issue 43)."""
    if not formulas:
        return
    from ...core.errors import BrasKitError
    from ...motion.formula_limits import formula_position_violations

    for joint, text in formulas.items():
        try:
            violations = formula_position_violations(robot, joint, text, MOTION_SECONDS)
        except BrasKitError:
            continue  # not a formula the motion module accepts: not literal enough to judge
        for violation in violations:
            yield joint, text, violation


@package_rule("BK614", "robot-description-not-given", ERROR)
def robot_description_not_given(pkg: Package) -> Iterator[Hit]:
    """robot_state_publisher needs the URDF text in its robot_description parameter."""
    for launch in pkg.launch_files:
        for node in launch.nodes:
            if node.package != "robot_state_publisher" or node.parameters is None:
                continue  # parameters built in a way only running the file would tell
            if node.arguments:
                continue  # robot_state_publisher reads a file argument (its deprecated fallback): BK632 checks it
            if "robot_description" not in node.parameters:
                yield _at(launch.path, node.line, "" if node.has_parameters else "none",
                          fix="parameters=[{'robot_description': description}]")
