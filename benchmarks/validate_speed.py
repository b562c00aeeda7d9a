"""How fast is `bras-kit validate`, as a whole process, next to ROS's `check_urdf`?

Runs on the built-in tutorial arm and on generated chains of 1,000 and 10,000 links (each a
box segment with an inertial on a revolute joint), times the median of a few whole-process runs
of each tool, and prints a table. Also checks, with ``python -X importtime``, that validating
the tutorial arm imports none of the heavy rendering/plotting modules.

    python benchmarks/validate_speed.py [--runs 5] [--sizes 1000 10000]
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

HEAVY = ("pyrender", "matplotlib", "trimesh", "yourdfpy", "PIL", "imageio", "scipy", "OpenGL")


def chain_urdf(count: int) -> str:
    """A straight chain of ``count`` links: a 0.1 m box segment each, joined by revolute joints at the tips."""
    parts = ['<?xml version="1.0"?>', f'<robot name="chain_{count}">']
    for i in range(count):
        parts.append(
            f'  <link name="l{i}">\n'
            f'    <visual><origin xyz="0 0 0.05"/><geometry><box size="0.02 0.02 0.1"/></geometry>'
            f'<material name="m{i % 3}"><color rgba="0.{i % 3 + 2} 0.4 0.9 1"/></material></visual>\n'
            f'    <inertial><origin xyz="0 0 0.05"/><mass value="0.1"/>'
            f'<inertia ixx="8.667e-05" ixy="0" ixz="0" iyy="8.667e-05" iyz="0" izz="6.667e-06"/></inertial>\n'
            f'  </link>')
        if i:
            parts.append(
                f'  <joint name="j{i}" type="revolute"><parent link="l{i - 1}"/><child link="l{i}"/>'
                f'<origin xyz="0 0 0.1"/><axis xyz="0 1 0"/>'
                f'<limit lower="-1.57" upper="1.57" effort="10" velocity="1.0"/></joint>')
    parts.append("</robot>")
    return "\n".join(parts) + "\n"


def timed(argv: list[str], runs: int) -> tuple[float, float, int]:
    """Median wall time and median CPU time (user + system) of ``runs`` whole-process runs, and
    the exit status. CPU time stays meaningful when other work shares the machine."""
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


def heavy_imports(argv: list[str]) -> list[str]:
    """Heavy modules imported while running ``argv`` (a ``bras_kit`` command), from -X importtime."""
    done = subprocess.run([sys.executable, "-X", "importtime", "-m", "bras_kit", *argv],
                          capture_output=True, text=True)
    names = {line.split("|")[-1].strip().split(".")[0] for line in done.stderr.splitlines()
             if line.startswith("import time:") and "|" in line}
    return sorted(n for n in names if n in HEAVY)


def findings_count(path: str | None) -> str:
    from bras_kit.validate import validate, validate_path

    if path is None:
        from bras_kit.model.authoring import arm

        return str(len(validate(arm())))
    return str(len(validate_path(path)))


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=5, help="runs per measurement (median)")
    parser.add_argument("--sizes", type=int, nargs="*", default=[1000, 10000], help="chain lengths")
    args = parser.parse_args()

    heavy = heavy_imports(["validate"])
    print(f"heavy modules imported by 'bras-kit validate': {', '.join(heavy) if heavy else 'none'}")

    bras_kit = [sys.executable, "-m", "bras_kit", "validate"]
    check_urdf = shutil.which("check_urdf")
    rows = []
    with tempfile.TemporaryDirectory(prefix="bras-kit-bench-") as folder:
        from bras_kit.model.authoring import arm_urdf

        tutorial = os.path.join(folder, "bras.urdf")
        with open(tutorial, "w", encoding="utf-8") as handle:
            handle.write(arm_urdf())
        cases = [("built-in arm (xacro expanded)", 3, None), ("bras.urdf (tutorial)", 3, tutorial)]
        for size in args.sizes:
            path = os.path.join(folder, f"chain_{size}.urdf")
            with open(path, "w", encoding="utf-8") as handle:
                handle.write(chain_urdf(size))
            cases.append((f"chain_{size}.urdf", size, path))
        for label, links, path in cases:
            wall, cpu, code = timed(bras_kit + ([path] if path else []), args.runs)
            peer = timed([check_urdf, path], args.runs) if check_urdf and path else None
            rows.append((label, links, wall, cpu, code, peer, findings_count(path)))

    print(f"\nmedian of {args.runs} whole-process runs, wall clock / CPU (python {sys.version.split()[0]}, "
          f"load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs)\n")
    header = (f"{'input':30} {'links':>6} {'bras-kit validate (wall/cpu)':>29} {'exit':>5} {'findings':>9} "
              f"{'check_urdf (wall/cpu)':>23}")
    print(header)
    print("-" * len(header))
    for label, links, wall, cpu, code, peer, count in rows:
        theirs = f"{peer[0]:9.3f}s / {peer[1]:6.3f}s" if peer is not None else "-"
        print(f"{label:30} {links:>6} {wall:15.3f}s / {cpu:8.3f}s {code:>5} {count:>9} {theirs:>23}")
    chains = [(links, cpu) for label, links, _, cpu, *_ in rows if label.startswith("chain_")]
    if len(chains) >= 2:
        (n1, t1), (n2, t2) = chains[0], chains[-1]
        base = rows[1][3]  # CPU of start-up and the 3-link tutorial file: the fixed cost
        print(f"\nCPU time: {n2 // n1}x the links -> {(t2 - base) / (t1 - base):.1f}x the time "
              f"after subtracting the {base:.3f}s start-up")
    if check_urdf is None:
        print("check_urdf not found (apt install liburdfdom-tools) - peer column left empty")
    return 1 if heavy else 0


if __name__ == "__main__":
    raise SystemExit(main())
