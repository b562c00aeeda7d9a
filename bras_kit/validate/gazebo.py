"""BK7xx: what Gazebo will make of the robot (libsdformat 12's URDF reader, see :mod:`.urdf2sdf`).

RViz draws any URDF that urdfdom reads; Gazebo first converts it to SDF, and that conversion
refuses some models (a link and a joint sharing a name), silently drops others' links (no
``<inertial>``, mass <= 1e-6, and everything below), merges links on fixed joints (their frames
disappear) and rewrites meshes and colours. These rules say so before the learner finds out.

Severity follows where the learner is (docs/gazebo.md): a half-done job that will break in
Gazebo (one link left without ``<inertial>`` while others have one, a name shared by a link and a
joint) is a warning in any case. What contradicts nothing in the tutorial (whose arm has no
``<inertial>``, no ``world`` link and bright colours, none of which RViz minds) is a note, given
only with ``bras-kit validate --target gazebo`` (the learner says they are heading there), which
also raises every refusal and every lost part to an error (:data:`TARGET_SEVERITY`).
"""

from __future__ import annotations

import math
from collections.abc import Iterator

from ..findings.registry import ERROR, INFO, WARNING, Hit, hit, rule
from .context import Context
from .urdf2sdf import GazeboModel, gazebo_model

GAZEBO = "gazebo"
TARGETS = (GAZEBO,)
# the severity of a rule when the learner validates for Gazebo (--target gazebo)
TARGET_SEVERITY: dict[str, dict[str, str]] = {
    GAZEBO: {
        "BK700": ERROR,  # refused: "Joint with non-unique name"
        "BK701": ERROR,  # refused: "A model must have at least one link"
        "BK702": ERROR,  # links lost
        "BK703": ERROR,  # links lost
        "BK704": WARNING,  # frames lost, bodies kept
        "BK705": WARNING,  # the robot falls over
        "BK706": WARNING,  # links fall through the floor and through each other
        "BK707": WARNING,  # meshes found only with the resource path set
        "BK708": INFO,  # colours changed, nothing lost
        "BK709": ERROR,  # refused: a link posed relative to a joint that is not there
        "BK710": ERROR,  # refused: "Pose values must be finite"
        "BK711": ERROR,  # refused: "A link named ... has invalid inertia"
    },
}
LISTED = 6  # names listed in one message before "..."


def heading_there(ctx: Context) -> bool:
    """Notes about Gazebo (the infos) are given only when the learner says they are heading there:
    the tutorial's own arm has no <inertial>, no world link and bright colours, and RViz minds none."""
    return ctx.target == GAZEBO


def model(ctx: Context) -> GazeboModel | None:
    """The predicted SDF model, computed once per validation (None: not one tree, BK1xx say why)."""
    return ctx.derived("gazebo.model", lambda c: gazebo_model(c.robot))


def names(items: list[str] | tuple[str, ...]) -> str:
    shown = ", ".join(items[:LISTED])
    return shown + (f", ... ({len(items)})" if len(items) > LISTED else "")


def _has_any_inertial(ctx: Context) -> bool:
    return any(link.inertial is not None for link in ctx.robot.links)


@rule("BK700", "gazebo-name-shared-by-link-and-joint", WARNING)
def name_shared(ctx: Context) -> Iterator[Hit]:
    """A link and a joint with one name: urdfdom keeps links and joints apart, SDF puts both in one
    frame namespace (FrameSemantics.cc: "Joint with non-unique name")."""
    if not ctx.is_robot:
        return
    for name, joint in ctx.joints.items():
        link = ctx.links.get(name)
        if link is None:
            continue
        yield hit("joint", name, joint.line, shared=name, link_line=link.line or 0, joint_line=joint.line or 0,
                  rename=f"{name}_link" if name + "_link" not in ctx.links else f"{name}_body")


@rule("BK701", "gazebo-nothing-to-simulate", INFO)
def nothing_to_simulate(ctx: Context) -> Iterator[Hit]:
    """No link has an <inertial>: the tutorial's arm before its exercise. Gazebo writes no link."""
    if not heading_there(ctx):
        return
    found = model(ctx)
    if found is None or not found.empty or _has_any_inertial(ctx):
        return
    root = next(iter(ctx.graph.roots), None)
    line = ctx.links[root].line if root in ctx.links else ctx.robot.line
    yield hit("robot", ctx.robot.name, line, root=root or "", count=len(ctx.robot.links))


def _dropped(ctx: Context, reason: str) -> Iterator[Hit]:
    found = model(ctx)
    if found is None:
        return
    for drop in found.dropped:
        if drop.reason != reason:
            continue
        link = ctx.links[drop.link]
        lost = [n for n in drop.lost_links if n != drop.link]
        variant = "merged" if drop.merged_into else ("empty" if found.empty else ("below" if lost else ""))
        line = link.inertial.line if reason == "mass" and link.inertial is not None else link.line
        yield hit("link", drop.link, line, variant, link=drop.link, below=names(lost), count=len(lost),
                  joints=names(list(drop.lost_joints)), into=drop.merged_into or "",
                  mass=drop.mass if drop.mass is not None else 0.0,
                  lost_links=list(drop.lost_links), lost_joints=list(drop.lost_joints))


@rule("BK702", "gazebo-link-dropped", WARNING)
def link_dropped(ctx: Context) -> Iterator[Hit]:
    """A link without <inertial> (after merging fixed links) while other links have one: libsdformat
    does not model it, nor anything below it (parser_urdf.cc CreateSDF), and says nothing."""
    if _has_any_inertial(ctx):
        yield from _dropped(ctx, "no-inertial")


@rule("BK703", "gazebo-mass-too-small", WARNING)
def mass_too_small(ctx: Context) -> Iterator[Hit]:
    """|mass| <= 1e-6 kg (ignition::math::equal(mass, 0.0)): dropped like a link without <inertial>."""
    yield from _dropped(ctx, "mass")


@rule("BK704", "gazebo-fixed-links-merged", INFO)
def fixed_links_merged(ctx: Context) -> Iterator[Hit]:
    """Links on fixed joints are merged into their parent: their frames (a TCP, a camera mount)
    are not in the SDF model. One note per robot, naming them."""
    if not heading_there(ctx):
        return
    found = model(ctx)
    if found is None or found.empty or not found.merged:
        return
    first = found.merged[0]
    joint = ctx.joints.get(first.joint)
    frames = [m.link for m in found.merged]
    yield hit("robot", ctx.robot.name, joint.line if joint is not None else ctx.robot.line,
              "one" if len(frames) == 1 else "", link=first.link, into=first.into, joint=first.joint,
              frames=names(frames), count=len(frames), merged={m.link: m.into for m in found.merged})


@rule("BK705", "gazebo-not-anchored", INFO)
def not_anchored(ctx: Context) -> Iterator[Hit]:
    """No link ``world`` at the root: Gazebo spawns a free body, and an arm falls over."""
    if not heading_there(ctx):
        return
    found = model(ctx)
    if found is None or found.empty or found.anchored or not found.moving:
        return
    root = found.links[0]
    yield hit("link", root, ctx.links[root].line, link=root)


@rule("BK706", "gazebo-moving-link-without-collision", INFO)
def moving_link_without_collision(ctx: Context) -> Iterator[Hit]:
    """A moving link Gazebo keeps with no <collision> in its merged body falls through the floor and
    through the other links. One note per robot."""
    if not heading_there(ctx):
        return
    found = model(ctx)
    if found is None or found.empty:
        return
    bare = [name for name in found.links if name in found.moving
            and not any(ctx.links[member].collisions for member in found.bodies.get(name, (name,)))]
    if bare:
        first = ctx.links[bare[0]]
        yield hit("link", bare[0], first.line, "one" if len(bare) == 1 else "", link=bare[0], links=names(bare),
                  count=len(bare), names=bare)


@rule("BK707", "gazebo-package-mesh", INFO)
def package_mesh(ctx: Context) -> Iterator[Hit]:
    """``package://P/...`` becomes ``model://P/...``: Gazebo finds it only when the folder holding
    P is on its resource path (parser_urdf.cc CreateGeometry)."""
    if not heading_there(ctx):
        return
    found = model(ctx)
    if found is None or found.empty:
        return
    kept = found.kept_links
    meshes = [(link, geometry) for link in ctx.robot.links if link.name in kept
              for geometry in [*(v.geometry for v in link.visuals), *(c.geometry for c in link.collisions)]
              if geometry is not None and (geometry.filename or "").startswith("package://")]
    if not meshes:
        return
    packages = sorted({(g.filename or "")[len("package://"):].split("/")[0] for _, g in meshes})
    link, geometry = meshes[0]
    uri = "model://" + (geometry.filename or "")[len("package://"):]
    yield hit("robot", ctx.robot.name, geometry.line or link.line, filename=geometry.filename, uri=uri,
              packages=", ".join(packages), package=packages[0], count=len(meshes))


def gazebo_colour(rgba: tuple[float, ...]) -> tuple[float, float, float, float]:
    """The diffuse colour libsdformat writes for a URDF rgba (CreateVisual: r/0.8, clamped to 1;
    the ambient is 0.5*r/0.4, the same)."""
    r, g, b, a = rgba
    return (min(max(r / 0.8, 0.0), 1.0), min(max(g / 0.8, 0.0), 1.0), min(max(b / 0.8, 0.0), 1.0), a)


def _text(values: tuple[float, ...]) -> str:
    return " ".join(f"{v:.3g}" for v in values)


@rule("BK708", "gazebo-colour-changed", INFO)
def colour_changed(ctx: Context) -> Iterator[Hit]:
    """Colours Gazebo cannot show: it divides each of r, g, b by 0.8 and caps it at 1, so a
    component above 0.8 saturates (two such colours may become one). One note per robot."""
    if not heading_there(ctx):
        return
    found = model(ctx)
    if found is None or found.empty:
        return
    kept = found.kept_links
    seen: dict[str, tuple[tuple[float, ...], tuple[float, ...]]] = {}
    rgba: tuple[float, ...] | None
    first_line = None
    for link in ctx.robot.links:
        if link.name not in kept:
            continue
        for visual in link.visuals:
            rgba = ctx.robot.material_rgba(visual)
            if rgba is None or not all(math.isfinite(v) for v in rgba):
                continue
            key = (visual.material.name if visual.material is not None else None) or _text(rgba)
            if key not in seen:
                seen[key] = (tuple(rgba), gazebo_colour(rgba))
                first_line = first_line or (visual.material.line if visual.material is not None else None) \
                    or visual.line
    saturated = {k: v for k, v in seen.items() if any(c > 0.8 for c in v[0][:3])}
    if not saturated:
        return  # brighter by 1.25, but every colour still distinct: bras-kit gazebo shows it
    name, (rgba, shown) = next(iter(saturated.items()))
    yield hit("robot", ctx.robot.name, first_line, material=name, rgba=_text(rgba), gazebo=_text(shown),
              saturated=", ".join(saturated), count=len(saturated),
              colours={k: list(v[1]) for k, v in saturated.items()})


@rule("BK709", "gazebo-joint-not-converted", WARNING)
def joint_not_converted(ctx: Context) -> Iterator[Hit]:
    """A floating or planar joint has no SDF type: libsdformat writes its child link posed
    relative to the missing joint, and the model is refused."""
    found = model(ctx)
    if found is None:
        return
    for link, joint_name in found.unattached:
        joint = ctx.joints[joint_name]
        yield hit("joint", joint_name, joint.line, joint=joint_name, type=joint.type, link=link)


@rule("BK710", "gazebo-zero-mass-merged-into-massless-link", WARNING)
def zero_mass_merged(ctx: Context) -> Iterator[Hit]:
    """0 kg merged into 0 kg: dMassAdd divides by the summed mass, the centre of mass is NaN."""
    found = model(ctx)
    if found is None:
        return
    for name in found.nan_inertials:
        link = ctx.links[name]
        yield hit("link", name, link.line, link=name)


@rule("BK711", "gazebo-inertia-refused", WARNING)
def inertia_refused(ctx: Context) -> Iterator[Hit]:
    """The inertia libsdformat writes for a link (its own, plus the links merged into it) fails
    ignition-math's MassMatrix3::IsValid: a negative moment or mass, or principal moments A + B < C
    beyond rounding. Gazebo refuses the model ("A link named X has invalid inertia")."""
    found = model(ctx)
    if found is None:
        return
    for name in found.invalid_inertias:
        link = ctx.links[name]
        merged = [member for member in found.bodies.get(name, (name,)) if member != name
                  and ctx.links[member].inertial is not None]
        line = link.inertial.line if link.inertial is not None else link.line
        yield hit("link", name, line, "merged" if merged else "", link=name, merged=names(merged))
