"""Motion programs: joint positions as functions of time, sampled like recorded /joint_states.

A :class:`Motion` comes from the tutorial's animation node, formulas of ``t``, a fixed pose or
a waypoint file (:mod:`.sources`); :func:`sample` turns it into :class:`JointStates`
(:mod:`.core`); :func:`check_limits` and :func:`waypoint_speeds` find where joints go past their
limits (:mod:`.limits`, :mod:`.waypoints`); :mod:`.states_io` writes and reads the samples.

Modules import one way: core <- interpolation, limits, specs <- waypoints <- sources; states_io <- core;
core, limits, specs <- formula_limits (a formula followed without numpy, for BK623).
"""

from __future__ import annotations

from typing import TYPE_CHECKING

# name -> the module that defines it: each is imported the first time one of its names is asked
# for (PEP 562), so that BK623, which needs only core, limits and specs, loads no waypoint reader,
# bag reader or interpolation (issue 43)
_WHERE = {
    **dict.fromkeys(("DEFAULT_DURATION", "DEFAULT_RATE", "MAX_VALUES", "JointStates", "Motion", "Track",
                     "Waypoints", "sample", "sample_count", "sample_loop"), "core"),
    "INTERPOLATIONS": "interpolation",
    **dict.fromkeys(("TOLERANCE", "LimitViolation", "check_limits", "clamp", "describe_violation", "joint_unit",
                     "value_in_degrees"), "limits"),
    **dict.fromkeys(("TUTORIAL_FORMULAS", "formula_motion", "motion_from_specs", "pose_motion", "tutorial_motion",
                     "waypoint_motion"), "sources"),
    **dict.fromkeys(("WAYPOINT_SUFFIXES", "spec_kind"), "specs"),
    **dict.fromkeys(("read_states", "states_to_csv", "states_to_json", "states_to_messages"), "states_io"),
    **dict.fromkeys(("SegmentSpeed", "describe_segment", "read_waypoints", "waypoint_speeds"), "waypoints"),
}

if TYPE_CHECKING:
    from .core import (
        DEFAULT_DURATION,
        DEFAULT_RATE,
        MAX_VALUES,
        JointStates,
        Motion,
        Track,
        Waypoints,
        sample,
        sample_count,
        sample_loop,
    )
    from .interpolation import INTERPOLATIONS
    from .limits import (
        TOLERANCE,
        LimitViolation,
        check_limits,
        clamp,
        describe_violation,
        joint_unit,
        value_in_degrees,
    )
    from .sources import (
        TUTORIAL_FORMULAS,
        formula_motion,
        motion_from_specs,
        pose_motion,
        tutorial_motion,
        waypoint_motion,
    )
    from .specs import WAYPOINT_SUFFIXES, spec_kind
    from .states_io import read_states, states_to_csv, states_to_json, states_to_messages
    from .waypoints import SegmentSpeed, describe_segment, read_waypoints, waypoint_speeds


def __getattr__(name: str) -> object:
    if name not in _WHERE:
        raise AttributeError(f"module {__name__!r} has no attribute {name!r}")
    import importlib

    value = getattr(importlib.import_module(f".{_WHERE[name]}", __name__), name)
    globals()[name] = value
    return value


__all__ = [
    "DEFAULT_DURATION",
    "DEFAULT_RATE",
    "INTERPOLATIONS",
    "MAX_VALUES",
    "TOLERANCE",
    "TUTORIAL_FORMULAS",
    "WAYPOINT_SUFFIXES",
    "JointStates",
    "LimitViolation",
    "Motion",
    "SegmentSpeed",
    "Track",
    "Waypoints",
    "check_limits",
    "clamp",
    "describe_segment",
    "describe_violation",
    "formula_motion",
    "joint_unit",
    "value_in_degrees",
    "motion_from_specs",
    "pose_motion",
    "read_states",
    "read_waypoints",
    "sample",
    "sample_count",
    "sample_loop",
    "spec_kind",
    "states_to_csv",
    "states_to_json",
    "states_to_messages",
    "tutorial_motion",
    "waypoint_motion",
    "waypoint_speeds",
]
