"""A memo bounded in bytes, for what drawing keeps between scenes of one process (placed mesh
pieces, meshes already in a renderer's OpenGL context)."""

from __future__ import annotations

from typing import Any


class BoundedMemo:
    """Values by key, up to ``budget`` bytes in all (each value's size given by its owner). Past
    the budget everything is dropped at once: a class of learners handing in the same robot is
    the case served, and a new robot starts afresh. A value larger than the budget is not kept.
    Values should hold whatever their key names by identity, so an id in a key is never reused."""

    def __init__(self, budget: int) -> None:
        self.budget = budget
        self._kept: dict[Any, Any] = {}
        self._bytes = 0

    def get(self, key: Any) -> Any:
        return self._kept.get(key)

    def put(self, key: Any, value: Any, size: int) -> None:
        if self._bytes + size > self.budget:
            self._kept.clear()
            self._bytes = 0
        if size <= self.budget:
            self._kept[key] = value
            self._bytes += size
