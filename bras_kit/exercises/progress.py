"""Progress, kept beside the exercises in the learner's folder (``progress.json``): which set,
the current exercise, and for each exercise whether it passed, when, how many checks and hints
it took. Plain JSON a teacher can read, and ``bras-kit grade`` counts.

::

    {"format": 1, "set": "builtin", "lang": "fr", "current": "03-elbow-origin",
     "exercises": {"01-links": {"passed": true, "passed_at": "2026-11-26T16:40:02Z",
                                "checks": 4, "hints": 1}}}
"""

from __future__ import annotations

import contextlib
import errno
import fcntl
import json
import os
import time
from collections.abc import Callable, Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..core.errors import BrasKitError
from ..core.i18n import LANGUAGES
from ..core.message import M

PROGRESS_FILE = "progress.json"
LOCK_FILE = ".progress.json.lock"
FORMAT = 1
MAX_PROGRESS_BYTES = 1 << 20
MAX_COUNT = 10**9  # checks and hints of one exercise
MAX_DIGITS = 12  # a number in progress.json longer than this is not one bras-kit wrote


@dataclass
class Progress:
    folder: Path
    set: str
    current: str
    exercises: dict[str, dict[str, Any]] = field(default_factory=dict)
    lang: str = ""  # the language the track was laid out in ("" in a track made before it was kept)
    stamp: tuple[int, int, int] = (0, 0, 0)  # (inode, mtime_ns, size) of the file this was read from or written to

    def entry(self, exercise_id: str) -> dict[str, Any]:
        return self.exercises.setdefault(exercise_id, {"passed": False, "checks": 0, "hints": 0})

    def passed(self, exercise_id: str) -> bool:
        return bool(self.exercises.get(exercise_id, {}).get("passed"))

    def hints_seen(self, exercise_id: str) -> int:
        return int(self.exercises.get(exercise_id, {}).get("hints", 0))

    def as_dict(self) -> dict[str, Any]:
        kept = {"lang": self.lang} if self.lang else {}
        return {"format": FORMAT, "set": self.set, **kept, "current": self.current, "exercises": self.exercises}


def progress_path(folder: str | os.PathLike[str]) -> Path:
    return Path(folder) / PROGRESS_FILE


def find_track_folder(start: str | os.PathLike[str]) -> Path | None:
    """The folder holding ``progress.json``: ``start`` or one of its parents."""
    here = Path(start).resolve()
    for folder in (here, *here.parents):
        if os.path.lexists(folder / PROGRESS_FILE):
            return folder
    return None


_REFUSED = {
    "link_out": M("progress.json is a symbolic link that leads out of the track: bras-kit neither reads nor "
                  "writes through it"),
    "outside": M("progress.json is a symbolic link that leads out of the track: bras-kit neither reads nor "
                 "writes through it"),
    "loop": M("progress.json is a loop of symbolic links"),
    "too_large": M("the progress file is too large"),
}
_NOT_A_FILE = M("progress.json is not a regular file (a named pipe, a device, a socket or a folder): bras-kit "
                "does not read it")


def stamp(folder: str | os.PathLike[str]) -> tuple[int, int, int]:
    """(inode, mtime_ns, size) of ``progress.json`` itself (a link is not followed), (0, 0, 0) when missing:
    changed whenever a process replaces the file."""
    try:
        info = os.stat(progress_path(folder), follow_symlinks=False)
    except OSError:
        return (0, 0, 0)
    return (info.st_ino, info.st_mtime_ns, info.st_size)


def _raw(folder: str | os.PathLike[str]) -> bytes:
    """The bytes of progress.json, read through the one reader: never through a link out of the
    track, never a pipe or a device, at most 1 MiB."""
    from ..trust.learner_files import Unreadable, read_bytes

    path = progress_path(folder)
    try:
        return read_bytes(str(path), (str(folder),), limit=MAX_PROGRESS_BYTES)
    except Unreadable as exc:
        if exc.kind == "missing":
            raise BrasKitError(M("no exercise track here"), path=str(folder),
                               hint=M("lay one out with 'bras-kit exercises init DIR', then run the command in "
                                      "DIR")) from None
        raise BrasKitError(_REFUSED.get(exc.kind, _NOT_A_FILE), path=str(path),
                           hint=M("remove it, or put the track's own progress.json back in its place")) from None


def _number(text: str) -> int | float:
    if len(text.lstrip("-").split(".")[0].split("e")[0].split("E")[0]) > MAX_DIGITS:
        raise ValueError(f"a number of {len(text)} digits")
    return float(text) if any(c in text for c in ".eE") else int(text)


def _parse(data: bytes) -> Any:
    text = data.decode("utf-8")
    return json.loads(text, parse_int=_number, parse_float=_number, parse_constant=_refuse_constant)


def _refuse_constant(name: str) -> Any:
    raise ValueError(f"{name} is not JSON")


_COUNTS = ("checks", "hints")


def _problem(data: Any) -> tuple[Any, ...] | None:
    """What makes ``data`` a progress file bras-kit did not write: (message words...) or None."""
    if not isinstance(data, dict) or not isinstance(data.get("set"), str):
        return (M("the progress file is not one of bras-kit's"),)
    for key in ("current", "lang"):
        if key in data and not isinstance(data[key], str):
            return (M("'{key}' in the progress file must be text, not {value}", key=key,
                      value=type(data[key]).__name__),)
    exercises = data.get("exercises", {})
    if not isinstance(exercises, dict):
        return (M("'{key}' in the progress file must be a mapping", key="exercises"),)
    for name, entry in exercises.items():
        if not isinstance(entry, dict):
            return (M("exercise '{name}' in the progress file must be a mapping", name=name[:80]),)
        for key in _COUNTS:
            value = entry.get(key, 0)
            if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= MAX_COUNT:
                return (M("'{key}' of exercise '{name}' in the progress file must be a whole number from 0 to "
                          "{most}", key=key, name=name[:80], most=MAX_COUNT),)
        if not isinstance(entry.get("passed", False), bool):
            return (M("'{key}' of exercise '{name}' in the progress file must be true or false", key="passed",
                      name=name[:80]),)
        if not isinstance(entry.get("passed_at", ""), str):
            return (M("'{key}' of exercise '{name}' in the progress file must be text, not {value}",
                      key="passed_at", name=name[:80], value=type(entry["passed_at"]).__name__),)
    return None


def read_progress(folder: str | os.PathLike[str], *, keep_aside: bool = False) -> Progress:
    """The track's progress, read through the one reader. A file bras-kit cannot take is a
    :class:`BrasKitError` naming why; with ``keep_aside`` (the track's own commands) a copy of
    its bytes is kept beside it first, and the message says where: nothing the learner recorded
    is lost, whatever they do next."""
    path = progress_path(folder)
    before = stamp(folder)
    data = _raw(folder)
    reason: Any = None
    try:
        parsed = _parse(data)
    except (UnicodeDecodeError, ValueError, RecursionError) as exc:
        # ValueError: not JSON, or a number past MAX_DIGITS; RecursionError: nested thousands deep
        reason = M("the progress file cannot be read ({reason})",
                   reason=("nested too deep" if isinstance(exc, RecursionError) else str(exc)[:200]))
    else:
        problem = _problem(parsed)
        if problem is not None:
            reason = problem[0]
    if reason is not None:
        kept = _keep_aside(Path(folder), data) if keep_aside else None
        raise BrasKitError(reason, path=str(path),
                           hint=M("it is plain JSON: fix it by hand (a copy of it as it was is kept in {copy}), "
                                  "or lay the track out again in another folder", copy=kept) if kept else
                           M("it is plain JSON: fix it by hand, or lay the track out again in another folder"))
    exercises = {str(k): dict(v) for k, v in parsed.get("exercises", {}).items()}
    lang = parsed.get("lang")
    return Progress(Path(folder), parsed["set"], str(parsed.get("current", "")), exercises,
                    lang if lang in LANGUAGES else "", before)


def _keep_aside(folder: Path, data: bytes) -> str | None:
    """``data`` as a new file progress.json.bad-N in the track (N the first free number, or the copy
    of these very bytes kept before), its name; None when it cannot be written."""
    from ..trust.learner_files import read_bytes, write_file

    for number in range(1, 1000):
        name = f"{PROGRESS_FILE}.bad-{number}"
        try:
            write_file(str(folder), name, data, replace=False)
        except FileExistsError:
            with contextlib.suppress(OSError):
                if read_bytes(str(folder / name), (str(folder),), limit=MAX_PROGRESS_BYTES) == data:
                    return str(folder / name)
            continue
        except OSError:
            return None
        return str(folder / name)
    return None


@contextlib.contextmanager
def _locked(folder: Path) -> Iterator[None]:
    """The track's lock (flock on .progress.json.lock beside progress.json, never through a link):
    one process at a time reads, changes and replaces the file."""
    from ..trust.beneath import open_root

    try:
        top = open_root(str(folder))
        try:
            fd = os.open(LOCK_FILE, os.O_RDWR | os.O_CREAT | os.O_NOFOLLOW | os.O_CLOEXEC, 0o666, dir_fd=top)
        finally:
            os.close(top)
    except OSError as exc:
        raise BrasKitError(M("the track's lock file cannot be opened ({reason})",
                             reason="a symbolic link" if exc.errno == errno.ELOOP else exc.strerror or str(exc)),
                           path=str(folder / LOCK_FILE), hint=M("remove it: bras-kit makes it again")) from None
    try:
        fcntl.flock(fd, fcntl.LOCK_EX)
        yield
    finally:
        os.close(fd)  # closing releases the lock


def _write(progress: Progress) -> None:
    from ..trust.beneath import Outside
    from ..trust.learner_files import write_file

    text = json.dumps(progress.as_dict(), indent=2, ensure_ascii=False) + "\n"
    try:
        write_file(str(progress.folder), PROGRESS_FILE, text.encode("utf-8"))
    except (Outside, OSError) as exc:
        raise BrasKitError(M("the progress file cannot be written ({reason})", reason=exc.strerror or str(exc)),
                           path=str(progress_path(progress.folder))) from None
    progress.stamp = stamp(progress.folder)


def write_progress(progress: Progress) -> None:
    """A new track's progress, written whole to a temporary file then renamed (never through a
    link), so a reader never sees half of it. Changes to a track go through :func:`update_progress`."""
    with _locked(progress.folder):
        _write(progress)


def update_progress(progress: Progress, change: Callable[[Progress], Any]) -> Any:
    """``change`` applied to the progress on disk, under the track's lock, and the result
    written atomically: what another process recorded meanwhile (a check in a second terminal)
    is kept. ``progress`` (this process's copy) is then the merged state. Returns what
    ``change`` returned."""
    with _locked(progress.folder):
        fresh = read_progress(progress.folder, keep_aside=True)
        result = change(fresh)
        _write(fresh)
    progress.set, progress.current, progress.exercises = fresh.set, fresh.current, fresh.exercises
    progress.lang, progress.stamp = fresh.lang, fresh.stamp
    return result


def reload_if_changed(progress: Progress) -> bool:
    """Whether another process replaced progress.json since this copy was read or written; if so,
    ``progress`` is the file's state now."""
    if stamp(progress.folder) == progress.stamp:
        return False
    with _locked(progress.folder):
        fresh = read_progress(progress.folder)
    progress.set, progress.current, progress.exercises = fresh.set, fresh.current, fresh.exercises
    progress.lang, progress.stamp = fresh.lang, fresh.stamp
    return True


def now() -> str:
    return time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
