"""The robot as data: links, joints, origins, limits, inertials and materials, each with its source line.

Parsing is lenient on purpose: a number that cannot be used (text, a decimal comma, nan, inf,
the wrong count) is kept as NaN -- never replaced by a default -- and recorded as an
:class:`Issue` (its line, element, attribute, text and what it is for), so that the validator can
report every problem at once and nothing crashes. A missing attribute is ``None`` (or the URDF's
default where URDF has one). Commands that compute with the model refuse it first with the
validator's own finding (:mod:`bras_kit.validate.usable`); code that needs a usable tree calls
:func:`bras_kit.kinematics.frames.tf_tree`, which raises a clear :class:`~bras_kit.core.errors.ModelError`.
"""

from __future__ import annotations

import math
import re
from dataclasses import dataclass, field

from .xmlio import Node

Vec3 = tuple[float, float, float]

JOINT_TYPES = ("revolute", "continuous", "prismatic", "fixed", "floating", "planar")
MOVABLE_TYPES = ("revolute", "continuous", "prismatic")
GEOMETRY_KINDS = ("box", "cylinder", "sphere", "mesh")
XACRO_NAMESPACE_PREFIX = "xacro:"
# What a value is for: ``kinematics`` (a joint's origin, axis, mimic), ``limits`` (<limit>),
# ``dynamics`` (<dynamics>), ``visual`` (a visual's origin, shape, colour; named materials),
# ``collision``, ``inertial``, ``safety`` (<safety_controller>).
PARTS = ("kinematics", "limits", "dynamics", "visual", "collision", "inertial", "safety")
# A number written but unusable (text, a decimal comma, nan, inf) is kept as NaN, never replaced by
# a default: whatever is computed from it is NaN too, and the robot's issues say where it was.
UNREADABLE = math.nan


@dataclass
class Issue:
    """Something the parser could not read as written; the validator turns these into findings.

    kind: ``missing_attribute``, ``bad_number``, ``non_finite``, ``unexpanded_xacro``,
    ``unknown_geometry``, ``root_not_robot``, ``late_xml_declaration``.
    ``part`` says what the value is for, so that a command can tell whether it needs it (see
    :data:`PARTS`); "" for issues about the file or the robot as a whole.
    """

    kind: str
    line: int
    element: str
    name: str | None
    attribute: str | None = None
    value: str | None = None
    part: str = ""


@dataclass
class Origin:
    """An <origin>: translation (m) and roll, pitch, yaw (rad)."""

    xyz: Vec3 = (0.0, 0.0, 0.0)
    rpy: Vec3 = (0.0, 0.0, 0.0)
    line: int | None = None


@dataclass
class Geometry:
    """A <geometry>: the shape's kind and the sizes that kind reads."""

    kind: str  # box, cylinder, sphere, mesh; "" when absent or unknown
    size: Vec3 | None = None
    radius: float | None = None
    length: float | None = None
    filename: str | None = None
    scale: Vec3 | None = None
    line: int | None = None


@dataclass
class Material:
    """A <material>: named, with a colour or a texture (or a reference to a named one)."""

    name: str | None
    rgba: tuple[float, float, float, float] | None = None
    texture: str | None = None
    line: int | None = None


@dataclass
class Visual:
    """A <visual> of a link: what RViz draws."""

    origin: Origin
    geometry: Geometry | None
    material: Material | None = None
    name: str | None = None
    line: int | None = None


@dataclass
class Collision:
    """A <collision> of a link: what a simulator and a planner test contacts with."""

    origin: Origin
    geometry: Geometry | None
    name: str | None = None
    line: int | None = None


@dataclass
class Inertial:
    """An <inertial>: mass (kg), centre of mass (origin) and inertia tensor (kg m²)."""

    origin: Origin
    mass: float | None
    inertia: dict[str, float | None]  # ixx ixy ixz iyy iyz izz
    line: int | None = None

    def matrix(self) -> list[list[float]]:
        """The inertia tensor; a value missing from <inertia> (which urdfdom refuses) is NaN."""
        i = {k: (v if v is not None else UNREADABLE) for k, v in self.inertia.items()}
        return [
            [i["ixx"], i["ixy"], i["ixz"]],
            [i["ixy"], i["iyy"], i["iyz"]],
            [i["ixz"], i["iyz"], i["izz"]],
        ]


@dataclass
class Link:
    """A <link>: a rigid body, with what is drawn, what collides and how it weighs."""

    name: str | None
    visuals: list[Visual] = field(default_factory=list)
    collisions: list[Collision] = field(default_factory=list)
    inertial: Inertial | None = None
    line: int | None = None


@dataclass
class Limit:
    """A joint's <limit>: position bounds (rad or m), effort and velocity."""

    lower: float | None = None
    upper: float | None = None
    effort: float | None = None
    velocity: float | None = None
    line: int | None = None


@dataclass
class Mimic:
    """A joint's <mimic>: its value follows another joint's (multiplier, offset)."""

    joint: str | None
    multiplier: float = 1.0
    offset: float = 0.0
    line: int | None = None


@dataclass
class Dynamics:
    """``<dynamics damping friction>``: N.m.s/rad (N.s/m) and N.m (N); None when not written."""

    damping: float | None = None
    friction: float | None = None
    line: int | None = None


@dataclass
class SafetyController:
    """``<safety_controller>`` as written: attribute -> text (checked by the validator, BK230)."""

    attributes: dict[str, str] = field(default_factory=dict)
    line: int | None = None


@dataclass
class Joint:
    """A <joint>: how ``child`` moves relative to ``parent``, where (origin) and about which axis."""

    name: str | None
    type: str | None
    parent: str | None
    child: str | None
    origin: Origin = field(default_factory=Origin)
    axis: Vec3 | None = None  # None: not written (URDF default is 1 0 0); NaN: written, unusable
    limit: Limit | None = None
    mimic: Mimic | None = None
    line: int | None = None
    axis_line: int | None = None
    dynamics: Dynamics | None = None
    safety: SafetyController | None = None

    @property
    def movable(self) -> bool:
        return self.type in MOVABLE_TYPES and self.mimic is None

    @property
    def axis_or_default(self) -> Vec3:
        """The axis as written, URDF's 1 0 0 when there is no <axis>; NaN when an <axis> is written
        without a usable xyz (never a default in place of what the learner wrote)."""
        if self.axis is not None:
            return self.axis
        if self.axis_line is not None:
            return (UNREADABLE, UNREADABLE, UNREADABLE)
        return (1.0, 0.0, 0.0)

    def bounds(self) -> tuple[float, float]:
        """Position bounds; unbounded for continuous joints and missing limits; a bound not written
        is URDF's 0; a bound written but unusable is NaN (so nothing is ever "within" it)."""
        if self.type == "continuous" or self.limit is None:
            return (-math.inf, math.inf)
        lower = self.limit.lower if self.limit.lower is not None else 0.0
        upper = self.limit.upper if self.limit.upper is not None else 0.0
        return (lower, upper)


@dataclass
class Robot:
    """A URDF <robot> as read (links, joints, named materials), with the problems met reading it."""

    name: str | None
    links: list[Link] = field(default_factory=list)
    joints: list[Joint] = field(default_factory=list)
    materials: list[Material] = field(default_factory=list)
    issues: list[Issue] = field(default_factory=list)
    path: str | None = None
    root_tag: str = "robot"
    line: int | None = None
    source_text: str | None = None
    # the folders its files may be read from (a package's robot, a learner's submission): its
    # includes and meshes go through the one reader beneath them; None for a file the user named
    roots: tuple[str, ...] | None = None

    def link(self, name: str) -> Link | None:
        return next((link for link in self.links if link.name == name), None)

    def joint(self, name: str) -> Joint | None:
        return next((joint for joint in self.joints if joint.name == name), None)

    def material(self, name: str) -> Material | None:
        return next((m for m in self.materials if m.name == name), None)

    @property
    def link_names(self) -> list[str]:
        return [link.name for link in self.links if link.name]

    @property
    def joint_names(self) -> list[str]:
        return [joint.name for joint in self.joints if joint.name]

    def movable_joints(self) -> list[Joint]:
        """Joints a user drives (revolute, continuous, prismatic; not mimic), in file order."""
        return [joint for joint in self.joints if joint.movable]

    def child_joint(self, link_name: str) -> Joint | None:
        """The joint whose child is ``link_name`` (the first one, if the file has several)."""
        return next((j for j in self.joints if j.child == link_name), None)

    def material_rgba(self, visual: Visual) -> tuple[float, float, float, float] | None:
        """The visual's colour: its inline colour, else the named top-level material's."""
        if visual.material is None:
            return None
        if visual.material.rgba is not None:
            return visual.material.rgba
        if visual.material.name:
            named = self.material(visual.material.name)
            if named is not None:
                return named.rgba
        return None


# What urdfdom reads as a number (a C++ stream in the classic locale): ASCII digits, a sign, a
# decimal point, an exponent. Python's float() also takes '١' (Arabic-Indic), '１' (full width)
# and '1_0', which no URDF reader does; nan and inf are kept (the validator reports them, BK207).
_NUMBER = re.compile(r"[+-]?(?:(?:[0-9]+\.?[0-9]*|\.[0-9]+)(?:[eE][+-]?[0-9]+)?|nan|inf|infinity)",
                     re.IGNORECASE | re.ASCII)


def parse_number(text: str) -> float | None:
    """``text`` as urdfdom reads a number, or None when it is not one."""
    return float(text) if _NUMBER.fullmatch(text) else None


def parse_numbers(text: str) -> tuple[float, ...] | None:
    """Space-separated numbers as urdfdom reads them (``"0 0 0.6"``), or None when one is not a number."""
    # On ASCII words without '_', float() takes exactly what _NUMBER matches (a sign, digits, one
    # point, an exponent, nan, inf, infinity): one C call a word instead of a regex and a call
    # (a 17,133-link file has 290,000 such attributes)
    if not text.isascii() or "_" in text:
        return None
    try:
        return tuple(map(float, text.split()))
    except ValueError:
        return None


class _Reader:
    """Reads typed attributes from nodes, recording an Issue instead of raising."""

    def __init__(self, robot: Robot) -> None:
        self.robot = robot
        self.part = ""  # what the values being read are for (see PARTS)

    def issue(self, kind: str, node: Node, name: str | None, attribute: str | None = None,
              value: str | None = None) -> None:
        self.robot.issues.append(Issue(kind, node.line, node.tag, name, attribute, value, self.part))

    def text(self, node: Node, attribute: str, owner: str | None, required: bool = True) -> str | None:
        value = node.get(attribute)
        if value is None and required:
            self.issue("missing_attribute", node, owner, attribute)
        return value

    def floats(self, node: Node, attribute: str, count: int, owner: str | None,
               required: bool = False) -> tuple[float, ...] | None:
        raw = node.get(attribute)
        if raw is None:
            if required:
                self.issue("missing_attribute", node, owner, attribute)
            return None
        values = parse_numbers(raw)
        if values is None or len(values) != count:
            self.issue("bad_number", node, owner, attribute, raw)
            return (UNREADABLE,) * count
        if not all(math.isfinite(v) for v in values):
            self.issue("non_finite", node, owner, attribute, raw)
        return values

    def number(self, node: Node, attribute: str, owner: str | None,
               required: bool = False) -> float | None:
        values = self.floats(node, attribute, 1, owner, required)
        return values[0] if values else None

    def origin(self, node: Node | None, owner: str | None) -> Origin:
        if node is None:
            return Origin()
        xyz = self.floats(node, "xyz", 3, owner) or (0.0, 0.0, 0.0)  # the URDF default when not written
        rpy = self.floats(node, "rpy", 3, owner) or (0.0, 0.0, 0.0)
        return Origin(xyz, rpy, node.line)  # type: ignore[arg-type]

    def geometry(self, node: Node | None, owner: str | None) -> Geometry | None:
        if node is None:
            return None
        shape = next((c for c in node.children if c.tag in GEOMETRY_KINDS), None)
        if shape is None:
            unknown = node.children[0].tag if node.children else None
            self.issue("unknown_geometry", node, owner, None, unknown)
            return Geometry("", line=node.line)
        geometry = Geometry(shape.tag, line=shape.line)
        if shape.tag == "box":
            geometry.size = self.floats(shape, "size", 3, owner, required=True)  # type: ignore[assignment]
        elif shape.tag == "cylinder":
            geometry.radius = self.number(shape, "radius", owner, required=True)
            geometry.length = self.number(shape, "length", owner, required=True)
        elif shape.tag == "sphere":
            geometry.radius = self.number(shape, "radius", owner, required=True)
        else:
            geometry.filename = self.text(shape, "filename", owner)
            geometry.scale = self.floats(shape, "scale", 3, owner)  # type: ignore[assignment]
        return geometry

    def material(self, node: Node | None, owner: str | None) -> Material | None:
        if node is None:
            return None
        color = node.find("color")
        texture = node.find("texture")
        rgba = self.floats(color, "rgba", 4, owner, required=True) if color is not None else None
        return Material(
            node.get("name"),
            rgba,  # type: ignore[arg-type]
            texture.get("filename") if texture is not None else None,
            node.line,
        )

    def inertial(self, node: Node | None, owner: str | None) -> Inertial | None:
        if node is None:
            return None
        mass_node = node.find("mass")
        mass = self.number(mass_node, "value", owner, required=True) if mass_node is not None else None
        if mass_node is None:
            self.issue("missing_attribute", node, owner, "mass")
        inertia_node = node.find("inertia")
        keys = ("ixx", "ixy", "ixz", "iyy", "iyz", "izz")
        inertia: dict[str, float | None] = dict.fromkeys(keys)
        if inertia_node is None:
            self.issue("missing_attribute", node, owner, "inertia")
        else:
            for key in keys:
                inertia[key] = self.number(inertia_node, key, owner, required=True)
        return Inertial(self.origin(node.find("origin"), owner), mass, inertia, node.line)

    def link(self, node: Node) -> Link:
        name = self.text(node, "name", None)
        link = Link(name, line=node.line)
        for v in node.findall("visual"):
            self.part = "visual"
            link.visuals.append(Visual(
                self.origin(v.find("origin"), name),
                self.geometry(v.find("geometry"), name),
                self.material(v.find("material"), name),
                v.get("name"),
                v.line,
            ))
        for c in node.findall("collision"):
            self.part = "collision"
            link.collisions.append(Collision(
                self.origin(c.find("origin"), name),
                self.geometry(c.find("geometry"), name),
                c.get("name"),
                c.line,
            ))
        self.part = "inertial"
        link.inertial = self.inertial(node.find("inertial"), name)
        self.part = ""
        return link

    def joint(self, node: Node) -> Joint:
        self.part = "kinematics"
        name = self.text(node, "name", None)
        joint_type = self.text(node, "type", name)
        parent_node, child_node = node.find("parent"), node.find("child")
        parent = self.text(parent_node, "link", name) if parent_node is not None else None
        child = self.text(child_node, "link", name) if child_node is not None else None
        if parent_node is None:
            self.issue("missing_attribute", node, name, "parent")
        if child_node is None:
            self.issue("missing_attribute", node, name, "child")
        joint = Joint(name, joint_type, parent, child, self.origin(node.find("origin"), name),
                      line=node.line)
        axis_node = node.find("axis")
        if axis_node is not None:
            joint.axis = self.floats(axis_node, "xyz", 3, name, required=True)  # type: ignore[assignment]
            joint.axis_line = axis_node.line
        limit_node = node.find("limit")
        if limit_node is not None:
            self.part = "limits"
            joint.limit = Limit(
                self.number(limit_node, "lower", name),
                self.number(limit_node, "upper", name),
                self.number(limit_node, "effort", name),
                self.number(limit_node, "velocity", name),
                limit_node.line,
            )
        mimic_node = node.find("mimic")
        if mimic_node is not None:
            self.part = "kinematics"
            multiplier = self.number(mimic_node, "multiplier", name)
            offset = self.number(mimic_node, "offset", name)
            joint.mimic = Mimic(
                self.text(mimic_node, "joint", name),
                1.0 if multiplier is None else multiplier,
                0.0 if offset is None else offset,
                mimic_node.line,
            )
        dynamics_node = node.find("dynamics")
        if dynamics_node is not None:
            self.part = "dynamics"
            joint.dynamics = Dynamics(self.number(dynamics_node, "damping", name),
                                      self.number(dynamics_node, "friction", name), dynamics_node.line)
        safety_node = node.find("safety_controller")
        if safety_node is not None:
            joint.safety = SafetyController(dict(safety_node.attrib), safety_node.line)
        self.part = ""
        return joint


def robot_from_xml(root: Node, path: str | None = None, source_text: str | None = None) -> Robot:
    """Build a :class:`Robot` from a parsed XML tree, recording every unreadable part as an Issue."""
    robot = Robot(root.get("name"), path=path, root_tag=root.tag, line=root.line,
                  source_text=source_text)
    reader = _Reader(robot)
    if root.late_declaration is not None:
        robot.issues.append(Issue("late_xml_declaration", root.late_declaration, "?xml", None, None,
                                  root.late_declaration_after))
    if root.tag != "robot":
        reader.issue("root_not_robot", root, None, None, root.tag)
        return robot
    for node in root.iter():
        if node.tag.startswith(XACRO_NAMESPACE_PREFIX) or any(
            "${" in value or "$(" in value for value in node.attrib.values()
        ):
            reader.issue("unexpanded_xacro", node, node.get("name"), None, node.tag)
    for node in root.children:
        reader.part = ""
        if node.tag == "link":
            robot.links.append(reader.link(node))
        elif node.tag == "joint":
            robot.joints.append(reader.joint(node))
        elif node.tag == "material":
            reader.part = "visual"
            material = reader.material(node, node.get("name"))
            if material is not None:
                robot.materials.append(material)
    return robot
