"""bras-kit motion: a motion program -> a joint-state sequence, checked against the joint limits.

Output files look like a recording of /joint_states:
  CSV (long form): ``time,name,position,velocity``, one row per joint per sample;
  JSON: a list of messages ``{"time": t, "name": [...], "position": [...], "velocity": [...]}``.
Samples are taken at k / rate for k = 0 .. floor(duration * rate): 10 s at 20 Hz gives 201 samples
(both ends), so a CSV has 201 x joints rows after its header.
"""

from __future__ import annotations

import argparse
import math
import sys

from ..core.errors import ParameterError
from ..core.i18n import labelled, say
from ..core.message import M, Mn
from ._common import (
    add_force_argument,
    add_model_arguments,
    add_node_argument,
    add_topic_argument,
    apply_node,
    joint_values,
    load_model,
    warn,
    warn_motion_notes,
)

_EPILOG = """\
motion SPEC (repeatable):
  tutorial                 the tutorial's node: epaule=0.8*sin(t), coude=1.2*sin(0.7*t) (+ poignet)
  JOINT=FORMULA            a formula of the time t in seconds, e.g. coude=1.2*sin(0.7*t)
                           (numbers, t, pi, e, + - * / ** %, sin cos tan asin acos atan atan2
                           sqrt exp log abs min max clip floor ceil deg)
  FILE.csv|.json|.yaml     waypoints: time,JOINT,... (CSV) or {"waypoints": [{"time": 0,
                           "positions": {"epaule": 0}}, ...]}
  BAG                      a ROS 2 bag (folder with metadata.yaml, .mcap or .db3): its
                           /joint_states (or --topic NAME), linear between samples
Joints no spec drives stay at 0 (or their --set value; 'tutorial' drives all the others).

examples:
  bras-kit motion                                  summary of the tutorial's motion
  bras-kit motion -o states.csv                    10 s at 20 Hz: 201 samples x 2 joints
  bras-kit motion --motion coude=2.5*sin(t)        warns: coude goes past its upper limit
  bras-kit motion --wrist --motion tutorial --set poignet=0.5 -o states.json
  bras-kit motion --motion path.yaml --interpolation cubic --clamp -o states.csv
  bras-kit motion -o run.mcap                      a ROS 2 bag: run/run.mcap + run/metadata.yaml
  bras-kit motion --motion ~/bags/rosbag2_2024_05_01/   limits checked on a real recording
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = _EPILOG
    add_model_arguments(parser)
    parser.add_argument("-m", "--motion", action="append", default=[], metavar="SPEC",
                        help="a waypoint file; default: tutorial")
    add_node_argument(parser)
    parser.add_argument("--set", dest="set_values", action="append", default=[], metavar="JOINT=VALUE",
                        help="the joint is held at it")
    parser.add_argument("--duration", type=float, metavar="S",
                        help="sampled (default: the last waypoint's time, else 10)")
    parser.add_argument("--rate", type=float, default=None, metavar="HZ",
                        help="default: 20, like the tutorial's node")
    parser.add_argument("--interpolation", choices=("linear", "cubic"),
                        help="default: the file's own, else linear; cubic is smooth (C1), starts and ends at rest and never overshoots a waypoint")
    parser.add_argument("--clamp", action="store_true",
                        help="keep positions inside the joint limits (default: warn only)")
    parser.add_argument("--strict", action="store_true",
                        help="a limit still exceeded")
    add_topic_argument(parser)
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="the joint states to FILE (.csv or .json; '-' for stdout; .mcap, .db3 or FOLDER/ for a ROS 2 bag with /robot_description, /tf and /joint_states) instead of printing a summary")
    parser.add_argument("--format", choices=("csv", "json", "bag"),
                        help="default: from the -o extension; csv for '-'")
    add_force_argument(parser)


def _output_format(args: argparse.Namespace) -> str | None:
    if args.output is None:
        if args.format:
            raise ParameterError(M("--format needs -o FILE (or -o - for stdout)"))
        return None
    if args.format:
        return str(args.format)
    from ..motion.states_io import states_format

    fmt = states_format(args.output)
    if fmt is None:
        raise ParameterError(M("cannot tell the format of '{path}'", path=args.output),
                             hint=M("end the file name in .csv, .json or .mcap (a ROS 2 bag), or pass --format csv|json"))
    return fmt


def run(args: argparse.Namespace) -> int:
    from ..motion import (
        DEFAULT_RATE,
        WAYPOINT_SUFFIXES,
        check_limits,
        clamp,
        describe_segment,
        describe_violation,
        motion_from_specs,
        sample,
        waypoint_speeds,
    )
    from ..motion.states_io import check_states_output, write_states

    if args.file and args.file.lower().endswith(WAYPOINT_SUFFIXES):
        raise ParameterError(M("'{path}' looks like a waypoint file, not a robot", path=args.file),
                             hint=M("pass it as --motion {path} (FILE is the robot: .urdf or .xacro)", path=args.file))
    fmt = _output_format(args)
    if fmt == "bag" and args.output == "-":
        raise ParameterError(M("a ROS 2 bag is a folder: it cannot go to standard output"),
                             hint=M("give -o run.mcap (the bag is the folder run/)"))
    if fmt is not None and args.output != "-":
        check_states_output(args.output, args.force, fmt)
    apply_node(args, args.duration)
    robot = load_model(args)
    motion = motion_from_specs(robot, args.motion, joint_values(args.set_values), args.interpolation, args.topic,
                               recorded=args.recorded)
    warn_motion_notes(motion)
    if args.interpolation and not any(t.waypoints is not None for t in motion.tracks):
        warn(M("--interpolation only applies to waypoint files"), args.lang)
    rate = DEFAULT_RATE if args.rate is None else args.rate
    states = sample(motion, args.duration, rate)
    segments = waypoint_speeds(robot, motion)
    violations = check_limits(robot, states)
    clamped = []
    if args.clamp:
        clamped = [v for v in violations if v.kind == "position"]
        states = clamp(robot, states)
        violations = check_limits(robot, states)
    lang = args.lang
    for segment in segments[:10]:
        warn(describe_segment(segment), lang)
    if len(segments) > 10:
        warn(M("... and {count} more waypoint segments too fast", count=len(segments) - 10), lang)
    reported = {s.joint for s in segments}
    for v in clamped:
        warn(M("clamped: {what}", what=describe_violation(v)), lang)
    for v in violations:
        if v.kind == "velocity" and v.joint in reported:
            continue  # already named segment by segment
        warn(describe_violation(v), lang)
    if any(v.kind == "position" for v in violations):
        print("  " + labelled(M("hint"), say(M("pass --clamp to keep positions inside the limits, or lower the "
                                                "amplitude"), lang), lang), file=sys.stderr)
    if fmt is None:
        print(_summary(robot, motion, states, violations, clamped, rate, lang))
    else:
        written = write_states(robot, states, args.output, args.force, fmt)
        if written is not None:
            print(say(written), file=sys.stderr)
    return 1 if args.strict and (violations or segments) else 0


def _summary(robot, motion, states, violations, clamped, rate: float, lang: str) -> str:
    from ..motion import joint_unit
    from ..motion.sources import motion_title

    duration = float(states.times[-1]) if len(states) else 0.0
    lines = [say(M("motion: {label}; {duration:g} s at {rate:g} Hz, {samples} samples x {joints} joints",
                   label=motion_title(motion.label) if motion.label else M("fixed pose"), duration=duration,
                   rate=rate, samples=len(states), joints=len(states.names)), lang)]
    if not states.names:
        lines.append(say(M("the robot has no movable joint"), lang))
        return "\n".join(lines)
    header = tuple(say(word, lang) for word in (M("joint"), "min", "max", M("lower"), M("upper"), "max|vel|",
                                                 M("vel.limit"), M("limits"), M("source")))
    rows = [header]
    unusable = 0
    sources = motion.sources()
    for k, name in enumerate(states.names):
        joint = robot.joint(name)
        lower, upper = joint.bounds() if joint else (float("-inf"), float("inf"))
        speed = joint.limit.velocity if joint is not None and joint.limit is not None else None
        status = [say(M("clamped (upper)") if v.side == "upper" else M("clamped (lower)"), lang)
                  for v in clamped if v.joint == name]
        status += [say(M("too fast") if v.kind == "velocity" else M("past upper") if v.side == "upper"
                       else M("past lower"), lang)
                   for v in violations if v.joint == name]
        unit = joint_unit(joint)
        numbers = (states.positions[:, k].min(), states.positions[:, k].max(), lower, upper,
                   abs(states.velocities[:, k]).max(), speed if speed is not None else 0.0)
        if any(math.isnan(v) for v in numbers):  # nothing is "ok" beside a value that is not a number
            status.append(say(M("not a number"), lang))
            unusable += 1
        rows.append((
            name,
            f"{states.positions[:, k].min():.3f}",
            f"{states.positions[:, k].max():.3f}",
            f"{lower:g}", f"{upper:g}",
            f"{abs(states.velocities[:, k]).max():.3f}",
            f"{speed:g} {unit}/s" if speed else "-",
            ", ".join(status) or say(M("ok"), lang),
            say(sources.get(name, ""), lang),
        ))
    widths = [max(len(row[i]) for row in rows) for i in range(len(header))]
    for row in rows:
        cells = [cell.ljust(width) if i in (0, 7, 8) else cell.rjust(width)
                 for i, (cell, width) in enumerate(zip(row, widths))]
        lines.append("  ".join(cells).rstrip())
    problems = len(violations)
    if unusable:
        lines.append(say(Mn("{n} joint has a value that is not a number: no limit check holds for it",
                            "{n} joints have a value that is not a number: no limit check holds for them",
                            unusable), lang))
        return "\n".join(lines)
    lines.append(say(M("all within limits") if not problems else
                     Mn("{n} limit violation (see the warnings above)", "{n} limit violations (see the warnings above)",
                        problems), lang))
    return "\n".join(lines)
