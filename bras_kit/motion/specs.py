"""What a motion spec is (``tutorial``, ``JOINT=FORMULA``, a waypoint file, a ROS 2 bag), read
without loading any motion: the package rule BK623 asks this much of a node's formulas."""

from __future__ import annotations

import os

from ..core.errors import ParameterError
from ..core.message import M

WAYPOINT_SUFFIXES = (".csv", ".json", ".yaml", ".yml")


def split_formula(spec: str) -> tuple[str, str, str]:
    """``"epaule = 0.8*sin(t)"`` -> (joint, formula, the text before the formula)."""
    name, sep, formula = spec.partition("=")
    if not sep or not name.strip():
        raise ParameterError(M("'{spec}' is not JOINT=FORMULA", spec=spec),
                             hint=M("write e.g. epaule=0.8*sin(t) (the time is t, in seconds)"))
    return name.strip(), formula, spec[: len(name) + 1]


def spec_kind(spec: str) -> str:
    """"tutorial", "file" (a waypoint file), "bag" (a ROS 2 bag) or "formula"; else a ParameterError."""
    text = spec.strip()
    if text.lower() == "tutorial":
        return "tutorial"
    if text.lower().rstrip("/").endswith((".mcap", ".db3", "metadata.yaml")) or (
            "=" not in text and os.path.isfile(os.path.join(text, "metadata.yaml"))):
        return "bag"
    if text.lower().endswith(WAYPOINT_SUFFIXES):
        return "file"
    if "=" in text:
        return "formula"
    raise ParameterError(M("'{spec}' is not a motion", spec=spec),
                         hint=M("give 'tutorial', JOINT=FORMULA (e.g. epaule=0.8*sin(t)), "
                                "a waypoint file (.csv, .json, .yaml) or a ROS 2 bag (folder, .mcap, .db3)"))
