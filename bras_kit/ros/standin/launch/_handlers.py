"""launch/event_handlers/*.py (Jazzy), for the handlers learners register: each fires only on an
event that happened (see _events.py)."""

from __future__ import annotations

from typing import Any

from ._events import ProcessEvent, ProcessExited, ProcessStarted


class EventHandler:
    def __init__(self, *, matcher: Any = None, entities: Any = None, handle_once: bool = False) -> None:
        self._matcher = matcher
        self._entities = [] if entities is None else (list(entities) if isinstance(entities, (list, tuple))
                                                      else [entities])
        self._bras_once = handle_once

    @property
    def handle_once(self) -> bool:
        return self._bras_once

    def _bras_matches(self, event: Any) -> bool:
        return bool(self._matcher(event)) if self._matcher is not None else False

    def _bras_handle(self, event: Any, context: Any) -> list:
        return list(self._entities)


class _OnActionEvent(EventHandler):
    """on_action_event_base.py: the target by identity, a predicate, or any process (None)."""

    EVENT: type[ProcessEvent] = ProcessStarted

    def __init__(self, *, target_action: Any = None, on_event: Any = None, **kwargs: Any) -> None:
        super().__init__(handle_once=bool(kwargs.get("handle_once", False)))
        self.target_action = target_action
        self._on = on_event

    def _bras_matches(self, event: Any) -> bool:
        if not isinstance(event, self.EVENT):
            return False
        target = self.target_action
        if target is None:
            return True
        if callable(target) and not hasattr(target, "execute"):
            return bool(target(event.action))
        return event.action is target

    def _bras_handle(self, event: Any, context: Any) -> list:
        on = self._on
        if on is None:
            return []
        if callable(on):  # on_action_event_base.py handle(): a function of (event, context)
            on = on(event, context)
            if on is None:
                return []
        return list(on) if isinstance(on, (list, tuple)) else [on]


class OnProcessStart(_OnActionEvent):
    EVENT = ProcessStarted

    def __init__(self, *, target_action: Any = None, on_start: Any = None, **kwargs: Any) -> None:
        super().__init__(target_action=target_action, on_event=on_start, **kwargs)


class OnProcessExit(_OnActionEvent):
    """A node runs until Ctrl-C: what follows its exit never starts during the launch."""

    EVENT = ProcessExited

    def __init__(self, *, target_action: Any = None, on_exit: Any = None, **kwargs: Any) -> None:
        super().__init__(target_action=target_action, on_event=on_exit, **kwargs)


class OnExecutionComplete(_OnActionEvent):
    """Taken as the target's start: its execute() has completed when it starts."""

    EVENT = ProcessStarted

    def __init__(self, *, target_action: Any = None, on_completion: Any = None, **kwargs: Any) -> None:
        super().__init__(target_action=target_action, on_event=on_completion, **kwargs)


class OnShutdown(EventHandler):
    def __init__(self, *, on_shutdown: Any = None, **kwargs: Any) -> None:
        super().__init__()


class OnProcessIO(EventHandler):
    def __init__(self, **kwargs: Any) -> None:
        super().__init__()


class OnIncludeLaunchDescription(EventHandler):
    def __init__(self, **kwargs: Any) -> None:
        super().__init__()
