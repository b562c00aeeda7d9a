"""How fast is bras-kit run? The peer is ``ros2 run`` itself, which runs a node in real time:
one simulated second per wall second, whatever the machine.

1. simulated seconds per wall second for the tutorial's node (tests/data/tutorial_package),
   the whole ``run_node`` call (fork, stand-in imports, the node, the recording sent back) and
   the node alone (measured in the child);
2. start -> first frame in the viewer: ``bras-kit view --node PKG`` (runs the node first) beside
   ``bras-kit view`` (the tutorial motion, no node), until headless chromium shows the orange
   forearm.

    python benchmarks/run_speed.py
"""

from __future__ import annotations

import signal
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
TUTORIAL = ROOT / "tests" / "data" / "tutorial_package"  # the tutorial's package as printed
CHROMIUM_ARGS = ["--no-sandbox", "--disable-background-networking", "--disable-component-update",
                 "--disable-sync", "--no-first-run", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]


def simulated_speed(repeat: int = 5) -> None:
    from bras_kit.run import run_node

    run_node(str(TUTORIAL), duration=1.0)  # warm: modules compiled and cached
    for duration in (10.0, 60.0, 600.0):
        whole, node = [], []
        for _ in range(repeat):
            start = time.perf_counter()
            recording = run_node(str(TUTORIAL), duration=duration)
            whole.append(time.perf_counter() - start)
            node.append(recording.wall_seconds)
        w, n = statistics.median(whole), statistics.median(node)
        print(f"{duration:6.0f} s of node time ({len(recording.messages):6d} messages): "
              f"run_node {w:6.3f} s = {duration / w:7.0f} x real time; the node alone {n:6.3f} s = "
              f"{duration / n:7.0f} x  (ros2 run: 1 x)")


def threads_speed(repeat: int = 5) -> None:
    """10 s of node time of nodes with threads: a worker thread with create_rate().sleep() and
    rclpy.spin in the main thread, and a MultiThreadedExecutor whose reentrant 2 Hz callback
    sleeps 0.3 s beside a 20 Hz timer (tests/data/run/jazzy/). Every switch between the node's
    threads is a real OS thread handing over the simulated clock."""
    from bras_kit.run import run_node

    jazzy = ROOT / "tests" / "data" / "run" / "jazzy"
    for name in ("worker_thread_rate.py", "multithreaded_groups.py"):
        run_node(str(jazzy / name), duration=1.0)
        whole, node = [], []
        for _ in range(repeat):
            start = time.perf_counter()
            recording = run_node(str(jazzy / name), duration=10.0)
            whole.append(time.perf_counter() - start)
            node.append(recording.wall_seconds)
        print(f"{name:26s} 10 s of node time ({len(recording.messages)} messages): run_node "
              f"{statistics.median(whole):.3f} s, the node alone {statistics.median(node):.3f} s")


def _first_frame(arguments: list[str]) -> float:
    from playwright.sync_api import sync_playwright

    from benchmarks.view_latency import _free_port, _orange_pixels  # type: ignore[import-not-found]

    port = _free_port()
    with sync_playwright() as playwright:
        browser = playwright.chromium.launch(executable_path="/usr/bin/chromium", headless=True, args=CHROMIUM_ARGS)
        start = time.perf_counter()
        process = subprocess.Popen([sys.executable, "-m", "bras_kit", "view", *arguments, "--no-browser",
                                    "--port", str(port)], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
        try:
            process.stdout.readline()  # type: ignore[union-attr]
            page = browser.new_page(viewport={"width": 1000, "height": 700})
            page.goto(f"http://127.0.0.1:{port}")
            while _orange_pixels(page) < 200:
                time.sleep(0.05)
            elapsed = time.perf_counter() - start
        finally:
            process.send_signal(signal.SIGINT)
            process.communicate(timeout=30)
            browser.close()
    return elapsed


def first_frame(repeat: int = 3) -> None:
    for label, arguments in (("view --node PKG", ["--node", str(TUTORIAL)]), ("view (no node)", [])):
        times = [_first_frame(arguments) for _ in range(repeat)]
        print(f"start -> first frame, {label:16s}: median {statistics.median(times):5.2f} s "
              f"(min {min(times):5.2f} s, {repeat} runs)")


if __name__ == "__main__":
    sys.path.insert(0, str(ROOT))
    simulated_speed()
    threads_speed()
    if "--no-browser" not in sys.argv:
        first_frame()
