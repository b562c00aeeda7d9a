"""Motion programs: joint positions as functions of time, sampled like recorded /joint_states.

A :class:`Motion` comes from the tutorial's animation node, formulas of ``t``, a fixed pose or
a waypoint file (:mod:`.sources`); :func:`sample` turns it into :class:`JointStates`
(:mod:`.core`); :func:`check_limits` and :func:`waypoint_speeds` find where joints go past their
limits (:mod:`.limits`, :mod:`.waypoints`); :mod:`.states_io` writes and reads the samples.

Modules import one way: core <- interpolation, limits <- waypoints <- sources; states_io <- core.
"""

from __future__ import annotations

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
    spec_kind,
    tutorial_motion,
    waypoint_motion,
)
from .states_io import read_states, states_to_csv, states_to_json, states_to_messages
from .waypoints import (
    WAYPOINT_SUFFIXES,
    SegmentSpeed,
    describe_segment,
    read_waypoints,
    waypoint_speeds,
)

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
