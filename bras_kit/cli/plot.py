"""bras-kit plot: joint angles over time against their limits, and the path of the tool tip."""

from __future__ import annotations

import argparse
import sys

from ..core.i18n import say
from ..core.message import M
from ._common import (
    add_force_argument,
    add_model_arguments,
    add_topic_argument,
    joint_values,
    warn,
    warn_motion_notes,
)

DEFAULT_OUTPUT = "plot.png"


def configure(parser: argparse.ArgumentParser) -> None:
    add_model_arguments(parser)
    parser.add_argument("--motion", action="append", default=[], metavar="SPEC",
                        help="a file of waypoints (.csv, .json, .yaml) or a ROS 2 bag (folder, .mcap, .db3); default: the tutorial's animation")
    add_topic_argument(parser)
    parser.add_argument("--set", dest="values", action="append", default=[], metavar="JOINT=VALUE",
                        help="the joint is held at it")
    parser.add_argument("--interpolation", choices=("linear", "cubic"),
                        help="of a file (default: the file's own, else linear)")
    parser.add_argument("--duration", type=float, metavar="S",
                        help="plotted (default: the waypoints' end, else 10)")
    parser.add_argument("--rate", type=float, metavar="HZ", help="default 20, like the tutorial")
    parser.add_argument("-o", "--output", metavar="FILE", help="an image: .png, .svg or .pdf (default plot.png)")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..diagrams import FIGURE_FORMATS, output_suffix, plot_motion, tip_point
    from ..motion import DEFAULT_RATE, check_limits, describe_violation, motion_from_specs, sample
    from ._common import check_writable, load_model, save_with

    output = args.output or DEFAULT_OUTPUT
    output_suffix(output, FIGURE_FORMATS)
    check_writable(output, args.force)
    robot = load_model(args)
    motion = motion_from_specs(robot, args.motion, joint_values(args.values) or None, args.interpolation, args.topic)
    warn_motion_notes(motion)
    states = sample(motion, args.duration, args.rate if args.rate is not None else DEFAULT_RATE)
    save_with(output, args.force, lambda temporary: plot_motion(robot, states, path=temporary, lang=args.lang), announce=False)
    link, offset = tip_point(robot)
    duration = float(states.times[-1]) if len(states.times) else 0.0
    print(say(M("wrote {path}: {count} samples over {duration:g} s; tip = '{link}' + ({offset})",
                path=output, count=len(states.times), duration=duration, link=link,
                offset=", ".join(f"{v:g}" for v in offset)), args.lang), file=sys.stderr)
    for violation in check_limits(robot, states):
        warn(describe_violation(violation), args.lang)
    return 0
