"""The MuJoCo model (MJCF) built from bras-kit's robot model, not from MuJoCo's own URDF import.

MuJoCo reads URDF, but it drops the visuals, fuses links held by fixed joints and adds no motor.
Here every link becomes a body (so joint names, link names and visuals survive), every movable
joint a hinge or slide with its range, and a motor whose force is clipped at ``<limit effort>``.
Visual shapes are drawn but never touch anything (``contype=0``); ``<collision>`` shapes collide
with each other and with a floor put under the lowest point of the fixed base.

Meshes are resolved by bras-kit (``package://``, relative paths) and handed to MuJoCo as assets;
formats MuJoCo cannot read (DAE) are converted to STL from the decoded mesh (:mod:`bras_kit.meshes`).
A visual mesh whose file gives its own materials becomes one geom per material piece, each with
that colour (RViz's rule: the mesh's materials win, the URDF ``<material>`` colours the rest).
"""

from __future__ import annotations

import contextlib
import math
import os
from collections.abc import Iterator, Mapping, Sequence
from dataclasses import dataclass, field
from xml.sax.saxutils import quoteattr

import numpy as np

from ..core import backends
from ..core.errors import ModelError
from ..core.message import M, Mn
from ..kinematics.frames import matrix_to_quat_xyzw, rpy_to_matrix
from ..model.robot import Geometry, Joint, Origin, Robot

MUJOCO_MESH_SUFFIXES = (".stl", ".obj", ".msh")
DEFAULT_KP = 100.0  # N.m/rad (N/m for sliders)
DEFAULT_KD = 10.0  # N.m.s/rad
MAX_NESTED_BODIES = 496  # MuJoCo's XML reader (tinyxml2) stops at 500 nested elements
DEFAULT_TIMESTEP = 0.002  # s, MuJoCo's own default
DEFAULT_INTEGRATOR = "implicitfast"  # stable with stiff motor damping; RK4 for energy studies
WATER_DENSITY = 1000.0  # kg/m^3, what MuJoCo gives a body known only by its shapes
VISUAL_GROUP, COLLISION_GROUP = 1, 3
COLLISION_RGBA = "0.9 0.3 0.3 0.35"


@dataclass
class MeshAsset:
    name: str  # file name MuJoCo sees (an asset key)
    data: bytes
    source: str  # the file bras-kit read
    converted: bool = False


@dataclass
class Actuated:
    """A joint driven by a motor: its MJCF name, effort (inf: none written) and kind."""

    joint: str
    effort: float
    kind: str  # "hinge" or "slide"


@dataclass
class MjcfModel:
    """An MJCF document and what a simulation needs to drive it.

    ``xml`` references meshes by the names in ``assets``; :meth:`compile` loads it in memory,
    ``xml_with_meshdir`` gives the text for a file whose meshes sit in a folder.
    """

    robot_name: str
    xml: str
    assets: dict[str, MeshAsset]
    actuated: list[Actuated]
    mimics: list[tuple[str, str, float, float]]  # follower, leader, multiplier, offset
    floor_z: float
    excluded: list[tuple[str, str, str]]  # parent body, child body, joint between them ("" : overlap at zero pose)
    density_links: list[str] = field(default_factory=list)  # massed from <collision> at 1000 kg/m^3
    massless_links: list[str] = field(default_factory=list)  # moving, no inertial, no collision
    converted: list[str] = field(default_factory=list)  # DAE (or other) meshes turned into STL
    dynamics: dict[str, tuple[float, float]] = field(default_factory=dict)  # joint -> (damping, friction) written
    damping_given: bool = False  # True: one damping for every joint was asked for, not the URDF's <dynamics>

    def compile(self):
        """The ``mujoco.MjModel`` (a :class:`ModelError` with MuJoCo's reason when it refuses)."""
        return compile_xml(self.xml, {a.name: a.data for a in self.assets.values()}, self.robot_name)

    def xml_with_meshdir(self, meshdir: str) -> str:
        return self.xml.replace('<compiler angle="radian"', f'<compiler meshdir={quoteattr(meshdir)} angle="radian"', 1)


@contextlib.contextmanager
def quiet_mujoco() -> Iterator[list[str]]:
    """MuJoCo's warnings collected in a list instead of printed and appended to ./MUJOCO_LOG.TXT.

    Without a handler, MuJoCo writes every warning to stderr and to a log file in the working
    folder; bras-kit writes nothing but the outputs asked for, and reports instability itself
    (the simulation's time and joint, from ``MjData.warning``).
    """
    mujoco = backends.mujoco()

    collected: list[str] = []
    previous = mujoco.get_mju_user_warning()
    mujoco.set_mju_user_warning(collected.append)
    try:
        yield collected
    finally:
        mujoco.set_mju_user_warning(previous)


def compile_xml(xml: str, assets: Mapping[str, bytes], name: str = "robot"):
    mujoco = backends.mujoco()

    try:
        with quiet_mujoco():
            return mujoco.MjModel.from_xml_string(xml, dict(assets))
    except ValueError as exc:
        reason = " ".join(str(exc).split())
        hint = M("check the file with bras-kit validate; bras-kit mjcf -o model.xml shows what MuJoCo was given")
        if "inertia" in reason:
            hint = M("check the <inertial> of that link (bras-kit validate)")
        if "mass and inertia" in reason:
            hint = M("give every moving link an <inertial> (built-in arm: --inertials)")
        raise ModelError(M("MuJoCo refuses the model of '{name}': {reason}", name=name, reason=reason),
                         element="mujoco", hint=hint) from None


def _f(value: float) -> str:
    return f"{float(value):.10g}"


def _vec(values: Sequence[float]) -> str:
    return " ".join(_f(v) for v in values)


def _quat(rpy: Sequence[float]) -> str | None:
    if not any(rpy):
        return None
    x, y, z, w = matrix_to_quat_xyzw(rpy_to_matrix(rpy))
    return _vec((w, x, y, z))


def _pose_attrs(origin: Origin) -> str:
    out = ""
    if any(origin.xyz):
        out += f' pos="{_vec(origin.xyz)}"'
    quat = _quat(origin.rpy)
    if quat:
        out += f' quat="{quat}"'
    return out


def _name(text: str | None) -> str:
    return quoteattr(text or "")


class _Meshes:
    """Mesh files read once, keyed by the file and scale, given short unique asset names."""

    def __init__(self, robot: Robot, package_paths: Sequence[str]) -> None:
        self.robot, self.package_paths = robot, package_paths
        self.assets: dict[str, MeshAsset] = {}
        self._keys: dict[tuple[str, tuple[float, ...]], str] = {}
        self._piece_names: dict[tuple[str, str, tuple[float, ...]], list[tuple[str, tuple[float, float, float, float] | None]]] = {}
        self.converted: list[str] = []
        self.scales: dict[str, tuple[float, ...]] = {}  # MuJoCo scales a <mesh> asset, not a <geom>

    def asset(self, geometry: Geometry) -> tuple[str, str]:
        """(mesh name, scale attribute) for a mesh geometry."""
        from ..meshes import DecodeError, read_mesh_file
        from ..render.scene import mesh_source

        path, roots = mesh_source(geometry.filename or "", self.robot, self.package_paths, geometry.line)
        scale = tuple(geometry.scale or (1.0, 1.0, 1.0))
        key = (path, scale)
        if key not in self._keys:
            name = self._name(path)
            suffix = os.path.splitext(path)[1].lower()
            if suffix in MUJOCO_MESH_SUFFIXES:
                try:
                    data = read_mesh_file(path, roots)  # the one reader: beneath a learner's folders
                except DecodeError as exc:
                    raise ModelError(M("cannot read mesh {path}: {reason}", path=path, reason=exc.reason),
                                     path=self.robot.path, line=geometry.line, element="mesh") from None
                self.assets[name] = MeshAsset(name + suffix, data, path)
            else:
                data = self._decoded(path, geometry, roots)
                self.assets[name] = MeshAsset(name + ".stl", binary_stl(data.vertices, data.faces), path, True)
                self.converted.append(path)
            self._keys[key] = name
            self.scales[name] = scale
        return self._keys[key], ""

    def pieces(self, geometry: Geometry) -> list[tuple[str, tuple[float, float, float, float] | None]] | None:
        """(mesh name, own colour) of each material piece of a mesh whose file gives colours of
        its own; None for a mesh with one piece and no material (the URDF's colour applies)."""
        from ..render.scene import mesh_source

        path, roots = mesh_source(geometry.filename or "", self.robot, self.package_paths, geometry.line)
        data = self._decoded(path, geometry, roots)
        if len(data) == 1 and all(p.color is None for p in data.pieces()):
            return None
        scale = tuple(geometry.scale or (1.0, 1.0, 1.0))
        key = (path, "pieces", scale)
        if key not in self._piece_names:
            names = []
            for piece in data.pieces():
                name = self._name(path)
                self.assets[name] = MeshAsset(name + ".stl", binary_stl(piece.vertices, piece.faces), path, True)
                self.scales[name] = scale
                names.append((name, piece.color))
            self._piece_names[key] = names
            if path not in self.converted:
                self.converted.append(path)
        return self._piece_names[key]

    def _name(self, path: str) -> str:
        stem = os.path.splitext(os.path.basename(path))[0]
        name = f"m{len(self.assets)}_{stem}"
        return name

    def _decoded(self, path: str, geometry: Geometry, roots: tuple[str, ...] | None = None):
        from ..render.scene import mesh_file_data

        return mesh_file_data(path, self.robot, geometry.line, roots=roots)

    def xml(self) -> list[str]:
        return [f'    <mesh name="{name}" file="{asset.name}"{_scale_attr(self.scales.get(name, (1.0, 1.0, 1.0)))} '
                'inertia="shell"/>' for name, asset in self.assets.items()]


def _scale_attr(scale: tuple[float, ...]) -> str:
    return f' scale="{_vec(scale)}"' if scale != (1.0, 1.0, 1.0) else ""


def binary_stl(vertices: np.ndarray, faces: np.ndarray) -> bytes:
    """Triangles as a binary STL file (facet normals from the winding)."""
    corners = np.asarray(vertices, dtype=np.float32)[np.asarray(faces)]  # (F, 3, 3)
    normals = np.cross(corners[:, 1] - corners[:, 0], corners[:, 2] - corners[:, 0])
    lengths = np.linalg.norm(normals, axis=1, keepdims=True)
    normals = (normals / np.where(lengths > 0, lengths, 1.0)).astype(np.float32)
    records = np.zeros(len(faces), dtype=[("normal", "<f4", 3), ("corners", "<f4", (3, 3)), ("attribute", "<u2")])
    records["normal"], records["corners"] = normals, corners
    return b"bras-kit".ljust(80, b" ") + np.uint32(len(faces)).tobytes() + records.tobytes()


def _geom_shape(geometry: Geometry | None, meshes: _Meshes) -> str | None:
    """The type/size (or mesh) attributes of one URDF shape; None when it has no usable shape."""
    if geometry is None:
        return None
    if geometry.kind == "box" and geometry.size and all(v for v in geometry.size):
        return f'type="box" size="{_vec([abs(v) / 2 for v in geometry.size])}"'
    if geometry.kind == "cylinder" and geometry.radius and geometry.length:
        return f'type="cylinder" size="{_f(abs(geometry.radius))} {_f(abs(geometry.length) / 2)}"'
    if geometry.kind == "sphere" and geometry.radius:
        return f'type="sphere" size="{_f(abs(geometry.radius))}"'
    if geometry.kind == "mesh" and geometry.filename:
        name, _ = meshes.asset(geometry)
        return f'type="mesh" mesh="{name}"'
    return None


def _rgba(robot: Robot, visual) -> str:
    rgba = robot.material_rgba(visual) or (0.7, 0.7, 0.7, 1.0)
    return _vec(rgba)


def _mesh_scale(geometry: Geometry | None, meshes: _Meshes) -> str:
    if geometry is None or geometry.kind != "mesh" or not geometry.filename:
        return ""
    return meshes.asset(geometry)[1]


def _has_mass(inertial) -> bool:
    """An <inertial> worth writing: ``mass="0"`` with a zero tensor (a frame-only link) counts as none."""
    if inertial is None:
        return False
    return bool(inertial.mass) or any(v for v in inertial.inertia.values())


def _inertial_xml(link) -> str:
    inertial = link.inertial
    i = {k: (v if v is not None else 0.0) for k, v in inertial.inertia.items()}
    tensor = np.array([[i["ixx"], i["ixy"], i["ixz"]], [i["ixy"], i["iyy"], i["iyz"]], [i["ixz"], i["iyz"], i["izz"]]])
    if any(inertial.origin.rpy):
        # MuJoCo takes fullinertia with no orientation: the URDF's tensor, given in the frame
        # turned by rpy, is turned into the link's frame (R I R^T)
        rotation = rpy_to_matrix(inertial.origin.rpy)
        tensor = rotation @ tensor @ rotation.T
    if not tensor.any():  # a point mass (Talos's sensor frames): MuJoCo's fullinertia wants eigenvalues > 0
        inertia = 'diaginertia="0 0 0"'
    else:
        inertia = f'fullinertia="{_vec((tensor[0, 0], tensor[1, 1], tensor[2, 2], tensor[0, 1], tensor[0, 2], tensor[1, 2]))}"'
    return f'<inertial pos="{_vec(inertial.origin.xyz)}" mass="{_f(inertial.mass or 0.0)}" {inertia}/>'


def joint_dynamics(joint: Joint, damping: float | None = None) -> tuple[float, float]:
    """(damping, friction) of ``joint``: its ``<dynamics>`` (0 when not written, as Gazebo does);
    ``damping``, when given, replaces the URDF's damping on every joint."""
    dynamics = joint.dynamics

    def usable(value: float | None) -> float:
        return float(value) if value is not None and math.isfinite(value) and value > 0 else 0.0

    written = usable(dynamics.damping) if dynamics is not None else 0.0
    friction = usable(dynamics.friction) if dynamics is not None else 0.0
    return (usable(damping) if damping is not None else written), friction


def _joint_xml(joint: Joint, kp_effort: float, gravity_compensation: bool, damping: float, friction: float) -> str:
    kind = "slide" if joint.type == "prismatic" else "hinge"
    attrs = f'name={_name(joint.name)} type="{kind}" axis="{_vec(_unit(joint.axis_or_default))}"'
    if joint.type != "continuous" and joint.limit is not None:
        lower, upper = joint.bounds()
        if math.isfinite(lower) and math.isfinite(upper) and lower < upper:
            attrs += f' range="{_f(lower)} {_f(upper)}"'
    if math.isfinite(kp_effort):
        attrs += f' actuatorfrcrange="{_f(-kp_effort)} {_f(kp_effort)}"'
    if gravity_compensation:
        attrs += ' actuatorgravcomp="true"'
    if damping:
        attrs += f' damping="{_f(damping)}"'
    if friction:
        attrs += f' frictionloss="{_f(friction)}"'
    return f"<joint {attrs}/>"


def _refuse_unusable(robot: Robot) -> None:
    """MuJoCo is never handed a default (no damping, an unlimited motor, the x axis...) in place of a
    value the reader could not use: the validator's first error about such a value, at its line
    (the command line refuses these models before, listing every finding)."""
    from ..validate.usable import EVERY_PART, blocking_findings

    findings = blocking_findings(robot, EVERY_PART)
    if findings:
        first = findings[0]
        raise ModelError(M("{code} {finding}: MuJoCo is given no default in its place (bras-kit validate lists "
                           "every such value)", code=first.code, finding=first.message),
                         path=robot.path, line=first.line, hint=first.hint)


def _unit(axis: Sequence[float]) -> tuple[float, float, float]:
    norm = math.sqrt(sum(v * v for v in axis))
    if not norm or not math.isfinite(norm):
        return (1.0, 0.0, 0.0)
    return (axis[0] / norm, axis[1] / norm, axis[2] / norm)


def joint_effort(joint: Joint) -> float:
    """``<limit effort>`` in N.m (N), or infinity when it is missing or not positive."""
    effort = joint.limit.effort if joint.limit is not None else None
    return float(effort) if effort is not None and math.isfinite(effort) and effort > 0 else math.inf


def _tree(robot: Robot) -> tuple[str, dict[str, list[Joint]]]:
    from ..kinematics.frames import tf_tree

    tree = tf_tree(robot)  # raises a clear ModelError for loops, several roots, unknown links
    children: dict[str, list[Joint]] = {}
    for joint in robot.joints:
        if joint.parent and joint.child:
            children.setdefault(joint.parent, []).append(joint)
    return tree.root, children


def build_mjcf(robot: Robot, *, package_paths: Sequence[str] = (), kp: float | Mapping[str, float] = DEFAULT_KP,
               kd: float | Mapping[str, float] = DEFAULT_KD, timestep: float = DEFAULT_TIMESTEP,
               integrator: str = DEFAULT_INTEGRATOR, control: str = "pd", damping: float | None = None) -> MjcfModel:
    """The MJCF of ``robot``: bodies, joints with ranges, motors at +-effort, collisions, a floor.

    ``control``: ``none`` (no motor: the arm only falls), ``pd`` (motors are PD servos,
    ``force = kp (ctrl - q) - kd qdot`` clipped to the effort) or ``pd+gravity`` (MuJoCo also
    adds each joint's gravity torque to its motor, inside the same effort clip). Each joint's
    damping and friction come from its ``<dynamics>`` (none when absent, as in Gazebo);
    ``damping`` (N.m.s/rad or N.s/m), when given, replaces the damping of every movable joint.
    A moving link without ``<inertial>`` and without ``<collision>`` is a :class:`ModelError`
    (MuJoCo cannot move a body with no mass).
    """
    from .controllers import check_control

    gravity_compensation = check_control(control) == "pd+gravity"
    _refuse_unusable(robot)
    root, children = _tree(robot)
    meshes = _Meshes(robot, package_paths)
    actuated: list[Actuated] = []
    mimics: list[tuple[str, str, float, float]] = []
    density_links: list[str] = []
    massless: list[str] = []
    body_lines: list[str] = []
    dynamics: dict[str, tuple[float, float]] = {}

    def gain(value: float | Mapping[str, float], joint: str, default: float) -> float:
        return float(value.get(joint, default)) if isinstance(value, Mapping) else float(value)

    def emit(link_name: str, joint: Joint | None, depth: int) -> str | None:
        """Write one body's opening and contents; return its closing line (None for the world)."""
        link = robot.link(link_name)
        pad = "  " * depth
        attrs = f"name={_name(link_name)}"
        if joint is not None:
            attrs += _pose_attrs(joint.origin)
        if gravity_compensation:
            attrs += ' gravcomp="1"'
        # MuJoCo's own world body takes the place of a URDF root link named "world"
        opened = not (joint is None and link_name == "world")
        if opened:
            body_lines.append(f"{pad}<body {attrs}>")
        moving = joint is not None and joint.type in ("revolute", "continuous", "prismatic")
        if moving and joint is not None:
            effort = joint_effort(joint) if joint.mimic is None else math.inf
            joint_damping, friction = joint_dynamics(joint, damping)
            dynamics[joint.name or ""] = (joint_damping, friction)
            body_lines.append(f"{pad}  {_joint_xml(joint, effort, gravity_compensation, joint_damping, friction)}")
            if joint.mimic is not None:
                mimics.append((joint.name or "", joint.mimic.joint or "", joint.mimic.multiplier, joint.mimic.offset))
            else:
                actuated.append(Actuated(joint.name or "", effort, "slide" if joint.type == "prismatic" else "hinge"))
        if link is not None and opened:
            if _has_mass(link.inertial):
                body_lines.append(f"{pad}  {_inertial_xml(link)}")
            elif moving:
                if any(_geom_shape(c.geometry, meshes) for c in link.collisions):
                    density_links.append(link_name)
                else:
                    massless.append(link_name)
            for n, visual in enumerate(link.visuals, 1):
                pieces = meshes.pieces(visual.geometry) if visual.geometry is not None and \
                    visual.geometry.kind == "mesh" and visual.geometry.filename else None
                if pieces:
                    fallback = robot.material_rgba(visual) or (0.7, 0.7, 0.7, 1.0)
                    for k, (mesh_name, own) in enumerate(pieces, 1):
                        body_lines.append(
                            f'{pad}  <geom name={_name(f"{link_name}/visual{n}.{k}")} type="mesh" mesh="{mesh_name}"'
                            f'{_pose_attrs(visual.origin)} rgba="{_vec(own or fallback)}" contype="0" '
                            f'conaffinity="0" group="{VISUAL_GROUP}" density="0"/>')
                    continue
                shape = _geom_shape(visual.geometry, meshes)
                if shape:
                    body_lines.append(
                        f'{pad}  <geom name={_name(f"{link_name}/visual{n}")} {shape}'
                        f'{_mesh_scale(visual.geometry, meshes)}{_pose_attrs(visual.origin)} '
                        f'rgba="{_rgba(robot, visual)}" contype="0" conaffinity="0" group="{VISUAL_GROUP}" density="0"/>')
            for n, collision in enumerate(link.collisions, 1):
                shape = _geom_shape(collision.geometry, meshes)
                if shape:
                    mass = "" if not _has_mass(link.inertial) else ' density="0"'
                    body_lines.append(
                        f'{pad}  <geom name={_name(f"{link_name}/collision{n}")} {shape}'
                        f'{_mesh_scale(collision.geometry, meshes)}{_pose_attrs(collision.origin)} '
                        f'rgba="{COLLISION_RGBA}" group="{COLLISION_GROUP}"{mass}/>')
        return f"{pad}</body>" if opened else None

    # depth first with a stack, not recursion: a chain of a thousand links is a valid URDF
    stack: list[tuple[str, Joint | None, int] | str | None] = [(root, None, 2)]
    while stack:
        item = stack.pop()
        if item is None or isinstance(item, str):
            if item is not None:
                body_lines.append(item)
            continue
        link_name, joint, depth = item
        if depth - 1 > MAX_NESTED_BODIES:
            raise ModelError(M("link '{link}' is {count} links down its chain; MuJoCo reads at most {limit} bodies "
                               "nested in one another", link=link_name, count=depth - 1, limit=MAX_NESTED_BODIES),
                             path=robot.path, line=(robot.link(link_name) or robot.links[0]).line, element="link",
                             hint=M("simulate a shorter chain ('bras-kit tree' and 'bras-kit validate' read any size)"))
        stack.append(emit(link_name, joint, depth))
        stack.extend((child.child or "", child, depth + 1) for child in reversed(children.get(link_name, [])))
    if massless:
        raise ModelError(
            Mn("link {links} moves but has no <inertial> (and no <collision> to weigh): MuJoCo cannot simulate "
               "a body with no mass",
               "{n} links move but have no <inertial> (and no <collision> to weigh): {links}; MuJoCo cannot simulate "
               "a body with no mass", len(massless), links=massless),
            path=robot.path, line=(robot.link(massless[0]) or robot.links[0]).line, element="link",
            hint=M("built-in arm: pass --inertials; your own file: add <inertial> with mass and inertia to each "
                   "moving link"))

    actuators = []
    for a in actuated if control != "none" else []:
        p, d = gain(kp, a.joint, DEFAULT_KP), gain(kd, a.joint, DEFAULT_KD)
        limit = f' forcelimited="true" forcerange="{_f(-a.effort)} {_f(a.effort)}"' if math.isfinite(a.effort) else ""
        actuators.append(f'    <general name={_name(a.joint)} joint={_name(a.joint)} gainprm="{_f(p)}" '
                         f'biastype="affine" biasprm="0 {_f(-p)} {_f(-d)}"{limit}/>')
    equality = [f'    <joint joint1={_name(f)} joint2={_name(leader)} polycoef="{_f(off)} {_f(mul)} 0 0 0"/>'
                for f, leader, mul, off in mimics]
    draft = _document(robot, body_lines, meshes, actuators, equality, [], 0.0, timestep, integrator)
    model = compile_xml(draft, {a.name: a.data for a in meshes.assets.values()}, robot.name or "robot")
    floor_z, excluded = _floor_and_touching(model, robot)
    contact = [f'    <exclude body1={_name(p)} body2={_name(c)}/>' for p, c, _ in excluded]
    xml = _document(robot, body_lines, meshes, actuators, equality, contact, floor_z, timestep, integrator)
    return MjcfModel(robot.name or "robot", xml, dict(meshes.assets), actuated, mimics, floor_z, excluded,
                     density_links, massless, meshes.converted, dynamics, damping is not None)


def _document(robot: Robot, bodies: list[str], meshes: _Meshes, actuators: list[str], equality: list[str],
              contact: list[str], floor_z: float, timestep: float, integrator: str) -> str:
    lines = [
        f"<mujoco model={_name(robot.name or 'robot')}>",
        "  <!-- written by bras-kit from the URDF: every link is a body, every movable joint has a motor"
        " clipped at its <limit effort>. Open it in MuJoCo's viewer: python -m mujoco.viewer, then drop this file"
        " on its window -->",
        '  <compiler angle="radian" autolimits="true" inertiafromgeom="auto"/>',
        f'  <option timestep="{_f(timestep)}" integrator="{integrator}"/>',
        '  <visual><headlight diffuse="0.6 0.6 0.6" ambient="0.3 0.3 0.3"/></visual>',
        "  <asset>",
        '    <texture name="grid" type="2d" builtin="checker" rgb1="0.85 0.85 0.85" rgb2="0.7 0.7 0.7"'
        ' width="256" height="256"/>',
        '    <material name="floor" texture="grid" texrepeat="8 8"/>',
        *meshes.xml(),
        "  </asset>",
        "  <worldbody>",
        '    <light name="sun" pos="1 -1 3" dir="-0.3 0.3 -1" directional="true"/>',
        f'    <geom name="floor" type="plane" size="0 0 0.05" pos="0 0 {_f(floor_z)}" material="floor"/>',
        *bodies,
        "  </worldbody>",
    ]
    for tag, items in (("contact", contact), ("equality", equality), ("actuator", actuators)):
        if items:
            lines += [f"  <{tag}>", *items, f"  </{tag}>"]
    lines.append("</mujoco>")
    return "\n".join(lines) + "\n"


def _world_boxes(model) -> tuple[np.ndarray, np.ndarray]:
    """Each geom's axis-aligned box in the world at the zero pose: centres and half sizes."""
    mujoco = backends.mujoco()

    data = mujoco.MjData(model)
    mujoco.mj_kinematics(model, data)
    centres = np.zeros((model.ngeom, 3))
    halves = np.zeros((model.ngeom, 3))
    for g in range(model.ngeom):
        rot = data.geom_xmat[g].reshape(3, 3)
        centre, half = model.geom_aabb[g, :3], model.geom_aabb[g, 3:]
        centres[g] = data.geom_xpos[g] + rot @ centre
        halves[g] = np.abs(rot) @ half
    return centres, halves


def _floor_and_touching(model, robot: Robot) -> tuple[float, list[tuple[str, str, str]]]:
    """The floor height (under the fixed base's lowest point) and the parent/child pairs whose shapes touch."""
    mujoco = backends.mujoco()

    centres, halves = _world_boxes(model)
    floor_geom = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_GEOM, "floor")
    fixed = [g for g in range(model.ngeom) if g != floor_geom and model.body_weldid[model.geom_bodyid[g]] == 0]
    floor_z = float(min((centres[g, 2] - halves[g, 2] for g in fixed), default=0.0))
    colliding = [g for g in range(model.ngeom) if g != floor_geom and model.geom_contype[g]]
    by_body: dict[int, list[int]] = {}
    for g in colliding:
        by_body.setdefault(int(model.geom_bodyid[g]), []).append(g)
    touching = []
    tol = 1e-4
    for joint in robot.joints:
        p = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, joint.parent or "")
        c = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, joint.child or "")
        if p < 0 or c < 0:
            continue
        if any(np.all(np.abs(centres[a] - centres[b]) <= halves[a] + halves[b] + tol)
               for a in by_body.get(p, []) for b in by_body.get(c, [])):
            touching.append((joint.parent or "", joint.child or "", joint.name or ""))
    return floor_z, touching + _overlapping_at_start(model, floor_geom)


def _overlapping_at_start(model, floor_geom: int) -> list[tuple[str, str, str]]:
    """Pairs of bodies (not parent and child) whose collision shapes already overlap at the zero pose.

    Left alone they push each other apart for ever (fingers of a gripper, a hand folded on the
    wrist): MuJoCo's own models exclude such pairs, so does bras-kit. The joint name is empty.
    """
    mujoco = backends.mujoco()

    data = mujoco.MjData(model)
    mujoco.mj_forward(model, data)
    pairs: list[tuple[str, str, str]] = []
    for contact in data.contact[:data.ncon]:
        if contact.dist >= 0 or floor_geom in (contact.geom1, contact.geom2):
            continue
        bodies = sorted(int(model.geom_bodyid[g]) for g in (contact.geom1, contact.geom2))
        names = tuple(mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) or "" for b in bodies)
        if bodies[0] != bodies[1] and (names[0], names[1], "") not in pairs:
            pairs.append((names[0], names[1], ""))
    return pairs
