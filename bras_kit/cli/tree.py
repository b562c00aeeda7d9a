"""bras-kit tree: the TF tree as indented text (links, and the joints between them)."""

from __future__ import annotations

import argparse
import sys

from ..core.message import M
from ._common import add_model_arguments, joint_values, warn, warn_out_of_limits


def configure(parser: argparse.ArgumentParser) -> None:
    add_model_arguments(parser)
    parser.add_argument("--set", dest="values", action="append", default=[], metavar="JOINT=VALUE",
                        help="shown on its joint")
    parser.add_argument("--ascii", action="store_true",
                        help="draw with ASCII only (automatic when the terminal cannot show box characters)")


def _can_print(text: str) -> bool:
    encoding = getattr(sys.stdout, "encoding", None) or "ascii"
    try:
        text.encode(encoding)
    except (UnicodeEncodeError, LookupError):
        return False
    return True


def run(args: argparse.Namespace) -> int:
    from ..diagrams import UNICODE_GLYPHS, tree_text
    from ..kinematics.frames import tf_tree
    from ._common import load_model

    robot = load_model(args)
    config = joint_values(args.values)
    glyphs = UNICODE_GLYPHS
    ascii_only = args.ascii or not _can_print(glyphs.branch + glyphs.last + glyphs.pipe + glyphs.arrow)
    text = tree_text(robot, config, ascii=ascii_only, lang=args.lang)
    if not _can_print(text):  # names the terminal cannot show: print '?' rather than fail
        encoding = getattr(sys.stdout, "encoding", None) or "ascii"
        text = text.encode(encoding, errors="replace").decode(encoding)
    sys.stdout.write(text)
    tree = tf_tree(robot)
    warn_out_of_limits(tree, config, lang=args.lang)
    for name in tree.unsupported_joints:
        warn(M("joint '{name}' is floating or planar: bras-kit keeps its child at the joint origin", name=name),
             args.lang)
    return 0
