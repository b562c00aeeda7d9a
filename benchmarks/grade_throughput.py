"""Submissions per second of bras-kit grade on this machine, next to what teachers do today:
a loop running urdfdom's check_urdf on each file (no score, no picture, no package checks).

For 50 and 500 generated submissions (the tutorial arm, the wrist exercise, a pitfall, a
broken file, in turn), whole command: check_urdf loop, bras-kit grade --jobs 2 with a picture
each, the same without pictures, and the same through a 2-worker Dask LocalCluster (started
before the clock: a cluster outlives one class). Every figure includes the command's start-up
and the writing of the report (CSV, JSON, one HTML page per learner).

    python benchmarks/grade_throughput.py [--sizes 50 500] [--robot ur5]

With --robot ur5 every learner hands in the UR5 of example-robot-data (meshes and their
colours in every picture; target of issue 25: 200 of them at 20 or more per second).

On a shared machine the wall-clock rate follows the other work running; the CPU seconds of
the whole grade --jobs 2 command (every process it started) and the load average are printed
beside it: 20 submissions per second on 2 cores is at most 0.1 s of CPU per submission.
"""

from __future__ import annotations

import argparse
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path


def make_class(folder: Path, count: int) -> None:
    from bras_kit.model.authoring import arm_urdf

    texts = [arm_urdf(), arm_urdf(wrist=True), arm_urdf(wrist=True, inertials=True),
             arm_urdf().replace('<origin xyz="0 0 0.6"/>', '<origin xyz="0 0 0.3"/>'), arm_urdf()[:900]]
    for k in range(count):
        (folder / f"learner{k:04d}.urdf").write_text(texts[k % len(texts)])


def make_mesh_class(folder: Path, count: int) -> None:
    """``count`` copies of example-robot-data's UR5 (7 .dae visuals, 7 .stl collisions), each a
    folder with its URDF naming its meshes by relative paths; mesh files are hard links."""
    import os
    import site

    share = next(Path(base) / "cmeel.prefix" / "share" / "example-robot-data" for base in site.getsitepackages()
                 if (Path(base) / "cmeel.prefix" / "share" / "example-robot-data").is_dir())
    ur = share / "robots" / "ur_description"
    prefix = "package://example-robot-data/robots/ur_description/meshes/ur5/"
    text = (ur / "urdf" / "ur5_robot.urdf").read_text().replace(prefix, "meshes/")
    for k in range(count):
        learner = folder / f"learner{k:04d}"
        for kind in ("visual", "collision"):
            (learner / "meshes" / kind).mkdir(parents=True)
            for mesh in (ur / "meshes" / "ur5" / kind).iterdir():
                os.link(mesh, learner / "meshes" / kind / mesh.name)
        (learner / "ur5.urdf").write_text(text)


CPU: dict[str, float] = {}  # CPU seconds (user + system, every child process included) of the last timed command


def timed(command: list[str]) -> float:
    import resource

    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    subprocess.run(command, capture_output=True, check=False)
    elapsed = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    CPU["last"] = after.ru_utime + after.ru_stime - before.ru_utime - before.ru_stime
    return elapsed


def check_urdf_loop(folder: Path) -> float:
    start = time.perf_counter()
    for file in sorted(folder.iterdir()):
        subprocess.run(["check_urdf", str(file)], capture_output=True, check=False)
    return time.perf_counter() - start


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--sizes", type=int, nargs="+", default=[50, 500])
    parser.add_argument("--robot", choices=["arm", "ur5"], default="arm",
                        help="ur5: every learner hands in example-robot-data's UR5 with its meshes (issue 25)")
    args = parser.parse_args()
    bras_kit = [sys.executable, "-m", "bras_kit", "grade"]
    import os

    print(f"{'submissions':>11}  {'check_urdf loop':>16}  {'grade --jobs 2':>15}  {'CPU s':>6}  {'CPU/sub':>8}  "
          f"{'no pictures':>12}  {'Dask 2 workers':>15}  {'load 1 min':>10}")
    for size in args.sizes:
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp) / "class"
            folder.mkdir()
            (make_mesh_class if args.robot == "ur5" else make_class)(folder, size)
            peer = check_urdf_loop(folder) if shutil.which("check_urdf") else float("nan")
            pool = timed([*bras_kit, str(folder), "-o", f"{tmp}/a", "--jobs", "2"])
            pool_cpu = CPU["last"]
            bare = timed([*bras_kit, str(folder), "-o", f"{tmp}/b", "--jobs", "2", "--no-pictures"])
            from distributed import LocalCluster

            with LocalCluster(n_workers=2, threads_per_worker=1, host="127.0.0.1", dashboard_address=None) as cluster:
                dask = timed([*bras_kit, str(folder), "-o", f"{tmp}/c", "--scheduler", cluster.scheduler_address])
            print(f"{size:>11}  {size / peer:>11.1f} /s  {size / pool:>10.1f} /s  {pool_cpu:>6.1f}  "
                  f"{1000 * pool_cpu / size:>5.0f} ms  {size / bare:>7.1f} /s  {size / dask:>10.1f} /s  "
                  f"{os.getloadavg()[0]:>10.2f}")


if __name__ == "__main__":
    main()
