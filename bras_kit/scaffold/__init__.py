"""``bras-kit new``: the tutorial's ROS 2 package written from templates (:mod:`.package`). The
lessons' ``from bras_kit.scaffold import scaffold_package`` is imported on first use."""

from __future__ import annotations

import importlib
from typing import Any

_LAZY = {'scaffold_package': '.package'}


def __getattr__(name: str) -> Any:
    module = _LAZY.get(name)
    if module is None:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    return getattr(importlib.import_module(module, __name__), name)


__all__ = list(_LAZY)
