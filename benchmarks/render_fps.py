"""Frames per second drawing the tutorial motion at 640x480: bras-kit vs pybullet's TinyRenderer
and MuJoCo's ``mujoco.Renderer`` (shadows off and on), and the memory of a long sequence
streamed into a GIF.

Run: python benchmarks/render_fps.py [--frames 200] [--long 1000] [--rounds 3]   (--long 10000 for the issue's check)
Both draw the same poses (the tutorial's node at 20 Hz) through the same camera (bras-kit's
framing, handed to pybullet as view and projection matrices). TinyRenderer is pybullet's CPU
rasteriser (no antialiasing); bras-kit runs OpenGL on Mesa's EGL (llvmpipe, no GPU here).
Memory is the process's resident size (VmRSS from /proc) after 100 and after --long frames.
"""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
import tempfile
import time

import numpy as np

from bras_kit.model.authoring import arm, arm_urdf
from bras_kit.motion import sample, tutorial_motion
from bras_kit.render import Renderer, render_motion
from bras_kit.render.sequence import GifWriter, palette_samples


def rss_mib() -> float:
    with open("/proc/self/status") as handle:
        for line in handle:
            if line.startswith("VmRSS:"):
                return int(line.split()[1]) / 1024.0
    return float("nan")


def bras_kit_fps(robot, positions: np.ndarray, **opts) -> tuple[float, float, str]:  # type: ignore[no-untyped-def]
    """(frames per second, seconds to open the renderer, backend name)."""
    start = time.perf_counter()
    with Renderer(robot, fit=positions, size=(640, 480), sequence=True, **opts) as renderer:
        renderer.render(positions[0])  # first frame compiles the shaders
        opened = time.perf_counter() - start
        start = time.perf_counter()
        count = sum(1 for _ in renderer.frames(positions))
        return count / (time.perf_counter() - start), opened, renderer.backend


def pictures_fps(robot, positions: np.ndarray) -> float:  # type: ignore[no-untyped-def]
    """Frames per second of a picture renderer (``Renderer.render`` one pose at a time, smooth edges)."""
    with Renderer(robot, fit=positions, size=(640, 480)) as renderer:
        renderer.render(positions[0])
        start = time.perf_counter()
        for q in positions:
            renderer.render(q)
        return len(positions) / (time.perf_counter() - start)


@contextlib.contextmanager
def quiet_c_output():  # type: ignore[no-untyped-def]
    sys.stdout.flush()
    saved = os.dup(1), os.dup(2)
    null = os.open(os.devnull, os.O_WRONLY)
    os.dup2(null, 1)
    os.dup2(null, 2)
    try:
        yield
    finally:
        os.dup2(saved[0], 1)
        os.dup2(saved[1], 2)
        for fd in (*saved, null):
            os.close(fd)


def tiny_renderer_fps(positions: np.ndarray, names: list[str], camera) -> float:  # type: ignore[no-untyped-def]
    with quiet_c_output():
        import pybullet as p

    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, "bras.urdf")
        with open(path, "w") as handle:
            handle.write(arm_urdf())
        with quiet_c_output():  # pybullet prints a banner and a warning per link without inertia
            client = p.connect(p.DIRECT)
            body = p.loadURDF(path, useFixedBase=True, physicsClientId=client)
        try:
            index = {p.getJointInfo(body, i, physicsClientId=client)[1].decode(): i
                     for i in range(p.getNumJoints(body, physicsClientId=client))}
            view = camera.view().T.reshape(-1).tolist()  # OpenGL column-major
            projection = camera.projection().T.reshape(-1).tolist()
            start = time.perf_counter()
            for row in positions:
                for name, value in zip(names, row):
                    p.resetJointState(body, index[name], float(value), physicsClientId=client)
                p.getCameraImage(640, 480, view, projection, renderer=p.ER_TINY_RENDERER, physicsClientId=client)
            return len(positions) / (time.perf_counter() - start)
        finally:
            p.disconnect(client)


MUJOCO = r'''
import ctypes, json, math, os, sys, time
os.environ["MUJOCO_GL"] = "egl"
os.environ["PYOPENGL_PLATFORM"] = "egl"
from OpenGL import EGL
if not hasattr(EGL, "EGLDeviceEXT"):  # PyOpenGL 3.1.0 (pyrender's pin) lacks the name MuJoCo's EGL module uses
    EGL.EGLDeviceEXT = ctypes.c_void_p
import mujoco
import numpy as np
from bras_kit.model.authoring import arm
from bras_kit.physics.mjcf import build_mjcf

job = json.loads(sys.argv[1])
positions, pose, yfov = np.array(job["positions"]), np.array(job["pose"]), job["yfov"]
model = build_mjcf(arm(inertials=True)).compile()
model.vis.global_.fovy = math.degrees(yfov)
data = mujoco.MjData(model)
renderer = mujoco.Renderer(model, job["height"], job["width"])
renderer.scene.flags[mujoco.mjtRndFlag.mjRND_SHADOW] = job["shadows"]
camera = mujoco.MjvCamera()
camera.type = mujoco.mjtCamera.mjCAMERA_FREE
forward = -pose[:3, 2]
camera.distance = job["distance"]
camera.lookat[:] = pose[:3, 3] + forward * job["distance"]
camera.azimuth = math.degrees(math.atan2(forward[1], forward[0]))
camera.elevation = math.degrees(math.asin(forward[2]))
columns = [model.joint(name).qposadr[0] for name in job["names"]]
def draw(row):
    data.qpos[columns] = row
    mujoco.mj_kinematics(model, data)
    renderer.update_scene(data, camera)
    return renderer.render()
draw(positions[0])
start = time.perf_counter()
for row in positions:
    draw(row)
print(len(positions) / (time.perf_counter() - start))
'''


def mujoco_fps(positions: np.ndarray, names: list[str], camera, shadows: bool) -> float:  # type: ignore[no-untyped-def]
    """MuJoCo's ``mujoco.Renderer`` on the same poses and camera, in a process of its own (EGL)."""
    import json
    import subprocess

    points_at = float(np.linalg.norm(camera.pose[:3, 3]))  # distance to the look-at point: any will do
    job = json.dumps({"positions": positions.tolist(), "names": names, "pose": camera.pose.tolist(),
                      "yfov": camera.yfov, "width": camera.width, "height": camera.height,
                      "distance": points_at, "shadows": shadows})
    result = subprocess.run([sys.executable, "-c", MUJOCO, job], capture_output=True, text=True)
    if result.returncode != 0:
        print(f"  (MuJoCo failed: {result.stderr.strip().splitlines()[-1] if result.stderr.strip() else '?'})")
        return float("nan")
    return float(result.stdout.strip().splitlines()[-1])


def streamed_memory(robot, frames: int) -> tuple[float, float, float]:  # type: ignore[no-untyped-def]
    """RSS after 100 frames and after all, and the seconds taken, for a GIF written to a file."""
    states = sample(tutorial_motion(robot), (frames - 1) / 20.0, 20.0)
    sequence = render_motion(robot, states, size=(640, 480), progress=False)
    after_100 = float("nan")
    start = time.perf_counter()
    with tempfile.TemporaryDirectory() as tmp:
        samples, stream = palette_samples(sequence)
        writer = GifWriter(os.path.join(tmp, "long.gif"), 20.0, samples)
        for count, frame in enumerate(stream, 1):
            writer.write(frame)
            if count == 100:
                after_100 = rss_mib()
        writer.close()
        size = os.path.getsize(os.path.join(tmp, "long.gif")) / 1024 / 1024
    print(f"  ({frames} frames -> GIF of {size:.1f} MiB)")
    return after_100, rss_mib(), time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__)
    parser.add_argument("--frames", type=int, default=200, help="frames for the speed test (default 200)")
    parser.add_argument("--long", type=int, default=1000, help="frames for the memory test (default 1000)")
    parser.add_argument("--rounds", type=int, default=3, help="alternating rounds; best of each (default 3)")
    args = parser.parse_args()

    robot = arm()
    states = sample(tutorial_motion(robot), (args.frames - 1) / 20.0, 20.0)
    positions = states.positions
    print(f"tutorial motion, {args.frames} frames at 640x480, {os.cpu_count()} CPU cores, no GPU, "
          f"best of {args.rounds} alternating rounds")
    with Renderer(robot, fit=positions, size=(640, 480), backend="software") as framing:
        camera = framing.camera
    # rounds alternate the renderers, so a busy machine slows them alike; each keeps its best round
    plain = smooth = supersampled = software = tiny = mujoco_plain = mujoco_shadows = 0.0
    opened, cold, backend = float("inf"), float("nan"), "?"
    for _ in range(args.rounds):
        fps, start_s, backend = bras_kit_fps(robot, positions, antialias=False)
        plain, opened = max(plain, fps), min(opened, start_s)
        cold = start_s if cold != cold else cold  # the first round opens OpenGL; later ones reuse it
        tiny = max(tiny, tiny_renderer_fps(positions, states.names, camera))
        mujoco_plain = max(mujoco_plain, mujoco_fps(positions, states.names, camera, shadows=False))
        smooth = max(smooth, bras_kit_fps(robot, positions, antialias=True)[0])
        supersampled = max(supersampled, pictures_fps(robot, positions))
        with Renderer(robot, fit=positions, size=(640, 480), backend="software") as sw:
            start = time.perf_counter()
            count = sum(1 for _ in sw.frames(positions[: max(20, args.frames // 5)]))
            software = max(software, count / (time.perf_counter() - start))
    mujoco_shadows = mujoco_fps(positions, states.names, camera, shadows=True)

    rows = [
        (f"bras-kit {backend}, sequences (no antialiasing, default)", plain),
        (f"bras-kit {backend}, 4x multisampling (sequences with --antialias)", smooth),
        (f"bras-kit {backend}, 2x2 supersampling (pictures' default)", supersampled),
        ("bras-kit software rasteriser (no OpenGL)", software),
        ("pybullet TinyRenderer", tiny),
        ("MuJoCo mujoco.Renderer, shadows off", mujoco_plain),
        ("MuJoCo mujoco.Renderer, default shadows", mujoco_shadows),
    ]
    print(f"{'renderer':58s} {'frames/s':>9s} {'vs Tiny':>8s} {'vs MuJoCo':>10s}")
    for label, fps in rows:
        print(f"{label:58s} {fps:9.1f} {fps / tiny:7.2f}x {fps / mujoco_plain:9.2f}x")
    print(f"targets: bras-kit sequences >= 2x TinyRenderer ({plain / tiny:.2f}x) and >= 1.5x MuJoCo "
          f"without shadows ({plain / mujoco_plain:.2f}x)")
    print(f"bras-kit renderer start (scene, camera, first frame): {cold:.2f} s with a new GL context, "
          f"{opened:.3f} s reusing the one an earlier renderer of that size left")

    print(f"memory streaming {args.long} frames into a GIF (resident set size):")
    after_100, after_all, seconds = streamed_memory(robot, args.long)
    print(f"  after 100 frames: {after_100:7.1f} MiB")
    print(f"  after {args.long} frames: {after_all:6.1f} MiB   (growth {after_all - after_100:+.1f} MiB, "
          f"{args.long / seconds:.0f} frames/s with GIF writing)")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
