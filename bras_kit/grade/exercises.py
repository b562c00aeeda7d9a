"""The exercise track in a learner's submission: how many exercises its ``progress.json`` (laid
out by ``bras-kit exercises init``) records as passed, for a column of the class's reports."""

from __future__ import annotations

import os

MAX_DEPTH = 3  # progress.json is looked for in the submission and up to three folders below


def find_progress(root: str) -> str | None:
    """The folder of the first ``progress.json`` in ``root`` or below it (hidden folders skipped)."""
    from ..exercises.progress import PROGRESS_FILE
    from ..trust.learner_files import is_file, is_folder, walk

    if not is_folder(root, (root,)):
        return None
    base = os.path.normpath(root).count(os.sep)
    # listed through the one reader: links to folders are not walked into, a pipe is no file
    for folder, dirs, files in walk(root, (root,)):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        if PROGRESS_FILE in files and is_file(os.path.join(folder, PROGRESS_FILE), (root,)):
            return folder
        if folder.count(os.sep) - base >= MAX_DEPTH:
            dirs[:] = []
    return None


def exercises_passed(root: str) -> str:
    """``"5/14"`` for the built-in track (``"5"`` for a teacher's own set), "" without a track or
    with a progress file that cannot be read. As recorded by the learner's ``bras-kit exercises``:
    ``bras-kit exercises check N -C FOLDER`` checks one again."""
    from ..core.errors import BrasKitError
    from ..exercises.manifest import BUILTIN, load_track
    from ..exercises.progress import MAX_PROGRESS_BYTES, PROGRESS_FILE, read_progress
    from ..trust.learner_files import read_bytes

    folder = find_progress(root)
    if folder is None:
        return ""
    try:
        # through the one reader first: a regular file inside the submission, of a bounded size,
        # opened without waiting (a pipe named progress.json would hold the class's run forever)
        read_bytes(os.path.abspath(os.path.join(folder, PROGRESS_FILE)), (os.path.abspath(root),), limit=MAX_PROGRESS_BYTES)
        progress = read_progress(folder)
    except (BrasKitError, OSError, ValueError, TypeError, RecursionError):  # nested, huge numbers: not counted
        return ""
    if progress.set == BUILTIN:
        ids = [exercise.id for exercise in load_track(BUILTIN).exercises]
        return f"{sum(progress.passed(i) for i in ids)}/{len(ids)}"
    return str(sum(bool(entry.get("passed")) for entry in progress.exercises.values()))
