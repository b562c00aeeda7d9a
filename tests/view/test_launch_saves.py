"""On reload the last save wins (issue 55): saves 0, 50, 100 and 200 ms apart while bras-kit launch
runs, each save writing the URDF and the .rviz together; after each pair, the terminal's last
report and the page (Chromium) both show the second save's state, finding for finding.

Each state i names the robot's root link pied{i} and sets the .rviz Fixed Frame to monde{i},
which is no link: BK610 names both, so a build made of the URDF of one save and the .rviz of
another (the mix the issue saw, 8 tries in 13) says so. Oracles: the texts written to the files
(what the last save holds), RViz's Global Status words, and the terminal against the page."""

from __future__ import annotations

import re
import threading
import time

import pytest
from launch_pages import Launched, page_findings, reports, same_findings, terminal_findings
from pages import wait as _wait

pytestmark = pytest.mark.slow

DELAYS_MS = (0, 50, 100, 200)


class Watched(Launched):
    """bras-kit launch with its terminal read as it prints (each report as it comes)."""

    def __init__(self, *args) -> None:
        super().__init__(*args)
        self.lines: list[str] = []
        self.reader = threading.Thread(target=lambda: self.lines.extend(iter(self.process.stdout.readline, "")),
                                       daemon=True)
        self.reader.start()

    def out(self) -> str:
        return "".join(self.lines)

    def stop(self) -> tuple[str, str]:
        import signal

        self.page.close()
        self.process.send_signal(signal.SIGINT)
        self.process.wait(60)
        self.reader.join(10)
        return self.out(), self.errors.read_text()


def _save(package, i: int, urdf: str, rviz: str) -> None:
    """One save of state i: the URDF, then the .rviz (as an editor's "save all" or a checkout)."""
    (package / "urdf" / "bras.urdf").write_text(re.sub(r'"(base|pied\d+)"', f'"pied{i}"', urdf), encoding="utf-8")
    (package / "rviz" / "bras_description.rviz").write_text(
        re.sub(r"Fixed Frame: \S+", f"Fixed Frame: monde{i}", rviz), encoding="utf-8")


def _terminal_says(out: str, i: int) -> bool:
    last = reports(out)[-1] if reports(out) else ""
    return f"'monde{i}'" in last and f"pied{i}" in last


def _page_says(page, i: int) -> bool:
    status = page.locator("[data-rviz='global-status']")
    return status.count() == 1 and f"Frame [monde{i}] does not exist" in status.inner_text() and \
        any(f"'monde{i}'" in m and f"pied{i}" in m for code, _, _, m in page_findings(page) if code == "BK610")


def test_the_last_save_wins_in_the_page_and_the_terminal(browser, tmp_path):
    from bras_kit.scaffold.package import scaffold_package

    package = tmp_path / "bras_description"
    scaffold_package(package)
    urdf = (package / "urdf" / "bras.urdf").read_text(encoding="utf-8")
    rviz = (package / "rviz" / "bras_description.rviz").read_text(encoding="utf-8")
    launched = Watched(browser, tmp_path, package, ["affichage.launch.py"], "en")
    page = launched.page
    seen: list[str] = []
    try:
        assert _wait(lambda: bool(reports(launched.out())), 120), launched.out()
        for k, delay in enumerate(DELAYS_MS):
            first, second = 2 * k + 1, 2 * k + 2
            _save(package, first, urdf, rviz)
            time.sleep(delay / 1000)
            _save(package, second, urdf, rviz)
            settled = _wait(lambda i=second: _terminal_says(launched.out(), i) and _page_says(page, i), 90)
            time.sleep(2.0)  # a build still under way would print again: the last one must stay
            out = launched.out()
            last = reports(out)[-1]
            assert settled and _terminal_says(out, second) and _page_says(page, second), \
                (delay, last, page_findings(page), page.locator("[data-rviz='global-status']").inner_text())
            assert same_findings(page_findings(page), terminal_findings(last)), "\n".join(map(repr, page_findings(page) + terminal_findings(last))) or \
                (delay, page_findings(page), terminal_findings(last))
            assert page.locator("[data-banner='count']").inner_text().startswith(f"{len(terminal_findings(last))} ")
            seen.append(f"{delay} ms: {len(reports(out))} reports")
    finally:
        out, err = launched.stop()
    assert "Traceback" not in err, err
    assert "saved: the package is built and launched again" in err
