"""Frames per second drawing the tutorial motion at 640x480: bras-kit vs pybullet's TinyRenderer,
and the memory of a long sequence streamed into a GIF.

Run: python benchmarks/render_fps.py [--frames 200] [--long 1000]
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

from bras_kit.authoring import arm, arm_urdf
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
    with Renderer(robot, fit=positions, size=(640, 480), **opts) as renderer:
        renderer.render(positions[0])  # first frame compiles the shaders
        opened = time.perf_counter() - start
        start = time.perf_counter()
        count = sum(1 for _ in renderer.frames(positions))
        return count / (time.perf_counter() - start), opened, renderer.backend


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
    args = parser.parse_args()

    robot = arm()
    states = sample(tutorial_motion(robot), (args.frames - 1) / 20.0, 20.0)
    positions = states.positions
    print(f"tutorial motion, {args.frames} frames at 640x480, {os.cpu_count()} CPU cores, no GPU")
    plain, opened, backend = bras_kit_fps(robot, positions, antialias=False)
    smooth, _, _ = bras_kit_fps(robot, positions, antialias=True)
    with Renderer(robot, fit=positions, size=(640, 480), backend="software") as sw:
        start = time.perf_counter()
        count = sum(1 for _ in sw.frames(positions[: max(20, args.frames // 5)]))
        software = count / (time.perf_counter() - start)
    with Renderer(robot, fit=positions, size=(640, 480), backend="software") as framing:
        camera = framing.camera
    tiny = tiny_renderer_fps(positions, states.names, camera)

    rows = [
        (f"bras-kit {backend}, sequences (no antialiasing, default)", plain),
        (f"bras-kit {backend}, 4x antialiasing (pictures' default)", smooth),
        ("bras-kit software rasteriser (no OpenGL)", software),
        ("pybullet TinyRenderer", tiny),
    ]
    print(f"{'renderer':58s} {'frames/s':>9s} {'vs Tiny':>8s}")
    for label, fps in rows:
        print(f"{label:58s} {fps:9.1f} {fps / tiny:7.2f}x")
    print(f"bras-kit renderer start (scene, camera, GL context, first frame): {opened:.2f} s")

    print(f"memory streaming {args.long} frames into a GIF (resident set size):")
    after_100, after_all, seconds = streamed_memory(robot, args.long)
    print(f"  after 100 frames: {after_100:7.1f} MiB")
    print(f"  after {args.long} frames: {after_all:6.1f} MiB   (growth {after_all - after_100:+.1f} MiB, "
          f"{args.long / seconds:.0f} frames/s with GIF writing)")
    sys.stdout.flush()


if __name__ == "__main__":
    main()
