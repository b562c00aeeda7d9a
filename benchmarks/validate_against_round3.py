"""`bras-kit validate` now and at round 3, side by side in one run (issue 43, point 6).

Two inputs, each validated by both source trees in turn (alternating runs, so both see the same
machine load), as whole processes started the way a user starts them:

- ``PKG_DIR``: the tutorial's package as ``bras-kit new`` makes it (package rules BK6xx, its
  launch file built and evaluated since round 4, its URDF);
- a 17,133-link chain (``validate_speed.chain_urdf``) with continuous joints: one BK208 warning
  per joint, 17,132 of them, which round 3 printed one by one.

The round-3 tree is an earlier checkout, run with ``PYTHONPATH`` (the installed entry point is
this tree's). Make it without touching your working tree::

    git worktree add /tmp/bras-kit-round3 4019739      # the last commit before "Round 4"
    python benchmarks/validate_against_round3.py --baseline /tmp/bras-kit-round3 [--runs 5]
    git worktree remove /tmp/bras-kit-round3

Both wall time (best and median) and CPU time (user + system of the process and its children,
median) are printed: the CPU column stays meaningful on a machine others share. Also printed:
what `bras-kit validate PKG_DIR` spends its time on now, phase by phase, one after the other in a
fresh process (``--phases PKG_DIR`` alone prints that table). The command itself runs the worker's
phases beside its own (bras_kit.ros.ahead.evaluate_ahead): on two cores its wall time is about
the longer of the two sides, plus Python's start and what both import before the fork. The 0.5 s
target was set on a machine where round 3 took 0.44-0.52 s: the ratio to round 3 (median wall) is
printed, with what it makes of that range, and the target is judged on the range's upper end. On
one core the two sides add up instead: ``taskset -c 0 python benchmarks/...`` gives that figure.

The untimed first run of each tree leaves what a learner's first command leaves: this boot's
record of the containment's trial (bras_kit.trust.contain), read by every later command instead of
forking a trial child; and each tree's bytecode.
"""

from __future__ import annotations

import argparse
import os
import resource
import statistics
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))

from _process import environment  # noqa: E402
from validate_speed import chain_urdf  # noqa: E402

TARGET_PACKAGE = 0.5  # seconds, whole process, `bras-kit validate PKG_DIR`
ROUND3_ON_TARGET_MACHINE = (0.44, 0.52)  # seconds: round 3 on the machine where the target was set
LINKS = 17_133


def timed(argv: list[str], env: dict[str, str], cwd: str) -> tuple[float, float, int, str]:
    """One run from ``cwd``: never from a source tree, which ``python -m`` would put first on sys.path."""
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    start = time.perf_counter()
    done = subprocess.run(argv, capture_output=True, text=True, env=env, cwd=cwd)
    wall = time.perf_counter() - start
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = after.ru_utime - before.ru_utime + after.ru_stime - before.ru_stime
    return wall, cpu, done.returncode, done.stdout


def phases(package: str) -> None:
    """Wall and CPU time of each phase of `bras-kit validate PKG_DIR`, in this (fresh) process."""
    clock: list[tuple[str, float, float]] = []

    def mark(label: str, since: tuple[float, float]) -> tuple[float, float]:
        own = resource.getrusage(resource.RUSAGE_SELF)
        kids = resource.getrusage(resource.RUSAGE_CHILDREN)
        now = (time.perf_counter(), own.ru_utime + own.ru_stime + kids.ru_utime + kids.ru_stime)
        clock.append((label, now[0] - since[0], now[1] - since[1]))
        return now

    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")  # as the command sets it (bras_kit.cli.main)
    start = mark("", (time.perf_counter(), 0.0))
    at = start
    import yaml  # noqa: F401

    from bras_kit.ros import launched
    at = mark("both, before the fork: the evaluation (bras_kit.ros.launched) and PyYAML", at)
    from bras_kit.trust.contain import available, begin_trial
    if begin_trial():  # no trial where this boot's record says one passed (bras_kit.trust.contain)
        from bras_kit.ros.launching import preload_planning
        preload_planning()
    available()
    at = mark("worker: libseccomp, the containment's trial (none once recorded this boot)", at)
    evaluated = launched.evaluate_package(package)
    at = mark("worker: build + launch file evaluated (setup.py's child, the launch file's beside it)", at)
    from bras_kit.validate import validate_path
    from bras_kit.validate.package import Package, validate_package
    at = mark("command: import the rules (the rest of bras_kit.validate; numpy is not imported)", at)
    validate_path(os.path.join(package, "urdf", "bras.urdf"))
    at = mark("command: the URDF rules on urdf/bras.urdf", at)
    read = Package(package)
    validate_package(package, package=read, launch=False)
    at = mark("command: package rules read statically (BK600-BK627; BK623 follows its formulas)", at)
    read.ahead = lambda root: evaluated
    validate_package(package, package=read, launch=True)
    at = mark("command: the evaluation's rules (BK630-BK639), on the worker's answer", at)
    if "numpy" in sys.modules:
        print("  (numpy was imported: a rule or a module on this path needs it again)")
    for label, wall, cpu in clock[1:]:
        print(f"  {label:88} {wall:7.3f}s wall {cpu:7.3f}s cpu")


def main() -> int:
    if sys.argv[1:2] == ["--phases"]:
        phases(sys.argv[2])
        return 0
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--baseline", required=True, metavar="DIR",
                        help="the round-3 source tree (a git worktree of 4019739)")
    parser.add_argument("--runs", type=int, default=5, help="timed runs per command (after one untimed)")
    parser.add_argument("--large-runs", type=int, default=2, help="timed runs on the 17,133-link file")
    args = parser.parse_args()
    if not os.path.isfile(os.path.join(args.baseline, "bras_kit", "__init__.py")):
        parser.error(f"{args.baseline} holds no bras_kit/ source tree")

    from bras_kit.scaffold.package import scaffold_package

    now_env = environment()
    now_env.pop("PYTHONPATH", None)
    then_env = {**environment(), "PYTHONPATH": os.path.abspath(args.baseline)}
    trees = (("now", now_env), ("round 3", then_env))
    command = [sys.executable, "-m", "bras_kit", "validate"]
    rows = []
    with tempfile.TemporaryDirectory(prefix="bras-kit-bench-") as folder:
        package = os.path.join(folder, "bras_description")
        scaffold_package(package)
        chain = os.path.join(folder, f"chain_{LINKS}.urdf")
        with open(chain, "w", encoding="utf-8") as handle:
            handle.write(chain_urdf(LINKS).replace('type="revolute"', 'type="continuous"'))
        size = os.path.getsize(chain) / (1 << 20)
        print("bras-kit validate PKG_DIR, phase by phase (now, after python and bras_kit.cli started):")
        subprocess.run([sys.executable, os.path.abspath(__file__), "--phases", package], env=now_env, check=True)
        print()
        for label, path, runs in (("validate PKG_DIR (bras-kit new)", package, args.runs),
                                  (f"validate chain_{LINKS}.urdf ({size:.1f} MiB)", chain, args.large_runs)):
            for _, env in trees:  # untimed: compiled modules and warm caches on both sides
                timed([*command, path], env, folder)
            walls: dict[str, list[float]] = {name: [] for name, _ in trees}
            cpus: dict[str, list[float]] = {name: [] for name, _ in trees}
            lines: dict[str, int] = {}
            for _ in range(runs):
                for name, env in trees:
                    wall, cpu, code, out = timed([*command, path], env, folder)
                    walls[name].append(wall)
                    cpus[name].append(cpu)
                    lines[name] = len(out.splitlines())
                    if code not in (0, 1):
                        print(f"{name}: exit code {code} on {path}", file=sys.stderr)
                        return 2
            origins = {name: timed([sys.executable, "-c", "import bras_kit; print(bras_kit.__file__)"], env,
                                   folder)[3].strip() for name, env in trees}
            if origins["now"] == origins["round 3"]:
                print(f"both trees load {origins['now']}: --baseline is not taken", file=sys.stderr)
                return 2
            for name, _ in trees:
                rows.append((label, name, min(walls[name]), statistics.median(walls[name]),
                             statistics.median(cpus[name]), lines[name]))

    print(f"{args.runs} runs ({args.large_runs} on the large file) each, alternating; python "
          f"{sys.version.split()[0]}, load average {os.getloadavg()[0]:.1f} on {os.cpu_count()} CPUs\n")
    header = f"{'command':44} {'tree':8} {'best wall':>10} {'median':>8} {'cpu':>8} {'lines out':>10}"
    print(header)
    print("-" * len(header))
    for label, name, best, median, cpu, count in rows:
        print(f"{label:44} {name:8} {best:9.3f}s {median:7.3f}s {cpu:7.3f}s {count:>10}")
    package_now = next(r for r in rows if r[1] == "now" and "PKG_DIR" in r[0])
    large = {r[1]: r for r in rows if "chain" in r[0]}
    package_then = next(r for r in rows if r[1] == "round 3" and "PKG_DIR" in r[0])
    ratio = package_now[3] / package_then[3]
    scaled = tuple(ratio * seconds for seconds in ROUND3_ON_TARGET_MACHINE)
    print(f"\nvalidate PKG_DIR now: best {package_now[2]:.3f} s here; now / round 3: {ratio:.2f} (median "
          f"wall), {package_now[4] / package_then[4]:.2f} (cpu). Where round 3 took "
          f"{ROUND3_ON_TARGET_MACHINE[0]}-{ROUND3_ON_TARGET_MACHINE[1]} s, that is {scaled[0]:.2f}-"
          f"{scaled[1]:.2f} s (target < {TARGET_PACKAGE} s: {'met' if scaled[1] < TARGET_PACKAGE else 'MISSED'})")
    print(f"large file now / round 3: {large['now'][3] / large['round 3'][3]:.2f} (median wall), "
          f"{large['now'][4] / large['round 3'][4]:.2f} (cpu)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
