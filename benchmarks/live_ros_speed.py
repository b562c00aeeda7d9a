"""What joining the real ROS 2 graph costs (issue 45), and what it must not cost the rest.

1. the wheels' re-exec: ``python -c pass`` in bras-kit's own venv and in a venv holding the Jazzy
   wheels (their ``.pth``, ros_wheels_bootstrapper, re-executes each Python process once), and
   ``import rclpy`` there: why the probe runs in a subprocess and bras-kit's venv stays without them;
2. ``bras-kit doctor --help`` and ``bras-kit --version`` start-up, and the modules ``doctor``
   without ``--ros`` imports (no ``bras_kit.live``, no rclpy: the other commands pay nothing);
3. ``bras-kit doctor --ros`` on the tutorial's graph (robot_state_publisher's stand-in and the
   tutorial's node in a loopback-only namespace): wall time of one look;
4. latency, message published -> shown: ``view --ros`` (the real node's JointState, from its
   DDS source timestamp to ``Viewer.show_joint_state`` returned, one connected page) beside
   ``view --node``'s live path (the node under bras-kit's stand-in, ``run_node(live=True)``, from
   the message's stamp to the same call). Issue 45: within 100 ms.

    python benchmarks/live_ros_speed.py

Run when the machine is quiet (the ``uptime`` line is printed first): 2 shared cores make these
numbers move a lot.
"""

from __future__ import annotations

import json
import os
import statistics
import subprocess
import sys
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
sys.path.insert(0, str(ROOT))
sys.path.insert(0, str(ROOT / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))
DATA = ROOT / "tests" / "data" / "live"


def _median_run(argv: list[str], runs: int = 15, env: dict[str, str] | None = None) -> float:
    subprocess.run(argv, capture_output=True, env=env)  # warm
    times = []
    for _ in range(runs):
        start = time.perf_counter()
        subprocess.run(argv, capture_output=True, env=env)
        times.append(time.perf_counter() - start)
    return statistics.median(times) * 1000


def _percentiles(samples: list[float]) -> str:
    ordered = sorted(samples)
    return (f"median {statistics.median(ordered) * 1000:6.1f} ms, p95 {ordered[int(0.95 * len(ordered))] * 1000:6.1f} ms"
            f" ({len(ordered)} messages)")


def reexec(ros_python: str) -> None:
    print(f"python -c pass, bras-kit's venv: {_median_run([sys.executable, '-c', 'pass']):6.1f} ms")
    print(f"python -c pass, the wheels' venv: {_median_run([ros_python, '-c', 'pass']):6.1f} ms")
    print(f"python -S -c pass, the wheels' venv (no site: no .pth, no re-exec): "
          f"{_median_run([ros_python, '-S', '-c', 'pass']):6.1f} ms")
    print(f"python -c 'import rclpy', the wheels' venv: {_median_run([ros_python, '-c', 'import rclpy'], 7):6.1f} ms")


def startup() -> None:
    from _process import bras_kit_command, environment

    command = bras_kit_command()
    print(f"bras-kit --version: {_median_run([*command, '--version'], env=environment()):6.1f} ms")
    print(f"bras-kit doctor --help: {_median_run([*command, 'doctor', '--help'], env=environment()):6.1f} ms")
    probe = ("import sys, bras_kit.cli.doctor as d, argparse; p = argparse.ArgumentParser(); d.configure(p); "
             "print([m for m in sys.modules if m.startswith(('bras_kit.live', 'rclpy', 'bras_kit.validate'))])")
    found = subprocess.run([sys.executable, "-c", probe], capture_output=True, text=True).stdout.strip()
    print(f"modules 'doctor' (no --ros) imports among bras_kit.live, rclpy, bras_kit.validate: {found}")


def _in_namespace(script: str, ros_python: str) -> str:
    from realros import graph_env, new_domain, shell_in_loopback_namespace

    done = subprocess.run(shell_in_loopback_namespace(script), cwd=DATA, capture_output=True, text=True,
                          env=graph_env(new_domain(), BRAS_KIT_ROS_PYTHON=ros_python), timeout=300)
    return done.stdout + done.stderr[-2000:]


def doctor_wall(ros_python: str) -> None:
    script = (f"{ros_python} state_publisher.py bras.urdf > /tmp/bk_rsp_$$ & a=$!; "
              f"{ros_python} animation.py > /tmp/bk_anim_$$ & b=$!; "
              "until grep -q ready /tmp/bk_rsp_$$ && grep -q ready /tmp/bk_anim_$$; do sleep 0.05; done; "
              f"for i in 1 2 3; do s=$(date +%s.%N); {sys.executable} -m bras_kit doctor --ros --format json "
              "> /dev/null; e=$(date +%s.%N); echo \"wall $s $e\"; done; kill $a $b; wait; rm -f /tmp/bk_*_$$")
    out = _in_namespace(script, ros_python)
    walls = [float(e) - float(s) for _, s, e in (line.split() for line in out.splitlines() if line.startswith("wall "))]
    print("bras-kit doctor --ros (default 3 s), tutorial graph: " + ", ".join(f"{w:.1f} s" for w in walls))


def view_ros_latency(ros_python: str, seconds: float = 8.0) -> None:
    script = (f"{ros_python} state_publisher.py bras.urdf > /tmp/bk_rsp_$$ & a=$!; "
              f"{ros_python} animation.py > /tmp/bk_anim_$$ & b=$!; "
              "until grep -q ready /tmp/bk_rsp_$$ && grep -q ready /tmp/bk_anim_$$; do sleep 0.05; done; "
              f"{sys.executable} {Path(__file__).resolve()} --view-ros-inside {ros_python} {seconds}; "
              "kill $a $b; wait; rm -f /tmp/bk_*_$$")
    out = _in_namespace(script, ros_python)
    line = next((line for line in out.splitlines() if line.startswith("[")), None)
    if line is None:
        print("view --ros: no measure:", out[-500:])
        return
    print("view --ros, published -> shown: " + _percentiles(json.loads(line)))


def _view_ros_inside(ros_python: str, seconds: float) -> None:
    """Inside the namespace: the feed and a viewer with one connected chromium page."""
    from playwright.sync_api import sync_playwright
    from test_view import ARGS, CHROMIUM, _free_port

    from bras_kit.view import Source, Viewer
    from bras_kit.view.live_ros import RosFeed

    feed = RosFeed(ros_python).start()
    robot = feed.wait_for_robot(15)
    assert robot is not None, "no description"
    with Viewer(Source(robot=robot), port=_free_port()) as viewer, sync_playwright() as playwright:
        feed.attach(viewer)
        browser = playwright.chromium.launch(executable_path=CHROMIUM, headless=True, args=ARGS)
        page = browser.new_page()
        page.goto(viewer.url)
        page.wait_for_selector("text=coude", timeout=60_000)
        feed.latencies.clear()
        time.sleep(seconds)
        samples = list(feed.latencies)
        browser.close()
    feed.stop()
    print(json.dumps(samples))


def view_node_latency(seconds: float = 8.0) -> None:
    from bras_kit.run import run_node

    package = ROOT / "tests" / "data" / "launch" / "tutorial" / "bras_description"
    arrivals: list[tuple[float, float]] = []

    def deliver(state: object) -> None:
        arrivals.append((time.time(), state.stamp))  # type: ignore[attr-defined]

    run_node(str(package), "animation", duration=seconds, live=True, keep=False, on_joint_state=deliver)
    # the stand-in's stamps are its simulated clock, held to the wall clock from an unknown start:
    # the lag of each message behind the quickest one (a lower bound of the latency)
    lags = [(t - stamp) for t, stamp in arrivals[5:]]
    quickest = min(lags)
    print("view --node (stand-in, live), lag behind the quickest message: "
          + _percentiles([lag - quickest for lag in lags]))


def main() -> None:
    if len(sys.argv) == 4 and sys.argv[1] == "--view-ros-inside":
        _view_ros_inside(sys.argv[2], float(sys.argv[3]))
        return
    from realros import oracle_python

    print(subprocess.run(["uptime"], capture_output=True, text=True).stdout.strip())
    ros_python = os.environ.get("BRAS_KIT_ROS_PYTHON") or oracle_python()
    reexec(ros_python)
    startup()
    doctor_wall(ros_python)
    view_ros_latency(ros_python)
    view_node_latency()


if __name__ == "__main__":
    main()
