"""``bras-kit exercises``: the tutorial as a track of small exercises on the learner's own files,
like rustlings: exercises are data (:mod:`.manifest`), each check judges what a file does with
the project's machinery (:mod:`.checks`), progress lives beside the exercises (:mod:`.progress`).

::

    from bras_kit.exercises import init_track, open_track, check_exercise
    init_track("exos")                       # lays out the built-in track
    track, progress = open_track("exos")
    outcome = check_exercise(track, progress, track.exercise(1))
    outcome.state                            # "passed", "failed" or "broken"
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

from ..core.errors import BrasKitError
from ..core.message import M
from .checks import BROKEN, CHECKS, FAILED, PASSED, Outcome, run_checks
from .manifest import BUILTIN, START, Exercise, Track, load_track
from .progress import (
    PROGRESS_FILE,
    Progress,
    find_track_folder,
    now,
    read_progress,
    update_progress,
    write_progress,
)

__all__ = ["BROKEN", "BUILTIN", "CHECKS", "FAILED", "PASSED", "PROGRESS_FILE", "Exercise", "Outcome", "Progress",
           "Track", "check_exercise", "copy_files", "current_exercise", "exercise_files", "find_track_folder",
           "init_track", "load_track", "open_track", "reveal_hint", "reset_exercise", "start_files"]


def start_files(exercise: Exercise, which: str = START) -> list[str]:
    """The files of the exercise's ``start/`` (or ``solution/``) folder, relative to it, listed
    through the one reader (no link followed out of the exercise's folder)."""
    from ..trust.learner_files import Unreadable, walk

    root = exercise.folder / which
    out: list[str] = []
    try:
        for folder, dirs, files in walk(str(root), (str(exercise.folder),)):
            dirs[:] = sorted(d for d in dirs if d != "__pycache__")
            out.extend(os.path.relpath(os.path.join(folder, f), root) for f in sorted(files) if not f.endswith(".pyc"))
    except Unreadable as exc:
        if exc.kind != "missing":
            raise _refused(str(root), exc) from None
    return out


def _refused(path: str, exc: OSError) -> BrasKitError:
    from ..trust.beneath import Outside

    if isinstance(exc, Outside) and exc.kind in ("link_out", "outside"):
        return BrasKitError(M("'{path}' leads out of the track through a symbolic link: bras-kit reads and writes "
                              "nothing through it", path=exc.path), path=path,
                            hint=M("replace the link with a folder of the track (or remove it), then run the "
                                   "command again"))
    reason = exc.strerror or str(exc)
    return BrasKitError(M("'{path}' cannot be used ({reason})", path=getattr(exc, "path", path), reason=reason),
                        path=path)


def copy_files(exercise: Exercise, target: str | os.PathLike[str], which: str = START, *,
               root: str | os.PathLike[str] | None = None) -> list[Path]:
    """``start/`` (or ``solution/``) of the exercise copied into ``target`` (its folder in the
    track), each file read through the one reader and written under ``root`` (default:
    ``target``) without following a link out of it: a file replaced whole (a temporary beside
    it, then renamed), never written through a link."""
    from ..trust.beneath import Outside
    from ..trust.learner_files import read_bytes, write_file

    base = Path(root) if root is not None else Path(target)
    if root is None:
        os.makedirs(base, exist_ok=True)  # the folder named: made as a learner would make it
    inner = os.path.relpath(os.path.abspath(target), os.path.abspath(base))
    names = start_files(exercise, which)
    for folder in sorted({os.path.dirname(os.path.normpath(os.path.join(inner, n))) for n in names}):
        _writable(base, folder)  # every folder refused before any file is written: no half-reset
    written = []
    for name in names:
        relative = os.path.normpath(os.path.join(inner, name))
        try:
            data = read_bytes(str(exercise.folder / which / name), (str(exercise.folder),))
            write_file(str(base), relative, data)
        except (Outside, OSError) as exc:
            raise _refused(str(base / relative), exc) from None
        written.append(Path(target) / name)
    return written


def _writable(base: Path, folder: str) -> None:
    """A folder of the track that :func:`copy_files` may write into (or make); else the refusal."""
    from ..trust.beneath import FOLDER, Outside, open_beneath

    if folder in ("", "."):
        return
    try:
        os.close(open_beneath(str(base), folder, want=FOLDER))
    except Outside as exc:
        if exc.kind != "missing":
            raise _refused(str(base / folder), exc) from None


def exercise_files(folder: str | os.PathLike[str], exercise: Exercise) -> list[Path]:
    return [Path(folder) / exercise.id / name for name in exercise.files]


def init_track(folder: str | os.PathLike[str], source: str = BUILTIN, lang: str = "") -> Track:
    """Lay out every exercise's starting files in ``folder`` (made if missing) and a fresh
    progress file, which keeps ``lang``: the track speaks it wherever it is started from.
    Refuses a folder that already holds a track or any of the files."""
    track = load_track(source)
    root = Path(folder)
    if root.exists() and not root.is_dir():
        raise BrasKitError(M("'{path}' is a file, not a folder", path=str(root)),
                           hint=M("give a new folder's name: bras-kit exercises init exos"))
    if (root / PROGRESS_FILE).exists():
        raise BrasKitError(M("this folder already holds an exercise track"), path=str(root),
                           hint=M("go on with 'bras-kit exercises' in it, or choose another folder"))
    taken = [str(root / exercise.id) for exercise in track.exercises if (root / exercise.id).exists()]
    if taken:
        raise BrasKitError(M("nothing was written: {paths} already exist", paths=taken),
                           hint=M("choose another folder: bras-kit exercises init exos"))
    root.mkdir(parents=True, exist_ok=True)
    for exercise in track.exercises:
        copy_files(exercise, root / exercise.id, root=root)
    source_text = BUILTIN if str(source) == BUILTIN else str(Path(source).resolve())
    write_progress(Progress(root, source_text, track.exercises[0].id, {}, lang))
    return track


def open_track(folder: str | os.PathLike[str] | None = None) -> tuple[Track, Progress]:
    """The track whose ``progress.json`` is in ``folder`` (default: the current folder or a parent)."""
    found = find_track_folder(folder or os.getcwd()) if folder is None else Path(folder)
    if found is None:
        raise BrasKitError(M("no exercise track in this folder or above it"),
                           hint=M("lay one out with 'bras-kit exercises init DIR', then run the command in DIR"))
    progress = read_progress(found, keep_aside=True)
    return load_track(progress.set), progress


def current_exercise(track: Track, progress: Progress) -> Exercise | None:
    """The exercise the learner is on (None when every exercise passed)."""
    for exercise in track.exercises:
        if exercise.id == progress.current:
            return exercise
    return next((e for e in track.exercises if not progress.passed(e.id)), None)


def check_exercise(track: Track, progress: Progress, exercise: Exercise, lang: str | None = None,
                   *, record: bool = True) -> Outcome:
    """Check one exercise in the learner's folder and record it; a pass on the current exercise
    moves the track on to the next one not yet passed."""
    from ..core.i18n import current_language

    outcome = run_checks(progress.folder / exercise.id, exercise.checks, lang or current_language())
    if record:
        update_progress(progress, lambda fresh: _record_check(track, fresh, exercise, outcome))
    return outcome


def _record_check(track: Track, progress: Progress, exercise: Exercise, outcome: Outcome) -> None:
    entry = progress.entry(exercise.id)
    entry["checks"] = int(entry.get("checks", 0)) + 1
    if outcome.state == PASSED:
        if not entry.get("passed"):
            entry["passed_at"] = now()
        entry["passed"] = True
        if progress.current in ("", exercise.id):
            following = [e for e in track.exercises if e.number > exercise.number and not progress.passed(e.id)]
            progress.current = following[0].id if following else ""
    else:
        entry["passed"] = False


def reveal_hint(progress: Progress, exercise: Exercise, shown: int = 0) -> int:
    """The next hint of the exercise is shown (the one after those seen and after ``shown``, the
    hint already on screen): the number of hints seen now (at most 3)."""

    def reveal(fresh: Progress) -> int:
        entry = fresh.entry(exercise.id)
        entry["hints"] = min(3, max(int(entry.get("hints", 0)), shown) + 1)
        return int(entry["hints"])

    seen: int = update_progress(progress, reveal)
    return seen


def reset_exercise(progress: Progress, exercise: Exercise) -> list[Path]:
    """The exercise's starting files laid out again over the learner's (the caller asked first),
    never through a link out of the track."""
    written = copy_files(exercise, progress.folder / exercise.id, root=progress.folder)

    def reset(fresh: Progress) -> Any:
        entry = fresh.entry(exercise.id)
        entry["passed"] = False
        entry.pop("passed_at", None)
        fresh.current = exercise.id

    update_progress(progress, reset)
    return written
