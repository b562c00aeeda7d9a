"""What Gazebo's URDF reader (libsdformat's ``parser_urdf.cc``) will make of a robot, as data.

Gazebo never reads a URDF as RViz does: libsdformat converts it to an SDF model first, and the
conversion keeps, merges and drops links by rules of its own. This module predicts the result
from the robot model, following ``src/parser_urdf.cc`` of gazebosim/sdformat at tag
``sdformat12_12.3.0`` (Gazebo Fortress, ROS 2 Humble; the lines cited are that file's):

* ``ReduceFixedJoints`` (l. 410) first merges every link hanging from a ``fixed`` joint into its
  parent ("lumping"), children first, unless the parent is ``world`` or a ``<gazebo
  reference="JOINT">`` holds ``<preserveFixedJoint>`` or ``<disableFixedJointLumping>`` set to
  ``true``, ``yes`` or ``1`` (l. 1498-1515, ``FixedJointShouldBeReduced`` l. 3350). A merged
  link's ``<inertial>`` is added into its parent's (``ReduceInertialToParent`` l. 760, which
  creates the parent's inertial when it has none): masses add up.
* ``CreateSDF`` (l. 2634) then walks the tree from the root (from ``world``'s children when the
  root is ``world``) and stops at any link other than ``world`` whose inertial, after merging,
  is missing or has ``ignition::math::equal(mass, 0.0)`` (l. 2643), that is ``|mass| <= 1e-6``:
  that link, every link below it and their joints are not modelled, without an error.
* A link is written (``CreateLink``) when its joint's parent is ``world``, it has no joint, or
  its joint is not merged; its joint is written by ``CreateJoint`` (l. 2900), except
  ``floating`` and ``planar`` joints, which have no SDF type: the link is written, posed
  relative to a joint that is not there.

The oracle in the tests is libsdformat itself (``cmdCheck``/``cmdPrint``, what ``ign sdf -k/-p``
call); nothing here calls it. urdfdom sorts a link's children by joint name (a ``std::map``),
so :attr:`GazeboModel.links` lists links in the order ``ign sdf -p`` prints them.
"""

from __future__ import annotations

from dataclasses import dataclass, field

from ..model.robot import Link, Origin, Robot
from ._dmass import UrdfInertial, finite_pose, merge_into_parent, valid_mass_matrix

MASS_EPSILON = 1e-6  # ignition::math::equal's default tolerance (math/Helpers.hh)
TRUE_WORDS = ("true", "yes", "1")  # parser_urdf.cc l. 1502: lowerStr(value) == "true" || "yes", or "1"
UNCONVERTED_TYPES = ("floating", "planar")  # CreateJoint l. 2918: no SDF joint type


@dataclass(frozen=True)
class Dropped:
    """A link Gazebo does not model, and what goes with it.

    ``reason`` is ``"no-inertial"`` or ``"mass"`` (``mass`` then holds the merged mass).
    ``merged_into`` is set when the link itself is merged (a frame link hanging from a fixed
    joint): its shapes survive in that link, only what hangs below it by moving joints is lost.
    """

    link: str
    reason: str
    mass: float | None
    lost_links: tuple[str, ...]  # the link (unless merged) and every link below it that Gazebo would have written
    lost_joints: tuple[str, ...]
    merged_into: str | None = None


@dataclass(frozen=True)
class Merged:
    """A link merged into ``into`` through the fixed joint ``joint``: its frame disappears."""

    link: str
    into: str
    joint: str


@dataclass(frozen=True)
class GazeboModel:
    """The SDF model libsdformat 12 writes for a URDF, and why it differs from the URDF."""

    links: tuple[str, ...]
    joints: tuple[str, ...]
    joint_types: dict[str, str]  # SDF types: revolute, prismatic, fixed (a continuous joint is revolute)
    merged: tuple[Merged, ...]
    dropped: tuple[Dropped, ...]
    anchored: bool  # the root is the link ``world``: the model is fixed to the ground
    preserved: frozenset[str]  # fixed joints kept by <preserveFixedJoint>/<disableFixedJointLumping>
    bodies: dict[str, tuple[str, ...]] = field(default_factory=dict)  # written link -> it and links merged into it
    masses: dict[str, float] = field(default_factory=dict)  # written link -> mass after merging
    moving: frozenset[str] = frozenset()  # written links hanging from a moving joint
    clashes: tuple[str, ...] = ()  # names both of a written link and of a written joint
    unattached: tuple[tuple[str, str], ...] = ()  # (link, floating or planar joint) written without its joint
    nan_inertials: tuple[str, ...] = ()  # written links whose merged centre of mass is NaN (0 kg merged into 0 kg)
    invalid_inertias: tuple[str, ...] = ()  # written links whose (merged) inertia MassMatrix3::IsValid refuses

    @property
    def empty(self) -> bool:
        """No link written: "A model must have at least one link"."""
        return not self.links

    @property
    def kept_links(self) -> frozenset[str]:
        """Every URDF link whose body Gazebo keeps: the links written and those merged into them."""
        return frozenset(member for body in self.bodies.values() for member in body)

    @property
    def refused(self) -> bool:
        """libsdformat's check fails (``ign sdf -k`` does not say "Valid.")."""
        return self.empty or bool(self.clashes) or bool(self.unattached) or bool(self.nan_inertials) \
            or bool(self.invalid_inertias)


def preserved_joints(robot: Robot) -> frozenset[str]:
    """Joints named by ``<gazebo reference="J">`` holding ``<preserveFixedJoint>`` or
    ``<disableFixedJointLumping>`` set to true (the model does not carry ``<gazebo>``; its
    source text does)."""
    if not robot.source_text or "<gazebo" not in robot.source_text:
        return frozenset()
    from ..core.errors import BrasKitError
    from ..model.xmlio import parse_xml

    try:
        root = parse_xml(robot.source_text, robot.path)
    except BrasKitError:
        return frozenset()
    out = set()
    for node in root.children:
        reference = node.get("reference")
        if node.tag != "gazebo" or not reference:
            continue
        for child in node.children:
            if child.tag in ("preserveFixedJoint", "disableFixedJointLumping"):
                value = child.get("value") if child.get("value") is not None else child.text
                if (value or "").strip().lower() in TRUE_WORDS:
                    out.add(reference)
    return frozenset(out)


def gazebo_model(robot: Robot) -> GazeboModel | None:
    """The SDF model Gazebo will load, or None when the URDF is not one tree (urdfdom, under
    libsdformat, refuses it: the structure rules BK1xx say why)."""
    links = {link.name: link for link in robot.links if link.name}
    if len(links) != len([link for link in robot.links if link.name]) or not links:
        return None
    parent_joint: dict[str, _Edge] = {}
    children: dict[str, list[_Edge]] = {}
    for joint in robot.joints:
        if joint.parent not in links or joint.child not in links or joint.child in parent_joint \
                or joint.parent == joint.child or not joint.name or joint.parent is None or joint.child is None:
            return None
        edge = _Edge(joint.name, str(joint.type), joint.parent, joint.child, joint.origin)
        parent_joint[joint.child] = edge
        children.setdefault(joint.parent, []).append(edge)
    roots = [name for name in links if name not in parent_joint]
    if len(roots) != 1:
        return None
    for joints in children.values():
        joints.sort(key=lambda j: j.name)  # urdfdom's std::map of joints
    preserved = preserved_joints(robot)

    def reduced(joint_child: str) -> bool:
        """FixedJointShouldBeReduced, and the parent is not ``world`` (l. 424)."""
        joint = parent_joint.get(joint_child)
        return joint is not None and joint.type == "fixed" and joint.name not in preserved \
            and joint.parent != "world"

    # ReduceFixedJoints: merged inertials, children first (an explicit stack: robots can be deep)
    order: list[str] = []
    stack = [roots[0]]
    while stack:
        name = stack.pop()
        order.append(name)
        stack.extend(j.child for j in reversed(children.get(name, [])))
    inertial: dict[str, UrdfInertial | None] = {name: _read(links[name]) for name in links}
    for name in reversed(order):  # every child before its parent; its merged children in urdfdom's order
        for edge in children.get(name, []):
            child = inertial[edge.child]
            if reduced(edge.child) and child is not None:
                inertial[name] = merge_into_parent(inertial[name], child, edge.origin)
    has_inertial = {name: inertial[name] is not None for name in links}
    mass = {name: value.mass if value is not None else 0.0 for name, value in inertial.items()}
    head: dict[str, str] = {}
    for name in order:  # parents before children
        head[name] = head[parent_joint[name].parent] if reduced(name) else name

    kept: list[str] = []
    merged: list[Merged] = []
    dropped: list[Dropped] = []
    walk = [j.child for j in reversed(children.get(roots[0], []))] if roots[0] == "world" else [roots[0]]
    while walk:
        name = walk.pop()
        if not has_inertial[name] or abs(mass[name]) <= MASS_EPSILON:
            below = _below(name, children)
            is_merged = reduced(name)
            same_body = [n for n in below if head[n] == head[name]] if is_merged else []
            lost_links = [n for n in below if n not in same_body]
            lost_joints = [parent_joint[n].name for n in lost_links if n in parent_joint]
            merged.extend(Merged(n, head[n], parent_joint[n].name) for n in same_body)
            if lost_links:
                dropped.append(Dropped(name, "mass" if has_inertial[name] else "no-inertial",
                                       mass[name] if has_inertial[name] else None, tuple(lost_links),
                                       tuple(lost_joints), head[name] if is_merged else None))
            continue
        if reduced(name):
            merged.append(Merged(name, head[name], parent_joint[name].name))
        else:
            kept.append(name)
        walk.extend(j.child for j in reversed(children.get(name, [])))

    written_joints: list[str] = []
    types: dict[str, str] = {}
    unattached: list[tuple[str, str]] = []
    moving: set[str] = set()
    for name in kept:
        if name not in parent_joint:
            continue
        edge = parent_joint[name]
        if edge.type in UNCONVERTED_TYPES:
            unattached.append((name, edge.name))
            continue
        written_joints.append(edge.name)
        types[edge.name] = "revolute" if edge.type == "continuous" else edge.type
        if edge.type in ("revolute", "continuous", "prismatic"):
            moving.add(name)
    lost = {n for d in dropped for n in d.lost_links}
    bodies: dict[str, list[str]] = {name: [] for name in kept}
    for name in order:
        if head.get(name) in bodies and name not in lost and (name in bodies or reduced(name)):
            bodies[head[name]].append(name)
    clashes = tuple(sorted(set(kept) & set(written_joints)))
    written = [(name, value) for name in kept if (value := inertial[name]) is not None]
    nan_inertials = tuple(name for name, value in written if not finite_pose(value))
    invalid = tuple(name for name, value in written if name not in nan_inertials and not valid_mass_matrix(value))
    return GazeboModel(tuple(kept), tuple(written_joints), types, tuple(merged), tuple(dropped),
                       roots[0] == "world", preserved, {k: tuple(v) for k, v in bodies.items()},
                       {name: mass[name] for name in kept}, frozenset(moving), clashes, tuple(unattached),
                       nan_inertials, invalid)


@dataclass(frozen=True)
class _Edge:
    """A joint of a tree whose names are all known (what urdfdom hands libsdformat)."""

    name: str
    type: str
    parent: str
    child: str
    origin: Origin


def _read(link: Link) -> UrdfInertial | None:
    return UrdfInertial.read(link.inertial) if link.inertial is not None else None


def _below(name: str, children: dict[str, list[_Edge]]) -> list[str]:
    out, stack = [], [name]
    while stack:
        current = stack.pop()
        out.append(current)
        stack.extend(j.child for j in reversed(children.get(current, [])))
    return out






def as_data(found: GazeboModel) -> dict[str, object]:
    """The JSON form of ``bras-kit gazebo --json``."""
    return {
        "loads": not found.refused,
        "links": list(found.links),
        "joints": [{"name": name, "type": found.joint_types[name]} for name in found.joints],
        "merged": [{"link": m.link, "into": m.into, "joint": m.joint} for m in found.merged],
        "dropped": [{"link": d.link, "reason": d.reason, "mass": d.mass, "merged_into": d.merged_into,
                     "lost_links": list(d.lost_links), "lost_joints": list(d.lost_joints)} for d in found.dropped],
        "frames_lost": [m.link for m in found.merged],
        "anchored": found.anchored,
        "preserved": sorted(found.preserved),
        "refusals": refusals(found),
    }


def refusals(found: GazeboModel) -> list[dict[str, str]]:
    """Why libsdformat refuses the model, as ``{"reason": ..., "name": ...}`` (empty: it loads)."""
    out = [{"reason": "empty", "name": ""}] if found.empty else []
    out += [{"reason": "name-shared", "name": name} for name in found.clashes]
    out += [{"reason": "joint-not-converted", "name": joint} for _, joint in found.unattached]
    out += [{"reason": "centre-of-mass-nan", "name": name} for name in found.nan_inertials]
    out += [{"reason": "invalid-inertia", "name": name} for name in found.invalid_inertias]
    return out


LOST_RGBA = (0.85, 0.1, 0.1, 1.0)


def as_gazebo_shows(robot: Robot, found: GazeboModel, *, only_kept: bool = False) -> Robot:
    """A copy of ``robot`` drawn as Gazebo would load it: kept links in Gazebo's colours (rgba / 0.8),
    the parts it loses in red (``only_kept``: left out). A refused model is all lost."""
    import dataclasses

    from ..model.robot import Material

    kept = frozenset() if found.refused else found.kept_links
    links = []
    for link in robot.links:
        if link.name in kept:
            visuals = []
            for visual in link.visuals:
                rgba = robot.material_rgba(visual)
                shown = None if rgba is None else (min(rgba[0] / 0.8, 1.0), min(rgba[1] / 0.8, 1.0),
                                                   min(rgba[2] / 0.8, 1.0), rgba[3])
                material = Material(None, shown) if shown is not None else visual.material
                visuals.append(dataclasses.replace(visual, material=material))
        elif only_kept:
            visuals = []
        else:
            visuals = [dataclasses.replace(v, material=Material(None, LOST_RGBA)) for v in link.visuals]
        links.append(dataclasses.replace(link, visuals=visuals))
    return dataclasses.replace(robot, links=links)
