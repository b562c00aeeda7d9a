"""An exercise set as data: a folder with ``track.yaml`` (the set's name and the exercises in
order) and one folder per exercise holding ``exercise.yaml`` (title, statement, three hints,
the lesson, the checks), ``start/`` (the files the learner starts from) and ``solution/`` (a
reference solution, for the tests and for a teacher; never shown to the learner).

The format is the same for the built-in track (``bras_kit/exercises/track/``) and for a
teacher's own set (``bras-kit exercises init DIR --track SET``)::

    # track.yaml
    name: bras-kit
    exercises: [01-links, 02-joints]
    title: {en: The tutorial arm, fr: Le bras du tutoriel}

    # 01-links/exercise.yaml
    files: [bras.urdf]
    title: {en: ..., fr: ...}      # en required; other languages optional (English is the fallback)
    statement: {en: ..., fr: ...}
    hints: {en: [..., ..., ...]}   # exactly three per language
    lesson: {en: lessons/en/01-describe-the-arm.ipynb}
    checks:                        # kind: findings | frame | tip | ... (see checks.py); hint: 1..3
      - {kind: findings, file: bras.urdf, hint: 1}

YAML (read with ``yaml.safe_load``, like the grader's rubric) rather than rustlings' TOML: the
project supports Python 3.10, which has no ``tomllib``. Nothing in a manifest is run: checks are
names of the project's own checks and their parameters (numbers, joint and link names, file
names inside the exercise).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..core.errors import BrasKitError
from ..core.message import M

BUILTIN = "builtin"
BUILTIN_DIR = Path(__file__).with_name("track")
TRACK_FILE = "track.yaml"
EXERCISE_FILE = "exercise.yaml"
START = "start"
SOLUTION = "solution"
HINTS = 3
MAX_MANIFEST_BYTES = 256 * 1024


@dataclass(frozen=True)
class Exercise:
    id: str  # the folder's name: "03-elbow-origin"
    number: int  # 1-based place in the track
    folder: Path  # where the manifest, start/ and solution/ live
    files: tuple[str, ...]  # the learner's files, relative to the exercise's folder
    title: dict[str, str]
    statement: dict[str, str]
    hints: dict[str, tuple[str, ...]]
    lesson: dict[str, str]
    checks: tuple[dict[str, Any], ...]

    def words(self, table: dict[str, Any], lang: str) -> Any:
        return table.get(lang) or table.get("en") or next(iter(table.values()), "")

    def title_in(self, lang: str) -> str:
        return str(self.words(self.title, lang))

    def statement_in(self, lang: str) -> str:
        return str(self.words(self.statement, lang)).strip()

    def hint_in(self, lang: str, number: int) -> str:
        hints = self.words(self.hints, lang)
        return str(hints[max(1, min(number, len(hints))) - 1])

    def lesson_in(self, lang: str) -> str:
        return str(self.words(self.lesson, lang)) if self.lesson else ""


@dataclass(frozen=True)
class Track:
    source: str  # "builtin" or the set's folder as given at init
    folder: Path
    name: str
    title: dict[str, str]
    exercises: tuple[Exercise, ...] = field(default=())

    def title_in(self, lang: str) -> str:
        return self.title.get(lang) or self.title.get("en") or self.name

    def exercise(self, key: str | int) -> Exercise:
        """An exercise by its number (1-based) or its id."""
        text = str(key).strip()
        for exercise in self.exercises:
            if text in (exercise.id, str(exercise.number)):
                return exercise
        raise BrasKitError(M("no exercise '{key}' in this track", key=text),
                           hint=M("the exercises are numbered 1 to {n}: 'bras-kit exercises list' shows them",
                                  n=len(self.exercises)))


# the built-in track's lessons are the source tree's lessons/ (the manifests name them from there)
SOURCE_ROOT = Path(__file__).resolve().parents[2]


def lesson_link(track: Track, exercise: Exercise, lang: str, start: str | os.PathLike[str]) -> str:
    """The exercise's lesson as a path that opens from ``start`` (the track's folder): the
    built-in track's manifests name lessons from the source tree, a set's from its own folder.
    A lesson that is not there (an install without the source tree) is named as written."""
    lesson = exercise.lesson_in(lang)
    if not lesson or "://" in lesson:
        return lesson
    full = ((SOURCE_ROOT if track.source == BUILTIN else track.folder) / lesson).resolve()
    if not full.is_file():
        return lesson
    here = Path(start).resolve()
    if os.path.commonpath([full, here]) == here.anchor:
        return str(full)  # nothing shared but the root: the full path reads better than ../../..
    return os.path.relpath(full, here)


def _read_manifest(path: Path, root: Path) -> dict[str, Any]:
    import yaml

    from ..trust import yaml_gate
    from ..trust.learner_files import Unreadable, read_text

    try:  # the one reader, inside the set's folder: no link out, no pipe, no device, no file past the bound
        text = read_text(str(path), (str(root),), limit=MAX_MANIFEST_BYTES)
        data = yaml_gate.load(text, loader=yaml.SafeLoader)
    except Unreadable as exc:
        if exc.kind == "too_large":
            raise BrasKitError(M("the manifest is too large"), path=str(path)) from None
        if exc.kind != "missing":
            raise BrasKitError(M("the manifest cannot be read ({reason})", reason=exc.strerror or str(exc)),
                               path=str(path)) from None
        raise BrasKitError(M("the manifest is missing"), path=str(path),
                           hint=M("an exercise set is a folder with track.yaml and one folder per exercise "
                                  "holding exercise.yaml")) from None
    except FileNotFoundError:
        raise BrasKitError(M("the manifest is missing"), path=str(path),
                           hint=M("an exercise set is a folder with track.yaml and one folder per exercise "
                                  "holding exercise.yaml")) from None
    except OSError as exc:
        raise BrasKitError(M("the manifest cannot be read ({reason})", reason=exc.strerror or str(exc)),
                           path=str(path)) from None
    except (yaml.YAMLError, UnicodeDecodeError) as exc:
        raise BrasKitError(M("the manifest is not valid YAML: {detail}", detail=str(exc)), path=str(path)) from None
    if not isinstance(data, dict):
        raise BrasKitError(M("the manifest must be a mapping of keys to values"), path=str(path))
    return data


def _languages(data: dict[str, Any], key: str, path: Path, *, required: bool = True) -> dict[str, str]:
    table = data.get(key, {})
    if not isinstance(table, dict) or (required and not isinstance(table.get("en"), str)) \
            or not all(isinstance(v, str) for v in table.values()):
        if not required and not table:
            return {}
        raise BrasKitError(M("'{key}' must be a table of texts by language, with 'en' at least", key=key),
                           path=str(path))
    return dict(table)


def _inside(name: Any, path: Path) -> str:
    """A file name of the manifest, checked to stay inside the exercise's folder."""
    if not isinstance(name, str) or not name or os.path.isabs(name) or ".." in Path(name).parts:
        raise BrasKitError(M("'{name}' is not a file inside the exercise's folder", name=str(name)),
                           path=str(path))
    return name


def load_exercise(folder: Path, number: int) -> Exercise:
    path = folder / EXERCISE_FILE
    data = _read_manifest(path, folder.parent)
    files = data.get("files")
    if not isinstance(files, list) or not files:
        raise BrasKitError(M("'files' must list the learner's files"), path=str(path))
    hints_table = data.get("hints", {})
    if not isinstance(hints_table, dict) or "en" not in hints_table:
        raise BrasKitError(M("'hints' must be a table of three hints by language, with 'en' at least"),
                           path=str(path))
    hints: dict[str, tuple[str, ...]] = {}
    for lang, items in hints_table.items():
        if not isinstance(items, list) or len(items) != HINTS or not all(isinstance(h, str) for h in items):
            raise BrasKitError(M("'hints.{lang}' must hold exactly three texts", lang=lang), path=str(path))
        hints[lang] = tuple(items)
    checks = data.get("checks", [])
    if not isinstance(checks, list) or not checks or not all(isinstance(c, dict) for c in checks):
        raise BrasKitError(M("an exercise needs at least one check under 'checks'"), path=str(path))
    from .checks import validate_check

    for check in checks:
        validate_check(check, path)
        for key in ("file", "robot"):
            if key in check:
                _inside(check[key], path)
    return Exercise(
        id=folder.name, number=number, folder=folder,
        files=tuple(_inside(name, path) for name in files),
        title=_languages(data, "title", path), statement=_languages(data, "statement", path),
        hints=hints, lesson=_languages(data, "lesson", path, required=False),
        checks=tuple(checks),
    )


def _distinct_folders(exercises: tuple[Exercise, ...], path: Path) -> None:
    """Each exercise's folder (its id: progress, hints and the learner's copy are kept under it)
    is its own, on a file system that ignores case or normalises accents too."""
    import unicodedata

    seen: dict[str, Exercise] = {}
    for exercise in exercises:
        first = seen.setdefault(unicodedata.normalize("NFC", exercise.id).casefold(), exercise)
        if first is not exercise:
            raise BrasKitError(M("exercises {first} and {second} would share the folder '{folder}'",
                                 first=first.number, second=exercise.number, folder=exercise.id),
                               path=str(path), hint=M("give each exercise a folder name of its own"))


def load_track(source: str | os.PathLike[str] = BUILTIN) -> Track:
    """The built-in track (``"builtin"``) or a teacher's set (its folder)."""
    folder = BUILTIN_DIR if str(source) == BUILTIN else Path(source)
    path = folder / TRACK_FILE
    data = _read_manifest(path, folder)
    ids = data.get("exercises")
    if not isinstance(ids, list) or not ids or not all(isinstance(i, (str, int)) for i in ids):
        raise BrasKitError(M("'exercises' must list the exercise folders in order"), path=str(path))
    exercises = tuple(load_exercise(folder / _inside(str(i), path), n) for n, i in enumerate(ids, 1))
    _distinct_folders(exercises, path)
    return Track(source=str(source), folder=folder, name=str(data.get("name", folder.name)),
                 title=_languages(data, "title", path, required=False), exercises=exercises)
