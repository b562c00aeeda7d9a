"""bras-kit doctor --ros: one look at the live ROS 2 graph, its findings printed (text or JSON)."""

from __future__ import annotations

import argparse
import json
import sys
from typing import Any

from ..core.i18n import say
from ..core.message import M, Mn


def run_ros(args: argparse.Namespace) -> int:
    from ..core.errors import ParameterError
    from ..live.doctor import diagnose
    from ..live.watch import look, ros_python
    from ..ros.graph import snapshot_from_json

    if args.duration is None:
        args.duration = DEFAULT_SECONDS
    if not 0.5 <= args.duration <= 60:
        raise ParameterError(M("--duration {seconds:g} is out of range", seconds=args.duration),
                             hint=M("give seconds between 0.5 and 60, e.g. 3"))
    lang = args.lang
    if args.from_file:
        data = _read_look(args.from_file)
    else:
        if args.save:
            from ._common import check_writable

            check_writable(args.save, args.force, option="--save")
        python = ros_python()  # no rclpy: said before anything is announced
        if args.format == "text":  # what the workspace, the shell and the machine got wrong, first
            from ._surroundings import print_surroundings

            print_surroundings(lang, graphics=False, shown=("note", "fail"))
        if args.format == "text":
            print(say(M("watching the ROS 2 graph for {seconds:g} s...", seconds=args.duration), lang),
                  file=sys.stderr, flush=True)
        data = look(args.duration, python)
        if args.save:
            from ..trust.outputs import write_text

            write_text(args.save, json.dumps(data, ensure_ascii=False) + "\n", args.force, announce=False)
    snapshot = snapshot_from_json(data)
    results = diagnose(snapshot)
    errors = sum(r.count("error") for r in results)
    code = 1 if errors else 0
    if args.format == "json":
        document = _document(snapshot, results, code, lang)
        # of this terminal and machine: said of a live look only, not of one read back
        document["surroundings"] = [] if args.from_file else _surroundings(lang)
        print(json.dumps(document, ensure_ascii=False, indent=2))
        return code
    print(_text(snapshot, results, lang), end="")
    return code


DEFAULT_SECONDS = 3.0
MAX_LOOK_BYTES = 64_000_000  # a 3 s look at a 1 kHz publisher is a few MB


def _read_look(path: str) -> dict[str, Any]:
    """A look saved with --save: JSON, checked field by field when read as a snapshot."""
    from ..core.errors import ParameterError

    try:
        with open(path, "rb") as file:
            raw = file.read(MAX_LOOK_BYTES + 1)
    except OSError as exc:
        from ..core.errors import os_reason

        raise ParameterError(M("cannot read {path}: {reason}", path=path, reason=os_reason(exc))) from None
    if len(raw) > MAX_LOOK_BYTES:
        raise ParameterError(M("{path} is larger than a look saved by --save can be", path=path))
    try:
        data = json.loads(raw.decode("utf-8"))
    except (UnicodeDecodeError, json.JSONDecodeError, RecursionError):
        data = None
    if not isinstance(data, dict) or data.get("kind") != "snapshot":
        raise ParameterError(M("{path} is not a look saved by 'bras-kit doctor --ros --save'", path=path),
                             hint=M("save one with: bras-kit doctor --ros --save look.json"))
    return data


def _facts(snapshot: Any) -> list[Any]:
    """What was seen, before what is wrong with it: the domain, the nodes, who publishes what."""
    from ..ros.topics import DESCRIPTION, JOINT_STATES
    from ..validate.live import LiveGraph, measured_rate

    facts = [M("ROS 2 graph on ROS_DOMAIN_ID {domain} ({rmw}, discovery {range}), watched {seconds:.1f} s",
               domain=snapshot.domain, rmw=snapshot.rmw or "?", range=snapshot.discovery_range or "SUBNET",
               seconds=snapshot.duration)]
    if snapshot.nodes:
        count = len(snapshot.nodes) + sum(n - 1 for n in snapshot.shared_names.values())  # two of one name: two
        facts.append(Mn("{n} node: {nodes}", "{n} nodes: {nodes}", count, nodes=list(snapshot.nodes)))
    for topic in (DESCRIPTION, JOINT_STATES):
        publishers = snapshot.publishers(topic)
        if publishers:
            facts.append(M("{topic} published by {nodes}", topic=topic,
                           nodes=", ".join(f"{e.node} ({e.reliability}, {e.durability})" for e in publishers)))
    rate = measured_rate(LiveGraph(snapshot))
    if rate is not None:
        facts.append(M("{count} joint states received, {rate:.1f} Hz", count=len(snapshot.joint_states), rate=rate))
    from ..live.doctor import robot_of
    from ..validate.live import rviz_fixed_frame, rviz_replay

    graph = LiveGraph(snapshot, robot_of(snapshot)[0])
    seen = rviz_replay(graph)
    if seen is not None:
        if snapshot.transforms is None:  # no tf2_msgs where the probe ran: what rsp publishes is inferred
            facts.append(M("robot_state_publisher, as its source runs, turns {published} of them into transforms "
                           "(inferred from its model: /tf and /tf_static were not seen, tf2_msgs does not import "
                           "where the probe runs)", published=seen.published))
        else:
            facts.append(Mn("robot_state_publisher, as its source runs, turns {published} of them into transforms; "
                            "{n} transform seen on /tf and /tf_static",
                            "robot_state_publisher, as its source runs, turns {published} of them into transforms; "
                            "{n} transforms seen on /tf and /tf_static", len(snapshot.transforms),
                            published=seen.published))
    frame = rviz_fixed_frame(graph)
    facts.append(M("RViz's Fixed Frame: {frame}, {source}", frame=frame.frame, source=frame.words()))
    return facts


def _text(snapshot: Any, results: list[Any], lang: str | None) -> str:
    from ..findings.report import finding_text

    lines = [say(fact, lang) for fact in _facts(snapshot)]
    blocks = [finding_text(r.path, f, lang) for r in results for f in r.findings]
    errors = sum(r.count("error") for r in results)
    warnings = sum(r.count("warning") for r in results)
    if blocks:
        lines += [""] + blocks + [""]
    if errors:
        lines.append(say(Mn("{n} problem keeps RViz empty or the arm still ({warnings}): see the hints",
                            "{n} problems keep RViz empty or the arm still ({warnings}): see the hints",
                            errors, warnings=Mn("{n} warning", "{n} warnings", warnings)), lang))
    elif warnings:
        lines.append(say(Mn("nothing keeps RViz from showing the arm moving; {n} warning above",
                            "nothing keeps RViz from showing the arm moving; {n} warnings above", warnings), lang))
    elif _frame_is_a_link(snapshot):  # the running rviz2's Fixed Frame is a link already
        lines.append(say(M("nothing keeps RViz from showing the arm moving: add RobotModel on /robot_description "
                           "if it is still empty"), lang))
    elif (root := _root_link(snapshot)) is not None:  # the frame to choose, by its name (the tutorial's: base)
        lines.append(say(M("nothing keeps RViz from showing the arm moving: set Fixed Frame to {root} "
                           "and add RobotModel on /robot_description if it is still empty", root=root), lang))
    else:
        lines.append(say(M("nothing keeps RViz from showing the arm moving: set Fixed Frame to the root link "
                           "and add RobotModel on /robot_description if it is still empty"), lang))
    return "\n".join(lines) + "\n"


def _frame_is_a_link(snapshot: Any) -> bool:
    """Whether the Fixed Frame the running rviz2 set (-f, its file) names a link of the robot."""
    from ..live.doctor import robot_of
    from ..validate.live import LiveGraph, rviz_fixed_frame

    robot = robot_of(snapshot)[0]
    frame = rviz_fixed_frame(LiveGraph(snapshot, robot))
    return robot is not None and frame.from_learner and frame.frame in robot.link_names


def _root_link(snapshot: Any) -> str | None:
    """The root link of the robot last published on /robot_description (None without one)."""
    from ..core.errors import BrasKitError
    from ..kinematics.frames import tf_tree
    from ..live.doctor import robot_of

    robot, _ = robot_of(snapshot)
    if robot is None:
        return None
    try:
        return tf_tree(robot).root
    except BrasKitError:  # a tree the kinematics refuse: the findings said why, the words stay general
        return None


def _surroundings(lang: str | None) -> list[dict[str, Any]]:
    """What the workspace, the shell and the machine got wrong (bras_kit.ros.surroundings), worded."""
    from ..doctor.surroundings import look

    return [{"area": c.area, "status": c.status, "name": say(c.name, lang), "found": say(c.found, lang),
             "fix": say(c.fix, lang) if c.fix is not None else None}
            for c in look(".", graphics=False) if c.status != "ok"]


def _document(snapshot: Any, results: list[Any], code: int, lang: str | None) -> dict[str, Any]:
    from ..live.doctor import robot_of
    from ..validate.live import LiveGraph, measured_rate, rviz_fixed_frame, timeline

    graph = LiveGraph(snapshot, robot_of(snapshot)[0])
    frame = rviz_fixed_frame(graph)
    return {
        "fixed_frame": {"frame": frame.frame, "source": frame.source, "path": frame.path, "pid": frame.pid,
                        "words": say(frame.words(), lang)},
        "transforms_seen": snapshot.transforms is not None,
        "timeline": [{"at": round(at, 2), "event": kind, **what} for at, kind, what in timeline(graph)],
        "domain": snapshot.domain,
        "rmw": snapshot.rmw,
        "discovery_range": snapshot.discovery_range,
        "seconds": round(snapshot.duration, 3),
        "nodes": list(snapshot.nodes),
        "publishers": {topic: [e.node for e in t.publishers] for topic, t in sorted(snapshot.topics.items())},
        "joint_states_received": len(snapshot.joint_states),
        "joint_states_rate": measured_rate(LiveGraph(snapshot)),
        "elsewhere": [{"domain": e.domain, "discovery_range": e.discovery_range, "nodes": list(e.nodes)}
                      for e in snapshot.elsewhere],
        "findings": [{"place": r.path, **f.as_dict(lang)} for r in results for f in r.findings],
        "exit_code": code,
    }
