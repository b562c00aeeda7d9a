"""BK5xx: mass and inertia, as a physics simulator (Gazebo) will read them.

RViz ignores <inertial> entirely; these rules matter once the arm is simulated. Expected
values come from the link's one primitive shape taken as a uniform solid of the given mass.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
else:
    from ..core.lazy_numpy import np

from ..findings.registry import ERROR, INFO, WARNING, Hit, hit, rule
from ..model.robot import MOVABLE_TYPES, Inertial, Link
from .context import Context
from .solids import finite, number, rotation, solid_moments, vector

MISMATCH_FACTOR = 2.0
KEYS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


@dataclass(frozen=True)
class Body:
    """A link's readable inertia: the tensor and its principal moments (ascending)."""

    link: Link
    inertial: Inertial
    tensor: np.ndarray
    moments: tuple[float, float, float]
    positive_definite: bool


def bodies(ctx: Context) -> list[Body]:
    """Every link whose six inertia values are finite numbers, moments computed in one batch."""
    return ctx.derived("inertia.bodies", _bodies)


def _bodies(ctx: Context) -> list[Body]:
    readable = [(link, inertial) for link, inertial in _inertials(ctx)
                if finite(*(inertial.inertia.get(k) for k in KEYS))]
    if not readable:
        return []
    tensors = np.array([inertial.matrix() for _, inertial in readable], dtype=float)
    # scaled so that huge values cannot overflow; eigenvalues scale back linearly
    scale = np.abs(tensors).max(axis=(1, 2))
    scale[scale == 0] = 1.0
    moments = np.linalg.eigvalsh(tensors / scale[:, None, None]) * scale[:, None]
    definite = (moments[:, 2] > 0) & (moments[:, 0] > 1e-12 * moments[:, 2])
    return [Body(link, inertial, tensors[i], tuple(moments[i].tolist()), bool(definite[i]))
            for i, (link, inertial) in enumerate(readable)]


def _inertials(ctx: Context) -> Iterator[tuple[Link, Inertial]]:
    for link in ctx.robot.links:
        if link.inertial is not None:
            yield link, link.inertial


def rigid_group(ctx: Context, link: Link) -> tuple[str, list[str]]:
    """The link that heads ``link``'s rigid body (climbing fixed joints) and every link fused into it.

    ROS tools (and physics engines) merge links joined by fixed joints into one body, so mass and
    inertia are judged on that fused body, not on each frame link of it.
    """
    parent_joint, children = ctx.graph.parent_joint, ctx.graph.children
    head = link.name or ""
    while head in parent_joint and parent_joint[head].type == "fixed":
        head = parent_joint[head].parent or ""
    members, stack = [], [head]
    while stack:
        name = stack.pop()
        members.append(name)
        stack.extend(j.child or "" for j in children.get(name, []) if j.type == "fixed")
    return head, members


def moves(ctx: Context, head: str) -> bool:
    """Whether the body headed by ``head`` moves relative to the world (it hangs from a moving joint)."""
    joint = ctx.graph.parent_joint.get(head)
    return joint is not None and joint.type != "fixed"


def _fused_has(ctx: Context, link: Link, has: object) -> bool:
    """Whether any link of ``link``'s rigid body passes ``has(link)``, or the body does not move."""
    head, members = rigid_group(ctx, link)
    if not moves(ctx, head):
        return True
    return any(has(ctx.links[name]) for name in members if name in ctx.links)  # type: ignore[operator]


def _has_mass(link: Link) -> bool:
    mass = link.inertial.mass if link.inertial is not None else None
    return mass is not None and math.isfinite(mass) and mass > 0


@rule("BK500", "mass-not-positive", ERROR)
def mass_not_positive(ctx: Context) -> Iterator[Hit]:
    """Negative mass is always wrong; zero mass only on a moving body whose fused links weigh nothing
    (frame links such as ``tool0`` or ``panda_hand_tcp``, and the fixed base, may be massless)."""
    for link, inertial in _inertials(ctx):
        mass = inertial.mass
        if mass is None or not math.isfinite(mass) or mass > 0:
            continue
        if mass < 0 or not _fused_has(ctx, link, _has_mass):
            yield hit("link", link.name, inertial.line, link=link.name, mass=mass)


@rule("BK501", "inertia-not-positive-definite", ERROR)
def inertia_not_positive_definite(ctx: Context) -> Iterator[Hit]:
    """A tensor with a negative moment is always wrong. A zero or flat one (a moment of 0) is
    wrong only on a moving body none of whose fused links has a positive-definite inertia: the
    root of a fixed-base robot and frame links fused into a heavier link need none."""
    definite = {body.link.name for body in bodies(ctx) if body.positive_definite}
    for body in bodies(ctx):
        if body.positive_definite:
            continue
        largest = max(abs(m) for m in body.moments)
        negative = body.moments[0] < -max(1e-9 * largest, 1e-12)  # not rounding noise of a zero tensor
        zero = not body.tensor.any()
        if not negative and _fused_has(ctx, body.link, lambda link: link.name in definite):
            continue
        if negative and _fused_appendage(ctx, body, definite):
            continue  # BK508: a simulator merges it into a valid body
        yield hit("link", body.link.name, body.inertial.line, "zero" if zero else "", link=body.link.name,
                  moments=body.moments)


GROSS_BREACH = 1.5  # largest moment over the sum of the two others: beyond this, no rounding explains it


def _fused_appendage(ctx: Context, body: Body, definite: set[str | None]) -> bool:
    """A massless link (under a thousandth of the rest of its body's mass) fused by fixed joints into a
    body that has a valid inertia (TIAGo's antennas):
    physics engines add its tensor into that body's, so a tiny defect of its own changes nothing."""
    head, members = rigid_group(ctx, body.link)
    others = [name for name in members if name != body.link.name]
    if head == body.link.name or not any(name in definite for name in others):
        return False
    mass = body.inertial.mass or 0.0
    inertials = [ctx.links[name].inertial for name in others if name in ctx.links]
    rest = sum(float(i.mass or 0.0) for i in inertials if i is not None)
    return 0 <= mass <= 1e-3 * rest  # massless next to the body it is fused into (TIAGo's 1 mg antennas)


def _moving_main_body(ctx: Context, body: Body) -> bool:
    """The link heads a moving body (a simulator simulates its inertia as written)."""
    head, _ = rigid_group(ctx, body.link)
    return head == body.link.name and moves(ctx, head)


def _gross(body: Body) -> bool:
    a, b, c = body.moments
    return c > GROSS_BREACH * (a + b)


@rule("BK502", "inertia-triangle-inequality", WARNING)
def inertia_triangle_inequality(ctx: Context) -> Iterator[Hit]:
    for body in bodies(ctx):
        a, b, c = body.moments
        if body.positive_definite and a + b < c * (1 - 1e-9) and not (_gross(body) and _moving_main_body(ctx, body)):
            yield hit("link", body.link.name, body.inertial.line, link=body.link.name, a=a, b=b, c=c)


@rule("BK507", "inertia-impossible-on-moving-body", ERROR)
def inertia_impossible_on_moving_body(ctx: Context) -> Iterator[Hit]:
    """BK502's breach, grossly (the largest moment over 1.5 times the two others), on a body that moves."""
    for body in bodies(ctx):
        a, b, c = body.moments
        if body.positive_definite and _gross(body) and _moving_main_body(ctx, body):
            yield hit("link", body.link.name, body.inertial.line, link=body.link.name, a=a, b=b, c=c,
                      ratio=c / (a + b))


@rule("BK508", "negative-moment-on-fused-appendage", WARNING)
def negative_moment_on_fused_appendage(ctx: Context) -> Iterator[Hit]:
    """BK501's negative moment, on a massless link fused into a valid body: merged away by simulators."""
    definite = {body.link.name for body in bodies(ctx) if body.positive_definite}
    for body in bodies(ctx):
        if body.positive_definite:
            continue
        largest = max(abs(m) for m in body.moments)
        if body.moments[0] < -max(1e-9 * largest, 1e-12) and _fused_appendage(ctx, body, definite):
            head, _ = rigid_group(ctx, body.link)
            yield hit("link", body.link.name, body.inertial.line, link=body.link.name, moments=body.moments,
                      body=head)


def _solid_text(kind: str, link: Link, ctx: Context) -> str:
    shape = ctx.shape(link)
    assert shape is not None
    g = shape[0].geometry
    assert g is not None
    if kind == "box":
        return f'<box size="{vector(g.size or ())}"/>'
    if kind == "cylinder":
        return f'<cylinder radius="{number(g.radius or 0)}" length="{number(g.length or 0)}"/>'
    return f'<sphere radius="{number(g.radius or 0)}"/>'


def expected_inertia(ctx: Context, link: Link) -> np.ndarray | None:
    """The inertia a uniform solid of the link's one primitive shape would have, in the
    <inertial> frame (about the shape's centre), or None when the link has no single primitive."""
    inertial, shape = link.inertial, ctx.shape(link)
    if inertial is None or shape is None or shape[0].geometry is None:
        return None
    mass = inertial.mass
    if mass is None or not math.isfinite(mass) or mass <= 0 or not finite(*inertial.origin.rpy):
        return None
    element = shape[0]
    moments = solid_moments(element.geometry, mass)  # type: ignore[arg-type]
    if moments is None or not all(math.isfinite(m) for m in moments):
        return None
    solid = np.diag(moments)
    if element.origin.rpy == (0.0, 0.0, 0.0) and inertial.origin.rpy == (0.0, 0.0, 0.0):
        return solid
    to_inertial = rotation(inertial.origin).T @ rotation(element.origin)
    return to_inertial @ solid @ to_inertial.T


def _spread(given: float, wanted: float) -> float:
    """How many times one moment is the other (both positive); infinite when the ratio overflows or
    one of them underflowed to 0."""
    if given <= 0 or wanted <= 0:
        return math.inf
    return max(given / wanted, wanted / given)


def _inertia_xml(tensor: np.ndarray) -> str:
    scale = float(np.abs(tensor).max())
    values = {
        "ixx": tensor[0, 0], "ixy": tensor[0, 1], "ixz": tensor[0, 2],
        "iyy": tensor[1, 1], "iyz": tensor[1, 2], "izz": tensor[2, 2],
    }
    parts = [f'{k}="{_sig(float(v), scale)}"' for k, v in values.items()]
    return "<inertia " + " ".join(parts) + "/>"


def _sig(value: float, scale: float) -> str:
    if abs(value) <= 1e-6 * scale:  # rounding noise of a rotation, not a product of inertia
        return "0"
    return f"{value:.3g}"


@rule("BK503", "inertia-mismatch", WARNING)
def inertia_mismatch(ctx: Context) -> Iterator[Hit]:
    for body in bodies(ctx):
        link, inertial, tensor = body.link, body.inertial, body.tensor
        if not body.positive_definite:
            continue
        expected = expected_inertia(ctx, link)
        if expected is None:
            continue
        # both diagonals are positive: both tensors are positive definite
        given, wanted = tensor.diagonal().tolist(), expected.diagonal().tolist()
        largest = max(wanted)
        if not (math.isfinite(largest) and largest >= sys.float_info.min):
            continue  # the solid's inertia underflows (a 1e-160 m box, a denormal mass): no ratio holds
        spreads = [
            _spread(given[i], wanted[i]) if wanted[i] >= 0.01 * largest else 1.0
            for i in range(3)  # a near-zero moment (thin rod about its length) has no meaningful ratio
        ]
        axis = max(range(3), key=lambda i: spreads[i])
        if spreads[axis] <= MISMATCH_FACTOR or not math.isfinite(spreads[axis]):
            continue  # an overflowing ratio (1e308 against 1e-10) says nothing a learner can use
        kind = ctx.shape(link)[0].geometry.kind  # type: ignore[index, union-attr]
        yield hit("link", link.name, inertial.line, "more" if given[axis] > wanted[axis] else "less",
                  link=link.name, key=("ixx", "iyy", "izz")[axis], given=given[axis],
                  expected=wanted[axis], factor=round(spreads[axis], 1), mass=inertial.mass,
                  solid=_solid_text(kind, link, ctx), inertia=_inertia_xml(expected))


@rule("BK504", "inertial-origin-misplaced", WARNING)
def inertial_origin_misplaced(ctx: Context) -> Iterator[Hit]:
    for link, inertial in _inertials(ctx):
        shape = ctx.shape(link)
        xyz = inertial.origin.xyz
        if shape is None or not all(math.isfinite(v) for v in xyz):
            continue
        bounds = shape[1]
        tol = max(0.001, 0.02 * max(bounds.lengths))
        k = bounds.long_axis()
        if not all(bounds.lo[i] - tol <= xyz[i] <= bounds.hi[i] + tol for i in range(3)):
            variant = "outside"
        elif k is not None and abs(xyz[k] - bounds.centre[k]) > bounds.lengths[k] / 4:
            variant = "end"  # a uniform segment balances at its middle, not near an end
        else:
            continue
        origin = f'<origin xyz="{vector(bounds.centre)}"'
        if any(inertial.origin.rpy):
            origin += f' rpy="{vector(inertial.origin.rpy)}"'
        yield hit("link", link.name, inertial.origin.line or inertial.line, variant, link=link.name, at=xyz,
                  span=bounds.span(k) if k is not None and variant == "end" else bounds.spans(), centre=bounds.centre,
                  origin=origin + "/>", expected=bounds.centre)


@rule("BK505", "inertial-missing", INFO)
def inertial_missing(ctx: Context) -> Iterator[Hit]:
    parent_joint = ctx.graph.parent_joint
    missing = [
        link for link in ctx.robot.links
        if link.inertial is None and link.name in parent_joint and parent_joint[link.name].type in MOVABLE_TYPES
    ]
    if missing:  # one note per robot: it is advice for later, not a defect of each link
        first = missing[0]
        yield hit("link", first.name, first.line, "one" if len(missing) == 1 else "",
                  link=first.name, links=[link.name for link in missing], count=len(missing))


@rule("BK506", "root-inertial", INFO)
def root_inertial(ctx: Context) -> Iterator[Hit]:
    roots = ctx.graph.roots
    if len(roots) == 1 and ctx.robot.joints:
        link = ctx.links[roots[0]]
        if link.inertial is not None:
            yield hit("link", link.name, link.inertial.line, link=link.name)
