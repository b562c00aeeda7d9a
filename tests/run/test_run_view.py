"""bras-kit view --node in a real browser (Debian's chromium, Playwright): the forearm moves the way
the learner's node moved it. Oracle: pixels of the orange forearm in screenshots."""

from __future__ import annotations

import signal
import subprocess
import sys
import time

import numpy as np
import pytest
from pages import ARGS, orange
from pages import free_port as _free_port
from pages import wait as _wait
from paths import TESTS

pytestmark = pytest.mark.slow

TUTORIAL = TESTS / "data" / "tutorial_package"
SCENE = (slice(0, 700), slice(0, 590))  # the 3D view left of the panel


def _orange(page) -> np.ndarray:
    return orange(page, SCENE, notice=None)  # no notice masked: as this test always read the scene


def test_view_node_shows_the_forearm_moving_as_the_node_moves_it(chromium):
    from playwright.sync_api import sync_playwright

    port = _free_port()
    process = subprocess.Popen([sys.executable, "-m", "bras_kit", "view", "--node", f"{TUTORIAL}:animation",
                                "--no-browser", "--port", str(port), "--lang", "en"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        assert f"http://127.0.0.1:{port}" in process.stdout.readline()
        with sync_playwright() as playwright:
            browser = playwright.chromium.launch(executable_path=chromium, headless=True, args=ARGS)
            page = browser.new_page(viewport={"width": 1000, "height": 700})
            page.goto(f"http://127.0.0.1:{port}")
            page.wait_for_selector("text=coude", timeout=60_000)
            assert _wait(lambda: len(_orange(page)) > 200), "the forearm is not drawn"
            # the motion is the node's recording, taken directly (no CSV round trip), and it plays
            # by itself, as the tutorial's arm starts oscillating when the node runs: no click on Play
            assert "animation.py" in page.inner_text("body")
            centres = []
            for _ in range(12):  # over a few seconds of the node's 10 s
                time.sleep(0.3)
                pixels = _orange(page)
                if len(pixels) > 200:
                    centres.append(pixels.mean(axis=0))
            browser.close()
        spread = np.ptp(np.array(centres)[:, 1])
        assert len(centres) >= 8 and spread > 40, f"the forearm did not move: {spread:.0f} px"
    finally:
        process.send_signal(signal.SIGINT)
        _, err = process.communicate(timeout=30)
    assert "Traceback" not in err
