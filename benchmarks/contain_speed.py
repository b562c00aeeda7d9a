"""What the containment costs an ordinary node: the tutorial's node (tests/data/tutorial_package,
``animation``) run for 10 s of node time by ``run_node``, contained (bras_kit/trust/contain.py:
user, mount, network and PID namespaces set up in the forked child) beside today's figure
without walls. The goal: under 0.5 s of wall time contained. The peer is ``ros2 run``, which
takes 10 s of wall time for 10 s of node time.

    python benchmarks/contain_speed.py

Measured (2 cores shared with other jobs, Linux 6.18, Python 3.12), median of 15 runs:

    machine nearly idle:        without walls 0.15 s, contained 0.15-0.26 s
    load average 13 on 2 cores: without walls 0.36-0.80 s, contained 0.36-0.65 s (noise > cost)

Setting the walls up costs about 70 ms under that load (a second fork, for the PID
namespace's init, and some twenty mount calls); the audit hook that reports what the walls
stopped costs nothing measurable.
"""

from __future__ import annotations

import statistics
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TUTORIAL = ROOT / "tests" / "data" / "tutorial_package"


def main(repeat: int = 15) -> None:
    from bras_kit.run import run_node
    from bras_kit.trust.contain import available

    print(f"containment here: {available()}")
    run_node(str(TUTORIAL), "animation", duration=1.0)  # warm: modules compiled and cached
    for label, mode in (("without walls (today)", "off"), ("contained", "require")):
        times, messages = [], 0
        for _ in range(repeat):
            start = time.perf_counter()
            recording = run_node(str(TUTORIAL), "animation", duration=10.0, contain=mode)
            times.append(time.perf_counter() - start)
            messages = len(recording.messages)
        print(f"10 s of node time, {label:22s}: median {statistics.median(times):.3f} s, "
              f"min {min(times):.3f} s, max {max(times):.3f} s ({messages} messages, {repeat} runs)")


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    main()
