"""bras-kit view in a real browser: Debian's chromium, headless, driven by Playwright, WebGL on
the CPU (SwiftShader). The oracles are what the page shows (pixels of the orange forearm, the
panel's text) and what the Python side holds, never the viewer's own idea of itself."""

from __future__ import annotations

import subprocess
import sys
import time

import numpy as np
import pytest
from page_words import page_words
from pages import close_notices as _close_notices
from pages import ended as _ended
from pages import free_port as _free_port
from pages import open_page as _open
from pages import orange as _orange
from pages import robot_box as _robot_box
from pages import screenshot as _screenshot
from pages import viser_client_words as _viser_client_words
from pages import wait as _wait

pytestmark = pytest.mark.slow


def test_page_loads_from_this_computer_only_and_draws_the_arm(browser, viewer):
    requests: list[str] = []
    page = _open(browser, viewer.url, requests)
    assert _wait(lambda: len(_orange(page)) > 200), "the orange forearm is not drawn"
    hosts = {url.split("/")[2] for url in requests if "://" in url and not url.startswith("data:")}
    assert hosts == {viewer.url.split("/")[2]}, hosts
    assert viewer.url.startswith("http://127.0.0.1:")
    page.close()


def test_moving_the_coude_slider_moves_the_arm_on_both_sides(browser, viewer):
    page = _open(browser, viewer.url)
    assert _wait(lambda: len(_orange(page)) > 200)
    before = _orange(page).mean(axis=0)
    session = next(iter(viewer.sessions.values()))
    coude = page.get_by_role("slider").nth(1)
    coude.focus()
    page.keyboard.press("End")  # the slider's upper bound: the coude's limit, 2 rad
    assert _wait(lambda: session.values["coude"] == pytest.approx(2.0))
    assert session.values["epaule"] == 0.0
    assert _wait(lambda: np.linalg.norm(_orange(page).mean(axis=0) - before) > 20), "the forearm did not move"
    # the readout: the tip, by hand: shoulder at z=0.05, bras 0.6 up, forearm 0.5 turned 2 rad about y
    tip = viewer.model.tip(viewer.model.poses(session.values))
    np.testing.assert_allclose(tip, [0.5 * np.sin(2.0), 0.0, 0.65 + 0.5 * np.cos(2.0)], atol=1e-12)
    assert _wait(lambda: f"x={tip[0]:.3f}" in page.inner_text("body"))
    page.close()


def test_each_browser_has_its_own_controls(browser, viewer):
    first, second = _open(browser, viewer.url), _open(browser, viewer.url)
    assert _wait(lambda: len(viewer.sessions) == 2)
    one, two = viewer.sessions.values()
    one.set_values({"epaule": 1.0})
    assert two.values["epaule"] == 0.0
    first.close()
    second.close()


def test_saving_the_file_reloads_the_model_and_shows_the_finding(browser, viewer, arm_file):
    page = _open(browser, viewer.url)
    session = next(iter(viewer.sessions.values()))
    session.set_values({"coude": 0.5})
    text = arm_file.read_text()
    extra = ('  <link name="pince"/>\n'
             '  <joint name="pince_joint" type="revolute">\n'
             '    <parent link="avant_bras"/><child link="pince"/>\n'
             '    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/>\n'
             '    <limit lower="-1" upper="1" effort="5" velocity="1"/>\n'
             '  </joint>\n</robot>')
    arm_file.write_text(text.replace("</robot>", extra))
    assert _wait(lambda: "pince" in viewer.model.tree.links, 30), "not reloaded"
    assert _wait(lambda: "BK308" in page.inner_text("body"), 30), "the finding is not shown"
    # the page has the new link: its slider in the panel, its frame's name in the 3D view
    assert _wait(lambda: page.get_by_text("pince_joint", exact=True).count() == 1, 30)
    assert _wait(lambda: page.get_by_text("pince", exact=True).count() == 1, 30)
    assert session.values["coude"] == 0.5  # kept across the reload
    assert "pince_joint" in session.values
    arm_file.write_text(text.replace("</robot>", "<link name=\n"))  # no longer XML
    assert _wait(lambda: viewer.error is not None, 30)
    assert _wait(lambda: "cannot be read" in page.inner_text("body"), 30)
    assert "pince" in viewer.model.tree.links  # the last good model stays
    page.close()


def test_exported_page_replays_the_arm_from_disk(browser, tmp_path):
    out = tmp_path / "bras.html"
    done = subprocess.run([sys.executable, "-m", "bras_kit", "view", "--export", str(out), "--duration", "2"],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    assert "https://" not in out.read_text()
    page = browser.new_page(viewport={"width": 1000, "height": 700})
    requests: list[str] = []
    page.on("request", lambda request: requests.append(request.url))
    page.goto(out.as_uri())
    assert _wait(lambda: len(_orange(page)) > 200, 60), "the exported page draws no arm"
    assert all(url.startswith(("file://", "data:", "blob:")) for url in requests), requests
    # it replays: the forearm is seen in more than one place within a second
    places = [_orange(page).mean(axis=0)]
    assert _wait(lambda: places.append(_orange(page).mean(axis=0)) or
                 max(np.linalg.norm(p - places[0]) for p in places) > 10, 3), "the exported arm does not move"
    page.close()
    again = subprocess.run([sys.executable, "-m", "bras_kit", "view", "--export", str(out)],
                           capture_output=True, text=True, timeout=120)
    assert again.returncode == 2 and "--force" in again.stderr


def test_view_command_serves_and_stops_on_ctrl_c(tmp_path):
    import signal

    port = _free_port()
    process = subprocess.Popen([sys.executable, "-m", "bras_kit", "view", "--no-browser", "--port", str(port)],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        line = process.stdout.readline()
        assert f"http://127.0.0.1:{port}" in line
        import urllib.request

        assert b"<html" in urllib.request.urlopen(f"http://127.0.0.1:{port}", timeout=10).read()
    finally:
        process.send_signal(signal.SIGINT)
        out, err = _ended(process, 20)
    assert process.returncode == 0
    assert "Traceback" not in err
    assert "(viser)" not in line + out + err  # bras-kit prints its own lines, not viser's banner


def test_the_page_speaks_french(browser, arm_file):
    from bras_kit.view import Source, Viewer

    with Viewer(Source(path=str(arm_file)), port=_free_port(), lang="fr") as viewer:
        page = _open(browser, viewer.url)
        assert _wait(lambda: "Pose au hasard" in page.inner_text("body"))
        text = page.inner_text("body")
        assert "Articulations" in text and "Pointe" in text
        assert "Random pose" not in text and "Joints" not in text
        page.close()


def test_viser_s_own_words_are_french_in_a_french_page(browser, arm_file):
    """No word of viser's client is left in English under --lang fr: text, tooltips, titles,
    aria-labels, placeholders; a node viser adds later (a tooltip, a notice) is worded too."""
    from bras_kit.view import Source, Viewer

    english = _viser_client_words()
    assert {"Minimize panel", "Software WebGL rendering detected", "About Viser"} <= english  # the oracle reads
    with Viewer(Source(path=str(arm_file)), port=_free_port(), lang="fr") as viewer:
        page = _open(browser, viewer.url)
        assert _wait(lambda: "Rendu WebGL logiciel" in page.inner_text("body"), 20)
        shown = page_words(page)
        left = sorted({text for text in shown if text in english or text.startswith("Edit props for ")})
        assert left == [], left
        assert "Réduire le panneau" in shown
        # a tooltip is added to the page's body when the mouse rests on a button: worded as it comes
        page.evaluate("""() => { const tip = document.createElement('div'); tip.id = 'probe';
            tip.setAttribute('role', 'tooltip'); tip.textContent = 'Minimize'; document.body.appendChild(tip); }""")
        assert _wait(lambda: page.inner_text("#probe") == "Réduire", 30)
        page.close()


def test_the_arm_follows_the_slider_while_the_mouse_drags_it(browser, viewer):
    page = _open(browser, viewer.url)
    assert _wait(lambda: len(_orange(page)) > 200)
    session = next(iter(viewer.sessions.values()))
    thumb = page.get_by_role("slider").nth(1)  # coude's thumb, at 0 in -2 .. 2: mid-track
    box = thumb.bounding_box()
    x, y = box["x"] + box["width"] / 2, box["y"] + box["height"] / 2
    page.mouse.move(x, y)
    page.mouse.down()
    seen = []
    for step in range(1, 6):
        page.mouse.move(x + 12 * step, y, steps=2)
        _wait(lambda: session.values["coude"] > (seen[-1] if seen else 0.0), 2)
        seen.append(session.values["coude"])
    # the button is still down: every step already reached Python, each further than the last
    assert all(b > a for a, b in zip([0.0, *seen], seen)), seen
    page.mouse.up()
    page.close()


def test_play_moves_the_arm_and_the_panel_shows_the_joint_past_its_limit(browser, arm_file):
    from bras_kit.view import Source, Viewer

    # coude's limits are -2 .. 2 rad: 2.5 sin(3t) leaves them twice a period (2.1 s)
    with Viewer(Source(path=str(arm_file)), port=_free_port(), motion_specs=["coude=2.5*sin(3*t)"]) as viewer:
        page = _open(browser, viewer.url)
        assert _wait(lambda: len(_orange(page)) > 200)
        session = next(iter(viewer.sessions.values()))
        assert "out of limits" not in page.inner_text("body")
        page.get_by_text("Play", exact=True).click()
        assert _wait(lambda: session.playing and session.values["coude"] != 0.0), "play did not start"
        row = page.locator("[data-joint='coude']")
        colours = []
        # a row being replaced reads as unstyled for a moment: wait for a settled red row
        assert _wait(lambda: colours.append(row.evaluate("e => [getComputedStyle(e).color, e.innerText]"))
                     or ("out of limits" in colours[-1][1] and colours[-1][0] != ""), 10)
        assert colours[-1][0] == "rgb(198, 40, 40)"  # #c62828, while past the limit
        assert _wait(lambda: row.evaluate("e => getComputedStyle(e).color") != "rgb(198, 40, 40)", 30)
        page.get_by_text("Play", exact=True).click()  # pause
        assert _wait(lambda: not session.playing)
        held = session.values["coude"]
        time.sleep(0.3)
        assert session.values["coude"] == held
        page.close()


# -- what learners see: framing, typed joint values, the error banner, reading a link's pose ----

def _panel_left(page) -> float:
    box = page.get_by_text("Display", exact=True).first.bounding_box()
    return box["x"] - 12  # the folder's frame starts a little left of its title


def _assert_framed(page, viewer=None) -> None:
    """The arm covers at least 40 % of the 3D view's height or width, and none of it is under
    the panel: measured with the panel folded away."""
    left = _panel_left(page)
    page.locator("body").hover()
    _close_notices(page)
    page.get_by_text("Display", exact=True).first.wait_for()
    page.evaluate("document.querySelectorAll('[class*=ControlPanel], .mantine-Paper-root')"
                  ".forEach(e => { if (e.getBoundingClientRect().left > 300) e.style.visibility = 'hidden' })")
    time.sleep(0.5)
    top, bottom, first, last = _robot_box(_screenshot(page))
    height, width = 700, left
    assert (bottom - top) >= 0.4 * height or (last - first) >= 0.4 * width, (top, bottom, first, last, left)
    assert last < left, f"the arm reaches column {last}, under the panel from {left}"
    assert top > 0 and bottom < height - 1 and first > 0, "the arm is cut by the edge of the view"


def test_the_view_opens_on_the_arm_left_of_the_panel(browser, viewer):
    page = _open(browser, viewer.url)
    assert _wait(lambda: len(_orange(page)) > 200)
    time.sleep(1.0)  # the camera is placed once the browser has said its size
    _assert_framed(page)
    page.close()


def test_a_reload_that_makes_the_arm_three_times_larger_frames_it_again(browser, viewer, arm_file, tmp_path):
    page = _open(browser, viewer.url)
    assert _wait(lambda: len(_orange(page)) > 200)
    large = tmp_path / "grand.urdf"
    done = subprocess.run([sys.executable, "-m", "bras_kit", "urdf", "--param", "bras_length=1.8",
                           "--param", "avant_bras_length=1.5", "-o", str(large)], capture_output=True)
    assert done.returncode == 0, done.stderr
    arm_file.write_text(large.read_text())
    assert _wait(lambda: viewer.model.scale > 3.0, 30), viewer.model.scale
    time.sleep(1.5)
    _assert_framed(page)
    page.close()


def test_the_exported_page_opens_on_the_arm(browser, tmp_path):
    out = tmp_path / "bras.html"
    done = subprocess.run([sys.executable, "-m", "bras_kit", "view", "--export", str(out), "--motion",
                           "coude=0.3*sin(t)", "--duration", "2"], capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    page = browser.new_page(viewport={"width": 1000, "height": 700})
    page.goto(out.as_uri())
    assert _wait(lambda: len(_orange(page)) > 200, 60)
    _close_notices(page)
    top, bottom, first, last = _robot_box(_screenshot(page)[:650])  # above the play bar
    assert (bottom - top) >= 0.4 * 650 or (last - first) >= 0.4 * 1000, (top, bottom, first, last)
    assert top > 0 and bottom < 649 and first > 0 and last < 999
    page.close()


def _joint_box(page, joint: str):
    """The text box labelled "JOINT =" under the joint's slider."""
    return page.get_by_text(f"{joint} =", exact=True).locator("xpath=ancestor::*[.//input][1]").locator("input")


def test_typed_joint_values_read_like_the_command_line(browser, viewer):
    page = _open(browser, viewer.url)
    session = next(iter(viewer.sessions.values()))
    # the sliders' own number boxes (which read 0,5 as 5) are hidden
    assert _wait(lambda: page.locator(".mantine-NumberInput-root").first.is_hidden(), 30)
    coude = _joint_box(page, "coude")
    for typed, expected in (("0,5", 0.5), ("pi/4", np.pi / 4), ("30deg", np.radians(30)), ("-1,25", -1.25)):
        coude.fill("")
        coude.type(typed, delay=30)
        assert _wait(lambda want=expected: session.values["coude"] == pytest.approx(want, abs=1e-12), 30), \
            (typed, session.values)
    assert 'data-note' not in session.joint_note.content
    coude.fill("")
    coude.type("90", delay=30)  # coude's limits are -2 .. 2 rad: 90 rad means 90 degrees
    # SwiftShader draws on the CPU: on a busy machine the page may take seconds to show the note
    # (typed a key at a time: "9" gets its own note, "9deg", before "90" gets "90deg")
    assert _wait(lambda: "looks like degrees" in page.inner_text("body") and "90deg" in page.inner_text("body"),
                 30), session.joint_note.content
    assert session.values["coude"] == pytest.approx(-1.25)  # refused: the arm stays where it was
    page.get_by_text("Allow values past the limits", exact=True).click()
    coude.fill("")
    coude.type("2,5", delay=30)
    assert _wait(lambda: session.values["coude"] == pytest.approx(2.5), 30)  # asked for: past the limit
    page.close()


def test_the_banner_names_the_file_and_line_until_the_file_reads_again(browser, viewer, arm_file):
    page = _open(browser, viewer.url)
    banner = page.locator("[data-banner='count']")
    assert _wait(lambda: banner.count() == 1 and "finding" in banner.inner_text())
    text = arm_file.read_text()
    arm_file.write_text(text.replace("</robot>", "<link name=\n"))  # no longer XML
    error = page.locator("[data-banner='error']")
    assert _wait(lambda: error.count() == 1, 30)
    shown = error.inner_text()
    assert "bras.urdf" in shown and "line" in shown and "cannot be read" in shown, shown
    # at the top of the panel: above the Display folder
    assert error.bounding_box()["y"] < page.get_by_text("Display", exact=True).first.bounding_box()["y"]
    arm_file.write_text(text)
    assert _wait(lambda: error.count() == 0, 30)
    page.close()


def test_clicking_the_forearm_reads_its_pose_in_the_fixed_frame(browser, viewer):
    page = _open(browser, viewer.url)
    assert _wait(lambda: len(_orange(page)) > 200)
    _close_notices(page)
    session = next(iter(viewer.sessions.values()))
    row, column = _orange(page).mean(axis=0)
    page.mouse.click(float(column), float(row))
    assert _wait(lambda: session.selected == "avant_bras", 30)
    # by hand: the forearm's frame is 0.05 (base) + 0.6 (bras) above the base, not turned
    assert _wait(lambda: "[0.000, 0.000, 0.650]" in page.inner_text("body"))
    assert "tf2_echo base avant_bras" in page.inner_text("body")
    page.close()


def test_the_time_slider_shows_the_motion_at_the_chosen_time(browser, arm_file):
    from bras_kit.view import Source, Viewer

    with Viewer(Source(path=str(arm_file)), port=_free_port(), motion_specs=["coude=sin(t)"]) as viewer:
        page = _open(browser, viewer.url)
        session = next(iter(viewer.sessions.values()))
        scrubber = page.get_by_role("slider").nth(3)  # epaule, coude, speed, time
        scrubber.focus()
        page.keyboard.press("Home")
        for _ in range(150):  # steps of 0.01 s
            page.keyboard.press("ArrowRight")
        assert _wait(lambda: session.values["coude"] == pytest.approx(np.sin(1.5), abs=1e-9)), session.values
        assert not session.playing
        page.close()
