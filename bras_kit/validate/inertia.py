"""BK5xx: mass and inertia, as a physics simulator (Gazebo) will read them.

RViz ignores <inertial> entirely; these rules matter once the arm is simulated. Expected
values come from the link's one primitive shape taken as a uniform solid of the given mass.
"""

from __future__ import annotations

import math
from collections.abc import Iterator

import numpy as np

from ..model import Inertial, Link
from .context import Context
from .registry import ERROR, INFO, WARNING, Hit, hit, rule
from .solids import number, rotation, solid_inertia, vector

MOVING_TYPES = ("revolute", "continuous", "prismatic")
MISMATCH_FACTOR = 2.0
KEYS = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")


def _tensor(inertial: Inertial) -> np.ndarray | None:
    values = [inertial.inertia.get(k) for k in KEYS]
    if any(v is None or not math.isfinite(v) for v in values):
        return None
    return np.array(inertial.matrix(), dtype=float)


def _principal(tensor: np.ndarray) -> np.ndarray:
    """Principal moments, ascending (computed on the scaled tensor so huge values cannot overflow)."""
    scale = float(np.abs(tensor).max())
    if scale == 0.0:
        return np.zeros(3)
    return np.linalg.eigvalsh(tensor / scale) * scale


def _positive_definite(moments: np.ndarray) -> bool:
    return bool(moments[-1] > 0 and moments[0] > 1e-12 * moments[-1])


def _inertials(ctx: Context) -> Iterator[tuple[Link, Inertial]]:
    for link in ctx.robot.links:
        if link.inertial is not None:
            yield link, link.inertial


@rule("BK500", "mass-not-positive", ERROR)
def mass_not_positive(ctx: Context) -> Iterator[Hit]:
    for link, inertial in _inertials(ctx):
        mass = inertial.mass
        if mass is not None and math.isfinite(mass) and mass <= 0:
            yield hit("link", link.name, inertial.line, link=link.name, mass=mass)


@rule("BK501", "inertia-not-positive-definite", ERROR)
def inertia_not_positive_definite(ctx: Context) -> Iterator[Hit]:
    for link, inertial in _inertials(ctx):
        tensor = _tensor(inertial)
        if tensor is None:
            continue
        moments = _principal(tensor)
        if not _positive_definite(moments):
            variant = "zero" if not tensor.any() else ""
            yield hit("link", link.name, inertial.line, variant, link=link.name,
                      moments=tuple(float(m) for m in moments))


@rule("BK502", "inertia-triangle-inequality", ERROR)
def inertia_triangle_inequality(ctx: Context) -> Iterator[Hit]:
    for link, inertial in _inertials(ctx):
        tensor = _tensor(inertial)
        if tensor is None:
            continue
        a, b, c = (float(m) for m in _principal(tensor))
        if _positive_definite(np.array([a, b, c])) and a + b < c * (1 - 1e-9):
            yield hit("link", link.name, inertial.line, link=link.name, a=a, b=b, c=c)


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
    if mass is None or not math.isfinite(mass) or mass <= 0:
        return None
    element = shape[0]
    solid = solid_inertia(element.geometry, mass)  # type: ignore[arg-type]
    if solid is None:
        return None
    in_link = rotation(element.origin) @ solid @ rotation(element.origin).T
    to_inertial = rotation(inertial.origin)
    expected = to_inertial.T @ in_link @ to_inertial
    return expected if np.isfinite(expected).all() else None


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
    for link, inertial in _inertials(ctx):
        tensor = _tensor(inertial)
        if tensor is None or not _positive_definite(_principal(tensor)):
            continue
        expected = expected_inertia(ctx, link)
        if expected is None:
            continue
        given, wanted = np.diag(tensor), np.diag(expected)  # positive: both tensors are positive definite
        largest = float(wanted.max())
        spreads = [
            max(given[i] / wanted[i], wanted[i] / given[i]) if wanted[i] >= 0.01 * largest else 1.0
            for i in range(3)  # a near-zero moment (thin rod about its length) has no meaningful ratio
        ]
        axis = int(np.argmax(spreads))
        if spreads[axis] <= MISMATCH_FACTOR:
            continue
        kind = ctx.shape(link)[0].geometry.kind  # type: ignore[index, union-attr]
        yield hit("link", link.name, inertial.line, "more" if given[axis] > wanted[axis] else "less",
                  link=link.name, key=("ixx", "iyy", "izz")[axis], given=float(given[axis]),
                  expected=float(wanted[axis]), factor=round(float(spreads[axis]), 1), mass=inertial.mass,
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
                  span=bounds.span(k) if variant == "end" else bounds.spans(), centre=bounds.centre,
                  origin=origin + "/>", expected=bounds.centre)


@rule("BK505", "inertial-missing", INFO)
def inertial_missing(ctx: Context) -> Iterator[Hit]:
    parent_joint = ctx.graph.parent_joint
    missing = [
        link for link in ctx.robot.links
        if link.inertial is None and link.name in parent_joint and parent_joint[link.name].type in MOVING_TYPES
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
