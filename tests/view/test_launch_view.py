"""bras-kit launch in a real browser (Debian's chromium, headless, SwiftShader WebGL, driven by
Playwright, as tests/view/test_view.py): the launch file starts the package's node and the arm moves
by itself, with nobody touching the page. Oracle: the pixels of the orange forearm."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from pages import free_port as _free_port
from pages import launch as _launch
from pages import launch_url as _url
from pages import orange as _orange
from pages import wait as _wait
from paths import TESTS

pytestmark = pytest.mark.slow


def _page_where_the_arm_moves_by_itself(browser, process: subprocess.Popen, errors: Path):
    """The launch's page, once the arm is drawn and its forearm has moved with nobody touching it."""
    page = browser.new_page(viewport={"width": 1000, "height": 700})
    page.goto(_url(process, errors))
    page.wait_for_selector("text=coude", timeout=60_000)
    assert _wait(lambda: len(_orange(page)) > 200, 60), "the arm is not drawn"
    first = _orange(page).mean(axis=0)
    moved = []
    assert _wait(lambda: moved.append(np.abs(_orange(page).mean(axis=0) - first).max()) or moved[-1] > 5, 60), \
        f"the forearm did not move by itself: {moved}"
    return page


def test_launch_file_starting_the_node_moves_the_arm_by_itself(browser, tmp_path):
    from bras_kit.scaffold.package import scaffold_package

    scaffold_package(tmp_path / "bras_description")
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    errors = tmp_path / "stderr.txt"
    process = _launch([str(tmp_path / "bras_description"), "affichage.launch.py", "--port", str(_free_port()),
                       "--duration", "20", "animation:=true"], env, errors)
    try:
        page = _page_where_the_arm_moves_by_itself(browser, process, errors)
        page.close()
    finally:
        process.send_signal(signal.SIGINT)
        process.wait(timeout=30)


def test_run_in_a_second_terminal_moves_the_launched_arm(browser, tmp_path):
    """The tutorial's step 7: the display is launched (sliders, no node), then
    'bras-kit run bras_description animation' beside it makes the arm oscillate."""
    package = TESTS / "data" / "launch" / "tutorial" / "bras_description"
    runtime = tmp_path / "runtime"
    runtime.mkdir(mode=0o700)
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    env["XDG_RUNTIME_DIR"] = str(runtime)
    errors = tmp_path / "stderr.txt"
    process = _launch([str(package), "--port", str(_free_port())], env, errors)
    try:
        url = _url(process, errors)
        page = browser.new_page(viewport={"width": 1000, "height": 700})
        page.goto(url)
        page.wait_for_selector("text=coude", timeout=60_000)
        from launch_pages import step_six as _step_six

        _step_six(page)  # the tutorial's launch opens an empty RViz: the learner sets it up (step 6)
        assert _wait(lambda: len(_orange(page)) > 200, 60), "the arm is not drawn"
        first = _orange(page).mean(axis=0)
        time.sleep(1.0)
        assert np.abs(_orange(page).mean(axis=0) - first).max() < 2, "nothing publishes yet: the arm stays still"
        # live (no -o, --json, --gif nor --duration): it joins the launch, until it is stopped
        node = subprocess.Popen([sys.executable, "-m", "bras_kit", "run", str(package), "animation",
                                 "--quiet"], stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        try:
            moved = []
            assert _wait(lambda: moved.append(np.abs(_orange(page).mean(axis=0) - first).max()) or moved[-1] > 5,
                         30), f"the forearm did not follow the node: {moved}"
        finally:
            node.terminate()
            node.wait(timeout=30)
        page.close()
    finally:
        process.send_signal(signal.SIGINT)
        process.wait(timeout=30)


def test_saving_a_file_of_the_package_builds_and_launches_it_again(browser, tmp_path):
    """The node moves the arm live; the learner saves motion.py with a still pose: the package is
    built and launched again, the new node runs, and the forearm stops where the new code holds it."""
    from bras_kit.scaffold.package import scaffold_package

    package = tmp_path / "bras_description"
    scaffold_package(package)
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    errors = tmp_path / "stderr.txt"
    process = _launch([str(package), "affichage.launch.py", "--port", str(_free_port()), "--duration", "2",
                       "animation:=true"], env, errors)
    try:
        page = _page_where_the_arm_moves_by_itself(browser, process, errors)
        motion = package / "bras_description" / "motion.py"
        motion.write_text(motion.read_text() + "\n\ndef joint_positions(elapsed):\n    return [0.0, 1.2]\n"
                          "\n\ndef joint_velocities(elapsed):\n    return [0.0, 0.0]\n")

        def still() -> bool:
            before = _orange(page).mean(axis=0)
            time.sleep(1.0)
            return bool(np.abs(_orange(page).mean(axis=0) - before).max() < 1)

        assert _wait(still, 60), "the arm still moves: the saved node was not launched again"
        assert "motion.py" in errors.read_text()
        page.close()
    finally:
        process.send_signal(signal.SIGINT)
        process.wait(timeout=30)
