"""How long does `bras-kit validate PKGDIR` take, as a whole process, on the package `bras-kit new` makes?

Scaffolds the package (default, and with --wrist --inertials), then times the median of a few
whole-process runs of: Python starting and doing nothing (the floor), urdfdom's `check_urdf` on
the package's URDF (the peer for the URDF part), `bras-kit validate urdf/bras.urdf` (the URDF
rules only) and `bras-kit validate PKGDIR` (package rules BK6xx plus every .urdf/.xacro in it).
The target for the last one is under 0.5 s.

    python benchmarks/validate_package_speed.py [--runs 7]
"""

from __future__ import annotations

import argparse
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time

TARGET = 0.5  # seconds, whole process


def timed(argv: list[str], runs: int) -> tuple[float, float, int]:
    """Median wall time, median CPU time (user + system) and the exit status of ``runs`` runs."""
    walls, cpus, code = [], [], 0
    for _ in range(runs):
        before = resource.getrusage(resource.RUSAGE_CHILDREN)
        start = time.perf_counter()
        done = subprocess.run(argv, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        walls.append(time.perf_counter() - start)
        after = resource.getrusage(resource.RUSAGE_CHILDREN)
        cpus.append(after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime)
        code = done.returncode
    return statistics.median(walls), statistics.median(cpus), code


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=7, help="runs per measurement (median)")
    args = parser.parse_args()

    from bras_kit.scaffold.package import scaffold_package

    bras_kit = [sys.executable, "-m", "bras_kit", "validate"]
    check_urdf = shutil.which("check_urdf")
    rows = []
    with tempfile.TemporaryDirectory(prefix="bras-kit-bench-") as folder:
        for label, options in (("default", {}), ("--wrist --inertials", {"wrist": True, "inertials": True})):
            package = os.path.join(folder, label.replace("-", "").replace(" ", "_") or "default", "bras_description")
            scaffold_package(package, **options)
            urdf = os.path.join(package, "urdf", "bras.urdf")
            cases = [("python -c pass (floor)", [sys.executable, "-c", "pass"])]
            if check_urdf:
                cases.append(("check_urdf urdf/bras.urdf", [check_urdf, urdf]))
            cases += [("bras-kit validate urdf/bras.urdf", [*bras_kit, urdf]),
                      ("bras-kit validate PKGDIR", [*bras_kit, package])]
            for what, argv in cases:
                wall, cpu, code = timed(argv, args.runs)
                rows.append((label, what, wall, cpu, code))

    print(f"median of {args.runs} whole-process runs, wall clock / CPU (python {sys.version.split()[0]}, "
          f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs)\n")
    header = f"{'package (bras-kit new)':22} {'command':34} {'wall':>8} {'cpu':>8} {'exit':>5}"
    print(header)
    print("-" * len(header))
    for label, what, wall, cpu, code in rows:
        print(f"{label:22} {what:34} {wall:7.3f}s {cpu:7.3f}s {code:>5}")
    worst = max(wall for _, what, wall, _, _ in rows if what == "bras-kit validate PKGDIR")
    verdict = "met" if worst < TARGET else "MISSED"
    print(f"\nslowest 'bras-kit validate PKGDIR': {worst:.3f} s (target < {TARGET} s: {verdict})")
    return 0 if worst < TARGET else 1


if __name__ == "__main__":
    sys.exit(main())
