"""The ``bras-kit`` command: thin argument parsing over the library.

Each command lives in its own module under ``bras_kit.cli`` with ``configure(parser)`` and
``run(args) -> int``. Only the module of the command being run is imported, so ``--help``
and light commands never load pyrender, matplotlib or trimesh.
"""

from __future__ import annotations

import argparse
import importlib
import os
import sys
from collections.abc import Sequence

from .. import __version__
from ..errors import BrasKitError

# name -> one-line help. The module is bras_kit.cli.<name> (``xacro`` lives in ``xacro_cmd``).
COMMANDS: dict[str, str] = {
    "demo": "make everything for the tutorial arm: package, checks, pictures, GIF, diagrams",
    "urdf": "print or write the tutorial arm's URDF (--wrist, --inertials, --set NAME=VALUE)",
    "xacro": "expand any xacro file to URDF without ROS ($(find) from --package-path)",
    "new": "scaffold the tutorial's ROS 2 package (package.xml, setup.py, launch, RViz, node)",
    "validate": "check URDF/xacro files for the tutorial's pitfalls and URDF defects",
    "explain": "print the long explanation of a validator rule (e.g. BK301)",
    "tree": "print the TF tree: links, joint names and types",
    "fk": "forward kinematics: each link's pose (xyz, quaternion, rpy), like tf2_echo",
    "motion": "turn a motion program into a joint-state sequence (CSV/JSON), checked against limits",
    "render": "draw the arm off-screen: PNG, image sequence, GIF or MP4",
    "frames": "draw the frame tree (like view_frames): PDF, SVG, PNG or DOT",
    "plot": "plot joint angles with their limits and the path of the tool tip",
    "reach": "inverse kinematics: joint values that put the tip at X Y Z, and a motion there",
    "workspace": "draw the region the tip can reach within the joint limits",
    "simulate": "physics with MuJoCo: gravity, motors limited by effort, collisions",
    "mjcf": "write the MuJoCo model (MJCF) bras-kit builds from the URDF",
}

_MODULES = {"xacro": "xacro_cmd"}


def _command_module(name: str):  # type: ignore[no-untyped-def]
    return importlib.import_module(f"{__name__}.{_MODULES.get(name, name)}")


def build_parser(selected: str | None) -> argparse.ArgumentParser:
    parser = argparse.ArgumentParser(
        prog="bras-kit",
        description="Describe, check, move and show a robot arm without ROS "
        "(the arm of the tutorial 'Simuler un bras robotisé avec ROS 2').",
        epilog="Run 'bras-kit COMMAND --help' for a command's options. "
        "Start with 'bras-kit demo'.",
    )
    parser.add_argument("--version", action="version", version=f"bras-kit {__version__}")
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", title="commands")
    for name, summary in COMMANDS.items():
        command_parser = sub.add_parser(name, help=summary, description=summary[0].upper() + summary[1:] + ".")
        if name == selected:
            _command_module(name).configure(command_parser)
    return parser


def _selected_command(argv: Sequence[str]) -> str | None:
    for arg in argv:
        if not arg.startswith("-"):
            return arg if arg in COMMANDS else None
    return None


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    selected = _selected_command(argv)
    parser = build_parser(selected)
    args = parser.parse_args(argv)
    if args.command is None:
        parser.print_help()
        return 0
    try:
        return int(_command_module(args.command).run(args) or 0)
    except BrasKitError as exc:
        print(f"bras-kit {args.command}: error: {exc}", file=sys.stderr)
        return 2
    except KeyboardInterrupt:
        print("interrupted", file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except MemoryError:
        print(f"bras-kit {args.command}: error: out of memory: the input is too large for this machine",
              file=sys.stderr)
        return 2
    except OSError as exc:  # a file problem no command caught: still one line, never a traceback
        where = f"{exc.filename}: " if getattr(exc, "filename", None) else ""
        print(f"bras-kit {args.command}: error: {where}{exc.strerror or exc}", file=sys.stderr)
        return 2
    except Exception as exc:  # a bug: say so in one line; BRAS_KIT_DEBUG=1 shows the traceback
        if os.environ.get("BRAS_KIT_DEBUG"):
            raise
        print(f"bras-kit {args.command}: internal error: {type(exc).__name__}: {exc}\n"
              "  hint: this is a bug in bras-kit; run again with BRAS_KIT_DEBUG=1 and report the traceback",
              file=sys.stderr)
        return 2
