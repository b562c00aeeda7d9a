"""Physics speed: simulated seconds per wall-clock second, and the whole ``bras-kit simulate --gif``.

Side by side, in one run:
  * bras-kit (MuJoCo, PD motors inside MuJoCo, 2 ms steps, set point moved at 500 Hz) on the
    tutorial arm (target: at least 500x real time) and on a 7-joint mesh robot (Franka panda
    from example-robot-data, DAE visuals converted, STL collisions);
  * the peer: pybullet on the same tutorial arm, position motors limited by the same efforts,
    at its default 240 Hz step, driven from Python like a ROS control loop would be;
  * whole-process ``bras-kit simulate --inertials --duration 6 --gif`` (imports, model, physics,
    120 frames drawn by bras-kit's renderer, GIF written) in fresh processes.

Run: python benchmarks/physics_speed.py [--seconds 60] [--repeat 3]
"""

from __future__ import annotations

import argparse
import math
import os
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def best_of(repeat: int, run) -> float:  # type: ignore[no-untyped-def]
    times = []
    for _ in range(repeat):
        start = time.perf_counter()
        run()
        times.append(time.perf_counter() - start)
    return min(times)


def bras_kit_rate(robot, seconds: float, repeat: int, package_paths=()) -> float:  # type: ignore[no-untyped-def]
    from bras_kit.physics import simulate

    simulate(robot, duration=0.1, package_paths=package_paths)  # warm up: imports, first compile
    wall = best_of(repeat, lambda: simulate(robot, control="pd+gravity", duration=seconds,
                                            package_paths=package_paths))
    return seconds / wall


def pybullet_rate(seconds: float, repeat: int) -> float:
    import pybullet as p

    from bras_kit.model.authoring import arm_urdf

    path = os.path.join(tempfile.mkdtemp(), "bras.urdf")
    Path(path).write_text(arm_urdf(inertials=True))
    p.connect(p.DIRECT)
    body = p.loadURDF(path, useFixedBase=True)
    p.setGravity(0, 0, -9.81)
    dt = 1 / 240

    def run() -> None:
        steps = int(seconds / dt)
        for k in range(steps):
            t = k * dt
            p.setJointMotorControlArray(body, [0, 1], p.POSITION_CONTROL,
                                        targetPositions=[0.8 * math.sin(t), 1.2 * math.sin(0.7 * t)], forces=[10, 10])
            p.stepSimulation()

    try:
        return seconds / best_of(repeat, run)
    finally:
        p.disconnect()


def panda():  # type: ignore[no-untyped-def]
    from bras_kit.model.authoring import load

    robots = Path(sys.prefix) / "lib" / f"python{sys.version_info.major}.{sys.version_info.minor}" / "site-packages" \
        / "cmeel.prefix" / "share" / "example-robot-data" / "robots"
    return load(robots / "panda_description" / "urdf" / "panda.urdf", package_paths=[str(robots.parent)]), \
        [str(robots.parent)]


def whole_process(repeat: int) -> list[float]:
    times = []
    env = {**os.environ, "PYOPENGL_PLATFORM": "egl", "MPLBACKEND": "Agg"}
    for _ in range(repeat):
        out = os.path.join(tempfile.mkdtemp(), "sim.gif")
        start = time.perf_counter()
        subprocess.run([sys.executable, "-m", "bras_kit", "simulate", "--inertials", "--duration", "6", "--gif", out],
                       check=True, capture_output=True, env=env)
        times.append(time.perf_counter() - start)
    return times


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--seconds", type=float, default=60.0, help="simulated seconds per run")
    parser.add_argument("--repeat", type=int, default=3)
    args = parser.parse_args()
    from bras_kit.model.authoring import arm

    arm_rate = bras_kit_rate(arm(inertials=True), args.seconds, args.repeat)
    robot, paths = panda()
    panda_rate = bras_kit_rate(robot, args.seconds / 4, args.repeat, paths)
    peer = pybullet_rate(args.seconds, args.repeat)
    print(f"simulated seconds per wall second ({args.seconds:g} s simulated, best of {args.repeat}):")
    print(f"  bras-kit / MuJoCo, tutorial arm (2 joints)   {arm_rate:8.0f}x  (target >= 500x)")
    print(f"  bras-kit / MuJoCo, panda (7 joints, meshes)  {panda_rate:8.0f}x")
    print(f"  pybullet, tutorial arm, 240 Hz Python loop   {peer:8.0f}x")
    times = whole_process(args.repeat)
    print(f"whole process, bras-kit simulate --inertials --duration 6 --gif: best {min(times):.2f} s, "
          f"median {statistics.median(times):.2f} s")


if __name__ == "__main__":
    main()
