"""bras-kit fk: each link's pose for a joint configuration, like tf2_echo."""

from __future__ import annotations

import argparse
import json
import math

from ..core.i18n import say
from ..core.message import M, Message
from ._common import add_model_arguments, joint_values, warn, warn_out_of_limits


def configure(parser: argparse.ArgumentParser) -> None:
    add_model_arguments(parser)
    parser.add_argument("--set", dest="values", action="append", default=[], metavar="JOINT=VALUE",
                        help="others are 0")
    parser.add_argument("--link", help="only this link is printed (relative to the root)")
    parser.add_argument("--from", dest="source", metavar="A", help="the frame A, with --to B: the pose of B in the frame of A")
    parser.add_argument("--to", dest="target", metavar="B", help="with --from: the pose of B in the frame of A")
    parser.add_argument("--format", choices=("text", "json"), default="text")


def _text_block(title: Message, pose: dict[str, list[float]], lang: str | None) -> str:
    """tf2_echo's block, its headings worded in ``lang`` (the numbers as tf2_echo prints them)."""
    x, y, z = pose["xyz"]
    qx, qy, qz, qw = pose["quat_xyzw"]
    r, p, yaw = pose["rpy"]
    rotation = say(M("Rotation:"), lang)
    indent = " " * (len(rotation) + 3)
    return (
        f"{say(title, lang)}\n"
        f"- {say(M('Translation:'), lang)} [{x:.6f}, {y:.6f}, {z:.6f}]\n"
        f"- {rotation} {say(M('in Quaternion (xyzw)'), lang)} [{qx:.6f}, {qy:.6f}, {qz:.6f}, {qw:.6f}]\n"
        f"{indent}{say(M('in RPY (radian)'), lang)} [{r:.6f}, {p:.6f}, {yaw:.6f}]\n"
        f"{indent}{say(M('in RPY (degree)'), lang)} "
        f"[{math.degrees(r):.6f}, {math.degrees(p):.6f}, {math.degrees(yaw):.6f}]"
    )


def run(args: argparse.Namespace) -> int:
    from ..core.errors import ParameterError
    from ..kinematics.frames import describe_transform, fk, relative_transform, tf_tree
    from ._common import load_model

    if (args.source is None) != (args.target is None):
        raise ParameterError(M("--from and --to go together"), hint=M("e.g. --from base --to avant_bras"))
    robot = load_model(args)
    tree = tf_tree(robot)
    config = joint_values(args.values)
    tree.config_vector(config)  # unknown joint names fail here, before any output
    warn_out_of_limits(tree, config, lang=args.lang)
    for name in tree.unsupported_joints:
        warn(M("joint '{name}' is floating or planar: its child is shown at the joint origin, not moved", name=name),
             args.lang)
    full = {name: float(config.get(name, 0.0)) for name in tree.dof}
    if args.source is not None:
        pose = describe_transform(relative_transform(tree, config, args.source, args.target))
        if args.format == "json":
            print(_json({"from": args.source, "to": args.target, "config": full, **pose}))
            return 0
        print(_text_block(M("At {parent} -> {child}", parent=args.source, child=args.target), pose, args.lang))
        return 0
    transforms = fk(tree, config)
    names = [tree.links[tree.index(args.link)]] if args.link else list(tree.links)
    poses = {name: describe_transform(transforms[name]) for name in names}
    if args.format == "json":
        print(_json({"root": tree.root, "config": full, "links": poses}))
        return 0
    for name, pose in poses.items():
        print(_text_block(M("At {parent} -> {child}", parent=tree.root, child=name), pose, args.lang))
    return 0


def _json(document: dict) -> str:
    """JSON text; a NaN or infinity (from a non-finite <origin> or axis) is an error, never printed."""
    from ..core.errors import ModelError

    try:
        return json.dumps(document, indent=2, allow_nan=False)
    except ValueError:
        raise ModelError(M("a pose is not a finite number: the model holds nan or inf in an <origin> or <axis>"),
                         hint=M("run bras-kit validate on the file to see where")) from None
