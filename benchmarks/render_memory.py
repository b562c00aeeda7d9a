"""Memory over a long stream of pictures of a mesh robot (issue 25: it must stay flat): the
resident size after 1,000 frames and after --frames (10,000) of example-robot-data's UR5, drawn
one at a time as a GIF writer or a notebook would consume them.

Run: python benchmarks/render_memory.py [--frames 10000] [--size 160x120]
"""

from __future__ import annotations

import argparse
import os
import site
import time

import numpy as np


def resident_mib() -> float:
    with open("/proc/self/statm") as handle:
        return int(handle.read().split()[1]) * os.sysconf("SC_PAGE_SIZE") / 2**20


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--frames", type=int, default=10_000)
    parser.add_argument("--size", default="160x120")
    args = parser.parse_args()
    from bras_kit.kinematics.frames import tf_tree
    from bras_kit.model.authoring import load
    from bras_kit.render import render_motion

    share = next(os.path.join(base, "cmeel.prefix", "share") for base in site.getsitepackages()
                 if os.path.isdir(os.path.join(base, "cmeel.prefix", "share", "example-robot-data")))
    robot = load(os.path.join(share, "example-robot-data", "robots", "ur_description", "urdf", "ur5_robot.urdf"),
                 package_paths=[share])
    dof = len(tf_tree(robot).dof)
    t = np.arange(args.frames) / 20.0
    q = 0.8 * np.sin(t[:, None] * (1.0 + 0.1 * np.arange(dof)))
    width, height = (int(v) for v in args.size.split("x"))
    marks = {}
    start = time.perf_counter()
    for k, _ in enumerate(render_motion(robot, q, progress=False, size=(width, height), package_paths=[share]), 1):
        if k in (100, 1000, args.frames):
            marks[k] = resident_mib()
    seconds = time.perf_counter() - start
    print(f"UR5, {args.frames} frames at {args.size} in {seconds:.1f} s")
    for k, mib in marks.items():
        print(f"  resident after {k:>6} frames: {mib:7.1f} MiB")
    if 1000 in marks:
        print(f"  growth from frame 1,000 to {args.frames:,}: {marks[args.frames] - marks[1000]:+.1f} MiB")


if __name__ == "__main__":
    main()
