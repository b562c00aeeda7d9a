"""Whole-process time for one 640x480 picture of real mesh robots from example-robot-data (UR5:
7 .dae, Panda: 10 .dae) against a plain pybullet script loading the same URDF and writing one
TinyRenderer frame with Pillow. Target (issue 25): with the decoded-mesh cache warm (every run
after the first), bras-kit at most 1.3x the script.

Run: python benchmarks/render_mesh_still_process.py [--repeat 9] [--mujoco-python PATH]
Fresh processes, alternating run after run (see _process.py). bras-kit is timed twice per
robot: as a user runs it again (cache warm) and with --no-cache (every .dae decoded again, the
cost of a first run).

--mujoco-python adds MuJoCo's renderer (``mujoco.Renderer`` on EGL) as a second peer, run by
that interpreter: MuJoCo needs a newer PyOpenGL than the 3.1.0 bras-kit pins for pyrender, so it
lives in its own virtualenv, made once with

    python -m venv /tmp/mj && /tmp/mj/bin/pip install mujoco numpy pillow

then ``--mujoco-python /tmp/mj/bin/python``. MuJoCo's URDF import drops the visuals, so the
peer loads the MJCF ``bras-kit mjcf`` writes from the same URDF (built once, untimed: the
peer's input, as the URDF is pybullet's) and writes one 640x480 PNG with Pillow
(benchmarks/_mujoco_peer.py).
"""

from __future__ import annotations

import argparse
import os
import site
import sys
import tempfile

from _process import alternate, bras_kit_command, ratio, table

MUJOCO_PEER = os.path.join(os.path.dirname(os.path.abspath(__file__)), "_mujoco_peer.py")

TARGET = 1.3

PEER = r'''
import os, sys
fd = os.dup(1); null = os.open(os.devnull, os.O_WRONLY); os.dup2(null, 1); os.dup2(null, 2)
import numpy as np, pybullet as p
from PIL import Image
p.connect(p.DIRECT)
p.setAdditionalSearchPath(sys.argv[3])
body = p.loadURDF(sys.argv[1], useFixedBase=True)
os.dup2(fd, 1)
view = p.computeViewMatrix([1.9, -2.7, 1.6], [0.3, 0.0, 0.45], [0, 0, 1])
projection = p.computeProjectionMatrixFOV(30, 640 / 480, 0.1, 20)
rgba = p.getCameraImage(640, 480, view, projection, renderer=p.ER_TINY_RENDERER)[2]
Image.fromarray(np.reshape(rgba, (480, 640, 4))[..., :3].astype(np.uint8)).save(sys.argv[2])
'''

ROBOTS = {"UR5": "ur_description/urdf/ur5_robot.urdf", "Panda": "panda_description/urdf/panda.urdf"}


def _share() -> str:
    for base in site.getsitepackages():
        share = os.path.join(base, "cmeel.prefix", "share")
        if os.path.isdir(os.path.join(share, "example-robot-data")):
            return share
    raise SystemExit("example-robot-data is not installed (pip install example-robot-data)")


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--repeat", type=int, default=9)
    parser.add_argument("--baseline", metavar="DIR",
                        help="also time the bras-kit source tree in DIR (e.g. `git archive main` unpacked)")
    parser.add_argument("--mujoco-python", metavar="PATH",
                        help="a Python with mujoco, numpy and pillow: adds MuJoCo's renderer as a peer")
    args = parser.parse_args()
    share = _share()
    ours = bras_kit_command()
    commands = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, relative in ROBOTS.items():
            urdf = os.path.join(share, "example-robot-data", "robots", relative)
            out = os.path.join(tmp, f"{name}.png")
            base = ours + ["render", urdf, "--package-path", share, "-o", out, "--force"]
            if args.baseline:
                start = ("import sys; sys.path.insert(0, sys.argv.pop(1)); sys.argv[0] = 'bras-kit'; "
                         "from bras_kit.cli import run; run()")
                commands.append((f"baseline render {name}", [sys.executable, "-c", start, args.baseline] + base[1:]))
            commands += [(f"bras-kit render {name} (cache warm)", base),
                         (f"bras-kit render {name} --no-cache", base + ["--no-cache"]),
                         (f"pybullet TinyRenderer {name}", [sys.executable, "-c", PEER, urdf, out + ".peer.png",
                                                            os.path.dirname(urdf)])]
            if args.mujoco_python:
                commands.append((f"MuJoCo Renderer {name}", mujoco_peer(args.mujoco_python, urdf, share, tmp, out)))
        commands.append(("python -c pass (floor)", [sys.executable, "-c", "pass"]))
        times = alternate(commands, args.repeat)
    print(f"one 640x480 picture, whole process, {args.repeat} alternating runs each, {os.cpu_count()} cores")
    table(times)
    for name in ROBOTS:
        for label in (f"bras-kit render {name} (cache warm)", f"bras-kit render {name} --no-cache"):
            value = ratio(times, label, f"pybullet TinyRenderer {name}")
            verdict = f"target <= {TARGET} -> {'met' if value <= TARGET else 'NOT met'}" if "warm" in label else ""
            print(f"ratio {label} / pybullet (medians): {value:.2f}  {verdict}")
            if args.mujoco_python:
                print(f"ratio {label} / MuJoCo (medians): {ratio(times, label, f'MuJoCo Renderer {name}'):.2f}")


def mujoco_peer(python: str, urdf: str | None, share: str, tmp: str, out: str, frames: int = 1, fps: int = 20,
                size: tuple[int, int] = (640, 480)) -> list[str]:
    """The MuJoCo peer's command: the MJCF of ``urdf`` (None: the tutorial arm, given the
    masses MuJoCo needs with --inertials; the same shapes) built by ``bras-kit mjcf`` (once,
    here), drawn ``frames`` times by ``_mujoco_peer.py`` under ``python``."""
    import subprocess

    model = os.path.join(tmp, os.path.splitext(os.path.basename(urdf or "bras"))[0] + "_mujoco.xml")
    source = [urdf, "--package-path", share] if urdf else ["--inertials"]
    subprocess.run(bras_kit_command() + ["mjcf", *source, "-o", model, "--force"], check=True, capture_output=True)
    suffix = ".png" if frames == 1 else ".gif"
    return [python, MUJOCO_PEER, model, out + ".mujoco" + suffix, str(frames), str(fps), str(size[0]), str(size[1]),
            *(["swing"] if urdf and frames > 1 else [])]


if __name__ == "__main__":
    main()
