"""The launch page is RViz as the launch file starts it (issue 55), in a real browser (Debian's
chromium, headless, SwiftShader WebGL, Playwright): the tutorial's launch (rviz2 without -d) opens
an empty RViz, the learner does step 6 by clicks, Save Config writes a .rviz RViz reads.

Oracles: RViz's own words (Global Status "Frame [map] does not exist", "Error subscribing: Empty
topic name"), the pixels of the arm (its blue upper arm and orange forearm), RViz's default
configuration (tests/data/rviz/rviz_common_default.rviz) for the saved file's shape, and the
terminal's findings, code for code against the page's."""

from __future__ import annotations

import os
import time

import pytest
import yaml
from launch_pages import FINDING, Launched, page_findings, reports, same_findings, terminal_findings
from launch_pages import add as _add
from launch_pages import arm_pixels as _arm_pixels
from launch_pages import copy_tutorial as _copy_tutorial
from launch_pages import field as _field
from launch_pages import seen as _seen
from launch_pages import type_in as _type
from pages import wait as _wait
from paths import TESTS

from bras_kit.ros.rviz.config import GRID, ROBOT_MODEL, TF, read_config

pytestmark = pytest.mark.slow

DEFAULT = TESTS / "data" / "rviz" / "rviz_common_default.rviz"


def _global_status(page) -> str:
    return page.locator("[data-rviz='global-status']").inner_text()


def _display_texts(page) -> list[str]:
    return page.locator("[data-rviz-display]").evaluate_all("(all) => all.map(e => e.innerText)")


def _forearm_pixels(page) -> int:
    """The orange forearm's pixels alone: the TF display's axes are blue, red and green, never orange."""
    from launch_pages import NOTICE, SCENE
    from pages import screenshot as _screenshot

    image = _screenshot(page)[SCENE]
    r, g, b = image[..., 0], image[..., 1], image[..., 2]
    # the forearm's orange has little blue; the red x axes' smoothed edges (236, 128, 132) have much
    orange = (r > 120) & (r - b > 100) & (g > 0.35 * r) & (g < 0.7 * r) & (b < 0.4 * r)
    orange[NOTICE] = False
    return int(orange.sum())


def _blank(page) -> str:
    blank = page.locator("[data-banner='blank']")
    return blank.inner_text() if blank.count() else ""


@pytest.mark.parametrize(("lang", "title", "reason"), [
    ("en", "RViz shows nothing", "Fixed Frame [map] does not exist"),
    ("fr", "RViz n'affiche rien", "Fixed Frame [map] n'existe pas"),
])
def test_the_tutorials_launch_opens_an_empty_rviz(browser, tmp_path, lang, title, reason):
    """rviz2 without -d: Fixed Frame map, one Grid, Global Status "Frame [map] does not exist", no
    arm; the terminal's BK613 says the same, and the page lists the terminal's findings."""
    launched = Launched(browser, tmp_path, _copy_tutorial(tmp_path), [], lang)
    try:
        page = launched.page
        assert _wait(lambda: "Frame [map] does not exist" in _global_status(page), 60), page.inner_text("body")
        assert _field(page, "Fixed Frame").input_value() == "map"
        assert page.locator("[data-rviz-display]").evaluate_all("(a) => a.map(e => e.dataset.rvizDisplay)") == ["Grid"]
        assert _wait(lambda: title in _blank(page) and reason in _blank(page), 30), _blank(page)
        for label in ("Fixed Frame", "Add"):  # the tutorial's words, in every language
            assert page.get_by_text(label, exact=True).count() >= 1
        codes = launched.page_codes()
        rows = page_findings(page)
        order = page.locator("[data-finding]").evaluate_all("(all) => all.map(e => e.dataset.finding)")
        hints = page.locator("[data-hint]").evaluate_all("(all) => all.map(e => e.innerText)")
        time.sleep(3.0)  # the grid is drawn by now: no arm in it
        assert _arm_pixels(page) == 0, _seen(page, tmp_path, "an arm is drawn in an empty RViz")
    finally:
        out, err = launched.stop()
    assert "Traceback" not in err
    assert "BK613" in codes
    assert sorted(FINDING.findall(out)) == codes, out
    assert order[0] == "BK613"  # all infos here: the one about what RViz shows comes first
    if lang == "en":  # finding for finding (the severity's word is the terminal's language's)
        assert same_findings(rows, terminal_findings(reports(out)[-1])), (rows, out)
    if lang == "en":  # each finding's fix, as the terminal gives it
        said = [line.split("hint: ", 1)[1].strip() for line in out.splitlines() if line.startswith("  hint: ")]
        assert sorted(h.lstrip("\u2192 ").strip() for h in hints) == sorted(said), (hints, said)


def test_step_six_by_clicks_then_save_config_reads_back(browser, tmp_path):
    """Fixed Frame base, Add RobotModel, its Description Topic, Add TF: the arm appears only at the
    step RViz would draw it. Save Config writes rviz/bras_description.rviz in RViz's shape, which
    reads back as the page's configuration; a second save asks before replacing it."""
    package = _copy_tutorial(tmp_path)
    launched = Launched(browser, tmp_path, package, [], "en")
    saved = package / "rviz" / "bras_description.rviz"
    try:
        page = launched.page
        assert _wait(lambda: "does not exist" in _global_status(page), 60)
        _type(page, "Fixed Frame", "base")
        assert _wait(lambda: "Fixed Frame: OK" in _global_status(page), 20), _global_status(page)
        assert _wait(lambda: "No RobotModel display" in _blank(page), 20), _blank(page)
        _add(page, "RobotModel")
        assert _wait(lambda: "Error subscribing: Empty topic name" in " ".join(_display_texts(page)), 20)
        time.sleep(2.0)
        assert _arm_pixels(page) == 0, _seen(page, tmp_path, "the arm is drawn with an empty Description Topic")
        _type(page, "Description Topic", "/robot_description")
        assert _wait(lambda: _arm_pixels(page) > 500, 60), _seen(page, tmp_path, "step 6 does not draw the arm")
        assert _wait(lambda: _blank(page) == "", 10), _blank(page)
        assert "URDF parsed OK" in " ".join(_display_texts(page))
        _add(page, "TF")
        assert _wait(lambda: "avant_bras: Transform OK" in _display_texts(page)[-1], 20), _display_texts(page)
        page.get_by_role("button", name="Save Config", exact=True).click()
        assert _wait(lambda: saved.exists(), 20)
        assert _wait(lambda: page.locator("[data-rviz='saved'][data-state='saved']").count() == 1, 20)
        first = saved.read_bytes()
        page.get_by_role("button", name="Save Config", exact=True).click()  # again: it asks
        assert _wait(lambda: page.locator("[data-rviz='saved'][data-state='exists']").count() == 1, 20)
        assert saved.read_bytes() == first
        page.get_by_role("button", name="Remove").nth(1).click()  # the RobotModel: no arm any more
        # the forearm drawn is thousands of pixels (2,385 at step 6); a few are where axes cross
        assert _wait(lambda: _forearm_pixels(page) < 30, 30), \
            _seen(page, tmp_path, "the arm stays without its RobotModel")
        assert _wait(lambda: "No RobotModel display" in _blank(page), 20)
        page.get_by_role("button", name="Overwrite", exact=True).click()  # replaced, as asked
        assert _wait(lambda: saved.read_bytes() != first, 20)
        codes = launched.page_codes()
        rows = page_findings(page)
    finally:
        out, err = launched.stop()
    assert "Traceback" not in err
    assert sorted(FINDING.findall(out)) == codes, out
    assert same_findings(rows, terminal_findings(reports(out)[-1])), (rows, out)
    assert "built and launched again" not in err  # Save Config's own file is no learner's save
    assert "(os.path.join('share', package_name, 'rviz'), glob('rviz/*.rviz'))," in err
    assert "arguments=['-d', os.path.join(get_package_share_directory('bras_description'), 'rviz', " \
           "'bras_description.rviz')]," in err
    back = read_config(first.decode("utf-8"))
    assert back.fixed_frame == "base"
    assert [(d.kind, d.enabled) for d in back.displays] == [(GRID, True), (ROBOT_MODEL, True), (TF, True)]
    assert back.displays[1].description_topic == "/robot_description"
    ours, theirs = (yaml.load(t, Loader=yaml.BaseLoader) for t in (first.decode(), DEFAULT.read_text()))
    assert set(ours) == set(theirs)
    assert set(theirs["Visualization Manager"]) <= set(ours["Visualization Manager"])
    assert [d.kind for d in read_config(saved.read_text()).displays] == [GRID, TF]  # Overwrite: after Remove


def test_a_wrong_fixed_frame_then_set_right_in_the_page(browser, tmp_path):
    """A configuration whose Fixed Frame is no frame (monde): RViz's Global Status, the terminal's
    BK610, no arm; the learner types base in Fixed Frame and the arm is drawn."""
    from bras_kit.scaffold.package import scaffold_package

    package = tmp_path / "bras_description"
    scaffold_package(package)
    rviz = package / "rviz" / "bras_description.rviz"
    rviz.write_text(rviz.read_text(encoding="utf-8").replace("Fixed Frame: base", "Fixed Frame: monde"),
                    encoding="utf-8")
    launched = Launched(browser, tmp_path, package, ["affichage.launch.py"], "en")
    try:
        page = launched.page
        assert _wait(lambda: "Frame [monde] does not exist" in _global_status(page), 60), page.inner_text("body")
        assert _field(page, "Fixed Frame").input_value() == "monde"
        assert "No transform from [avant_bras] to [monde]" in " ".join(_display_texts(page))
        codes = launched.page_codes()
        rows = page_findings(page)
        time.sleep(3.0)
        assert _arm_pixels(page) == 0
        _type(page, "Fixed Frame", "base")
        assert _wait(lambda: _arm_pixels(page) > 500, 60), _seen(page, tmp_path, "Fixed Frame base draws no arm")
        assert "Fixed Frame: OK" in _global_status(page)
        assert _wait(lambda: _blank(page) == "", 10)
    finally:
        out, err = launched.stop()
    assert "Traceback" not in err
    assert "BK610" in codes
    assert sorted(FINDING.findall(out)) == codes, out
    assert same_findings(rows, terminal_findings(reports(out)[-1])), (rows, out)


def test_step_seven_the_learners_node_beside_the_launch_lifts_bk620(browser, tmp_path):
    """Step 7: the slider window removed from the launch file, BK620 (nothing publishes
    /joint_states) in the terminal and the page; 'bras-kit run PKG animation' beside it moves the
    arm: the page no longer lists BK620 and the terminal says why; the node stopped, BK620 is back
    in both. Oracle: the terminal's report, finding for finding, and the forearm's pixels moving."""
    import subprocess
    import sys

    import numpy as np
    from launch_pages import page_findings, reports, step_six, terminal_findings, without_lines
    from pages import orange

    package = _copy_tutorial(tmp_path)
    without_lines(package / "launch" / "affichage.launch.py", "joint_state_publisher_gui")
    launched = Launched(browser, tmp_path, package, [], "en")
    node = None
    try:
        page = launched.page
        step_six(page)
        assert _wait(lambda: "BK620" in launched.page_codes(), 60)
        before = page_findings(page)
        env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
        env["XDG_RUNTIME_DIR"] = str(tmp_path / "runtime")  # the launch's bus
        node = subprocess.Popen([sys.executable, "-m", "bras_kit", "run", str(package), "animation", "--quiet"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        assert _wait(lambda: "BK620" not in launched.page_codes(), 60), page.inner_text("body")
        assert _wait(lambda: _arm_pixels(page) > 500, 30), _seen(page, tmp_path, "the node's arm is not drawn")
        first = orange(page).mean(axis=0)
        moving = []
        assert _wait(lambda: moving.append(np.abs(orange(page).mean(axis=0) - first).max()) or moving[-1] > 5, 30), \
            moving
        lifted = page_findings(page)
        assert lifted == [f for f in before if f[0] != "BK620"]
        assert "BK620 does not hold while it runs" in launched.errors.read_text()
        node.terminate()
        node.wait(30)
        assert _wait(lambda: "BK620" in launched.page_codes(), 30), page.inner_text("body")
        back = page_findings(page)
    finally:
        if node is not None and node.poll() is None:
            node.kill()
        out, err = launched.stop()
    assert "Traceback" not in err
    assert "BK620 holds again" in err
    last = terminal_findings(reports(out)[-1])
    assert [f[0] for f in back] == [f[0] for f in last] and back == before
    assert "BK620" in [f[0] for f in last]


def test_a_launch_without_rviz2_shows_no_viewer_and_says_how_to_start_rviz(browser, tmp_path):
    """No rviz2 in the launch file: no RViz window opens in ROS, so the page draws no arm and no
    grid, says RViz is not started and how to start it; the terminal's BK615 says the same, and
    the page lists the terminal's findings, finding for finding."""
    from launch_pages import page_findings, reports, same_findings, terminal_findings, without_lines

    package = _copy_tutorial(tmp_path)
    without_lines(package / "launch" / "affichage.launch.py", "package='rviz2'")
    launched = Launched(browser, tmp_path, package, [], "en")
    try:
        page = launched.page
        assert _wait(lambda: "RViz is not started" in _blank(page), 60), page.inner_text("body")
        assert "ros2 run rviz2 rviz2" in _blank(page)
        assert page.locator("[data-rviz='global-status']").count() == 0  # no RViz panel either
        launched.page_codes()
        rows = page_findings(page)
        time.sleep(3.0)
        assert _arm_pixels(page) == 0, _seen(page, tmp_path, "the arm is drawn although no RViz is started")
    finally:
        out, err = launched.stop()
    assert "Traceback" not in err
    last = terminal_findings(reports(out)[-1])
    assert "BK615" in [f[0] for f in last]
    assert same_findings(rows, last), (rows, last)


def _robot_model_removed(text: str) -> str:
    start = text.index("    - Alpha: 1\n      Class: rviz_default_plugins/RobotModel")
    return text[:start] + text[text.index("    - Class: rviz_default_plugins/TF", start):]


def _tf_removed(text: str) -> str:
    start = text.index("    - Class: rviz_default_plugins/TF")
    return text[:start] + text[text.index("\n  Enabled: true\n", start) + 1:]  # Visualization Manager's own


# each display of the scaffolded .rviz missing or set wrong: (the change, whether RViz draws the arm,
# the finding the terminal gives, RViz's own words the page shows)
DISPLAYS = {
    "no_robot_model": (_robot_model_removed, False, "BK611", "No RobotModel display"),
    "robot_model_unchecked": (lambda t: t.replace("      Enabled: true\n      Links:", "      Enabled: false\n      Links:"),
                              False, "BK611", "unchecked"),
    "topic_misspelt": (lambda t: t.replace("Value: /robot_description", "Value: /robot_descripton"), False, "BK611",
                       "Nothing publishes /robot_descripton"),
    "no_tf": (_tf_removed, True, "BK612", None),
}


@pytest.mark.parametrize("case", list(DISPLAYS))
def test_each_display_missing_or_wrong_as_rviz_shows_it(browser, tmp_path, case):
    """A .rviz whose RobotModel is missing, unchecked or reads the wrong topic, or has no TF: the
    page draws the arm exactly when RViz would, says why where it does not, and lists the
    terminal's findings, finding for finding (BK611, BK612 among them)."""
    from launch_pages import page_findings, reports, same_findings, terminal_findings

    from bras_kit.scaffold.package import scaffold_package

    change, drawn, code, words = DISPLAYS[case]
    package = tmp_path / "bras_description"
    scaffold_package(package)
    rviz = package / "rviz" / "bras_description.rviz"
    text = rviz.read_text(encoding="utf-8")
    changed = change(text)
    assert changed != text and read_config(changed).displays != read_config(text).displays
    rviz.write_text(changed, encoding="utf-8")
    launched = Launched(browser, tmp_path, package, ["affichage.launch.py"], "en")
    try:
        page = launched.page
        assert _wait(lambda: page.locator("[data-rviz='global-status']").count() == 1, 60), page.inner_text("body")
        launched.page_codes()
        rows = page_findings(page)
        if drawn:
            assert _wait(lambda: _arm_pixels(page) > 500, 60), _seen(page, tmp_path, "RViz would draw the arm")
        else:
            assert _wait(lambda: words in _blank(page), 30), _blank(page)
            time.sleep(3.0)
            # the TF display's axes stay (blue z axes among them): the orange forearm is the arm's
            assert _forearm_pixels(page) < 30, _seen(page, tmp_path, "an arm RViz would not draw")
    finally:
        out, err = launched.stop()
    assert "Traceback" not in err
    last = terminal_findings(reports(out)[-1])
    assert code in [f[0] for f in last]
    assert same_findings(rows, last), (rows, last)


def test_a_joint_the_node_never_sends_leaves_its_link_undrawn_as_in_rviz(browser, tmp_path):
    """The learner's node alone (no slider window) sends 'coud' for 'coude': robot_state_publisher
    publishes no transform for the elbow (it publishes the joints a message names and the URDF
    knows), so RViz draws the upper arm moving and no forearm, and its RobotModel says "No
    transform from [avant_bras] to [base]". The page draws what RViz draws. Oracles: the pixels of
    the forearm (orange) and of the arm, and RViz's words in the RobotModel's status."""
    import subprocess
    import sys

    from launch_pages import step_six, without_lines

    package = _copy_tutorial(tmp_path)
    without_lines(package / "launch" / "affichage.launch.py", "joint_state_publisher_gui")
    node_file = package / "bras_description" / "animation.py"
    node_file.write_text(node_file.read_text().replace("'coude'", "'coud'"))
    launched = Launched(browser, tmp_path, package, [], "en")
    node = None
    try:
        page = launched.page
        step_six(page)
        env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
        env["XDG_RUNTIME_DIR"] = str(tmp_path / "runtime")  # the launch's bus
        node = subprocess.Popen([sys.executable, "-m", "bras_kit", "run", str(package), "animation", "--quiet"],
                                stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL, env=env)
        assert _wait(lambda: "BK620" not in launched.page_codes(), 60), page.inner_text("body")
        assert _wait(lambda: _arm_pixels(page) > 300, 30), _seen(page, tmp_path, "the upper arm is not drawn")
        assert _wait(lambda: "No transform from [avant_bras] to [base]" in " ".join(_display_texts(page)), 30), \
            _display_texts(page)
        time.sleep(1.0)
        assert _forearm_pixels(page) < 50, _seen(page, tmp_path, "the forearm is drawn, RViz would not")
    finally:
        if node is not None and node.poll() is None:
            node.kill()
        launched.stop()
