"""Watch mode: the current exercise on screen, checked again as soon as one of its files is
saved (modification times polled a few times a second: no watcher thread, nothing to install,
and an editor's save-by-rename is seen like any other), the next hint on a key, the next
exercise when it passes.

In a terminal the screen is redrawn in place and keys are read one by one; when the output is
piped the screens follow each other as plain text, printed only when something changed.
"""

from __future__ import annotations

import contextlib
import os
import select
import shutil
import sys
import time
from collections.abc import Iterator
from pathlib import Path
from typing import IO

from ..core.i18n import say
from ..core.message import M
from ..trust.inert import CLEAR_SCREEN, Shown, emit, join
from . import check_exercise, current_exercise, open_track, reveal_hint
from .checks import Outcome
from .manifest import Exercise, Track
from .progress import Progress, reload_if_changed
from .screen import Style, done_lines, exercise_lines, keys_line, list_lines, wants_colour

POLL_SECONDS = 0.2


def snapshot(folder: Path, exercise: Exercise) -> tuple[tuple[str, int, int], ...]:
    """(path, mtime_ns, size) of every file of the exercise's folder (a file being written
    changes one of them; a missing file is a state too)."""
    from ..trust.learner_files import walk

    out = []
    root = folder / exercise.id
    with contextlib.suppress(OSError):  # listed through the one reader: no link followed out of the track
        for place, dirs, files in walk(str(root), (str(folder),)):
            dirs[:] = sorted(d for d in dirs if not d.startswith(".") and d != "__pycache__")
            for name in sorted(files):
                path = os.path.join(place, name)
                with contextlib.suppress(OSError):
                    info = os.stat(path)
                    out.append((path, info.st_mtime_ns, info.st_size))
    return tuple(out)


@contextlib.contextmanager
def _keys(stream: IO[str]) -> Iterator[bool]:
    """Single keys from a terminal (cbreak mode, restored on the way out); False when not a terminal."""
    try:
        fd = stream.fileno()
        interactive = os.isatty(fd)
    except (AttributeError, OSError, ValueError):
        interactive = False
    if not interactive:
        yield False
        return
    import termios
    import tty

    saved = termios.tcgetattr(fd)
    try:
        tty.setcbreak(fd)
        yield True
    finally:
        termios.tcsetattr(fd, termios.TCSADRAIN, saved)


def _pause(seconds: float) -> str:
    time.sleep(seconds)
    return ""


def _read_key(stream: IO[str], timeout: float) -> str:
    ready, _, _ = select.select([stream], [], [], timeout)
    if not ready:
        return ""
    return os.read(stream.fileno(), 32).decode("utf-8", errors="replace")[:1].lower()


class Watcher:
    def __init__(self, folder: Path | None, lang: str, out: IO[str], keys: IO[str]) -> None:
        self.track: Track
        self.progress: Progress
        self.track, self.progress = open_track(folder)
        self.lang, self.out, self.keys = lang, out, keys
        self.tty = out.isatty()
        self.style = Style(wants_colour(out))
        self.exercise: Exercise | None = current_exercise(self.track, self.progress)
        self.outcome: Outcome | None = None
        self.seen: tuple[tuple[str, int, int], ...] = ()
        self.note = ""
        self.last_screen: list[Shown] = []

    def width(self) -> int:
        return shutil.get_terminal_size((80, 24)).columns if self.tty else 80

    def check(self) -> None:
        if self.exercise is None:
            return
        self.seen = snapshot(self.progress.folder, self.exercise)
        if self.outcome is not None:
            self.draw(checking=True)
        self.outcome = check_exercise(self.track, self.progress, self.exercise, self.lang)
        if self.outcome.state == "passed":
            passed = self.exercise
            self.exercise = current_exercise(self.track, self.progress)
            self.note = say(M("exercise {number} passed: {title}", number=passed.number,
                              title=passed.title_in(self.lang)), self.lang)
            self.outcome = None
            if self.exercise is not None:
                self.check()

    def noticed(self) -> None:
        """progress.json was changed by another process: its record is shown (the counter, the
        list), and the watch moves on when that process passed the exercise on screen."""
        following = current_exercise(self.track, self.progress)
        if following is not None and following != self.exercise:
            self.exercise, self.outcome, self.note = following, None, ""
            self.check()
        self.draw(force=True)

    def screen(self, checking: bool = False) -> list[Shown]:
        width = self.width()
        if self.exercise is None:
            return done_lines(self.track, self.lang, width, self.style)
        lines: list[Shown] = []
        if self.note:
            lines.append(self.style(self.note, "green"))
        lines += exercise_lines(self.track, self.progress, self.exercise, None if checking else self.outcome,
                                self.lang, width, self.style)
        return lines

    def draw(self, checking: bool = False, force: bool = False) -> None:
        lines = self.screen(checking)
        if self.tty:
            stamp = time.strftime("%H:%M:%S")
            footer = keys_line(self.lang, self.width())
            emit(self.out, CLEAR_SCREEN, join("\n", lines), "\n", self.style(footer, "dim"), "\n",
                 self.style(say(M("checked at {time}", time=stamp), self.lang), "dim"))
        elif lines != self.last_screen or force:
            if checking:
                return
            emit(self.out, join("\n", lines), "\n\n", end="")
        self.last_screen = lines
        self.out.flush()

    def show_list(self) -> None:
        emit(self.out, CLEAR_SCREEN if self.tty else "",
             join("\n", list_lines(self.track, self.progress, self.lang, self.width(), self.style)))
        self.out.write(say(M("press any key to go back"), self.lang) + "\n")
        self.out.flush()

    def loop(self, once: bool = False) -> int:
        self.check()
        self.draw()
        with _keys(self.keys) as interactive:
            listing = False
            size = shutil.get_terminal_size((80, 24))
            while self.exercise is not None or interactive:
                key = _read_key(self.keys, POLL_SECONDS) if interactive else _pause(POLL_SECONDS)
                if listing and key:
                    listing = False
                    self.draw()
                    continue
                if key == "q":
                    break
                if key == "l":
                    listing = True
                    self.show_list()
                    continue
                if key == "h" and self.exercise is not None:
                    fitting = self.outcome.hint if self.outcome is not None and self.outcome.state == "failed" else 0
                    reveal_hint(self.progress, self.exercise, fitting)
                    self.draw()
                    continue
                if reload_if_changed(self.progress):  # a check or a hint in another terminal
                    self.noticed()
                    continue
                if self.exercise is not None and (key == "c" or snapshot(self.progress.folder, self.exercise)
                                                  != self.seen):
                    self.note = ""
                    self.check()
                    self.draw()
                    continue
                if self.tty and shutil.get_terminal_size((80, 24)) != size and not listing:
                    size = shutil.get_terminal_size((80, 24))
                    self.draw()
                if once:
                    break
        return 0


def watch(folder: Path | None, lang: str, out: IO[str] | None = None, keys: IO[str] | None = None) -> int:
    watcher = Watcher(folder, lang, out or sys.stdout, keys or sys.stdin)
    try:
        return watcher.loop()
    except KeyboardInterrupt:
        watcher.out.write("\n" + say(M("stopped: your progress is saved in {path}",
                                       path=str(watcher.progress.folder / "progress.json")), lang) + "\n")
        return 0
