"""What the whole-process benchmarks share: how to start ``bras-kit`` the way a user does, an
environment fair to both sides, and alternating timed runs.

- The console script installed beside this Python (a venv's ``bin/bras-kit``), not whatever
  ``bras-kit`` PATH finds first: a version manager's shim (pyenv's is a shell script) adds about
  0.15 s to every start and would be charged to bras-kit alone.
- ``PYTHONDONTWRITEBYTECODE`` is dropped and every command runs once untimed first, so both
  sides start from compiled modules and warm caches, as an installed tool does.
"""

from __future__ import annotations

import os
import statistics
import subprocess
import sys
import time
from collections.abc import Sequence


def bras_kit_command() -> list[str]:
    script = os.path.join(os.path.dirname(sys.executable), "bras-kit")
    return [script] if os.access(script, os.X_OK) else [sys.executable, "-m", "bras_kit"]


def environment() -> dict[str, str]:
    env = dict(os.environ)
    env.pop("PYTHONDONTWRITEBYTECODE", None)
    env.setdefault("PYOPENGL_PLATFORM", "egl")
    return env


def alternate(commands: Sequence[tuple[str, list[str]]], repeat: int) -> dict[str, list[float]]:
    """Seconds per run of each command, run after run in turn so all see the same machine load,
    after one untimed run of each."""
    env = environment()

    def timed(command: list[str]) -> float:
        start = time.perf_counter()
        subprocess.run(command, check=True, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        return time.perf_counter() - start

    for _, command in commands:
        timed(command)
    times: dict[str, list[float]] = {label: [] for label, _ in commands}
    for _ in range(repeat):
        for label, command in commands:
            times[label].append(timed(command))
    return times


def table(times: dict[str, list[float]], extra: dict[str, str] | None = None) -> None:
    print(f"{'command':44s} {'best s':>7s} {'median s':>9s}")
    for label, runs in times.items():
        print(f"{label:44s} {min(runs):7.3f} {statistics.median(runs):9.3f}"
              + (f"  {extra.get(label, '')}" if extra else ""))


def ratio(times: dict[str, list[float]], ours: str, peer: str) -> float:
    return statistics.median(times[ours]) / statistics.median(times[peer])
