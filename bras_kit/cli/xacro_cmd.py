"""bras-kit xacro: expand any xacro file with the real xacro package, without ROS."""

from __future__ import annotations

import argparse

from ._common import add_force_argument, write_text


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("file", metavar="FILE", help="the .xacro file to expand")
    parser.add_argument("mappings", nargs="*", metavar="NAME:=VALUE", help="xacro arguments")
    parser.add_argument("-o", "--output", metavar="FILE", help="FILE instead of printing")
    parser.add_argument("--package-path", action="append", default=[], metavar="DIR",
                        help="also a package or an install share/ tree; also $BRAS_KIT_PACKAGE_PATH")
    parser.add_argument("-v", "--verbose", action="store_true")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..model.xacro import expand_xacro
    from ._common import xacro_mappings

    text = expand_xacro(args.file, xacro_mappings(args.mappings), args.package_path)
    write_text(args.output, text, args.force)
    if args.verbose:
        import sys

        from ..core.i18n import say
        from ..model.package_paths import describe_package_folder, packages_used

        for name, folder in packages_used().items():
            print(say(describe_package_folder(name, folder), args.lang), file=sys.stderr)
    return 0
