"""Progress, kept beside the exercises in the learner's folder (``progress.json``): which set,
the current exercise, and for each exercise whether it passed, when, how many checks and hints
it took. Plain JSON a teacher can read, and ``bras-kit grade`` counts.

::

    {"format": 1, "set": "builtin", "lang": "fr", "current": "03-elbow-origin",
     "exercises": {"01-links": {"passed": true, "passed_at": "2026-11-26T16:40:02Z",
                                "checks": 4, "hints": 1}}}
"""

from __future__ import annotations

import json
import os
import time
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import BrasKitError
from ..i18n import LANGUAGES
from ..message import M

PROGRESS_FILE = "progress.json"
FORMAT = 1
MAX_PROGRESS_BYTES = 1 << 20


@dataclass
class Progress:
    folder: Path
    set: str
    current: str
    exercises: dict[str, dict[str, Any]] = field(default_factory=dict)
    lang: str = ""  # the language the track was laid out in ("" in a track made before it was kept)

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
        if (folder / PROGRESS_FILE).is_file():
            return folder
    return None


def read_progress(folder: str | os.PathLike[str]) -> Progress:
    path = progress_path(folder)
    try:
        if path.stat().st_size > MAX_PROGRESS_BYTES:
            raise BrasKitError(M("the progress file is too large"), path=str(path))
        data = json.loads(path.read_text(encoding="utf-8"))
    except FileNotFoundError:
        raise BrasKitError(M("no exercise track here"), path=str(folder),
                           hint=M("lay one out with 'bras-kit exercises init DIR', then run the command in DIR")) \
            from None
    except (OSError, UnicodeDecodeError, json.JSONDecodeError) as exc:
        raise BrasKitError(M("the progress file cannot be read ({reason})", reason=str(exc)), path=str(path),
                           hint=M("it is plain JSON: fix it by hand, or lay the track out again in another "
                                  "folder")) from None
    if not isinstance(data, dict) or not isinstance(data.get("set"), str):
        raise BrasKitError(M("the progress file is not one of bras-kit's"), path=str(path))
    found = data.get("exercises")
    exercises: dict[str, Any] = found if isinstance(found, dict) else {}
    clean = {str(k): dict(v) for k, v in exercises.items() if isinstance(v, dict)}
    lang = data.get("lang")
    return Progress(Path(folder), data["set"], str(data.get("current", "")), clean,
                    lang if lang in LANGUAGES else "")


def write_progress(progress: Progress) -> None:
    """Written whole to a temporary file then renamed, so a reader never sees half of it."""
    path = progress_path(progress.folder)
    temporary = path.with_name(f".{PROGRESS_FILE}.{os.getpid()}.tmp")
    temporary.write_text(json.dumps(progress.as_dict(), indent=2, ensure_ascii=False) + "\n", encoding="utf-8")
    os.replace(temporary, path)


def now() -> str:
    return time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())
