"""The launch page's own helpers (bras-kit launch running, its page in Chromium, the panel's
fields, RViz's Add, the tutorial's step 6), shared by the launch-page tests."""

from __future__ import annotations

import os
import re
import shutil
import signal
from pathlib import Path

from pages import ended as _ended
from pages import free_port as _free_port
from pages import launch as _launch
from pages import launch_url as _url
from pages import screenshot as _screenshot
from pages import wait as _wait

TUTORIAL = Path(__file__).parent / "data" / "launch" / "tutorial" / "bras_description"
SCENE = (slice(0, 640), slice(0, 590))  # the 3D view left of the panel, above the orientation triad
NOTICE = (slice(0, 200), slice(0, 330))  # viser's "Software WebGL" notice (an orange bar) over the scene
FINDING = re.compile(r"(?m)^\S+?:(?:\d+:)? (BK\d{3}) ")  # a finding as the terminal prints it


def arm_pixels(page) -> int:
    """How many pixels of the arm's blue upper arm and orange forearm the scene shows."""
    image = _screenshot(page)[SCENE]
    r, g, b = image[..., 0], image[..., 1], image[..., 2]
    blue = (b > 120) & (b - r > 70) & (b - g > 40)
    orange = (r > 120) & (r - b > 100) & (g > 0.35 * r) & (g < 0.7 * r)
    arm = blue | orange
    arm[NOTICE] = False
    return int(arm.sum())


def seen(page, tmp_path: Path, what: str) -> str:
    """A failed wait explained: ``what``, the arm's pixel count, the panel's text, and the page's
    screenshot saved in the test's folder (a failure in CI then says what the page showed)."""
    shot = tmp_path / "page.png"
    try:
        page.screenshot(path=str(shot))
        text = page.inner_text("body")
    except Exception as exc:  # noqa: BLE001 - the browser itself in trouble is the explanation
        return f"{what}; the page cannot be read: {exc}"
    return f"{what}; {arm_pixels(page)} arm pixels, screenshot {shot}; the page says:\n{text[:2000]}"


class Launched:
    """bras-kit launch running on ``package``, its page open in the browser."""

    def __init__(self, browser, tmp_path: Path, package: Path, items: list[str], lang: str) -> None:
        env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
        env["BRAS_KIT_LANG"] = lang
        runtime = tmp_path / "runtime"
        runtime.mkdir(mode=0o700)
        env["XDG_RUNTIME_DIR"] = str(runtime)  # its own bus: no other test's run joins it
        self.errors = tmp_path / "stderr.txt"
        self.process = _launch([str(package), *items, "--port", str(_free_port()), "--duration", "2"], env,
                               self.errors)
        self.page = browser.new_page(viewport={"width": 1000, "height": 700})
        self.page.goto(_url(self.process, self.errors))
        self.page.wait_for_selector("[data-banner='count']", timeout=60_000)

    def page_codes(self) -> list[str]:
        """The codes the page's Checks list, once the checks are in."""
        assert _wait(lambda: self.page.locator("[data-finding]").count() > 0 or
                     "No finding" in self.page.inner_text("body"), 120), self.page.inner_text("body")
        return sorted(self.page.locator("[data-finding]").evaluate_all("(all) => all.map(e => e.dataset.finding)"))

    def stop(self) -> tuple[str, str]:
        """Ctrl-C; what it printed on its terminal (stdout, stderr)."""
        self.page.close()
        self.process.send_signal(signal.SIGINT)
        out, _ = _ended(self.process)
        return out, self.errors.read_text()


def field(page, label: str):
    """The input of the panel's row labelled ``label`` (viser's labels name no input by id)."""
    return page.locator(f"xpath=//label[normalize-space()='{label}']/ancestor::div[.//input[not(@type='hidden')]][1]"
                        "//input[not(@type='hidden')]").first


def type_in(page, label: str, value: str) -> None:
    box = field(page, label)
    box.fill(value)
    box.press("Enter")


def add(page, kind: str) -> None:
    """RViz's Add: the display's class chosen, then the button."""
    before = page.locator("[data-rviz-display]").count()
    field(page, "Add").click()
    page.get_by_role("option", name=kind, exact=True).click()
    page.get_by_role("button", name="Add", exact=True).click()
    assert _wait(lambda: page.locator("[data-rviz-display]").count() == before + 1, 20)


def step_six(page) -> None:
    """The tutorial's step 6 in the page's RViz: Fixed Frame base, Add RobotModel, its Description Topic."""
    assert _wait(lambda: page.locator("[data-rviz='global-status']").count() == 1, 60), page.inner_text("body")
    type_in(page, "Fixed Frame", "base")
    add(page, "RobotModel")
    type_in(page, "Description Topic", "/robot_description")


def copy_tutorial(tmp_path: Path) -> Path:
    package = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL, package)
    return package


def without_lines(path: Path, word: str) -> str:
    """``path`` rewritten without its lines holding ``word``; returns the text it had."""
    text = path.read_text(encoding="utf-8")
    kept = [line for line in text.splitlines() if word not in line]
    assert len(kept) < len(text.splitlines()), f"no line of {path.name} holds {word}"
    path.write_text("\n".join(kept) + "\n", encoding="utf-8")
    return text


TERMINAL_FINDING = re.compile(r"^(?P<place>\S+?):(?:(?P<line>\d+):)? (?P<code>BK\d{3}) (?P<severity>\w+) (?P<message>.*)$")


def reports(out: str) -> list[str]:
    """The terminal's reports, each ending with its summary line ("N files checked: ...")."""
    parts = re.split(r"(?m)^\d+ files? checked: .*$", out)
    return parts[:-1]


def terminal_findings(report: str) -> list[tuple[str, str, str, str]]:
    """(code, severity, place, message) of each finding a terminal report prints."""
    out = []
    for line in report.splitlines():
        found = TERMINAL_FINDING.match(line)
        if found:
            place = found["place"] + (f":{found['line']}" if found["line"] else "")
            out.append((found["code"], found["severity"], place, found["message"].strip()))
    return sorted(out)


def page_findings(page) -> list[tuple[str, str, str, str]]:
    """(code, severity, place, message) of each finding the page's Checks list."""
    rows = page.locator("[data-finding]").evaluate_all(
        "(all) => all.map(e => [e.dataset.finding, e.dataset.severity, e.dataset.place,"
        " e.querySelector('[data-message]').innerText])")
    return sorted((code, severity, place, message.strip()) for code, severity, place, message in rows)


def same_findings(page_rows, terminal_rows) -> bool:
    """Finding for finding: the same code, severity and message, at the same place (the terminal
    names the file from where it was run, the page from the package folder)."""
    if len(page_rows) != len(terminal_rows):
        return False
    for (code, severity, place, message), (t_code, t_severity, t_place, t_message) in zip(
            sorted(page_rows, key=lambda r: (r[0], r[3])), sorted(terminal_rows, key=lambda r: (r[0], r[3]))):
        if (code, severity, message) != (t_code, t_severity, t_message):
            return False
        if not (t_place == place or t_place.endswith("/" + place) or (not place and ":" not in t_place)):
            return False
    return True
