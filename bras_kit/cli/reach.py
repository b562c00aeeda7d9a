"""bras-kit reach: joint values that put the tip at X Y Z, and a move there within the limits.

Exit codes: 0 reached; 1 not reached (or reached on a singular pose, or a move that leaves
the limits) with the closest pose still printed; 2 bad input.
"""

from __future__ import annotations

import argparse
import math
import re
import sys
import textwrap

from ..core.i18n import labelled, say
from ..core.message import M, Mn
from ._common import add_force_argument, add_model_arguments, check_writable, joint_values, warn

# argparse takes "-0.3" for a positional only in its plain forms; widen that to "-1e-3",
# "-.5" and "-inf", so that any negative coordinate parses (so does anything after "--").
_NEGATIVE_NUMBER = re.compile(r"^-(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^-(inf|infinity|nan)$", re.IGNORECASE)

GIF_RATE = 20.0
# The solvers' and elbows' names, as they are shown
_WORDS = {"analytic": M("analytic"), "numeric": M("numeric"), "up": M("up"), "down": M("down")}
GIF_HOLD = 0.5  # s of still frames at the end, to see the reached pose


def _coordinate(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(say(M("{text!r} is not a number (give metres, e.g. 0.4 or -0.25)",
                                               text=text))) from None
    if not math.isfinite(value):
        raise argparse.ArgumentTypeError(say(M("{text!r} is not a finite number (give metres, e.g. 0.4)", text=text)))
    return value


def configure(parser: argparse.ArgumentParser) -> None:
    parser._negative_number_matcher = _NEGATIVE_NUMBER
    parser.epilog = ("Negative coordinates parse as they are (reach -0.3 0 0.5); '--' before X Y Z "
                     "also works. Exit status: 0 reached, 1 not reached or singular, 2 bad input.")
    add_model_arguments(parser)
    for name in ("X", "Y", "Z"):
        parser.add_argument(name.lower(), metavar=name, type=_coordinate, help=f"target {name.lower()} in metres (root frame)")
    parser.add_argument("--from", dest="start", action="append", default=[], metavar="JOINT=VALUE",
                        help="a start pose, JOINT=VALUE (repeatable; other joints 0): the numeric solver and the move start there")
    parser.add_argument("--link", metavar="TIP", help="the link carrying the tip (default: the end of the longest chain)")
    parser.add_argument("--tip-offset", nargs=3, type=_coordinate, metavar=("X", "Y", "Z"),
                        help="default: the far end of the link's visual along its z, e.g. 0 0 0.5 for avant_bras")
    parser.add_argument("--rpy", nargs=3, type=_coordinate, metavar=("R", "P", "Y"),
                        help="also ask for the tip link's orientation (roll pitch yaw, rad; numeric solver)")
    parser.add_argument("--elbow", choices=("up", "down"),
                        help="two-joint arms: which of the two solutions (default: the one within limits "
                        "closest to the start)")
    parser.add_argument("--duration", type=_coordinate, metavar="S",
                        help="of the move (default and minimum: the shortest within the velocity limits)")
    parser.add_argument("--gif", metavar="OUT.gif", help="the move")
    parser.add_argument("--format", choices=("text", "json"), default="text",
                        help="text for people (default), json for programs")
    add_force_argument(parser)


def _states(motion):
    """The move sampled for rendering, the final pose held for a moment."""
    import numpy as np

    from ..motion import JointStates

    times = motion.times(GIF_RATE)
    hold = motion.duration + np.arange(1, int(GIF_HOLD * GIF_RATE) + 1) / GIF_RATE
    times = np.concatenate([times, hold])
    return JointStates(times=times, names=list(motion.names), positions=motion.positions(times),
                       velocities=motion.velocities(times))


def _view(robot, motion) -> str:
    """'front' (looking along y) when every moving joint turns about y, as in the tutorial arm."""
    moving = [robot.joint(n) for n, a, b in zip(motion.names, motion.start, motion.goal) if a != b]
    about_y = all(j is not None and j.axis is not None and abs(j.axis[0]) < 1e-9 and abs(j.axis[2]) < 1e-9
                  for j in moving)
    return "front" if moving and about_y else "iso"


def _write_gif(robot, motion, path: str, force: bool, target=None) -> None:
    from ..core.errors import BackendError

    try:
        from ..render import render_motion, save_gif
    except ImportError as exc:
        raise BackendError(M("cannot render the GIF: {reason}", reason=str(exc)),
                           hint=M("check the bras-kit install (pip install -e .)")) from None
    frames = render_motion(robot, _states(motion), view=_view(robot, motion),
                           targets=[tuple(target)] if target is not None else ())
    from ._common import save_with

    save_with(path, force, lambda temporary: save_gif(frames, temporary, GIF_RATE), option="--gif", announce=False)


def _angle(value: float, unit: str) -> str:
    value = 0.0 if abs(value) < 5e-7 else value  # no "-0.000000"
    if unit == "rad":
        return f"{value:+.6f} rad ({math.degrees(value):+8.2f} deg)"
    return f"{value:+.6f} m"


def _point_text(point) -> str:
    return "x={:.4f} y={:.4f} z={:.4f} m".format(*(float(v) + 0.0 for v in point))


def run(args: argparse.Namespace) -> int:
    import json

    from ..ik import motion_violations, reach_motion, serial_chain, solve_ik
    from ..kinematics.frames import rpy_to_matrix, tf_tree
    from ._common import format_config, load_model

    lang = args.lang
    if args.gif:
        check_writable(args.gif, args.force, option="--gif")
    robot = load_model(args)
    tree = tf_tree(robot)
    start = joint_values(args.start)
    tree.config_vector(start)  # unknown joint names fail here
    for name, value, lower, upper in tree.out_of_limits(start):
        warn(M("the start pose has {name}={value:g}, outside its limits {lower:g}..{upper:g}", name=name, value=value,
               lower=lower, upper=upper), lang)
    chain = serial_chain(tree, args.link, args.tip_offset)
    rotation = rpy_to_matrix(args.rpy) if args.rpy else None
    result = solve_ik(tree, (args.x, args.y, args.z), rotation=rotation, tip_link=chain.tip_link,
                      tip_offset=chain.tip_offset, start=start, elbow=args.elbow,
                      method="numeric" if rotation is not None else "auto")
    motion, violations = None, []
    if result.reachable:
        motion = reach_motion(tree, start, result.joints, args.duration)
        violations = motion_violations(tree, motion)
    elif args.duration is not None or args.gif:
        warn(M("no move: the target is not reached"), lang)
    if motion is not None and args.gif:
        _write_gif(robot, motion, args.gif, args.force, result.target)
    code = 0 if result.reachable and not result.singular and not violations else 1

    units = {name: ("m" if (j := robot.joint(name)) is not None and j.type == "prismatic" else "rad")
             for name in tree.dof}
    tip_text = f"{chain.tip_link} + ({', '.join(f'{v:g}' for v in chain.tip_offset)})"
    if args.format == "json":
        data = result.as_dict()
        data["tip_link"] = chain.tip_link
        data["tip_offset"] = [float(v) for v in chain.tip_offset]
        if motion is not None:
            move: dict[str, object] = {
                "from": {n: float(v) for n, v in zip(tree.dof, motion.start)},
                "duration": motion.duration,
                "peak_velocity": {n: float(v) for n, v in zip(tree.dof, motion.peak_velocities())},
                "violations": [str(v.describe()) for v in violations],
            }
            if args.gif:
                move["gif"] = args.gif
            data["motion"] = move
        print(json.dumps(data, indent=2))
        return code

    print(f"{say(M('target'), lang):10s} {_point_text(result.target)}  ({labelled(M('tip'), tip_text, lang)})")
    how = say(_WORDS[result.method], lang) + (", " + say(M("elbow {side}", side=_WORDS[result.elbow]), lang)
                                              if result.elbow else "")
    if result.method == "numeric":
        how += ", " + say(Mn("{n} iteration", "{n} iterations", result.iterations), lang)
    print(f"{say(M('reached'), lang) if result.reachable else say(M('NOT reached'), lang):10s} ({how})")
    if result.reason != "ok":
        print(textwrap.fill(say(result.message, lang), 100, initial_indent=" " * 11, subsequent_indent=" " * 13))
    print(say(M("joints"), lang) if result.reachable else say(M("closest pose within the limits"), lang))
    for name in tree.dof:
        joint = robot.joint(name)
        low, high = joint.bounds() if joint is not None else (-math.inf, math.inf)
        print(f"  {name:12s} {_angle(result.joints[name], units[name])}   {say(M('limits'), lang)} {low:g} .. {high:g}")
    print(f"{say(M('tip'), lang):10s} {_point_text(result.tip)}, "
          + say(M("{distance:.3g} m from the target", distance=result.residual), lang)
          + (", " + say(M("orientation off by {angle:.3g} rad", angle=result.rotation_residual), lang)
             if result.rotation_residual is not None else ""))
    for solution in result.solutions:
        if result.reachable and solution.elbow == result.elbow:
            continue
        state = say(M("within the limits"), lang) if solution.within_limits else \
            labelled(M("past the limits"), "; ".join(say(v.describe(), lang) for v in solution.violations), lang)
        values = ", ".join(f"{n}={solution.joints[n]:+.4f}" for n in tree.dof)
        print(say(M("elbow {side}", side=f"{say(_WORDS[solution.elbow], lang):4s}"), lang) + f" {values} ({state})")
    if motion is not None:
        peaks = []
        for name, peak in zip(tree.dof, motion.peak_velocities()):
            joint = robot.joint(name)
            limit = joint.limit.velocity if joint is not None and joint.limit is not None else None
            peaks.append(f"{name} {peak:.3g}" + (" " + say(M("of {limit:g}", limit=limit), lang) if limit else "")
                         + f" {units[name]}/s")
        print(f"{say(M('move'), lang):10s} " + say(M("{duration:.3f} s from {start} (quintic); peak speed {peaks}",
                                                      duration=motion.duration, start=format_config(start),
                                                      peaks=", ".join(peaks)), lang))
        if violations:
            print(" " * 11 + labelled(M("leaves the limits"), "; ".join(say(v.describe(), lang) for v in violations), lang))
        else:
            print(" " * 11 + say(M("within the position and velocity limits"), lang))
        if args.gif:
            print(say(M("wrote {path}", path=args.gif), lang))
    if code and result.reachable:  # reached, yet exit 1: say why, so a script's failure is explained
        why = M("the target is reached at a singular pose (a small move of the target needs a large joint move)") \
            if result.singular else M("the move there leaves the joint limits")
        print(say(M("exit code 1: {why}", why=why), lang), file=sys.stderr)
    return code
