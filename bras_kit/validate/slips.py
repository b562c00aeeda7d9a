"""Learners' slips the file reader accepts: angles in degrees, masses in grams, a comment closed
with ``->`` (BK214, BK509, and the "comment" wording of BK100).

Each is a number or a character away from right, so RViz shows something plausible and wrong:
``rpy="0 90 0"`` turns by 90 radians (14 turns and 77 degrees), a 500 g forearm written
``500`` weighs half a tonne in simulation, and ``<!-- ... ->`` is not a comment's end, so the
comment runs on to the next ``-->`` and hides the elements between (TinyXML2, which check_urdf
and RViz use, reads them as comment; Python's XML reader stops at the first ``--`` inside).
"""

from __future__ import annotations

import math
import re
from collections.abc import Iterator
from typing import Any

from ..findings.registry import ERROR, WARNING, Hit, hit, rule
from ..model.robot import Origin
from .context import Context
from .solids import half_extents, number

FULL_TURN = 2 * math.pi
# the densest element (osmium) is 22,590 kg/m3: past 30,000 no solid explains the mass
DENSEST = 30_000.0
LIGHTEST = 10.0  # kg/m3: the same mass read in grams must still be a plausible solid (foam is ~30)
HEAVY = 10.0  # kg: a placeholder inertial on a sensor frame (1 g on a 1 mm box) is dense, not heavy


def _degrees(rpy: tuple[float, ...]) -> bool:
    """An rpy written in degrees: a component past a full turn, each such one a whole number of degrees."""
    big = [v for v in rpy if math.isfinite(v) and abs(v) > FULL_TURN + 1e-9]
    return bool(big) and all(abs(v - round(v)) < 1e-9 for v in big)


def _origins(ctx: Context) -> Iterator[tuple[str, str | None, Origin]]:
    for joint in ctx.robot.joints:
        yield "joint", joint.name, joint.origin
    for link in ctx.robot.links:
        for visual in link.visuals:
            yield "link", link.name, visual.origin
        for collision in link.collisions:
            yield "link", link.name, collision.origin
        if link.inertial is not None:
            yield "link", link.name, link.inertial.origin


@rule("BK214", "rpy-in-degrees", ERROR)
def rpy_in_degrees(ctx: Context) -> Iterator[Hit]:
    """URDF angles are radians. A component past a full turn that is a whole number (90, 180, 45)
    is degrees: no one turns a part by exactly 90 radians."""
    for element, name, origin in _origins(ctx):
        rpy = origin.rpy
        if not _degrees(rpy):
            continue
        written = " ".join(number(v) for v in rpy)
        radians = " ".join(number(round(math.radians(v), 4)) for v in rpy)
        turned = max(rpy, key=abs)
        yield hit(element, name, origin.line, element, owner=name, rpy=written, radians=radians,
                  angle=number(turned), effective=number(round(math.degrees(math.remainder(turned, FULL_TURN)), 1)),
                  origin=f'<origin xyz="{" ".join(number(v) for v in origin.xyz)}" rpy="{radians}"/>')


def _volume(geometry: object) -> float | None:
    half = half_extents(geometry)  # type: ignore[arg-type]
    kind = getattr(geometry, "kind", "")
    if half is None or not all(math.isfinite(h) and h > 0 for h in half):
        return None
    # products, not powers: a float power raises OverflowError where a product goes to inf
    if kind == "box":
        volume = 8 * half[0] * half[1] * half[2]
    elif kind == "cylinder":
        volume = math.pi * half[0] * half[0] * 2 * half[2]
    elif kind == "sphere":
        volume = 4 / 3 * math.pi * half[0] * half[0] * half[0]
    else:
        return None
    return volume if 0 < volume < math.inf else None  # underflowed or overflowed: no density to judge


@rule("BK509", "mass-in-grams", WARNING)
def mass_in_grams(ctx: Context) -> Iterator[Hit]:
    """A mass of 10 kg or more, denser than any solid for the link's one primitive shape, and
    plausible once read as grams (sensor frames carry light placeholder masses on tiny boxes)."""
    for link in ctx.robot.links:
        inertial, shape = link.inertial, ctx.shape(link)
        if inertial is None or shape is None or inertial.mass is None or not math.isfinite(inertial.mass):
            continue
        volume = _volume(shape[0].geometry)
        if volume is None:
            continue
        density = inertial.mass / volume
        if inertial.mass >= HEAVY and density > DENSEST and density / 1000 >= LIGHTEST:
            yield hit("link", link.name, inertial.line, link=link.name, mass=number(inertial.mass),
                      density=f"{density:,.0f}", kilograms=number(inertial.mass / 1000),
                      shape=shape[0].geometry.kind if shape[0].geometry is not None else "")


# ---------------------------------------------------------------- a comment closed with "->"

_OPEN = re.compile(r"<!--")
_ELEMENT = re.compile(r"""<(link|joint)\b[^>]*?\bname\s*=\s*["']([^"']*)["']""")


def swallowing_comment(text: str) -> dict[str, Any] | None:
    """The first comment whose end is written ``->`` (a line of it ends so, before any ``-->``),
    with what TinyXML2 (check_urdf, RViz) hides up to the next ``-->``: its line, the line of the
    ``->``, the line of that ``-->`` and the links and joints in between."""
    for start in _OPEN.finditer(text):
        body_start = start.end()
        close = text.find("-->", body_start)
        arrow = re.search(r"(?<!-)->[ \t]*(?:\r?\n|$)", text[body_start:close if close >= 0 else len(text)])
        if arrow is None:
            continue
        arrow_at = body_start + arrow.start()
        end = close if close >= 0 else len(text)
        hidden = [f'<{m.group(1)} name="{m.group(2)}">' for m in _ELEMENT.finditer(text, arrow_at, end)]
        if not hidden:
            continue
        return {"line": text.count("\n", 0, start.start()) + 1, "arrow_line": text.count("\n", 0, arrow_at) + 1,
                "end_line": text.count("\n", 0, end) + 1 if close >= 0 else 0, "hidden": ", ".join(hidden),
                "first": hidden[0]}
    return None
