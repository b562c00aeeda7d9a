"""The events of a launch that bras-kit can tell have happened, and the handlers they fire.

launch's LaunchService emits ``ProcessStarted`` once a process really runs
(execute_local.py:590) and ``ProcessExited`` when it ends; an ``OnProcessStart`` /
``OnProcessExit`` handler matches the event's action by identity (or a predicate, or any
process when no target is given: on_action_event_base.py ``event_matcher``). Events are handled
after the entities that caused them are visited, so a handler registered after its target still
sees the target start. A target that never starts — never put in the description, or its
condition false — never emits the event, and what waits for it never starts.

Here a Node or ExecuteProcess "starts" when its ``execute`` is visited; a Node never exits by
itself during the launch (it runs until Ctrl-C), a plain process (``ExecuteProcess``) is taken to
run to its end.
"""

from __future__ import annotations

from typing import Any


class ProcessEvent:
    """launch/events/process/running_process_event.py, the fields learners read."""

    def __init__(self, action: Any, name: str) -> None:
        self.action = action
        self.name = name
        self.pid = 0
        self.cmd = list(getattr(action, "_bras_cmd", []))


class ProcessStarted(ProcessEvent):
    pass


class ProcessExited(ProcessEvent):
    returncode = 0


def record_start(context: Any, action: Any) -> None:
    """A process started: its ProcessStarted (and, for a plain process, ProcessExited) are due."""
    pending = context.__dict__.setdefault("_bras_events", [])
    name = type(action).__name__
    pending.append((ProcessStarted(action, name), context.delay))
    if not getattr(action, "_is_node", False):
        pending.append((ProcessExited(action, name), context.delay))


def fire_pending(context: Any, visit: Any) -> None:
    """Hand every due event to the registered handlers, visiting what they return, until none is left."""
    pending = context.__dict__.setdefault("_bras_events", [])
    while pending:
        event, delay = pending.pop(0)
        for handler in list(context.__dict__.get("_bras_handlers", [])):
            if not handler._bras_matches(event):
                continue
            entities = handler._bras_handle(event, context)
            handler._bras_fired = True
            if handler._bras_once:
                context._bras_handlers.remove(handler)
            saved, context.delay = context.delay, delay
            try:
                for entity in entities:
                    visit(entity, context)
            finally:
                context.delay = saved


def _executable(action: Any) -> str:
    executable = getattr(action, "node_executable", None)
    if isinstance(executable, str):
        return executable
    cmd = getattr(action, "cmd", None)
    if cmd and all(hasattr(s, "text") for s in cmd[0]):
        return "".join(s.text for s in cmd[0])
    return type(action).__name__


def unfired_start_handlers(context: Any) -> list[dict[str, Any]]:
    """The OnProcessStart handlers, once every due event was handled, whose target is an action
    that never started: what they hold never starts (on_action_event_base.py event_matcher)."""
    from ._handlers import OnProcessStart

    out = []
    for handler in context.__dict__.get("_bras_handlers", []):
        target = handler.target_action if isinstance(handler, OnProcessStart) else None
        if target is None or not hasattr(target, "execute") or getattr(handler, "_bras_fired", False):
            continue
        where = getattr(handler, "_bras_where", ("", 0))
        held = handler._on if isinstance(handler._on, (list, tuple)) else [handler._on]
        out.append({"file": where[0], "line": where[1], "target": _executable(target),
                    "waiting": [_executable(a) for a in held if a is not None and not callable(a)]})
    return out
