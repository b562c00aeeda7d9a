"""What the launch description started, recorded in the child (read by bras_kit.ros.launching)."""

from __future__ import annotations

import inspect
import os
from typing import Any

STANDIN = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BRAS_KIT = os.path.dirname(os.path.dirname(STANDIN))  # bras-kit's own frames (launching.py) are not the learner's

NODES: list[dict[str, Any]] = []
PROCESSES: list[dict[str, Any]] = []
LOGS: list[tuple[float, str, str, int]] = []
HANDLERS: list[str] = []
ARGUMENTS: list[dict[str, Any]] = []  # declared launch arguments
INCLUDED: list[str] = []  # the launch files included (IncludeLaunchDescription), in order
UNFIRED: list[dict[str, Any]] = []  # OnProcessStart handlers whose target never started
CURRENT: tuple[str, int] | None = None  # where the entity being executed was written
ROOTS: tuple[str, ...] = ()  # the folders of the learner's files (the package, its install tree)


def caller() -> tuple[str, int]:
    """The learner's file and line that made the entity: the first frame in the learner's files
    (``ROOTS``, when the evaluation set them) or else outside the stand-in and bras-kit; for an
    entity a front-end file made, the tag being parsed (``CURRENT``)."""
    frame = inspect.currentframe()
    while frame is not None:
        name = os.path.abspath(frame.f_code.co_filename)
        if ROOTS:
            if name.startswith(ROOTS):
                return name, frame.f_lineno
        elif not name.startswith((STANDIN, BRAS_KIT + os.sep)) and not name.startswith("<"):
            return name, frame.f_lineno
        frame = frame.f_back
    return CURRENT if CURRENT is not None else ("", 0)


def record_handler(handler: Any) -> None:
    HANDLERS.append(type(handler).__name__)


def reset() -> None:
    global CURRENT
    CURRENT = None
    for kept in (NODES, PROCESSES, LOGS, HANDLERS, ARGUMENTS, INCLUDED, UNFIRED):
        kept.clear()
