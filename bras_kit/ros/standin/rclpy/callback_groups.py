"""rclpy.callback_groups, simulated (rclpy/callback_groups.py): which callbacks may run together.

On the simulated clock a callback runs until it waits (sleeps, a rate, a future); a
MultiThreadedExecutor then starts the next ready callback its group allows, as its pool would.
"""

import weakref


class CallbackGroup:
    def __init__(self):
        self.entities = set()

    def add_entity(self, entity):
        self.entities.add(weakref.ref(entity))

    def has_entity(self, entity):
        return weakref.ref(entity) in self.entities

    def can_execute(self, entity):
        raise NotImplementedError()

    def beginning_execution(self, entity):
        raise NotImplementedError()

    def ending_execution(self, entity):
        raise NotImplementedError()


class ReentrantCallbackGroup(CallbackGroup):
    """callback_groups.py:80-90."""

    def can_execute(self, entity):
        return True

    def beginning_execution(self, entity):
        return True

    def ending_execution(self, entity):
        pass


class MutuallyExclusiveCallbackGroup(CallbackGroup):
    """callback_groups.py:93-117: one callback of the group at a time."""

    def __init__(self):
        super().__init__()
        self._active_entity = None

    def can_execute(self, entity):
        assert weakref.ref(entity) in self.entities
        return self._active_entity is None

    def beginning_execution(self, entity):
        assert weakref.ref(entity) in self.entities
        if self._active_entity is None:
            self._active_entity = entity
            return True
        return False

    def ending_execution(self, entity):
        assert self._active_entity == entity
        self._active_entity = None
