"""bras-kit workspace: draw the region the tip reaches, within the joint limits and without them."""

from __future__ import annotations

import argparse
import os

from ..core.i18n import say
from ..core.message import M
from ._common import add_force_argument, add_model_arguments, check_writable, save_with

FORMATS = (".png", ".svg", ".pdf")


def configure(parser: argparse.ArgumentParser) -> None:
    add_model_arguments(parser)
    parser.add_argument("-o", "--output", default="workspace.png", metavar="FILE",
                        help="a picture: .png, .svg or .pdf (default: workspace.png)")
    parser.add_argument("--samples", type=int, default=100_000, metavar="N",
                        help="random joint configurations per region (default: 100000)")
    parser.add_argument("--link", metavar="TIP", help="the link carrying the tip (default: the end of the longest chain)")
    parser.add_argument("--tip-offset", nargs=3, type=float, metavar=("X", "Y", "Z"),
                        help="default: the far end of the link's visual along its z")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..core.errors import ParameterError
    from ..ik import workspace_figure
    from ..kinematics.frames import tf_tree
    from ._common import load_model

    extension = os.path.splitext(args.output)[1].lower()
    if extension not in FORMATS:
        raise ParameterError(M("cannot write '{path}': unknown picture format", path=args.output),
                             hint=M("end the file name with {suffixes}", suffixes=", ".join(FORMATS)))
    if not 1 <= args.samples <= 5_000_000:
        raise ParameterError(M("--samples {samples} is out of range", samples=args.samples),
                             hint=M("give a number from 1 to 5000000"))
    check_writable(args.output, args.force)
    tree = tf_tree(load_model(args))
    figure, _axes, summary = workspace_figure(tree, args.samples, tip_link=args.link, tip_offset=args.tip_offset,
                                              lang=args.lang)
    save_with(args.output, args.force, figure.savefig, announce=False)
    h, v = summary.axes
    print(say(M("tip region in the {h}-{v} plane: {inside:.3f} m^2 within the joint limits, {free:.3f} m^2 if "
                "every joint turned freely; farthest tip {reach:.3f} m from the first joint",
                h=h, v=v, inside=summary.area_within_limits, free=summary.area_without_limits,
                reach=summary.max_reach), args.lang))
    print(say(M("wrote {path}", path=args.output), args.lang))
    return 0
