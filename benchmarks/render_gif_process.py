"""Whole-process time for a 120-frame GIF at 640x480 of the tutorial motion (6 s at 20 fps):
``bras-kit render --gif`` against a plain script doing the same job with pybullet's
TinyRenderer and Pillow's GIF writer. Target (issue 15): bras-kit at most 0.5x the script.

Run: python benchmarks/render_gif_process.py [--repeat 5] [--robot PATH.urdf --package-path DIR]
Each command runs in a fresh Python process (imports, model, OpenGL start-up and file
writing included). The two commands alternate, run after run, so both see the same machine
load (see _process.py for the fairness rules); the medians and their ratio are printed with
the GIF sizes. bras-kit draws its built-in arm; the script loads the same arm's URDF file.
--mujoco-python PATH adds MuJoCo's renderer as a peer (the same number of frames at the same size,
the GIF written with Pillow), run by a Python with mujoco, numpy and pillow, made once with

    python -m venv /tmp/mj && /tmp/mj/bin/pip install mujoco numpy pillow

(MuJoCo needs a newer PyOpenGL than the 3.1.0 bras-kit pins for pyrender). It loads the MJCF
``bras-kit mjcf`` writes from the same URDF (built once, untimed; MuJoCo's own URDF import
drops the visuals) and moves the joints as the pybullet script does (benchmarks/_mujoco_peer.py).
--robot draws a URDF file instead of the tutorial arm, e.g. Talos from example-robot-data (60 links,
206k triangles): --robot .../talos_data/robots/talos_full_v2.urdf --package-path
.../cmeel.prefix/share (target of issue 25: at most 5 s). The peer script then loads that file in
pybullet (package:// meshes found under the --package-path folders), frames the robot's bounding
box and swings every movable joint about the middle of its limits, one TinyRenderer frame each.
"""

from __future__ import annotations

import argparse
import os
import statistics
import sys
import tempfile

from _process import alternate, bras_kit_command, ratio, table

FRAMES, FPS, SIZE = 120, 20, (640, 480)
TARGET = 0.5

# The peer: what one would write without bras-kit (pybullet for pictures, Pillow for the GIF).
PEER = r'''
import math, os, sys
fd = os.dup(1); null = os.open(os.devnull, os.O_WRONLY); os.dup2(null, 1); os.dup2(null, 2)
import numpy as np, pybullet as p
from PIL import Image
path, out, count, fps = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
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

# The peer for any robot: every movable joint swings about the middle of its limits.
ROBOT_PEER = r'''
import math, os, sys
fd = os.dup(1); null = os.open(os.devnull, os.O_WRONLY); os.dup2(null, 1); os.dup2(null, 2)
import numpy as np, pybullet as p
from PIL import Image
path, out, count, fps = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
p.connect(p.DIRECT)
for folder in sys.argv[5:]:
    p.setAdditionalSearchPath(folder)
body = p.loadURDF(path, useFixedBase=True)
os.dup2(fd, 1)
joints = []
for j in range(p.getNumJoints(body)):
    info = p.getJointInfo(body, j)
    if info[2] in (p.JOINT_REVOLUTE, p.JOINT_PRISMATIC):
        low, high = (info[8], info[9]) if info[9] > info[8] else (-1.0, 1.0)
        joints.append((j, (low + high) / 2, (high - low) / 4))
boxes = [p.getAABB(body, link) for link in range(-1, p.getNumJoints(body))]
low, high = np.min([b[0] for b in boxes], axis=0), np.max([b[1] for b in boxes], axis=0)
centre, radius = (low + high) / 2, np.linalg.norm(high - low) / 2
eye = centre + radius * 2.6 * np.array([0.6, -0.75, 0.3])
view = p.computeViewMatrix(eye.tolist(), centre.tolist(), [0, 0, 1])
projection = p.computeProjectionMatrixFOV(45, 640 / 480, radius * 0.1, radius * 10)
frames = []
for k in range(count):
    t = k / fps
    for n, (j, middle, swing) in enumerate(joints):
        p.resetJointState(body, j, middle + swing * math.sin(2 * math.pi * t / 6 + n))
    rgba = p.getCameraImage(640, 480, view, projection, renderer=p.ER_TINY_RENDERER)[2]
    frames.append(Image.fromarray(np.reshape(rgba, (480, 640, 4))[..., :3].astype(np.uint8)))
frames[0].save(out, save_all=True, append_images=frames[1:], duration=1000 // fps, loop=0)
'''


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=5)
    parser.add_argument("--robot", help="a URDF to draw instead of the tutorial arm")
    parser.add_argument("--package-path", action="append", default=[], metavar="DIR",
                        help="where the robot's package:// meshes are (passed to bras-kit)")
    parser.add_argument("--mujoco-python", metavar="PATH",
                        help="a Python with mujoco, numpy and pillow: adds MuJoCo's renderer as a peer")
    args = parser.parse_args()
    from bras_kit.model.authoring import arm_urdf

    with tempfile.TemporaryDirectory() as tmp:
        urdf = os.path.join(tmp, "bras.urdf")
        with open(urdf, "w", encoding="utf-8") as handle:
            handle.write(arm_urdf())
        ours_gif, peer_gif = os.path.join(tmp, "bras.gif"), os.path.join(tmp, "peer.gif")
        ours = bras_kit_command() + ["render", *([args.robot] if args.robot else []), "--gif", ours_gif,
                                     *(f"--package-path={folder}" for folder in args.package_path),
                                     "--duration", str(FRAMES / FPS), "--fps", str(FPS),
                                     "--size", f"{SIZE[0]}x{SIZE[1]}", "--force"]
        if args.robot:
            peer = [sys.executable, "-c", ROBOT_PEER, args.robot, peer_gif, str(FRAMES), str(FPS), *args.package_path]
        else:
            peer = [sys.executable, "-c", PEER, urdf, peer_gif, str(FRAMES), str(FPS)]
        commands = [("bras-kit render --gif", ours, ours_gif), ("pybullet TinyRenderer + Pillow GIF", peer, peer_gif)]
        if args.mujoco_python:
            from render_mesh_still_process import mujoco_peer

            share = args.package_path[0] if args.package_path else tmp
            mujoco = mujoco_peer(args.mujoco_python, args.robot, share, tmp, os.path.join(tmp, "mujoco"),
                                 FRAMES, FPS, SIZE)
            commands.append(("MuJoCo Renderer + Pillow GIF", mujoco, mujoco[3]))
        times = alternate([(label, command) for label, command, _ in commands], args.repeat)
        sizes = {label: os.path.getsize(gif) / 1024 for label, _, gif in commands}
    print(f"{FRAMES} frames at {SIZE[0]}x{SIZE[1]}, whole process, {args.repeat} alternating runs each, "
          f"{os.cpu_count()} cores" + (f", {args.robot}" if args.robot else ""))
    table(times, {label: f"GIF {size:.0f} KiB" for label, size in sizes.items()})
    value = ratio(times, commands[0][0], commands[1][0])
    if args.robot:
        best = statistics.median(times[commands[0][0]])
        print(f"ratio bras-kit / pybullet script (medians): {value:.2f}; bras-kit median {best:.2f} s, "
              f"target <= 5 s -> {'met' if best <= 5.0 else 'NOT met'}")
    else:
        print(f"ratio bras-kit / pybullet script (medians): {value:.2f}  target <= {TARGET} -> "
              f"{'met' if value <= TARGET else 'NOT met'}")
    if args.mujoco_python:
        print(f"ratio bras-kit / MuJoCo script (medians): {ratio(times, commands[0][0], commands[-1][0]):.2f}")


if __name__ == "__main__":
    main()
