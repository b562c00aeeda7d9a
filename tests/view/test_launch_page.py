"""bras-kit launch's page and terminal tell one story (issue 43): both read one evaluation of the
package, and the page shows what RViz would show from it. In a real browser (Debian's chromium,
headless, SwiftShader WebGL, Playwright, as tests/view/test_launch_view.py).

Oracles: the pixels of the arm (its blue upper arm and orange forearm), the panel's text, and the
terminal's report, each finding's code printed by the terminal against those the page lists."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import time

import pytest
from launch_pages import (
    FINDING,
    Launched,
)
from launch_pages import (
    arm_pixels as _arm_pixels,
)
from launch_pages import (
    copy_tutorial as _copy_tutorial,
)
from launch_pages import (
    seen as _seen,
)
from launch_pages import (
    step_six as _step_six,
)
from launch_pages import (
    type_in as _type,
)
from launch_pages import (
    without_lines as _without_lines,
)
from pages import ended as _ended
from pages import free_port as _free_port
from pages import launch_url as _url
from pages import wait as _wait
from paths import TESTS

pytestmark = pytest.mark.slow

TUTORIAL = TESTS / "data" / "launch" / "tutorial" / "bras_description"
@pytest.mark.parametrize(("lang", "title", "reason"), [
    ("en", "RViz shows nothing", "Fixed Frame [monde] does not exist"),
    ("fr", "RViz n'affiche rien", "Fixed Frame [monde] n'existe pas"),
])
def test_a_fixed_frame_that_is_no_frame_draws_no_arm_and_the_page_says_why(browser, tmp_path, lang, title, reason):
    """RViz started with a configuration whose Fixed Frame is no frame of the robot draws nothing
    ("Frame [monde] does not exist"): the terminal says BK610, and the page draws no arm, says why,
    and lists the same findings; choosing a frame of the robot draws it, as in RViz."""
    from bras_kit.scaffold.package import scaffold_package

    package = tmp_path / "bras_description"
    scaffold_package(package)
    rviz = package / "rviz" / "bras_description.rviz"
    rviz.write_text(rviz.read_text(encoding="utf-8").replace("Fixed Frame: base", "Fixed Frame: monde"),
                    encoding="utf-8")
    launched = Launched(browser, tmp_path, package, ["affichage.launch.py"], lang)
    try:
        page = launched.page
        blank = page.locator("[data-banner='blank']")
        assert _wait(lambda: blank.count() == 1, 60), page.inner_text("body")
        assert title in blank.inner_text() and reason in blank.inner_text()
        codes = launched.page_codes()
        time.sleep(3.0)  # the scene has drawn its grid by now: no arm in it
        assert _arm_pixels(page) == 0
        page.screenshot(path=str(tmp_path / "fixed_frame_monde.png"))
        _type(page, "Fixed Frame", "base")  # RViz's Global Options field
        assert _wait(lambda: _arm_pixels(page) > 500, 60), \
            _seen(page, tmp_path, "choosing the base frame does not draw the arm")
        assert _wait(lambda: blank.count() == 0, 10)
    finally:
        out, err = launched.stop()
    assert "Traceback" not in err
    assert "BK610" in codes
    assert sorted(FINDING.findall(out)) == codes, out


def test_without_joint_state_publisher_the_page_has_no_sliders(browser, tmp_path):
    """No joint_state_publisher(_gui) in the launch file: no slider window in ROS, BK620 in the
    terminal; the page has no joint sliders either, says why, and lists the same findings. With
    step 6 done, RViz draws the base alone: nothing publishes /joint_states, so robot_state_publisher
    sends no transform for the moving links ("No transform from [bras] to [base]")."""
    package = _copy_tutorial(tmp_path)
    _without_lines(package / "launch" / "affichage.launch.py", "joint_state_publisher_gui")
    launched = Launched(browser, tmp_path, package, [], "en")
    try:
        page = launched.page
        assert _wait(lambda: "No joint_state_publisher(_gui) is started" in page.inner_text("body"), 60)
        assert page.get_by_text("coude =", exact=True).count() == 0  # the joints' boxes under their sliders
        assert page.get_by_role("button", name="Random pose").count() == 0 or \
            not page.get_by_role("button", name="Random pose").is_visible()
        _step_six(page)
        blank = page.locator("[data-banner='blank']")
        assert _wait(lambda: blank.count() == 1 and "No transform from [bras] to [base]" in blank.inner_text(), 30), \
            page.inner_text("body")
        time.sleep(3.0)
        assert _arm_pixels(page) == 0, _seen(page, tmp_path, "moving links drawn without /joint_states")
        codes = launched.page_codes()
    finally:
        out, err = launched.stop()
    assert "Traceback" not in err
    assert "BK620" in codes
    assert sorted(FINDING.findall(out)) == codes, out


# bras-kit launch with the learner's Ctrl-C at the instant the page is told the checks: what the
# page would list is kept, and what the terminal printed before it
CTRL_C_AS_THE_PAGE_SHOWS_THE_CHECKS = """
import json, sys
from bras_kit.view.viewer import Viewer
shown = []
def show_checks(self):
    shown.append(sorted(finding.code for _, finding in self.launch.findings()))
    raise KeyboardInterrupt
Viewer.show_checks = show_checks
from bras_kit.cli import main
code = main(sys.argv[1:])
sys.stdout.flush()
print("PAGE " + json.dumps(shown))
sys.exit(code)
"""


def test_the_terminal_has_said_the_findings_before_the_page_shows_them(tmp_path):
    """A Ctrl-C as the checks reach the page (the learner has seen them there) loses none of them in
    the terminal: each code the page is given was printed before it."""
    package = _copy_tutorial(tmp_path)
    _without_lines(package / "launch" / "affichage.launch.py", "joint_state_publisher_gui")
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    (tmp_path / "runtime").mkdir(mode=0o700)
    env["XDG_RUNTIME_DIR"] = str(tmp_path / "runtime")  # its own bus
    done = subprocess.run([sys.executable, "-c", CTRL_C_AS_THE_PAGE_SHOWS_THE_CHECKS, "launch", str(package),
                           "--port", str(_free_port()), "--duration", "1", "--lang", "en"],
                          capture_output=True, text=True, timeout=240, env=env)
    assert done.returncode == 0 and "Traceback" not in done.stderr, done.stderr
    out, _, page = done.stdout.rpartition("PAGE ")
    (codes,) = json.loads(page)
    assert "BK620" in codes
    assert sorted(FINDING.findall(out)) == codes, out


# bras-kit launch whose page is told the checks only once the file RELEASE exists: the page as it
# is while the package's checks still run
CHECKS_HELD = """
import os, sys, time
from bras_kit.view.viewer import Viewer
told = Viewer.show_checks
def show_checks(self):
    while not os.path.exists(os.environ["RELEASE"]):
        time.sleep(0.05)
    told(self)
Viewer.show_checks = show_checks
from bras_kit.cli import main
sys.exit(main(sys.argv[1:]))
"""


def test_while_the_checks_run_the_page_says_so_and_claims_no_finding(browser, tmp_path):
    """Before the terminal has the package's findings, the page says the package is being checked:
    neither "No finding" nor "0 findings"; then it lists what the terminal printed."""
    package = _copy_tutorial(tmp_path)
    _without_lines(package / "launch" / "affichage.launch.py", "joint_state_publisher_gui")
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    (tmp_path / "runtime").mkdir(mode=0o700)
    env.update(XDG_RUNTIME_DIR=str(tmp_path / "runtime"), RELEASE=str(tmp_path / "release"))
    errors = tmp_path / "stderr.txt"
    with open(errors, "w") as stderr:
        process = subprocess.Popen([sys.executable, "-c", CHECKS_HELD, "launch", str(package), "--port",
                                    str(_free_port()), "--duration", "1", "--lang", "en"],
                                   stdout=subprocess.PIPE, stderr=stderr, text=True, env=env)
    page = browser.new_page(viewport={"width": 1000, "height": 700})
    try:
        page.goto(_url(process, errors))
        page.wait_for_selector("[data-banner='count']", timeout=60_000)
        text = page.inner_text("body")
        assert "checking the package..." in text and "No finding" not in text and "0 findings" not in text, text
        (tmp_path / "release").touch()
        assert _wait(lambda: page.locator("[data-finding]").count() > 0, 120), page.inner_text("body")
        assert "checking the package..." not in page.inner_text("body")
        codes = sorted(page.locator("[data-finding]").evaluate_all("(all) => all.map(e => e.dataset.finding)"))
    finally:
        page.close()
        process.send_signal(signal.SIGINT)
        out, _ = _ended(process)
    assert "BK620" in codes and sorted(FINDING.findall(out)) == codes, out


def test_a_rebuild_shows_what_the_install_tree_now_holds(browser, tmp_path):
    """The urdf line removed from data_files while the launch runs: saved, built and launched
    again, ROS says "No such file" and BK601 in the terminal; the page no longer draws the old arm
    (ros2 launch stopped: nothing runs) and says why; the line put back, the arm is drawn again."""
    package = _copy_tutorial(tmp_path)
    launched = Launched(browser, tmp_path, package, [], "en")
    try:
        page = launched.page
        _step_six(page)  # RViz set up in the page: it stays so across the rebuilds
        assert _wait(lambda: _arm_pixels(page) > 500, 60), _seen(page, tmp_path, "the arm is not drawn")
        setup = package / "setup.py"
        before = _without_lines(setup, "'urdf'")
        assert _wait(lambda: "ros2 launch stopped" in page.inner_text("body"), 180), page.inner_text("body")
        assert _wait(lambda: _arm_pixels(page) == 0, 30), _seen(page, tmp_path, "the old arm stays on the page")
        assert _wait(lambda: "BK601" in launched.page_codes(), 120)
        setup.write_text(before, encoding="utf-8")
        assert _wait(lambda: _arm_pixels(page) > 500, 180), _seen(page, tmp_path, "the arm is not drawn again")
        assert "ros2 launch stopped" not in page.inner_text("body")
        # the arm can be drawn a moment before the panel drops the last build's findings: this
        # build's are in once BK601 is gone
        assert _wait(lambda: "BK601" not in launched.page_codes(), 120), page.inner_text("body")
        codes = launched.page_codes()
    finally:
        out, err = launched.stop()
    assert "No such file or directory" in err and "BK601" in out
    reports = re.split(r"(?m)^\d+ files? checked: .*$", out)  # each report ends with its summary line
    assert len(reports) >= 4, out  # the launch, the rebuild without the line, the one with it back
    assert "BK601" in FINDING.findall(reports[-3])
    assert sorted(FINDING.findall(reports[-2])) == codes, out  # the last report: the line put back
