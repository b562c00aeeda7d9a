"""bras-kit urdf: the tutorial arm's URDF from the xacro template."""

from __future__ import annotations

import argparse

from ..core.i18n import say
from ..core.message import M
from ._common import add_force_argument, template_values, write_text


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--wrist", action="store_true")
    parser.add_argument("--inertials", action="store_true")
    parser.add_argument("--collisions", action="store_true")
    parser.add_argument("--param", dest="params", action="append", default=[], metavar="NAME=VALUE",
                        help="a template parameter of the built-in arm; --list-params shows them")
    parser.add_argument("--set", dest="old_params", action="append", default=[], metavar="NAME=VALUE",
                        help=argparse.SUPPRESS)
    parser.add_argument("--list-params", action="store_true", help="list the template parameters and exit")
    parser.add_argument("-o", "--output", metavar="FILE", help="FILE instead of printing")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..model.authoring import arm_urdf, parse_assignments, template_parameters

    if args.list_params:
        for p in template_parameters().values():
            print(f"{p.name:20s} {p.kind:7s} " + say(M("default {value}", value=p.default), args.lang))
        return 0
    # with inertials, the base is fixed to a massless 'world' root, as bras-kit new does: KDL warns about
    # an inertia on the root (BK506) and Gazebo drops a root without one (BK702)
    text = arm_urdf(wrist=args.wrist, inertials=args.inertials, params=parse_assignments(template_values(args)),
                    collisions=args.collisions, world_anchor=args.inertials)
    write_text(args.output, text, args.force)
    return 0
