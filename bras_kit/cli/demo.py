"""bras-kit demo: everything the tutorial builds, for the built-in arm, in one folder."""

from __future__ import annotations

import argparse
import os
import sys
import time

from ._common import add_force_argument

DEMO_POSE = {"epaule": 0.8, "coude": 1.2}


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("outdir", nargs="?", default="bras-kit-demo", metavar="OUTDIR",
                        help="folder to write into (default: ./bras-kit-demo)")
    parser.add_argument("--wrist", action="store_true", help="use the arm with the wrist joint 'poignet'")
    parser.add_argument("--duration", type=float, default=9.0, help="seconds of tutorial motion in the GIF (default 9)")
    parser.add_argument("--fps", type=float, default=20.0, help="GIF frames per second (default 20, as the tutorial's node)")
    parser.add_argument("--size", default="480x360", help="image size WxH (default 480x360)")
    parser.add_argument("--backend", default="auto", choices=("auto", "egl", "osmesa", "software"),
                        help="rendering backend (default: auto)")
    add_force_argument(parser)


def _step(message: str) -> float:
    print(f"- {message} ...", end="", flush=True)
    return time.perf_counter()


def _done(start: float, path: str) -> None:
    print(f" {path} ({time.perf_counter() - start:.1f} s)")


def run(args: argparse.Namespace) -> int:
    from ..authoring import arm
    from ..diagrams import frame_diagram, plot_motion
    from ..errors import OutputExistsError
    from ..motion import check_limits, sample_loop, tutorial_motion
    from ..render import parse_size, render_motion, render_pose, save_gif, save_png
    from ..scaffold import scaffold_package
    from ..validate import validate

    outdir = args.outdir
    if os.path.isdir(outdir) and os.listdir(outdir) and not args.force:
        raise OutputExistsError(f"{outdir} exists and is not empty",
                                hint="pass --force to write into it, or name another folder")
    os.makedirs(outdir, exist_ok=True)
    size = parse_size(args.size)
    robot = arm(wrist=args.wrist)
    variant = "with the wrist 'poignet'" if args.wrist else "epaule + coude"
    print(f"bras-kit demo: the tutorial arm '{robot.name}' ({variant}) -> {outdir}/")

    start = _step("scaffolding the ROS 2 package")
    package_dir = os.path.join(outdir, "bras_description")
    scaffold_package(package_dir, wrist=args.wrist, force=args.force)
    _done(start, package_dir + "/")

    start = _step("validating the URDF")
    findings = validate(robot)
    problems = [f for f in findings if f.severity in ("error", "warning")]
    print(f" {len(problems)} errors or warnings ({time.perf_counter() - start:.1f} s)")
    for finding in problems:
        print(f"    {finding.code} {finding.severity}: {finding.message}")

    start = _step(f"rendering the pose {', '.join(f'{k}={v}' for k, v in DEMO_POSE.items())} with TF axes")
    pose_png = os.path.join(outdir, "pose.png")
    save_png(render_pose(robot, DEMO_POSE, size=size, tf=True, backend=args.backend), pose_png)
    _done(start, pose_png)

    start = _step(f"animating the tutorial motion ({args.duration:g} s at {args.fps:g} fps)")
    states = sample_loop(tutorial_motion(robot), args.duration, args.fps)
    gif = os.path.join(outdir, f"{robot.name}.gif")
    save_gif(render_motion(robot, states, size=size, backend=args.backend), gif, fps=args.fps)
    _done(start, gif)
    for violation in check_limits(robot, states):
        print(f"    warning: {violation.joint} leaves its {violation.kind} limit at t={violation.time:.2f} s")

    start = _step("drawing the frame tree")
    frames_pdf = os.path.join(outdir, "frames.pdf")
    frame_diagram(robot, DEMO_POSE, path=frames_pdf)
    frame_diagram(robot, DEMO_POSE, path=os.path.join(outdir, "frames.png"))
    _done(start, frames_pdf + " (+ .png)")

    start = _step("plotting joint angles and the tip path")
    plot_png = os.path.join(outdir, "motion.png")
    plot_motion(robot, states, path=plot_png)
    _done(start, plot_png)

    print(f"done. Open {gif} to see the arm move; build {package_dir} with colcon on a ROS 2 machine.")
    sys.stdout.flush()
    return 1 if any(f.severity == "error" for f in findings) else 0
