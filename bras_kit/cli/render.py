"""bras-kit render: draw the arm off-screen (PNG, numbered frames, GIF, MP4), as RViz would show it.

Heavy modules (pyrender, trimesh, PIL, imageio) are imported inside run(), never at start-up.
"""

from __future__ import annotations

import argparse
import contextlib
import math
import os
import re
import sys
from collections.abc import Iterable, Iterator
from typing import TYPE_CHECKING

from ..core.i18n import say
from ..core.message import M, Message, Mn
from ._common import (
    add_force_argument,
    add_model_arguments,
    add_node_argument,
    add_topic_argument,
    apply_node,
    check_writable,
    format_config,
    joint_values,
    load_model,
    warn,
    warn_motion_notes,
    warn_out_of_limits,
)

if TYPE_CHECKING:
    import numpy as np

PICTURE_SUFFIXES = (".png", ".jpg", ".jpeg", ".bmp", ".tif", ".tiff", ".webp")

_EPILOG = """\
outputs (any together; with none, writes ROBOT.png of the pose):
  -o pose.png               one picture: the --set pose (the first frame when animating)
  --gif [anim.gif]          the motion as a looping GIF (default name: ROBOT.gif)
  --mp4 [anim.mp4]          the motion as an H.264 video (default name: ROBOT.mp4)
  --frames-dir DIR          the motion as DIR/frame_0000.png, frame_0001.png ...
  --record run.mcap         the joint states drawn, as a ROS 2 bag (or .csv, .json)
The motion is --motion SPEC (tutorial, JOINT=FORMULA, a waypoint file or a ROS 2 bag, as in 'bras-kit motion');
without it, the tutorial's animation node. It lasts --duration seconds at --fps: duration x fps frames.

examples:
  bras-kit render                                   bras.png: the arm at the zero pose
  bras-kit render --gif                             bras.gif: the tutorial's motion, 10 s at 20 fps
  bras-kit render --set epaule=0.8 --set coude=1.2 --view front --tf -o pose.png
  bras-kit render --motion coude=1.5*sin(t) --duration 6.28 --mp4 coude.mp4
  bras-kit render my_robot.urdf --package-path ~/ws/src --view top -o top.png
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = _EPILOG
    add_model_arguments(parser)
    parser.add_argument("--set", dest="set_values", action="append", default=[], metavar="JOINT=VALUE",
                        help="others are 0")
    parser.add_argument("-m", "--motion", action="append", default=[], metavar="SPEC",
                        help="a waypoint file; default: tutorial")
    add_node_argument(parser)
    parser.add_argument("-o", "--output", metavar="PNG", help="the picture of the pose")
    parser.add_argument("--gif", nargs="?", const="", metavar="FILE")
    parser.add_argument("--mp4", nargs="?", const="", metavar="FILE", help="write the motion as an MP4")
    parser.add_argument("--frames-dir", metavar="DIR", help="write each frame as DIR/frame_NNNN.png")
    parser.add_argument("--record", metavar="FILE",
                        help="also write the joint states drawn: .mcap/.db3 (a ROS 2 bag for Foxglove and "
                             "ros2 bag play), .csv or .json")
    add_topic_argument(parser)
    parser.add_argument("--size", default="640x480", metavar="WxH", help="default 640x480")
    parser.add_argument("--fps", type=float, default=20.0, metavar="N",
                        help="of the animation (default 20, like the tutorial's node)")
    parser.add_argument("--duration", type=float, metavar="S",
                        help="of motion (default: the motion's own length, else 10)")
    parser.add_argument("--view", choices=("iso", "front", "side", "top"), default="iso",
                        help="camera direction: iso (three-quarter), front (x-z plane), side (y-z), top")
    parser.add_argument("--azimuth", type=float, metavar="DEG", help="camera azimuth from +x towards +y")
    parser.add_argument("--elevation", type=float, metavar="DEG", help="camera height angle, -90..90")
    parser.add_argument("--distance", type=float, metavar="M",
                        help="camera distance in metres (default: just far enough to see every pose)")
    parser.add_argument("--tf", action="store_true", help="draw each link's axes (x red, y green, z blue)")
    parser.add_argument("--no-grid", action="store_true", help="leave out the ground grid")
    parser.add_argument("--geometry", choices=("visual", "collision", "both"), default="visual",
                        help="default <visual>, like RViz's Visual/Collision Enabled (not --collisions, which adds shapes to the built-in arm)")
    parser.add_argument("--antialias", action=argparse.BooleanOptionalAction, default=None,
                        help="smooth edges (default: on for -o pictures, off for animations: "
                        "twice the speed without a GPU)")
    parser.add_argument("--background", default="white", metavar="COLOR",
                        help="a name, #rrggbb or 'r g b' in 0..1 (default white; 'rviz' for RViz's grey)")
    parser.add_argument("--backend", choices=("auto", "egl", "osmesa", "software"), default="auto",
                        help="auto is OpenGL on EGL, else OSMesa, else the (slower) software renderer")
    add_force_argument(parser)


def _file_name(robot_name: str | None) -> str:
    return re.sub(r"[^\w.-]+", "_", robot_name or "").strip("._") or "robot"


def _check_frames_dir(folder: str, force: bool) -> None:
    from ..core.errors import OutputExistsError

    if os.path.isdir(folder) and not force and any(re.fullmatch(r"frame_\d+\.png", n) for n in os.listdir(folder)):
        raise OutputExistsError(M("{folder} already holds frame_*.png files", folder=folder),
                                hint=M("pass --force to overwrite them, or choose another --frames-dir"))
    if os.path.islink(folder):
        raise OutputExistsError(M("{folder} is a symbolic link: refused", folder=folder),
                                hint=M("choose another --frames-dir"))
    if os.path.exists(folder) and not os.path.isdir(folder):
        raise OutputExistsError(M("{folder} exists and is not a folder", folder=folder),
                                hint=M("choose another --frames-dir"))


def _warn_limits(robot, states, lang: str | None) -> None:
    from ..motion import check_limits

    for v in check_limits(robot, states):
        if v.kind == "velocity":
            text = M("{joint}: speed {value:.4g} passes its limit {bound:g} at t={time:.2f} s "
                     "(drawn anyway, as RViz would)", joint=v.joint, value=v.value, bound=v.bound, time=v.time)
        else:
            text = M("{joint}: position {value:.4g} passes its limit {bound:g} at t={time:.2f} s "
                     "(drawn anyway, as RViz would)", joint=v.joint, value=v.value, bound=v.bound, time=v.time)
        warn(text, lang)


def run(args: argparse.Namespace) -> int:
    from ..core.errors import ParameterError
    from ..kinematics.frames import tf_tree
    from ..render import Renderer, render_motion, render_options
    from ..render.sequence import (
        FramesDirWriter,
        FrameWriter,
        GifWriter,
        Mp4Writer,
        gif_delay,
        palette_samples,
        save_png,
        write_frames,
    )
    from ..trust.outputs import staged

    opts = dict(size=args.size, view=args.view, tf=args.tf, grid=not args.no_grid, background=args.background,
                backend=args.backend, azimuth=args.azimuth, elevation=args.elevation, distance=args.distance,
                antialias=args.antialias, package_paths=tuple(args.package_path), geometry=args.geometry)
    options = render_options(**opts)  # bad values fail before the model is even loaded
    apply_node(args, args.duration)
    robot = load_model(args)
    if not (math.isfinite(args.fps) and 1 <= args.fps <= 120):
        raise ParameterError(M("--fps {fps:g} is out of range", fps=args.fps),
                             hint=M("give frames per second between 1 and 120, e.g. 20"))
    for option, path, suffix in (("--gif", args.gif, ".gif"), ("--mp4", args.mp4, ".mp4")):
        if path and path != "-" and not path.lower().endswith(suffix):
            raise ParameterError(M("{option} {path}: the file name does not end in {suffix}", option=option,
                                   path=path, suffix=suffix),
                                 hint=M("name the file like {option} arm{suffix} (the format follows the option)",
                                        option=option, suffix=suffix))
    if args.duration is not None and not (math.isfinite(args.duration) and args.duration > 0):
        raise ParameterError(M("--duration {duration:g} is not a positive time", duration=args.duration),
                             hint=M("give seconds, e.g. 10"))
    tree = tf_tree(robot)
    set_values = joint_values(args.set_values)
    tree.config_vector(set_values)  # unknown joints fail before anything is drawn
    warn_out_of_limits(tree, set_values, M("drawn anyway"), args.lang)

    stem = _file_name(robot.name)
    animated = args.gif is not None or args.mp4 is not None or args.frames_dir is not None
    defaulted = []
    if not animated and args.output is None:
        if args.motion or args.record or args.recorded:  # a motion (or a recording, a node's) asks for an animation
            args.gif = ""
            animated = True
        else:
            args.output = f"{stem}.png"
            defaulted.append(args.output)
    if args.gif == "":
        args.gif = f"{stem}.gif"
        defaulted.append(args.gif)
    if args.mp4 == "":
        args.mp4 = f"{stem}.mp4"
        defaulted.append(args.mp4)
    if args.output == "-" and not animated:  # a PNG on standard output: bras-kit render -o - | ...
        with Renderer(robot, fit=set_values, **opts) as renderer:
            save_png(renderer.render(set_values), sys.stdout.buffer)
        sys.stdout.flush()
        return 0
    if args.output is not None and not args.output.lower().endswith(PICTURE_SUFFIXES):
        raise ParameterError(M("-o {path}: cannot tell the picture format from the name", path=args.output),
                             hint=M("end the name with {suffixes}", suffixes=", ".join(PICTURE_SUFFIXES)))
    for path, option in ((args.output, "-o"), (args.gif, "--gif"), (args.mp4, "--mp4")):
        if path is not None:
            check_writable(path, args.force, option=option)
    if args.frames_dir is not None:
        _check_frames_dir(args.frames_dir, args.force)
    if args.record is not None:
        from ..motion.states_io import check_states_output

        check_states_output(args.record, args.force, option="--record")
    size = f"{options.width}x{options.height}"

    if not animated:
        with Renderer(robot, fit=set_values, **opts) as renderer, _writing(), \
                staged(args.output, args.force) as temporary:
            save_png(renderer.render(set_values), temporary)
            backend = renderer.backend
        _report(args.output, M("{pose}, {size}, {backend}", pose=format_config(set_values), size=size,
                               backend=backend), args.output in defaulted, args.lang)
        return 0

    from ..motion import motion_from_specs, sample_loop
    from ..motion.sources import motion_title

    motion = motion_from_specs(robot, args.motion, set_values or None, topic=args.topic,
                               recorded=getattr(args, "recorded", None))
    warn_motion_notes(motion)
    states = sample_loop(motion, args.duration, args.fps)
    _warn_limits(robot, states, args.lang)
    if args.gif and gif_delay(args.fps) * args.fps > 100.5:
        warn(M("a GIF plays at most 50 frames per second; {fps:g} fps will play slower", fps=args.fps), args.lang)
    frames = render_motion(robot, states, label="rendering", **opts)
    with frames, _writing(), contextlib.ExitStack() as outputs:
        def target(path: str, option: str) -> str:
            return outputs.enter_context(staged(path, args.force, option=option))

        writers: list[FrameWriter] = []
        stream: Iterable[np.ndarray] = frames
        if args.gif:
            samples, stream = palette_samples(frames)
            writers.append(GifWriter(target(args.gif, "--gif"), args.fps, samples))
        if args.mp4:
            writers.append(Mp4Writer(target(args.mp4, "--mp4"), args.fps))
        if args.frames_dir is not None:
            writers.append(FramesDirWriter(args.frames_dir, len(frames)))
        if args.output:
            save_png(frames[0], target(args.output, "-o"))
        backend = frames.renderer.backend
        written = write_frames(stream, writers)
    if args.record is not None:  # the states drawn, once the pictures are safely written
        from ..motion.states_io import write_states

        print(say(write_states(robot, states, args.record, args.force, option="--record"), args.lang), file=sys.stderr)
    details = Mn("{n} frame at {fps:g} fps ({seconds:g} s), {size}, {what}, {backend}",
                 "{n} frames at {fps:g} fps ({seconds:g} s), {size}, {what}, {backend}", written,
                 fps=args.fps, seconds=written / args.fps, size=size, what=motion_title(motion.label), backend=backend)
    for path in (args.gif, args.mp4):
        if path:
            _report(path, details, path in defaulted, args.lang)
    if args.frames_dir is not None:
        _report(os.path.join(args.frames_dir, "frame_*.png"), details, False, args.lang)
    if args.output:
        _report(args.output, M("first frame, {size}, {backend}", size=size, backend=backend), False, args.lang)
    return 0


@contextlib.contextmanager
def _writing() -> Iterator[None]:
    """A file that cannot be written (permissions, full disk) is a user error, not a traceback."""
    from ..core.errors import BrasKitError, os_reason

    try:
        yield
    except OSError as exc:
        raise BrasKitError(M("cannot write {path}: {reason}", path=exc.filename or M("the output"),
                             reason=os_reason(exc)),
                           hint=M("check the folder exists, is writable and has space")) from None


def _report(path: str, details: Message, defaulted: bool, lang: str | None) -> None:
    from ..core.i18n import say

    if defaulted:
        text = M("wrote {path} in the current folder (choose the name with the output option): {details}",
                 path=path, details=details)
    else:
        text = M("wrote {path}: {details}", path=path, details=details)
    print(say(text, lang), file=sys.stderr)
