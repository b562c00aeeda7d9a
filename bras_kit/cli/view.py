"""bras-kit view: the arm live in the browser, like RViz with the slider window, reloaded
when the file is saved."""

from __future__ import annotations

import argparse
import os
import sys

from ..core.i18n import say
from ..core.message import M
from ._common import (
    add_force_argument,
    add_model_arguments,
    add_no_browser_argument,
    add_node_argument,
    add_topic_argument,
    apply_node,
    warn,
)

EPILOG = """\
examples:
  bras-kit view                              the tutorial arm, sliders for epaule and coude
  bras-kit view urdf/bras.urdf.xacro         your file; save it and the page reloads
  bras-kit view bras_description             the package's robot, as its launch file loads it
  bras-kit view --node bras_description      the package's node moves the arm (it starts playing)
  bras-kit view --motion tutorial            play the tutorial's motion (play/pause/speed)
  bras-kit view --export bras.html           one HTML file replaying the motion, no server
  bras-kit view --ros                        the robot of your running ROS 2 graph, moving with /joint_states
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.epilog = EPILOG
    add_model_arguments(parser)
    parser.add_argument("-m", "--motion", action="append", default=[], metavar="SPEC",
                        help="a motion to play; a file of waypoints or joint states")
    add_node_argument(parser)
    add_topic_argument(parser)
    parser.add_argument("--port", type=int, default=8080, help="port of the page (default 8080; the next free one if taken)")
    parser.add_argument("--host", default="127.0.0.1",
                        help="address to listen on (default 127.0.0.1: this computer only)")
    parser.add_argument("--geometry", choices=("visual", "collision", "both"), default="visual",
                        help="what the page shows first (default <visual>; the Display checkboxes change it)")
    add_no_browser_argument(parser)
    parser.add_argument("--export", metavar="HTML",
                        help="write one self-contained HTML file replaying the motion, then stop")
    parser.add_argument("--duration", type=float, default=None, metavar="S",
                        help="with --export: of motion (default: the motion's length, else 10)")
    parser.add_argument("--fps", type=float, default=20.0, help="with --export (default 20)")
    parser.add_argument("--ros", action="store_true",
                        help="show its robot (/robot_description), moving with /joint_states, with what bras-kit doctor --ros finds")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..core.errors import ParameterError
    from ..model.authoring import arm, parse_assignments
    from ._common import xacro_mappings

    if args.ros:
        from ._view_ros import run_ros

        return run_ros(args)

    if not 0 <= args.port <= 65535:
        raise ParameterError(M("--port {port} is out of range", port=args.port),
                             hint=M("give a port between 1024 and 65535, e.g. 8080"))
    _package_description(args)
    apply_node(args, args.duration)
    if args.file is not None and (args.wrist or args.inertials or args.param or args.collisions):
        raise ParameterError(M("--wrist, --inertials, --collisions and --param apply to the built-in arm only"),
                             hint=M("drop FILE to use the built-in arm, or edit your file"))
    from ..view import Source

    if args.file is None:
        source = Source(robot=arm(wrist=args.wrist, inertials=args.inertials, params=parse_assignments(args.param),
                                  collisions=args.collisions), package_paths=tuple(args.package_path))
    else:
        source = Source(path=args.file, mappings=xacro_mappings(args.xacro_arg),
                        package_paths=tuple(args.package_path))
    from ._common import check_usable

    check_usable(source.load(), args)
    if args.export:
        return _export(args, source)
    return _serve(args, source)


def _package_description(args: argparse.Namespace) -> None:
    """FILE a package folder: the robot description its launch file loads (as bras-kit launch
    would show it), watched like any file; the package's parent folder resolves package://."""
    from ..core.errors import ParameterError

    folder = args.file
    if folder is None or not os.path.isdir(folder) or not os.path.isfile(os.path.join(folder, "package.xml")):
        return
    from ..ros.package import Package

    source = Package(folder).description_source()
    if source is None:
        raise ParameterError(M("the package {folder} has no robot description (urdf/*.urdf or *.xacro)", folder=folder),
                             hint=M("put the URDF in {folder}/urdf/, as the tutorial does", folder=folder))
    args.file = os.path.join(folder, source)
    args.package_path = [*args.package_path, os.path.dirname(os.path.abspath(folder))]


def _export(args: argparse.Namespace, source: object) -> int:
    from ..core.errors import ParameterError
    from ..motion import motion_from_specs, sample
    from ..motion.sources import motion_title
    from ..trust.outputs import write_text
    from ..view import export_html
    from ._common import check_writable, warn_motion_notes

    if not 1 <= args.fps <= 120:
        raise ParameterError(M("--fps {fps:g} is out of range", fps=args.fps),
                             hint=M("give frames per second between 1 and 120, e.g. 20"))
    check_writable(args.export, args.force, option="--export")
    robot = source.load()  # type: ignore[attr-defined]
    motion = motion_from_specs(robot, args.motion, topic=args.topic, recorded=args.recorded)
    warn_motion_notes(motion)
    states = sample(motion, args.duration if args.duration is not None else (motion.duration or 10.0), args.fps)
    title = say(M("{robot}: {motion} (bras-kit)", robot=robot.name or "robot",
                  motion=say(motion_title(motion.label), args.lang)), args.lang)
    page = export_html(robot, states, package_paths=source.package_paths,  # type: ignore[attr-defined]
                       lang=args.lang, title=title)
    write_text(args.export, page, args.force, announce=False)
    print(say(M("wrote {path}: {count} frames of {label}, open it in a browser (no server needed)", path=args.export,
                count=len(states.times), label=motion_title(motion.label)), args.lang), file=sys.stderr)
    return 0


def _serve(args: argparse.Namespace, source: object) -> int:
    from ..view import Viewer

    if args.host not in ("127.0.0.1", "localhost", "::1"):
        warn(M("listening on {host}: anyone who can reach this computer can see and move the arm", host=args.host),
             args.lang)
    from ._common import check_usable, open_page

    viewer = Viewer(source, host=args.host, port=args.port, lang=args.lang, motion_specs=args.motion,  # type: ignore[arg-type]
                    motion_topic=args.topic, geometry=args.geometry, recorded=args.recorded,
                    autoplay=args.recorded is not None,
                    refuse=lambda robot: check_usable(robot, args))
    try:
        print(say(M("bras-kit view: {url} (Ctrl-C to stop)", url=viewer.url), args.lang), flush=True)
        if source.path:  # type: ignore[attr-defined]
            print(say(M("watching {path}: save it and the page reloads", path=source.path), args.lang),  # type: ignore[attr-defined]
                  file=sys.stderr, flush=True)
        open_page(viewer.url, args)
        viewer.wait()
    except KeyboardInterrupt:  # Ctrl-C as soon as the address shows (before the wait began) stops it too
        pass
    finally:
        viewer.stop()
    return 0
