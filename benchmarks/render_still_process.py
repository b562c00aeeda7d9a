"""Whole-process time for one 640x480 picture of the tutorial arm: ``bras-kit render -o pose.png``
(antialiased, as stills are) against a plain pybullet script that loads the same URDF and
writes one TinyRenderer frame with Pillow. Target (issue 15): bras-kit at most 2x the script.

Run: python benchmarks/render_still_process.py [--repeat 15]
Fresh processes, alternating the commands run after run (see _process.py for the fairness
rules); medians and their ratios are printed. bras-kit is timed twice: the built-in arm (what
``bras-kit render`` draws with no file) and the same arm read from the URDF file the script
loads. A bare ``python -c pass`` is timed too, as the floor any Python command pays here.
"""

from __future__ import annotations

import argparse
import os
import sys
import tempfile

from _process import alternate, bras_kit_command, ratio, table

TARGET = 2.0

PEER = r'''
import os, sys
fd = os.dup(1); null = os.open(os.devnull, os.O_WRONLY); os.dup2(null, 1); os.dup2(null, 2)
import numpy as np, pybullet as p
from PIL import Image
p.connect(p.DIRECT)
body = p.loadURDF(sys.argv[1], useFixedBase=True)
os.dup2(fd, 1)
view = p.computeViewMatrix([1.9, -2.7, 1.6], [0.3, 0.0, 0.45], [0, 0, 1])
projection = p.computeProjectionMatrixFOV(30, 640 / 480, 0.1, 20)
rgba = p.getCameraImage(640, 480, view, projection, renderer=p.ER_TINY_RENDERER)[2]
Image.fromarray(np.reshape(rgba, (480, 640, 4))[..., :3].astype(np.uint8)).save(sys.argv[2])
'''


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=15)
    args = parser.parse_args()
    from bras_kit.model.authoring import arm_urdf

    ours = bras_kit_command()
    with tempfile.TemporaryDirectory() as tmp:
        urdf = os.path.join(tmp, "bras.urdf")
        with open(urdf, "w", encoding="utf-8") as handle:
            handle.write(arm_urdf())
        commands = [
            ("bras-kit render -o pose.png", ours + ["render", "-o", os.path.join(tmp, "a.png"), "--force"]),
            ("bras-kit render bras.urdf -o pose.png",
             ours + ["render", urdf, "-o", os.path.join(tmp, "b.png"), "--force"]),
            ("pybullet TinyRenderer + Pillow PNG", [sys.executable, "-c", PEER, urdf, os.path.join(tmp, "c.png")]),
            ("python -c pass (floor)", [sys.executable, "-c", "pass"]),
        ]
        times = alternate(commands, args.repeat)
    print(f"one 640x480 picture, whole process, {args.repeat} alternating runs each, {os.cpu_count()} cores")
    table(times)
    for label in ("bras-kit render -o pose.png", "bras-kit render bras.urdf -o pose.png"):
        value = ratio(times, label, "pybullet TinyRenderer + Pillow PNG")
        print(f"ratio {label} / pybullet script (medians): {value:.2f}  target <= {TARGET} -> "
              f"{'met' if value <= TARGET else 'NOT met'}")


if __name__ == "__main__":
    main()
