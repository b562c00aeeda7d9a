"""Whole-process time for a 120-frame GIF at 640x480 of the tutorial motion (6 s at 20 fps):
``bras-kit render --gif`` vs a plain script doing the same with pybullet's TinyRenderer and
Pillow's own GIF writer. Target for bras-kit: under 4 s.

Run: python benchmarks/render_gif_process.py [--repeat 3]
Each command runs in a fresh Python process (imports, model, OpenGL start-up and file writing
included); the best and the median wall-clock times of --repeat runs are printed with the GIF sizes.
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

FRAMES, FPS, SIZE = 120, 20, (640, 480)

# The peer: what one would write without bras-kit (pybullet for pictures, Pillow for the GIF).
PEER = r'''
import math, os, sys, tempfile
fd = os.dup(1); null = os.open(os.devnull, os.O_WRONLY); os.dup2(null, 1); os.dup2(null, 2)
import numpy as np, pybullet as p
from PIL import Image
from bras_kit.authoring import arm_urdf
out, count, fps = sys.argv[1], int(sys.argv[2]), int(sys.argv[3])
path = os.path.join(tempfile.mkdtemp(), "bras.urdf")
open(path, "w").write(arm_urdf())
p.connect(p.DIRECT)
body = p.loadURDF(path, useFixedBase=True)
os.dup2(fd, 1)
view = p.computeViewMatrix([1.9, -2.7, 1.6], [0.3, 0.0, 0.45], [0, 0, 1])
projection = p.computeProjectionMatrixFOV(30, 640 / 480, 0.1, 20)
frames = []
for k in range(count):
    t = k / fps
    p.resetJointState(body, 0, 0.8 * math.sin(t))
    p.resetJointState(body, 1, 1.2 * math.sin(0.7 * t))
    rgba = p.getCameraImage(640, 480, view, projection, renderer=p.ER_TINY_RENDERER)[2]
    frames.append(Image.fromarray(np.reshape(rgba, (480, 640, 4))[..., :3].astype(np.uint8)))
frames[0].save(out, save_all=True, append_images=frames[1:], duration=1000 // fps, loop=0)
'''


def timed(command: list[str]) -> float:
    start = time.perf_counter()
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    exe = shutil.which("bras-kit")
    ours_cmd = [exe] if exe else [sys.executable, "-m", "bras_kit"]
    with tempfile.TemporaryDirectory() as tmp:
        ours_gif, peer_gif = os.path.join(tmp, "bras.gif"), os.path.join(tmp, "peer.gif")
        ours = ours_cmd + ["render", "--gif", ours_gif, "--duration", str(FRAMES / FPS), "--fps", str(FPS),
                           "--size", f"{SIZE[0]}x{SIZE[1]}", "--force"]
        peer = [sys.executable, "-c", PEER, peer_gif, str(FRAMES), str(FPS)]
        rows = []
        for label, command, gif in (("bras-kit render --gif", ours, ours_gif),
                                    ("pybullet TinyRenderer + Pillow GIF", peer, peer_gif)):
            times = [timed(command) for _ in range(args.repeat)]
            rows.append((label, min(times), statistics.median(times), os.path.getsize(gif) / 1024))
    print(f"{FRAMES} frames at {SIZE[0]}x{SIZE[1]}, whole process, {args.repeat} runs each, {os.cpu_count()} cores")
    print(f"{'command':38s} {'best s':>7s} {'median s':>9s} {'GIF KiB':>8s}")
    for label, best, median, size in rows:
        print(f"{label:38s} {best:7.2f} {median:9.2f} {size:8.0f}")
    verdict = "met" if rows[0][2] < 4.0 else "NOT met"
    print(f"target: bras-kit under 4 s -> {verdict} (median {rows[0][2]:.2f} s)")


if __name__ == "__main__":
    main()
