"""BK3xx: the tutorial's "Pièges fréquents" that a file (and a pose or motion) can show.

* "Segments mal positionnés": a joint that is not at the end of its parent's segment (BK301),
  or a segment whose visual does not start at its own joint (BK302).
* "Les articulations dépassent": a pose or a motion outside the joint limits (BK303-BK305).
* "RViz reste vide" / "le robot ne bouge pas", as far as the file can cause them (BK306, BK307).

A "segment" is a link with exactly one box or cylinder visual that is clearly longer along one
axis than the others; only joints that move (revolute, continuous, prismatic) are checked, so
sensor mounts and tool frames on fixed joints may sit anywhere. A joint off to the side of its
parent's shape is reported only when the child's shape does not touch the parent's either
(links side by side on one axle, or a wheel under its chassis, are designs, not mistakes).
"""

from __future__ import annotations

import math
from collections.abc import Iterator
from typing import Any

from ..findings.registry import ERROR, WARNING, Hit, hit, rule
from ..model.robot import MOVABLE_TYPES, Joint, Link, Visual
from .context import Context
from .joints import unit
from .solids import AXES, Bounds, finite, number, vector

LIMIT_TOLERANCE = 1e-9


def tolerance(bounds: Bounds) -> float:
    """How far a joint may sit from a segment end: 2 mm, or 5 % of the shape's longest side."""
    return max(0.002, 0.05 * max(bounds.lengths))


NEAR_LENGTH = 0.25  # a child joint this far past a segment's ends (in segment lengths) is not on it


def origin_xml(xyz: tuple[float, ...], rpy: tuple[float, ...]) -> str:
    text = f'<origin xyz="{vector(xyz)}"'
    if any(rpy):
        text += f' rpy="{vector(rpy)}"'
    return text + "/>"


def _direction(ctx: Context, link: Link, bounds: Bounds, k: int, tol: float) -> int:
    """Which way a segment runs from its joint along axis k: towards its child joints if they
    say, otherwise towards its farther end (+1 when centred)."""
    for child in ctx.graph.children.get(link.name or "", []):
        if child.type in MOVABLE_TYPES and finite(*child.origin.xyz) and abs(child.origin.xyz[k]) > tol:
            return 1 if child.origin.xyz[k] > 0 else -1
    return 1 if abs(bounds.hi[k]) >= abs(bounds.lo[k]) else -1


def _segment_end(ctx: Context, link: Link, bounds: Bounds, k: int, at: float, tol: float) -> tuple[float, ...]:
    """Where a child joint may sit along axis k of ``link``'s segment (one or two acceptable values)."""
    if link.name not in ctx.graph.parent_joint:  # a root: the face on the joint's side
        return (bounds.hi[k] if at >= bounds.centre[k] else bounds.lo[k],)
    s = _direction(ctx, link, bounds, k, tol)
    far, near = (bounds.hi[k], bounds.lo[k]) if s > 0 else (bounds.lo[k], bounds.hi[k])
    if abs(near) <= tol:
        return (far,)
    # The segment does not start at its own joint (BK302 says so): accept the end as drawn,
    # but propose the end it will have once its visual starts at the joint.
    return (s * bounds.lengths[k], far)


@rule("BK301", "joint-not-at-segment-end", WARNING)
def joint_not_at_segment_end(ctx: Context) -> Iterator[Hit]:
    """The tutorial's heuristic, so a warning, and only where the parent looks like its segments:
    one box or cylinder clearly longer along one axis, the child joint on that axis and within
    or near its length. Prismatic joints are left out (a carriage sits anywhere on its rail), and
    so are joints beside the shape (motors on a chassis, a wheel under a cart)."""
    for joint in ctx.robot.joints:
        if joint.type not in ("revolute", "continuous") or not finite(*joint.origin.xyz, *joint.origin.rpy):
            continue
        parent = ctx.links.get(joint.parent or "")
        shape = ctx.shape(parent) if parent is not None else None
        if parent is None or shape is None:
            continue
        element, bounds = shape
        p = joint.origin.xyz
        k = bounds.long_axis()
        tol = tolerance(bounds)
        inside = tuple(min(max(p[i], bounds.lo[i]), bounds.hi[i]) for i in range(3))
        outside = math.dist(p, inside)
        side = max(0.001, 0.02 * max(bounds.lengths))  # off the axis by more than this: beside the segment
        on_axis = k is not None and all(bounds.lo[i] - side <= p[i] <= bounds.hi[i] + side for i in range(3) if i != k)
        tutorial_like = k is not None and _starts_at_its_joint(ctx, parent, bounds, k, tol)
        if on_axis:
            assert k is not None
            length = bounds.lengths[k]
            if not bounds.lo[k] - NEAR_LENGTH * length <= p[k] <= bounds.hi[k] + NEAR_LENGTH * length \
                    and not (tutorial_like and _apart(ctx, joint, bounds, tol)):
                continue  # far past the shape of something that is not the tutorial's segment
            ends = _segment_end(ctx, parent, bounds, k, p[k], tol)
            if any(abs(p[k] - end) <= tol for end in ends):
                continue
            expected = tuple(ends[0] if i == k else p[i] for i in range(3))
            beyond = outside > tol
            yield hit("joint", joint.name, joint.origin.line or joint.line, "beyond" if beyond else "short",
                      joint=joint.name, link=parent.name, tag=_tag(element), coord=f"{AXES[k]}={number(p[k])}",
                      distance=outside if beyond else abs(ends[0] - p[k]), span=bounds.span(k),
                      origin=origin_xml(expected, joint.origin.rpy), expected=expected)
        elif tutorial_like and _apart(ctx, joint, bounds, tol):
            # beside the tutorial's segment, the child's shape away from it: the segment's end is meant
            assert k is not None
            end = _segment_end(ctx, parent, bounds, k, p[k], tol)[0]
            expected = tuple(end if i == k else bounds.centre[i] for i in range(3))
            yield hit("joint", joint.name, joint.origin.line or joint.line, "beside",
                      joint=joint.name, link=parent.name, tag=_tag(element), xyz=tuple(p),
                      distance=math.dist(p, expected), span=bounds.span(k),
                      origin=origin_xml(expected, joint.origin.rpy), expected=expected)
        elif outside > tol and _apart(ctx, joint, bounds, tol) and _child_is_a_segment(ctx, joint, tol):
            # a segment drawn the tutorial's way, hung in the air away from its parent's body
            yield hit("joint", joint.name, joint.origin.line or joint.line, "detached",
                      joint=joint.name, link=parent.name, child=joint.child, tag=_tag(element), xyz=tuple(p),
                      distance=outside, origin=origin_xml(inside, joint.origin.rpy), expected=inside)


def _child_is_a_segment(ctx: Context, joint: Joint, tol: float) -> bool:
    child = ctx.links.get(joint.child or "")
    shape = ctx.shape(child) if child is not None else None
    if child is None or shape is None:
        return False
    k = shape[1].long_axis()
    return k is not None and _starts_at_its_joint(ctx, child, shape[1], k, tolerance(shape[1]))


def _starts_at_its_joint(ctx: Context, link: Link, bounds: Bounds, k: int, tol: float) -> bool:
    """The tutorial's segment: a non-root link whose shape starts at its own joint and runs along k,
    centred on the other two axes."""
    if link.name not in ctx.graph.parent_joint:
        return False
    if any(abs(bounds.centre[i]) > tol for i in range(3) if i != k):
        return False
    return min(abs(bounds.lo[k]), abs(bounds.hi[k])) <= tol


def _apart(ctx: Context, joint: Joint, bounds: Bounds, tol: float) -> bool:
    """The child link's one shape, placed by ``joint``, does not touch the parent's ``bounds``
    (a child without a shape of its own counts as apart when the joint itself is off the shape)."""
    child = ctx.links.get(joint.child or "")
    shape = ctx.shape(child) if child is not None else None
    if shape is None:
        return False
    return shape[1].moved(joint.origin).gap(bounds) > tol


def _tag(element: object) -> str:
    geometry = getattr(element, "geometry", None)
    return f"<{geometry.kind}>" if geometry is not None else "?"


@rule("BK302", "visual-not-at-joint", WARNING)
def visual_not_at_joint(ctx: Context) -> Iterator[Hit]:
    for link in ctx.robot.links:
        joint = ctx.graph.parent_joint.get(link.name or "")
        if joint is None or joint.type not in MOVABLE_TYPES or not link.visuals:
            continue
        shape = ctx.shape(link)
        if shape is None or not isinstance(shape[0], Visual):
            continue
        visual, bounds = shape
        k = bounds.long_axis()
        if k is None:
            continue
        tol = tolerance(bounds)
        s = _direction(ctx, link, bounds, k, tol)
        near = bounds.lo[k] if s > 0 else bounds.hi[k]
        if abs(near) <= tol:
            continue
        if abs(bounds.centre[k]) <= tol:
            variant = "centred"
        else:
            variant = "gap" if near * s > 0 else "overlap"
        xyz = tuple(v - near if i == k else v for i, v in enumerate(visual.origin.xyz))
        yield hit("link", link.name, visual.origin.line or visual.line, variant, link=link.name,
                  joint=joint.name, tag=_tag(visual), distance=abs(near), span=bounds.span(k),
                  origin=origin_xml(xyz, visual.origin.rpy), expected=xyz)


def _limit_line(joint: Joint) -> int | None:
    return (joint.limit.line if joint.limit is not None else None) or joint.line


@rule("BK303", "pose-outside-limits", ERROR)
def pose_outside_limits(ctx: Context) -> Iterator[Hit]:
    for name, value in (ctx.pose or {}).items():
        joint = ctx.joints.get(name)
        if joint is None:
            continue
        lower, upper = joint.bounds()
        if value > upper + LIMIT_TOLERANCE or value < lower - LIMIT_TOLERANCE:
            from ..motion import value_in_degrees

            above = value > upper
            side = "upper" if above else "lower"
            variant = f"degrees-{side}" if value_in_degrees(joint, value) else side
            yield hit("joint", name, _limit_line(joint), variant, joint=name, degrees=round(math.radians(value), 4),
                      value=float(value), bound=upper if above else lower,
                      excess=value - upper if above else lower - value, lower=lower, upper=upper,
                      unit=unit(joint))


def _violations(ctx: Context, kind: str) -> Iterator[tuple[Joint, Any]]:
    """Limit violations of the motion being checked (first and worst per joint and side)."""
    if ctx.states is None:
        return
    from ..motion import check_limits

    for violation in check_limits(ctx.robot, ctx.states):
        joint = ctx.joints.get(violation.joint)
        if violation.kind == kind and joint is not None:
            yield joint, violation


@rule("BK304", "motion-outside-limits", ERROR)
def motion_outside_limits(ctx: Context) -> Iterator[Hit]:
    for joint, v in _violations(ctx, "position"):
        lower, upper = joint.bounds()
        yield hit("joint", joint.name, _limit_line(joint), v.side, joint=joint.name, time=v.time,
                  bound=v.bound, worst=round(v.excess, 3), worst_time=v.peak_time, worst_value=round(v.value, 3),
                  samples=v.samples, lower=lower, upper=upper, unit=unit(joint))


@rule("BK305", "motion-too-fast", WARNING)
def motion_too_fast(ctx: Context) -> Iterator[Hit]:
    for joint, v in _violations(ctx, "velocity"):
        yield hit("joint", joint.name, _limit_line(joint), joint=joint.name, time=v.time,
                  speed=round(abs(v.value), 3), worst_time=v.peak_time, limit=v.bound, unit=unit(joint) + "/s")


@rule("BK306", "no-movable-joint", WARNING)
def no_movable_joint(ctx: Context) -> Iterator[Hit]:
    if ctx.robot.links and not any(j.type in MOVABLE_TYPES for j in ctx.robot.joints):
        yield hit("robot", ctx.robot.name, ctx.robot.line, "fixed" if ctx.robot.joints else "",
                  robot=ctx.robot.name, joints=len(ctx.robot.joints))


@rule("BK307", "nothing-to-show", WARNING)
def nothing_to_show(ctx: Context) -> Iterator[Hit]:
    links = ctx.robot.links
    if links and not any(link.visuals for link in links):
        with_collisions = any(link.collisions for link in links)
        yield hit("robot", ctx.robot.name, ctx.robot.line, "collisions" if with_collisions else "",
                  robot=ctx.robot.name, first=links[0].name)


@rule("BK308", "moving-leaf-invisible", WARNING)
def moving_leaf_invisible(ctx: Context) -> Iterator[Hit]:
    """A link at the end of a moving joint, with no child and no <visual>: its slider moves nothing
    on screen. Only checked when the robot shows something elsewhere (BK307 covers the rest)."""
    if not any(link.visuals for link in ctx.robot.links):
        return
    for link in ctx.robot.links:
        joint = ctx.graph.parent_joint.get(link.name or "")
        if joint is None or joint.type not in MOVABLE_TYPES or link.visuals:
            continue
        if ctx.graph.children.get(link.name or ""):
            continue
        yield hit("link", link.name, link.line, link=link.name, joint=joint.name)
