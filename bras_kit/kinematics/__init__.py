"""Frames: forward kinematics as robot_state_publisher computes it (:mod:`.frames`) and the tool
tip (:mod:`.tip`). The lessons' names (``from bras_kit.kinematics import describe_transform``) are
imported on first use, so numpy loads only then."""

from __future__ import annotations

from ..core.lazy import lazy_exports

_LAZY = {'fk': '.frames', 'fk_batch': '.frames', 'relative_transform': '.frames', 'describe_transform': '.frames', 'tf_tree': '.frames', 'TFTree': '.frames', 'rpy_to_matrix': '.frames', 'matrix_to_rpy': '.frames', 'matrix_to_quat_xyzw': '.frames', 'origin_matrix': '.frames', 'movable_names': '.frames', 'tool_tip': '.tip', 'link_tip': '.tip', 'end_link': '.tip'}


__getattr__ = lazy_exports(__name__, _LAZY)


__all__ = list(_LAZY)
