"""What do the xacro walls cost? The allow-list evaluator and the sandboxed child, next to plain xacro.

Prints three tables:

1. one expansion of the tutorial arm's xacro (a copy, so it counts as a stranger's file), in
   process: the real ``xacro`` package alone (its ``eval``), bras-kit with the evaluator only,
   bras-kit with the evaluator in a forked child with limits (what every CLI command does);
2. whole processes: ``xacro FILE`` (the real command) and ``bras-kit xacro FILE`` and
   ``bras-kit validate FILE`` (target: validate under 0.5 s);
3. the worst hostile files of ``tests/data/hostile``: wall time and peak memory of the child.

    python benchmarks/xacro_sandbox.py [--runs 20]
"""

from __future__ import annotations

import argparse
import contextlib
import io
import os
import resource
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
HOSTILE = ROOT / "tests" / "data" / "hostile"


def _median_ms(function, runs: int) -> float:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        function()
        times.append(time.perf_counter() - start)
    return statistics.median(times) * 1000


def _process_s(command: list[str], runs: int, cwd: str) -> float:
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(command, cwd=cwd, capture_output=True, check=False)
        times.append(time.perf_counter() - start)
    return statistics.median(times)


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--runs", type=int, default=20)
    args = parser.parse_args()

    import xacro

    from bras_kit.core.resources import robot_template
    from bras_kit.model.xacro import expand_xacro

    work = tempfile.mkdtemp()
    arm = os.path.join(work, "bras.urdf.xacro")
    shutil.copy(robot_template(), arm)

    def plain() -> None:
        with contextlib.redirect_stderr(io.StringIO()):
            xacro.process_file(arm).toprettyxml(indent="  ")
        xacro.init_stacks(None)

    rows = [
        ("real xacro (Python eval, no limits)", _median_ms(plain, args.runs)),
        ("bras-kit, allow-list evaluator in process", _median_ms(lambda: expand_xacro(arm, sandbox=False), args.runs)),
        ("bras-kit, evaluator + sandboxed child", _median_ms(lambda: expand_xacro(arm, sandbox=True), args.runs)),
    ]
    print(f"one expansion of the tutorial arm ({args.runs} runs, median)")
    for name, ms in rows:
        print(f"  {name:<45} {ms:8.1f} ms")
    print(f"  sandbox start-up (child minus in-process)     {rows[2][1] - rows[1][1]:8.1f} ms")

    runs = max(3, args.runs // 4)
    print(f"\nwhole process ({runs} runs, median)")
    for name, command in [
        ("xacro FILE (real)", [shutil.which("xacro") or "xacro", arm]),
        ("bras-kit xacro FILE", [sys.executable, "-m", "bras_kit", "xacro", arm]),
        ("bras-kit validate FILE", [sys.executable, "-m", "bras_kit", "validate", arm]),
    ]:
        print(f"  {name:<45} {_process_s(command, runs, work):8.3f} s")

    print("\nhostile files, bras-kit xacro, whole process (wall time, peak memory of the children)")
    for item in HOSTILE.iterdir():
        shutil.copy(item, os.path.join(work, item.name))
    fifo = os.path.join(work, "fifo.xacro")
    if not os.path.exists(fifo):
        os.mkfifo(fifo)
    results = []
    for path in sorted(HOSTILE.glob("*.xacro")):
        before = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        start = time.perf_counter()
        done = subprocess.run([sys.executable, "-m", "bras_kit", "xacro", path.name], cwd=work,
                              capture_output=True, text=True, check=False)
        elapsed = time.perf_counter() - start
        peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss
        last = done.stderr.strip().splitlines()[0][:90] if done.stderr.strip() else ""
        results.append((elapsed, path.name, peak if peak > before else None, done.returncode, last))
    for elapsed, name, peak, code, last in sorted(results, reverse=True):
        memory = f"{peak / 1024:7.0f} MiB" if peak else "  (below earlier peak)"
        print(f"  {name:<28} {elapsed:6.2f} s  {memory}  exit {code}  {last}")
    shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
