"""bras-kit frames: the frame tree drawn like tf2_tools view_frames (PDF, SVG, PNG) or as DOT."""

from __future__ import annotations

import argparse
import sys

from ..core.i18n import say
from ..core.message import M, Mn
from ._common import add_force_argument, add_model_arguments, joint_values, warn_out_of_limits

DEFAULT_OUTPUT = "frames.pdf"


def configure(parser: argparse.ArgumentParser) -> None:
    add_model_arguments(parser)
    parser.add_argument("-o", "--output", metavar="FILE",
                        help=".pdf, .svg, .png or .dot (default frames.pdf, like view_frames); '-' prints the DOT text")
    parser.add_argument("--set", dest="values", action="append", default=[], metavar="JOINT=VALUE",
                        help="the arm in this pose: joint values on the edges, link positions in the boxes")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..diagrams import FRAME_FORMATS, frame_diagram, frames_dot, output_suffix
    from ..kinematics.frames import tf_tree
    from ._common import check_writable, load_model, save_with, write_text

    output = args.output or DEFAULT_OUTPUT
    suffix = None if output == "-" else output_suffix(output, FRAME_FORMATS)
    robot = load_model(args)
    config = joint_values(args.values) or None
    tree = tf_tree(robot)
    tree.config_vector(config)  # unknown joint names fail here, before anything is written
    warn_out_of_limits(tree, config or {}, M("marked in red"), args.lang)
    if suffix is None or suffix == ".dot":
        write_text(None if suffix is None else output, frames_dot(robot, config, args.lang), args.force)
        return 0
    check_writable(output, args.force)
    save_with(output, args.force, lambda temporary: frame_diagram(robot, config, path=temporary, lang=args.lang), announce=False)
    written = M("wrote {path}: {frames}, {joints}", path=output,  # each count agrees with its noun (0 and 1: singular in French)
                frames=Mn("{n} frame", "{n} frames", len(tree.links)),
                joints=Mn("{n} joint", "{n} joints", len(tree.links) - 1))
    if not args.output:
        written = M("{text} (-o FILE.svg|png|dot for another format, -o - prints DOT)", text=written)
    print(say(written, args.lang), file=sys.stderr)
    return 0
