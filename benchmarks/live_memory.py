"""Does a node live beside bras-kit launch keep its memory flat?

The tutorial's node (tests/data/launch/tutorial, 20 Hz) runs live for ``--seconds`` (default
600: ten minutes) as ``bras-kit launch`` runs it (``run_node(live=True, keep=False)``: each
JointState handed over, nothing kept), beside its peer in the same run: the same node live as
``bras-kit run`` beside a launch runs it (``keep=True``: the recording kept for the findings at
the end). Every 10 s, the resident memory of each run's processes (the sandbox's child, the
containment's init and the node) is read from /proc.

    python benchmarks/live_memory.py [--seconds 600]
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
PACKAGE = ROOT / "tests" / "data" / "launch" / "tutorial" / "bras_description"


def _children() -> dict[int, int]:
    """pid -> parent pid, for every process."""
    out = {}
    for name in os.listdir("/proc"):
        if name.isdigit():
            try:
                with open(f"/proc/{name}/stat") as stat:
                    fields = stat.read().rsplit(")", 1)[1].split()
                out[int(name)] = int(fields[1])
            except (OSError, IndexError, ValueError):
                continue
    return out


def _rss_kib(pid: int) -> int:
    try:
        with open(f"/proc/{pid}/status") as status:
            for line in status:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1])
    except OSError:
        pass
    return 0


def _tree_rss(root: int, parents: dict[int, int]) -> int:
    total, todo = 0, [root]
    while todo:
        pid = todo.pop()
        total += _rss_kib(pid)
        todo += [child for child, parent in parents.items() if parent == pid]
    return total


def _one(keep: bool, seconds: float) -> None:
    """One live run in this process; prints how many states it handed over."""
    from bras_kit.run import run_node

    count = 0

    def deliver(_state: object) -> None:
        nonlocal count
        count += 1

    run_node(str(PACKAGE), "animation", duration=seconds, live=True, keep=keep, on_joint_state=deliver)
    print(count)


def main() -> None:
    parser = argparse.ArgumentParser()
    parser.add_argument("--seconds", type=float, default=600.0)
    parser.add_argument("--one", choices=("keep", "stream"), help=argparse.SUPPRESS)
    args = parser.parse_args()
    if args.one:
        _one(args.one == "keep", args.seconds)
        return
    import subprocess

    runs = {label: subprocess.Popen([sys.executable, __file__, "--one", one, "--seconds", str(args.seconds)],
                                    stdout=subprocess.PIPE, text=True)
            for label, one in (("as bras-kit launch runs it (keep=False)", "stream"),
                               ("as bras-kit run beside a launch (keep=True)", "keep"))}
    samples: dict[str, list[tuple[float, int]]] = {label: [] for label in runs}
    start = time.monotonic()
    while any(run.poll() is None for run in runs.values()):
        parents = _children()
        for label, run in runs.items():
            if run.poll() is None:
                samples[label].append((time.monotonic() - start, _tree_rss(run.pid, parents)))
        time.sleep(10.0)
    print(f"the tutorial's node live for {args.seconds:.0f} s (20 Hz): resident memory of the process and its children")
    print("| run | states handed over | RSS at 1 min | RSS at the end | growth after the first minute |")
    print("|---|---|---|---|---|")
    for label, run in runs.items():
        points = samples[label]
        count = (run.stdout.read() if run.stdout else "").strip() or "?"
        minute = next((kib for t, kib in points if t >= 60), points[-1][1])
        last = points[-1][1]
        print(f"| {label} | {count} | {minute / 1024:.1f} MiB | {last / 1024:.1f} MiB | "
              f"{(last - minute) / 1024:+.2f} MiB |")


if __name__ == "__main__":
    main()
