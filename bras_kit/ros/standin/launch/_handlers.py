"""launch/event_handlers/*.py (Jazzy), for the handlers learners register."""

from __future__ import annotations

from typing import Any


def _entities(value: Any) -> list:
    if value is None or callable(value):
        return []  # a callable handler gets an event bras-kit does not make
    return list(value) if isinstance(value, (list, tuple)) else [value]


class EventHandler:
    def __init__(self, *, matcher: Any = None, entities: Any = None, handle_once: bool = False) -> None:
        self._entities = _entities(entities)

    def _bras_followers(self) -> list:
        return []


class OnProcessStart(EventHandler):
    """Its actions start with the target (nodes start at once here)."""

    def __init__(self, *, target_action: Any = None, on_start: Any = None, **kwargs: Any) -> None:
        super().__init__()
        self.target_action = target_action
        self._on = _entities(on_start)

    def _bras_followers(self) -> list:
        return self._on


class OnProcessExit(EventHandler):
    """Its actions follow a process that ends by itself; a node runs until stopped, so what
    follows a node's exit never starts during the launch."""

    def __init__(self, *, target_action: Any = None, on_exit: Any = None, **kwargs: Any) -> None:
        super().__init__()
        self.target_action = target_action
        self._on = _entities(on_exit)

    def _bras_followers(self) -> list:
        from ._actions import ExecuteProcess

        target = self.target_action
        if target is not None and isinstance(target, ExecuteProcess) and not getattr(target, "_is_node", False):
            return self._on
        return []


class OnExecutionComplete(OnProcessStart):
    def __init__(self, *, target_action: Any = None, on_completion: Any = None, **kwargs: Any) -> None:
        super().__init__(target_action=target_action, on_start=on_completion)


class OnShutdown(EventHandler):
    def __init__(self, *, on_shutdown: Any = None, **kwargs: Any) -> None:
        super().__init__()


class OnProcessIO(EventHandler):
    def __init__(self, **kwargs: Any) -> None:
        super().__init__()


class OnIncludeLaunchDescription(EventHandler):
    def __init__(self, **kwargs: Any) -> None:
        super().__init__()
