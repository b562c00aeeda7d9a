"""What the launch description started, recorded in the child (read by bras_kit.ros.launching)."""

from __future__ import annotations

import inspect
import os
from typing import Any

STANDIN = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))

NODES: list[dict[str, Any]] = []
PROCESSES: list[dict[str, Any]] = []
LOGS: list[tuple[float, str, str, int]] = []
HANDLERS: list[str] = []
ARGUMENTS: list[dict[str, Any]] = []  # declared launch arguments
CURRENT: tuple[str, int] | None = None  # where the entity being executed was written


def caller() -> tuple[str, int]:
    """The learner's file and line that made the entity (the first frame outside the stand-in)."""
    frame = inspect.currentframe()
    while frame is not None:
        name = os.path.abspath(frame.f_code.co_filename)
        if not name.startswith(STANDIN) and not name.startswith("<"):
            return name, frame.f_lineno
        frame = frame.f_back
    return "", 0


def record_handler(handler: Any) -> None:
    HANDLERS.append(type(handler).__name__)


def reset() -> None:
    global CURRENT
    CURRENT = None
    for kept in (NODES, PROCESSES, LOGS, HANDLERS, ARGUMENTS):
        kept.clear()
