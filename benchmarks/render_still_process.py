"""Whole-process time for one 640x480 picture of the tutorial arm: ``bras-kit render -o pose.png``
(antialiased, as stills are) against a plain pybullet script that loads the same URDF and
writes one TinyRenderer frame with Pillow. Target (issue 15): bras-kit at most 2x the script.

Run: python benchmarks/render_still_process.py [--repeat 7]
Fresh processes, alternating the two commands run after run; medians and their ratio are
printed. A bare ``python -c pass`` is timed too, as the floor any Python command pays here.
"""

from __future__ import annotations

import argparse
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

TARGET = 2.0

PEER = r'''
import os, sys, tempfile
fd = os.dup(1); null = os.open(os.devnull, os.O_WRONLY); os.dup2(null, 1); os.dup2(null, 2)
import numpy as np, pybullet as p
from PIL import Image
from bras_kit.authoring import arm_urdf
path = os.path.join(tempfile.mkdtemp(), "bras.urdf")
open(path, "w").write(arm_urdf())
p.connect(p.DIRECT)
body = p.loadURDF(path, useFixedBase=True)
os.dup2(fd, 1)
view = p.computeViewMatrix([1.9, -2.7, 1.6], [0.3, 0.0, 0.45], [0, 0, 1])
projection = p.computeProjectionMatrixFOV(30, 640 / 480, 0.1, 20)
rgba = p.getCameraImage(640, 480, view, projection, renderer=p.ER_TINY_RENDERER)[2]
Image.fromarray(np.reshape(rgba, (480, 640, 4))[..., :3].astype(np.uint8)).save(sys.argv[1])
'''


def timed(command: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=7)
    args = parser.parse_args()
    exe = shutil.which("bras-kit")
    ours_cmd = [exe] if exe else [sys.executable, "-m", "bras_kit"]
    with tempfile.TemporaryDirectory() as tmp:
        commands = [
            ("bras-kit render -o pose.png", ours_cmd + ["render", "-o", os.path.join(tmp, "pose.png"), "--force"]),
            ("pybullet TinyRenderer + Pillow PNG", [sys.executable, "-c", PEER, os.path.join(tmp, "peer.png")]),
            ("python -c pass (floor)", [sys.executable, "-c", "pass"]),
        ]
        times: dict[str, list[float]] = {label: [] for label, _ in commands}
        for _ in range(args.repeat):
            for label, command in commands:
                times[label].append(timed(command))
    print(f"one 640x480 picture, whole process, {args.repeat} alternating runs each, {os.cpu_count()} cores")
    print(f"{'command':38s} {'best s':>7s} {'median s':>9s}")
    for label, _ in commands:
        print(f"{label:38s} {min(times[label]):7.2f} {statistics.median(times[label]):9.2f}")
    ratio = statistics.median(times[commands[0][0]]) / statistics.median(times[commands[1][0]])
    print(f"ratio bras-kit / pybullet script (medians): {ratio:.2f}  target <= {TARGET} -> "
          f"{'met' if ratio <= TARGET else 'NOT met'}")


if __name__ == "__main__":
    main()
