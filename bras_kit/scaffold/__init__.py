"""``bras-kit new``: the tutorial's ROS 2 package written from templates (:mod:`.package`). The
lessons' ``from bras_kit.scaffold import scaffold_package`` is imported on first use."""

from __future__ import annotations

from ..core.lazy import lazy_exports

_LAZY = {'scaffold_package': '.package'}


__getattr__ = lazy_exports(__name__, _LAZY)


__all__ = list(_LAZY)
