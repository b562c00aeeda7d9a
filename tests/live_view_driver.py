"""Driver of the ``view --ros`` test, run INSIDE one loopback-only network namespace (the nodes,
``bras-kit view --ros`` and chromium must reach each other there): it plays the graph's story and
prints one JSON object of what the page showed at each step.

    python live_view_driver.py ROS_PYTHON

1. robot_state_publisher's stand-in and the tutorial's node run; the page draws the arm and the
   forearm's orange moves between screenshots; the Checks say "No finding";
2. the slider window joins: the page shows BK811;
3. both joint state publishers leave; robot_state_publisher is replaced by one publishing the
   URDF with ``coude`` short of the tip: the page shows BK301 and the viewer is still serving.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
import time
from pathlib import Path

HERE = Path(__file__).resolve().parent
DATA = HERE / "data" / "live"
sys.path.insert(0, str(HERE))

from pages import ARGS, CHROMIUM  # noqa: E402
from pages import free_port as _free_port  # noqa: E402
from pages import orange as _orange  # noqa: E402
from pages import wait as _wait  # noqa: E402


def _node(python: str, *argv: str) -> subprocess.Popen[str]:
    process = subprocess.Popen([python, *argv], cwd=DATA, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    assert process.stdout is not None
    for line in process.stdout:  # the node says "ready" once its publisher exists
        if "ready" in line:
            break
    return process


def main() -> int:
    python = sys.argv[1]
    result: dict[str, object] = {}
    nodes = [_node(python, "state_publisher.py", str(DATA / "bras.urdf")), _node(python, "animation.py")]
    port = _free_port()
    view = subprocess.Popen([sys.executable, "-m", "bras_kit", "view", "--ros", "--no-browser", "--port", str(port)],
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    from playwright.sync_api import sync_playwright

    try:
        assert view.stdout is not None
        result["address_line"] = view.stdout.readline().strip()
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=CHROMIUM, headless=True, args=ARGS)
            page = browser.new_page(viewport={"width": 1000, "height": 700})
            page.goto(f"http://127.0.0.1:{port}")
            page.wait_for_selector("text=coude", timeout=60_000)
            result["drawn"] = _wait(lambda: len(_orange(page)) > 200, 30)
            centroids = []
            for _ in range(4):
                pixels = _orange(page)
                centroids.append(pixels.mean(axis=0).tolist() if len(pixels) else None)
                time.sleep(0.6)
            result["centroids"] = centroids
            result["no_finding"] = _wait(lambda: "No finding" in page.inner_text("body"), 10)

            nodes.append(_node(python, "slider_window.py", str(DATA / "bras.urdf")))
            result["bk811"] = _wait(lambda: page.query_selector("[data-finding='BK811']") is not None, 20)

            for process in nodes[1:]:
                process.terminate()
            nodes[0].terminate()
            nodes[0].wait(10)
            nodes[:] = [_node(python, "state_publisher.py", str(DATA / "bras_coude_court.urdf"))]
            result["bk301"] = _wait(lambda: page.query_selector("[data-finding='BK301']") is not None, 30)
            result["still_serving"] = view.poll() is None
            browser.close()
    finally:
        view.send_signal(2)  # Ctrl-C, as the learner stops it
        try:
            _, err = view.communicate(timeout=20)
        except subprocess.TimeoutExpired:
            view.kill()
            _, err = view.communicate()
        result["exit_code"] = view.returncode
        result["stderr"] = err[-3000:]
        for process in nodes:
            process.terminate()
        for process in nodes:
            try:
                process.wait(10)
            except subprocess.TimeoutExpired:
                process.kill()
                process.wait()
    print(json.dumps(result))
    return 0


if __name__ == "__main__":
    os.chdir(HERE)
    sys.exit(main())
