"""The lessons, in order. Each module defines one ``LESSON`` (and maybe ``SOLUTION``)."""

from __future__ import annotations

import importlib

from ._cells import Lesson
from ._track import track_cell

_MODULES = [
    "l01_describe",
    "l02_frames",
    "l03_see",
    "l04_package",
    "l05_motion",
    "l06_wrist",
    "l07_inertials",
    "l08_pitfalls",
    "l09_reach",
    "l10_xacro",
    "l11_physics",
]


def _collect() -> list[Lesson]:
    lessons = []
    for name in _MODULES:
        module = importlib.import_module(f"{__name__}.{name}")
        cell = track_cell(module.LESSON)
        if cell is not None and cell not in module.LESSON.cells:
            module.LESSON.cells.append(cell)  # the lesson points to the exercises that practise it
        lessons.append(module.LESSON)
        if hasattr(module, "SOLUTION"):
            lessons.append(module.SOLUTION)
    return lessons


LESSONS = _collect()
