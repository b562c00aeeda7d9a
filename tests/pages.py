"""What the browser-page tests share: Debian's chromium and its flags, a free port, waiting for a
condition, reading a child's output to its end, the page's pixels, bras-kit launch's address.

The ``browser`` fixture itself is in conftest.py (it needs the gate of system.py). Import these
as ``from pages import ...``; nothing here imports bras-kit, so the drivers that run in a
namespace of their own (live_view_driver.py) use them too.
"""

from __future__ import annotations

import socket
import subprocess
import sys
import threading
import time
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np

CHROMIUM = "/usr/bin/chromium"  # Debian's package chromium (system-packages.txt)
ARGS = ["--no-sandbox", "--disable-background-networking", "--disable-component-update", "--disable-sync",
        "--no-first-run", "--use-angle=swiftshader", "--enable-unsafe-swiftshader"]
SCENE = (slice(0, 700), slice(0, 590))  # the 3D view left of the panel (rows, columns)
NOTICE = (slice(0, 200), slice(0, 330))  # where viser shows its notice on SwiftShader (an orange bar: 660 pixels)


def free_port() -> int:
    """A TCP port of 127.0.0.1 nobody listens on (the system picks it)."""
    with socket.socket() as probe:
        probe.bind(("127.0.0.1", 0))
        return int(probe.getsockname()[1])


def wait(condition: Callable[[], Any], seconds: float = 30.0, every: float = 0.05) -> bool:
    """True as soon as ``condition()`` holds; past ``seconds``, its last answer."""
    end = time.monotonic() + seconds
    while time.monotonic() < end:
        if condition():
            return True
        time.sleep(every)
    return bool(condition())


def ended(process: subprocess.Popen, timeout: float = 60.0) -> tuple[str, str]:
    """``process.communicate(timeout=...)`` for a process some of whose output was already read
    line by line (the page's address). With a timeout, communicate reads the pipes' descriptors
    itself (CPython's ``Popen._communicate``) and drops what ``readline`` had read ahead into the
    text streams: a report printed with the address line was lost. Here each pipe is read to its
    end through its stream, in a thread of its own; past ``timeout`` the process is killed."""
    texts: list[list[str]] = [[], []]

    def read(stream, into: list[str]) -> None:
        for line in stream:
            into.append(line)

    readers = [threading.Thread(target=read, args=(stream, into), daemon=True)
               for stream, into in zip((process.stdout, process.stderr), texts) if stream is not None]
    for reader in readers:
        reader.start()
    try:
        process.wait(timeout)
    except subprocess.TimeoutExpired:
        process.kill()
        process.wait()
        raise
    finally:
        for reader in readers:
            reader.join(10)
    return "".join(texts[0]), "".join(texts[1])


def screenshot(page) -> np.ndarray:
    """The page as RGB integers (rows, columns, 3)."""
    from io import BytesIO

    from PIL import Image

    return np.asarray(Image.open(BytesIO(page.screenshot(timeout=120_000))).convert("RGB")).astype(int)


def orange(page, scene: tuple[slice, slice] = SCENE, notice: tuple[slice, slice] | None = NOTICE) -> np.ndarray:
    """Pixels of the forearm's orange (0.95 0.5 0.1), shaded: (row, column) of each, in ``scene``.
    The orange bar of viser's "Software WebGL" notice (``notice``) is not the forearm."""
    image = screenshot(page)[scene]
    r, g, b = image[..., 0], image[..., 1], image[..., 2]
    mask = (r > 120) & (r - b > 100) & (g > 0.35 * r) & (g < 0.7 * r)
    if notice is not None:
        mask[notice] = False
    return np.argwhere(mask)


def robot_box(image: np.ndarray) -> tuple[int, int, int, int]:
    """Rows and columns (top, bottom, left, right) of the arm's coloured pixels: the blue upper
    arm and the orange forearm (the white background, grey grid and dark names are not coloured);
    the view's orientation triad in the lower left corner is left out."""
    r, g, b = image[..., 0], image[..., 1], image[..., 2]
    blue = (b > 120) & (b - r > 70) & (b - g > 40)
    forearm = (r > 120) & (r - b > 100) & (g > 0.35 * r) & (g < 0.7 * r)
    mask = blue | forearm
    mask[-70:, :70] = False
    rows, columns = np.nonzero(mask)
    assert len(rows) > 300, "no arm drawn"
    return int(rows.min()), int(rows.max()), int(columns.min()), int(columns.max())


def open_page(browser, url: str, requests: list[str] | None = None):
    """A 1000x700 page at ``url``, once the panel shows the coude; ``requests`` collects the URLs it asks for."""
    page = browser.new_page(viewport={"width": 1000, "height": 700})
    if requests is not None:
        page.on("request", lambda request: requests.append(request.url))
    page.goto(url)
    page.wait_for_selector("text=coude", timeout=60_000)
    return page


def close_notices(page) -> None:
    """Chromium on SwiftShader makes viser show a "Software WebGL" notice over the scene: closed."""
    wait(lambda: page.get_by_text("Software WebGL").count() > 0, 3)
    for button in page.locator(".mantine-Notification-root button").all():
        button.click()
    assert wait(lambda: page.get_by_text("Software WebGL").count() == 0, 30)


def viser_client_words() -> set[str]:
    """viser's own English words, read from its client's source (the oracle: not bras-kit's list):
    the literal labels, tooltips, titles and placeholders of its components, and its notices."""
    import re

    import viser

    source = Path(viser.__file__).parent / "client" / "src"
    attribute = re.compile(r"""(?:label|tooltip|title|aria-label|placeholder|toggleLabel|toggleTooltip)=\{?\s*"""
                           r"""(?:[^"'{}]*\?\s*)?["']([^"'{}]+)["'](?:\s*:\s*["']([^"'{}]+)["'])?""")
    notice = re.compile(r"""title:\s*"([^"]+)",\s*message:\s*((?:"[^"]*"\s*\+?\s*)+)""")
    words: set[str] = set()
    for path in source.rglob("*.tsx"):
        text = path.read_text(encoding="utf-8")
        for match in attribute.finditer(text):
            words.update(word for word in match.groups() if word)
        for match in notice.finditer(text):
            words.add(match.group(1))
            words.add("".join(re.findall(r'"([^"]*)"', match.group(2))))
    return words


def launch(arguments: list[str], env: dict[str, str], errors: Path) -> subprocess.Popen:
    """bras-kit launch started as a learner starts it; what it says on stderr goes to ``errors``."""
    with open(errors, "w") as stderr:
        return subprocess.Popen([sys.executable, "-m", "bras_kit", "launch", *arguments],
                                stdout=subprocess.PIPE, stderr=stderr, text=True, env=env)


def launch_url(process: subprocess.Popen, errors: Path | None = None, seconds: float = 180) -> str:
    """The address bras-kit launch prints; if it ends or stays silent, what it said is in the failure
    (its stderr from ``errors``, or from its pipe when ``errors`` is None)."""
    end = time.monotonic() + seconds
    said = []
    while time.monotonic() < end:
        line = process.stdout.readline()  # type: ignore[union-attr]
        if "http://" in line:
            return "http://" + line.split("http://", 1)[1].split()[0]
        if not line and process.poll() is not None:
            break
        said.append(line)
    raise AssertionError(f"bras-kit launch printed no address (exit code {process.poll()}); "
                         f"stdout: {''.join(said)!r}; "
                         f"stderr: {errors.read_text() if errors else process.stderr.read()!r}")  # type: ignore[union-attr]
