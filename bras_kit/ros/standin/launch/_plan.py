"""What the launch description started, recorded in the child (read by bras_kit.ros.launching)."""

from __future__ import annotations

import inspect
import os
from typing import Any

STANDIN = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BRAS_KIT = os.path.dirname(os.path.dirname(STANDIN))  # bras-kit's own frames (launching.py) are not the learner's

# what bras-kit evaluates of one launch (the tutorial's: 3 nodes, no log): past it the launch
# stops, as data (Bound), where ros2 launch would start every node and print every line
MAX_NODES = 256
MAX_LOGS = 10_000  # LogInfo actions
MAX_LOG_CHARS = 1 << 20  # their text, all told

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


class Bound(BaseException):  # noqa: N818 - not an Exception: a learner's "except Exception" does not hide it
    """bras-kit's bound on what one launch starts or says (:data:`MAX_NODES`, :data:`MAX_LOGS`,
    :data:`MAX_LOG_CHARS`): the evaluation stops at the entity past it."""


_logged = [0]  # characters of LogInfo text recorded since reset()


def record_node(entry: dict[str, Any]) -> None:
    if len(NODES) >= MAX_NODES:
        raise Bound(f"the launch file starts more than {MAX_NODES} nodes, more than bras-kit evaluates")
    NODES.append(entry)


def record_log(entry: tuple[float, str, str, int]) -> None:
    _logged[0] += len(entry[1])
    if len(LOGS) >= MAX_LOGS or _logged[0] > MAX_LOG_CHARS:
        raise Bound(f"the launch file logs more than {MAX_LOGS} lines or {MAX_LOG_CHARS >> 20} MiB (LogInfo), "
                    "more than bras-kit keeps")
    LOGS.append(entry)


def record_handler(handler: Any) -> None:
    HANDLERS.append(type(handler).__name__)


def reset() -> None:
    global CURRENT
    CURRENT = None
    _logged[0] = 0
    for kept in (NODES, PROCESSES, LOGS, HANDLERS, ARGUMENTS, INCLUDED, UNFIRED):
        kept.clear()
