"""What the viewer shows of a robot, computed once from the model: the meshes of every link
(the renderer's own, so the browser and the pictures agree), the joints a slider moves, and
the link poses for a set of joint values. No XML is read here."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from ..kinematics.frames import TFTree, fk_batch, tf_tree
from ..model.robot import Robot
from ..motion.limits import TOLERANCE

Color = tuple[int, int, int]
COLLISION_COLOR: Color = (90, 160, 90)


@dataclass(frozen=True)
class Mesh:
    """Triangles fixed to link ``link`` (an index in ``tree.links``), in that link's frame."""

    link: int
    vertices: np.ndarray
    faces: np.ndarray
    color: Color
    opacity: float = 1.0


@dataclass(frozen=True)
class Slider:
    """A movable joint as the slider window shows it: bounds, and its unit."""

    joint: str
    lower: float
    upper: float
    unit: str  # "rad" or "m"


@dataclass(frozen=True)
class Follower:
    """A mimic joint: ``gain * leader + offset``, with its own limits (shown red past them)."""

    joint: str
    leader: str
    gain: float
    offset: float
    lower: float
    upper: float
    unit: str


@dataclass
class ViewModel:
    robot: Robot
    tree: TFTree
    visuals: list[Mesh]
    collisions: list[Mesh]
    sliders: list[Slider]
    followers: list[Follower]
    tip_link: int
    tip_offset: np.ndarray
    scale: float  # metres: the size of the robot, for triads, labels and the grid
    _zero: np.ndarray = field(init=False, repr=False)
    _boxes: list[tuple[np.ndarray, np.ndarray, int]] = field(init=False, repr=False)

    def __post_init__(self) -> None:
        self._zero = np.zeros(len(self.tree.dof))
        self._boxes = [(m.vertices.min(axis=0), m.vertices.max(axis=0), m.link) for m in self.visuals if len(m.vertices)]

    def config_vector(self, values: Mapping[str, float]) -> np.ndarray:
        q = self._zero.copy()
        for k, name in enumerate(self.tree.dof):
            if name in values:
                q[k] = float(values[name])
        return q

    def poses(self, values: Mapping[str, float], fixed_frame: int = 0) -> np.ndarray:
        """Each link's 4x4 pose in the frame of link ``fixed_frame`` (RViz's Fixed Frame)."""
        world = fk_batch(self.tree, self.config_vector(values))
        if fixed_frame:
            world = np.linalg.inv(world[fixed_frame]) @ world
        return world

    def box_points(self, values: Mapping[str, float] | None = None, fixed_frame: int = 0) -> np.ndarray:
        """The corners of each visual's bounding box and every frame origin, in the fixed frame
        (N x 3): what the camera must keep in view."""
        poses = self.poses(values or {}, fixed_frame)
        points = [poses[:, :3, 3]]
        for low, high, link in self._boxes:
            corners = np.array([[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1])
                                for z in (low[2], high[2])])
            points.append(corners @ poses[link][:3, :3].T + poses[link][:3, 3])
        return np.vstack(points)

    def swept_points(self, configs: Sequence[Mapping[str, float]], fixed_frame: int = 0) -> np.ndarray:
        """:meth:`box_points` for many poses at once (one batched forward kinematics)."""
        if not configs:
            return np.zeros((0, 3))
        world = fk_batch(self.tree, np.array([self.config_vector(c) for c in configs]))  # (N, L, 4, 4)
        if fixed_frame:
            world = np.linalg.inv(world[:, fixed_frame])[:, None] @ world
        points = [world[:, :, :3, 3].reshape(-1, 3)]
        for low, high, link in self._boxes:
            corners = np.array([[x, y, z] for x in (low[0], high[0]) for y in (low[1], high[1])
                                for z in (low[2], high[2])])
            rotations, origins = world[:, link, :3, :3], world[:, link, :3, 3]
            points.append((np.einsum("nij,kj->nki", rotations, corners) + origins[:, None]).reshape(-1, 3))
        return np.vstack(points)

    def tip(self, poses: np.ndarray) -> np.ndarray:
        pose = poses[self.tip_link]
        return pose[:3, :3] @ self.tip_offset + pose[:3, 3]

    def follower_values(self, values: Mapping[str, float]) -> dict[str, float]:
        """The value of each mimic joint for the leaders' ``values``."""
        return {f.joint: f.gain * float(values.get(f.leader, 0.0)) + f.offset for f in self.followers}

    def out_of_limits(self, values: Mapping[str, float]) -> set[str]:
        """The joints, sliders and mimic followers, past their limits for ``values``."""
        every = [(s.joint, s.lower, s.upper) for s in self.sliders]
        every += [(f.joint, f.lower, f.upper) for f in self.followers]
        given = {**values, **self.follower_values(values)}
        return {name for name, lower, upper in every
                if name in given and not lower - TOLERANCE <= given[name] <= upper + TOLERANCE}


def _rgb(color: Sequence[float]) -> Color:
    return tuple(int(round(255 * min(max(float(c), 0.0), 1.0))) for c in color[:3])  # type: ignore[return-value]


def _merged_by_colour(parts) -> list[Mesh]:
    """One mesh per link and colour: a mesh file's material pieces (Panda's link0 has 12) and a
    link's visuals of one colour reach the browser as one object."""
    groups: dict[tuple[int, tuple[float, ...]], list] = {}
    for part in parts:
        groups.setdefault((part.link, tuple(part.color)), []).append(part)
    out = []
    for (link, color), members in groups.items():
        starts = np.cumsum([0] + [len(p.vertices) for p in members])
        vertices = np.concatenate([p.vertices for p in members])
        faces = np.concatenate([np.asarray(p.faces) + start for p, start in zip(members, starts)])
        out.append(Mesh(link, vertices, faces, _rgb(color), float(color[3]) if len(color) > 3 else 1.0))
    return out


def view_model(robot: Robot, package_paths: Sequence[str] = ()) -> ViewModel:
    """The robot ready to show: visual and collision meshes per link, sliders, the tool tip."""
    from ..kinematics.tip import tool_tip
    from ..render.scene import collision_parts, robot_parts

    tree = tf_tree(robot)
    visuals = _merged_by_colour(robot_parts(tree, package_paths))
    collisions = [Mesh(p.link, p.vertices, p.faces, COLLISION_COLOR, 0.6) for p in collision_parts(tree, package_paths)]
    sliders = []
    for joint in tree.dof_joints():
        lower, upper = joint.bounds()
        if not (math.isfinite(lower) and math.isfinite(upper)):
            lower, upper = -math.pi, math.pi  # continuous joints: one turn each way
        sliders.append(Slider(joint.name or "?", float(lower), float(upper),
                              "m" if joint.type == "prismatic" else "rad"))
    followers = []
    for index, into in enumerate(tree.joints):
        if into is None or into.mimic is None:
            continue
        motion = tree.joint_motion(index)
        if motion.column >= 0:  # a mimic of a joint that moves (not of a fixed one)
            lower, upper = into.bounds()
            followers.append(Follower(into.name or "?", tree.dof[motion.column], motion.gain, motion.offset,
                                      float(lower), float(upper), "m" if motion.kind == "prismatic" else "rad"))
    tip_name, tip_offset = tool_tip(tree)
    zero = fk_batch(tree, np.zeros(len(tree.dof)))
    points = [zero[m.link][:3, :3] @ m.vertices.T + zero[m.link][:3, 3:4] for m in visuals]
    corners = np.hstack(points) if points else zero[:, :3, 3].T
    span = float(np.max(np.ptp(corners, axis=1))) if corners.size else 1.0
    return ViewModel(robot, tree, visuals, collisions, sliders, followers, tree.index(tip_name),
                     np.asarray(tip_offset, float), max(span, 0.05))


def wxyz(matrix: np.ndarray) -> tuple[float, float, float, float]:
    """viser's quaternion order (w, x, y, z) of a rotation matrix."""
    from ..kinematics.frames import matrix_to_quat_xyzw

    x, y, z, w = matrix_to_quat_xyzw(matrix)
    return (w, x, y, z)
