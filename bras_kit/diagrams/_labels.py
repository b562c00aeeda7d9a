"""Numbers and joint facts as short text, shared by the tree, the frame diagram and the plots."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

from ..core.i18n import say
from ..core.message import M
from ..kinematics.frames import TFTree
from ..model.robot import Joint
from ..motion import joint_unit


def format_number(value: float | None) -> str:
    """A short, stable rendering of a number: 4 significant digits, no ``-0``, ``?`` when missing."""
    if value is None:
        return "?"
    if not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if abs(value) < 1e-12:
        return "0"
    return f"{value:.4g}"


def format_vector(values: Sequence[float] | None) -> str:
    return " ".join(format_number(v) for v in values) if values is not None else "?"


def beyond_limits(joint: Joint, value: float) -> bool:
    lower, upper = joint.bounds()
    return bool(value < lower or value > upper)


def _range_text(joint: Joint, separator: str = "..", lang: str | None = None) -> str | None:
    """``-1.57..1.57`` for a bounded joint, None when there is nothing to show."""
    if joint.type in ("revolute", "prismatic"):
        if joint.limit is None:
            return say(M("no <limit>"), lang)
        return f"{format_number(joint.limit.lower)}{separator}{format_number(joint.limit.upper)}"
    return None


def _axis_text(joint: Joint, lang: str | None = None) -> str:
    text = format_vector(joint.axis_or_default)
    return text if joint.axis is not None else text + " (" + say(M("default"), lang) + ")"


def joint_summary(joint: Joint, lang: str | None = None) -> str:
    """One line about a joint: ``revolute, axis 0 1 0, -1.57..1.57``."""
    parts = [joint.type or say(M("no type"), lang)]
    if joint.type in ("revolute", "continuous", "prismatic"):
        parts.append(say(M("axis"), lang) + " " + _axis_text(joint, lang))
    limits = _range_text(joint, lang=lang)
    if limits is not None:
        parts.append(limits)
    if joint.mimic is not None:
        parts.append(say(M("mimics {joint}", joint=joint.mimic.joint), lang))
    return ", ".join(parts)


def joint_label_lines(joint: Joint, value: float | None = None, lang: str | None = None) -> list[str]:
    """The detail lines under a joint's name in the frame diagram (origin, axis, limits, value)."""
    lines = [joint.type or say(M("no type"), lang)]
    if joint.mimic is not None:
        lines[0] += (", " + say(M("mimics {joint}", joint=joint.mimic.joint), lang) + f" x{format_number(joint.mimic.multiplier)}"
                     f" {'+' if joint.mimic.offset >= 0 else '-'}{format_number(abs(joint.mimic.offset))}")
    lines.append("xyz " + format_vector(joint.origin.xyz))
    lines.append("rpy " + format_vector(joint.origin.rpy))
    if joint.type in ("revolute", "continuous", "prismatic"):
        lines.append(say(M("axis"), lang) + " " + _axis_text(joint, lang))
    limits = _range_text(joint, " .. ", lang)
    if limits is not None:
        lines.append(f"{say(M('limits'), lang)} {limits} {joint_unit(joint)}" if joint.limit is not None else limits)
    elif joint.type == "continuous":
        lines.append(say(M("no position limits"), lang))
    if joint.limit is not None and joint.type in ("revolute", "continuous", "prismatic"):
        lines.append(f"{say(M('effort'), lang)} {format_number(joint.limit.effort)}, "
                     f"{say(M('velocity'), lang)} {format_number(joint.limit.velocity)}")
    if value is not None:
        text = f"{say(M('value'), lang)} {format_number(value)} {joint_unit(joint)}"
        if joint.type != "prismatic":
            text += f" ({format_number(math.degrees(value))} deg)"
        if beyond_limits(joint, value):
            text += " " + say(M("OUT OF LIMITS"), lang)
        lines.append(text)
    return lines


def joint_values(tree: TFTree, config: Mapping[str, float] | None) -> dict[str, float]:
    """Every driven joint's value for ``config``: the movable ones, and mimic joints from their leader.

    Unknown or fixed joint names in ``config`` raise :class:`~bras_kit.core.errors.ParameterError`.
    """
    q = tree.config_vector(config)
    values = {name: float(v) for name, v in zip(tree.dof, q)}
    for joint in tree.robot.joints:  # file order
        if joint.mimic is None or joint.name is None:
            continue
        # the tree has already followed the mimic chain to the configuration column that drives it
        motion = tree.joint_motion(tree.index(joint.child or ""))
        if motion.kind != "fixed":
            values[joint.name] = motion.gain * values[tree.dof[motion.column]] + motion.offset
    return values
