"""The viewer in a learner's first hour: a French page with no English on it, the arm kept in view
at its extreme poses, and a tab closed during playback that leaves the terminal quiet.

Debian's chromium, headless, WebGL on the CPU (SwiftShader), as tests/view/test_view.py; the oracles
are what the page shows (the text a reader sees, the arm's pixels) and what the terminal got.
"""

from __future__ import annotations

import math
import os
import re
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest
from pages import free_port as _free_port
from pages import open_page as _open
from pages import orange as _orange
from pages import robot_box as _robot_box
from pages import screenshot as _screenshot
from pages import wait as _wait

pytestmark = pytest.mark.slow

SHOTS = os.environ.get("BRAS_KIT_SHOTS")  # a folder: the screenshots are kept there to be looked at

# What a reader sees: text nodes that are drawn (not sized to nothing, hidden or detached), and
# the ::after text the page's style sheet draws in their place.
_VISIBLE_TEXT = """() => {
  const out = [];
  const walk = document.createTreeWalker(document.body, NodeFilter.SHOW_TEXT);
  while (walk.nextNode()) {
    const node = walk.currentNode, element = node.parentElement, style = getComputedStyle(element);
    if (node.textContent.trim() && style.fontSize !== '0px' && style.display !== 'none'
        && style.visibility !== 'hidden' && element.getClientRects().length) out.push(node.textContent.trim());
  }
  for (const element of document.querySelectorAll('*')) {
    const after = getComputedStyle(element, '::after').content;
    if (after && after.startsWith('"') && after.length > 2) out.push(after.slice(1, -1));
  }
  return out;
}"""

# English words of viser's client and of bras-kit's own panel (none of them is French)
ENGLISH = re.compile(r"\b(Connected|Connecting|Inactive|Software|detected|rendering|unavailable|Display|Joints|"
                     r"Sliders|Motion|Play|Speed|Checks|Values|the|and|your|is|of)\b")


@pytest.fixture()
def arm_file(tmp_path: Path) -> Path:
    path = tmp_path / "bras.urdf"
    done = subprocess.run([sys.executable, "-m", "bras_kit", "urdf", "-o", str(path)], capture_output=True)
    assert done.returncode == 0, done.stderr
    return path


def _shot(page, name: str) -> None:
    if SHOTS:
        page.screenshot(path=str(Path(SHOTS) / name), timeout=120_000)


def test_the_french_page_shows_no_english(browser, arm_file) -> None:
    from bras_kit.view import Source, Viewer

    with Viewer(Source(path=str(arm_file)), port=_free_port(), lang="fr", motion_specs=["tutorial"]) as viewer:
        page = _open(browser, viewer.url)
        page.wait_for_selector("#webgl-software-rendering", timeout=60_000)  # SwiftShader: viser's notice
        assert _wait(lambda: "Rendu WebGL logiciel détecté" in page.evaluate(_VISIBLE_TEXT), 30)
        time.sleep(1.0)
        _shot(page, "french-page.png")
        seen = page.evaluate(_VISIBLE_TEXT)
        words = [re.sub(r"\S*/\S*", "", text) for text in seen]  # file paths are no sentences
        english = sorted({m.group() for text in words for m in ENGLISH.finditer(text)})
        assert not any(re.search(r"\w[:;?!](\s|$)", text) for text in words), words  # French spacing
        assert not english, f"English on the French page: {english}\n{seen}"
        assert "Affichage" in seen and "bras-kit · bras" in seen
        page.close()


@pytest.mark.parametrize("pose", [{"epaule": 1.57, "coude": 0.0}, {"epaule": -1.57, "coude": 0.0},
                                  {"epaule": 1.57, "coude": 2.0}])
def test_the_arm_stays_in_view_and_clear_of_the_panel_at_an_extreme_pose(browser, arm_file, pose) -> None:
    """Swung flat toward +x, the arm reaches 1.1 m from the shoulder (0.6 + 0.5, by hand): the
    camera placed for the zero pose alone put the forearm under the control panel."""
    from bras_kit.view import Source, Viewer

    with Viewer(Source(path=str(arm_file)), port=_free_port(), lang="fr") as viewer:
        page = _open(browser, viewer.url)
        assert _wait(lambda: len(_orange(page)) > 200)
        time.sleep(1.0)  # the camera is placed once the browser has said its size
        session = next(iter(viewer.sessions.values()))
        session.set_values(pose)
        tip = viewer.model.tip(viewer.model.poses(session.values))
        reach = 0.6 * math.sin(pose["epaule"]) + 0.5 * math.sin(pose["epaule"] + pose["coude"])
        assert tip[0] == pytest.approx(reach, abs=1e-9)
        for button in page.locator(".mantine-Notification-root button").all():
            button.click()
        panel = page.get_by_text("Affichage", exact=True).first.bounding_box()["x"] - 12
        page.evaluate("document.querySelectorAll('[class*=ControlPanel], .mantine-Paper-root')"
                      ".forEach(e => { if (e.getBoundingClientRect().left > 300) e.style.visibility = 'hidden' })")
        boxes = []  # the page redraws the new pose and frames it again: on a busy machine, seconds later

        def framed() -> bool:
            try:
                boxes.append(_robot_box(_screenshot(page)))
            except AssertionError:  # no arm in this frame (yet)
                return False
            top, bottom, first, last = boxes[-1]
            return bool(last < panel and top > 0 and bottom < 699 and first > 0)

        framed_in_time = _wait(framed, 30)
        name = "extreme-pose-" + "-".join(f"{k}{v:+.2f}" for k, v in pose.items()) + ".png"
        _shot(page, name)
        assert boxes, "no arm drawn"
        top, bottom, first, last = boxes[-1]
        assert last < panel, f"the arm reaches column {last}, under the panel from {panel}"
        assert framed_in_time, f"the arm is cut by the edge of the view (rows {top}-{bottom}, columns {first}-{last})"
        page.close()


def test_the_framed_box_holds_every_pose_within_the_limits() -> None:
    """The camera fits the arm's swept box (sampled poses) grown by SWEPT_MARGIN about its centre:
    every pose within the limits lies inside, the worst ones worked out by hand included."""
    from bras_kit.model.authoring import arm
    from bras_kit.view.framing import SWEPT_MARGIN, reach_points
    from bras_kit.view.model import view_model

    model = view_model(arm(), ())
    low, high = reach_points(model).min(axis=0), reach_points(model).max(axis=0)
    # by hand: flat at epaule = +-1.57, the tip is 1.1 m out (box half-width 0.03 more); z from
    # the base's bottom (-0.05) to the tip straight up (0.05 + 0.6 + 0.5 = 1.15)
    assert high[0] == pytest.approx(0.6 * math.sin(1.57) + 0.5 * math.sin(1.57) + 0.03 * math.cos(1.57), abs=0.01)
    assert low[0] == pytest.approx(-high[0], abs=1e-9)
    assert high[2] == pytest.approx(1.15, abs=1e-9)
    centre, half = (low + high) / 2, (high - low) / 2 * SWEPT_MARGIN
    # the lowest the forearm reaches, by hand: the upper arm flat (|epaule| = 1.57) and the forearm
    # straight down (epaule + coude = -+pi): its tip at z = 0.05 + 0.6 cos 1.57 - 0.5
    worst = [{"epaule": -1.57, "coude": 1.57 - math.pi}, {"epaule": 1.57, "coude": math.pi - 1.57}]
    rng = np.random.default_rng(2026)
    sampled = [{"epaule": e, "coude": c} for e, c in rng.uniform([-1.57, -2.0], [1.57, 2.0], size=(2000, 2))]
    for values in worst + sampled:
        points = model.box_points(values)
        assert (points >= centre - half - 1e-9).all() and (points <= centre + half + 1e-9).all(), values


def test_closing_the_tab_during_playback_leaves_the_terminal_quiet(browser, arm_file, recwarn) -> None:
    """viser warns (UserWarning, infra/_async_message_buffer.py) when a frame is queued for a
    connection that closed: the play loop does so for a tab closed mid-playback, before viser
    calls on_client_disconnect."""
    from bras_kit.view import Source, Viewer

    with Viewer(Source(path=str(arm_file)), port=_free_port(), motion_specs=["tutorial"]) as viewer:
        page = _open(browser, viewer.url)
        session = next(iter(viewer.sessions.values()))
        session.play.value = True
        session.playing = True
        start = session.play_time
        assert _wait(lambda: session.play_time > start + 0.5), "the motion does not play"
        page.close()  # the tab goes away mid-playback
        assert _wait(lambda: not viewer.sessions, 30), "viser never said the tab left"
        # the play loop's tick that took the session just before viser dropped it: it sends a
        # frame to the closed connection (what a closed tab does at any moment of playback)
        session.advance(0.1)
        time.sleep(0.5)
    said = [str(w.message) for w in recwarn.list]
    assert not [w for w in said if "closed connection" in w], said
