"""BK2xx: joint types, axes and limits, and numbers that are not numbers."""

from __future__ import annotations

import math
from collections.abc import Iterator

from ..findings.registry import ERROR, INFO, WARNING, Hit, hit, rule
from ..model.robot import MOVABLE_TYPES, Joint
from .context import Context
from .solids import finite, number
from .structure import comma_fix

LIMITED_TYPES = ("revolute", "prismatic")
AXIS_TYPES = ("revolute", "continuous", "prismatic", "planar")
UNIT_TOLERANCE = 1e-3
MAX_PRISMATIC_TRAVEL = 10.0  # metres: beyond this, the limits were almost surely written in mm or cm
MAX_REVOLUTE_ANGLE = 2 * math.pi + 0.01  # radians: beyond one turn either way, probably degrees


def unit(joint: Joint) -> str:
    """The unit of a joint's position: metres for prismatic joints, radians otherwise."""
    return "m" if joint.type == "prismatic" else "rad"


@rule("BK200", "limit-missing", ERROR)
def limit_missing(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        if joint.type in LIMITED_TYPES and joint.limit is None:
            yield hit("joint", joint.name, joint.line, joint.type or "", joint=joint.name, type=joint.type)


@rule("BK201", "limit-effort-velocity-missing", ERROR)
def limit_effort_velocity_missing(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        limit = joint.limit
        if limit is None:
            continue
        missing = [attribute for attribute, value in (("effort", limit.effort), ("velocity", limit.velocity))
                   if value is None and (limit.line, attribute) not in ctx.unreadable]
        if missing:
            yield hit("joint", joint.name, limit.line, joint=joint.name, missing=missing,
                      attributes=" ".join(f'{a}="{"10" if a == "effort" else "1.0"}"' for a in missing))


@rule("BK202", "limit-lower-above-upper", ERROR)
def limit_lower_above_upper(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        if joint.type in LIMITED_TYPES and joint.limit is not None:
            lower, upper = joint.bounds()
            if finite(lower, upper) and lower > upper:
                yield hit("joint", joint.name, joint.limit.line, joint=joint.name, lower=lower,
                          upper=upper, unit=unit(joint))


@rule("BK203", "limit-range-empty", WARNING)
def limit_range_empty(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        limit = joint.limit
        if joint.type in LIMITED_TYPES and limit is not None:
            lower, upper = joint.bounds()
            if finite(lower, upper) and lower == upper:
                unwritten = limit.lower is None and limit.upper is None
                if unwritten and any((limit.line, a) in ctx.unreadable for a in ("lower", "upper")):
                    continue  # an unreadable number, already reported by BK123
                yield hit("joint", joint.name, limit.line, "unwritten" if unwritten else "",
                          joint=joint.name, value=lower, unit=unit(joint))


def _axis_joints(ctx: Context) -> Iterator[tuple[Joint, tuple[float, float, float], float]]:
    for joint in ctx.robot.joints:
        if joint.type in AXIS_TYPES and joint.axis is not None and finite(*joint.axis):
            yield joint, joint.axis, math.hypot(*joint.axis)  # no overflow at 1e308, no underflow to 0


@rule("BK204", "axis-zero", ERROR)
def axis_zero(ctx: Context) -> Iterator[Hit]:
    for joint, _axis, norm in _axis_joints(ctx):
        if norm == 0.0:
            yield hit("joint", joint.name, joint.axis_line or joint.line, joint=joint.name, type=joint.type)


@rule("BK205", "axis-not-unit", WARNING)
def axis_not_unit(ctx: Context) -> Iterator[Hit]:
    for joint, axis, norm in _axis_joints(ctx):
        if norm > 0.0 and abs(norm - 1.0) > UNIT_TOLERANCE:
            direction = " ".join(f"{v / norm:.4g}" if v else "0" for v in axis)
            yield hit("joint", joint.name, joint.axis_line or joint.line, joint=joint.name, axis=axis,
                      norm=norm, unit=direction)


@rule("BK206", "axis-unreadable", ERROR)
def axis_unreadable(ctx: Context) -> Iterator[Hit]:
    for kind in ("missing_attribute", "bad_number"):
        for issue in ctx.issues(kind):
            if issue.element == "axis":
                variant, fixed, comma = comma_fix(issue.value or "", 3)
                yield hit("joint", issue.name, issue.line, "missing" if kind == "missing_attribute" else variant,
                          joint=issue.name, value=issue.value, fixed=fixed, comma=comma, part=issue.part)


@rule("BK207", "number-not-finite", ERROR)
def number_not_finite(ctx: Context) -> Iterator[Hit]:
    for issue in ctx.issues("non_finite"):
        element, name = ctx.owner(issue)
        yield hit(element, name, issue.line, tag=issue.element, attribute=issue.attribute, value=issue.value,
                  part=issue.part)


@rule("BK208", "continuous-with-bounds", WARNING)
def continuous_with_bounds(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        limit = joint.limit
        if joint.type == "continuous" and limit is not None and (limit.lower is not None or limit.upper is not None):
            written = [a for a, v in (("lower", limit.lower), ("upper", limit.upper)) if v is not None]
            yield hit("joint", joint.name, limit.line, joint=joint.name, attributes=written)


@rule("BK209", "limit-not-positive", WARNING)
def limit_not_positive(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        limit = joint.limit
        if joint.type not in MOVABLE_TYPES or limit is None:
            continue
        for attribute, value in (("effort", limit.effort), ("velocity", limit.velocity)):
            if value is not None and math.isfinite(value) and value <= 0:
                yield hit("joint", joint.name, limit.line, attribute, joint=joint.name, value=value)


@rule("BK210", "prismatic-travel-implausible", WARNING)
def prismatic_travel_implausible(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        if joint.type == "prismatic" and joint.limit is not None:
            lower, upper = joint.bounds()
            if finite(lower, upper) and upper - lower > MAX_PRISMATIC_TRAVEL:
                yield hit("joint", joint.name, joint.limit.line, joint=joint.name, travel=upper - lower,
                          lower=lower, upper=upper, lower_m=lower / 1000, upper_m=upper / 1000,
                          limit=MAX_PRISMATIC_TRAVEL)


MULTI_TURN = 4 * math.pi  # real joints turn up to two turns each way (ANYmal: ±3π, IRB 140 axis 6: ±400°)


def looks_like_degrees(lower: float, upper: float) -> bool:
    """Limits that are surely degrees: beyond two turns, or beyond one turn in whole numbers
    (±90, ±180, ±10...). Multi-turn limits in radians (±3π, ±6.98) are not whole numbers."""
    largest = max(abs(lower), abs(upper))
    if largest > MULTI_TURN:
        return True
    return largest > MAX_REVOLUTE_ANGLE and float(lower).is_integer() and float(upper).is_integer()


@rule("BK211", "revolute-limit-in-degrees", WARNING)
def revolute_limit_in_degrees(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        if joint.type == "revolute" and joint.limit is not None:
            lower, upper = joint.bounds()
            if finite(lower, upper) and looks_like_degrees(lower, upper):
                yield hit("joint", joint.name, joint.limit.line, joint=joint.name, lower=lower, upper=upper,
                          lower_rad=number(round(math.radians(lower), 4)),
                          upper_rad=number(round(math.radians(upper), 4)))


@rule("BK212", "fixed-joint-with-motion", WARNING)
def fixed_joint_with_motion(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        if joint.type != "fixed":
            continue
        has_axis, has_limit = joint.axis_line is not None, joint.limit is not None
        if has_axis or has_limit:
            variant = "both" if has_axis and has_limit else ("axis" if has_axis else "limit")
            line = joint.axis_line if has_axis else joint.limit.line  # type: ignore[union-attr]
            yield hit("joint", joint.name, line or joint.line, variant, joint=joint.name)


@rule("BK213", "axis-default", INFO)
def axis_default(ctx: Context) -> Iterator[Hit]:
    for joint in ctx.robot.joints:
        if joint.type in MOVABLE_TYPES and joint.axis_line is None:
            variant = "prismatic" if joint.type == "prismatic" else ""
            yield hit("joint", joint.name, joint.line, variant, joint=joint.name)


SAFETY_ATTRIBUTES = ("soft_lower_limit", "soft_upper_limit", "k_position", "k_velocity")


@rule("BK230", "safety-controller-unreadable", ERROR)
def safety_controller_unreadable(ctx: Context) -> Iterator[Hit]:
    """urdfdom refuses the whole file when a <safety_controller> number cannot be read or k_velocity is missing."""
    from ..model.robot import parse_number

    for joint in ctx.robot.joints:
        safety = joint.safety
        if safety is None:
            continue
        if "k_velocity" not in safety.attributes:
            yield hit("joint", joint.name, safety.line or joint.line, "missing", joint=joint.name,
                      attribute="k_velocity", value="")
        for attribute in SAFETY_ATTRIBUTES:
            value = safety.attributes.get(attribute)
            if value is not None and parse_number(value.strip()) is None:
                yield hit("joint", joint.name, safety.line or joint.line, "", joint=joint.name,
                          attribute=attribute, value=value)
