"""Transforms, the TF tree and forward kinematics (single pose or batched with numpy).

The tree is compiled once from a :class:`~bras_kit.model.robot.Robot` into flat arrays in
topological order, so forward kinematics is a loop over links (no recursion: a
10,000-link chain works) with every pose of a batch handled at once.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
else:
    from ..core.lazy_numpy import np

from ..core.errors import ModelError, ParameterError, UnknownJointError
from ..core.message import M, Message
from ..model.robot import MOVABLE_TYPES, Joint, Robot


def movable_joints_hint(names: Sequence[str]) -> Message:
    """"movable joints: epaule, coude" (or none), the hint of every unknown-joint error."""
    if not names:
        return M("movable joints: none")
    return M("movable joints: {names}", names=", ".join(names))

# ---------------------------------------------------------------- rotations


def rpy_to_matrix(rpy: Sequence[float]) -> np.ndarray:
    """URDF's fixed-axis roll, pitch, yaw: R = Rz(yaw) @ Ry(pitch) @ Rx(roll)."""
    r, p, y = rpy
    cr, sr, cp, sp, cy, sy = math.cos(r), math.sin(r), math.cos(p), math.sin(p), math.cos(y), math.sin(y)
    return np.array([
        [cy * cp, cy * sp * sr - sy * cr, cy * sp * cr + sy * sr],
        [sy * cp, sy * sp * sr + cy * cr, sy * sp * cr - cy * sr],
        [-sp, cp * sr, cp * cr],
    ])


def matrix_to_rpy(matrix: np.ndarray) -> tuple[float, float, float]:
    """Inverse of :func:`rpy_to_matrix` (pitch in [-pi/2, pi/2])."""
    m = np.asarray(matrix)[:3, :3]
    pitch = math.atan2(-m[2, 0], math.hypot(m[0, 0], m[1, 0]))
    if abs(abs(pitch) - math.pi / 2) < 1e-9:  # gimbal lock: put everything in yaw
        roll = 0.0
        yaw = math.atan2(-m[0, 1], m[1, 1])
    else:
        roll = math.atan2(m[2, 1], m[2, 2])
        yaw = math.atan2(m[1, 0], m[0, 0])
    return (roll, pitch, yaw)


def matrix_to_quat_xyzw(matrix: np.ndarray) -> tuple[float, float, float, float]:
    """Unit quaternion (x, y, z, w) of a rotation matrix, with w >= 0 like tf2."""
    m = np.asarray(matrix)[:3, :3]
    trace = m[0, 0] + m[1, 1] + m[2, 2]
    if trace > 0:
        s = 2.0 * math.sqrt(trace + 1.0)
        w, x, y, z = 0.25 * s, (m[2, 1] - m[1, 2]) / s, (m[0, 2] - m[2, 0]) / s, (m[1, 0] - m[0, 1]) / s
    elif m[0, 0] > m[1, 1] and m[0, 0] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[0, 0] - m[1, 1] - m[2, 2])
        w, x, y, z = (m[2, 1] - m[1, 2]) / s, 0.25 * s, (m[0, 1] + m[1, 0]) / s, (m[0, 2] + m[2, 0]) / s
    elif m[1, 1] > m[2, 2]:
        s = 2.0 * math.sqrt(1.0 + m[1, 1] - m[0, 0] - m[2, 2])
        w, x, y, z = (m[0, 2] - m[2, 0]) / s, (m[0, 1] + m[1, 0]) / s, 0.25 * s, (m[1, 2] + m[2, 1]) / s
    else:
        s = 2.0 * math.sqrt(1.0 + m[2, 2] - m[0, 0] - m[1, 1])
        w, x, y, z = (m[1, 0] - m[0, 1]) / s, (m[0, 2] + m[2, 0]) / s, (m[1, 2] + m[2, 1]) / s, 0.25 * s
    if w < 0:
        x, y, z, w = -x, -y, -z, -w
    return (x, y, z, w)


def origin_matrix(xyz: Sequence[float], rpy: Sequence[float]) -> np.ndarray:
    """Homogeneous 4x4 transform of a URDF <origin>."""
    out = np.eye(4)
    out[:3, :3] = rpy_to_matrix(rpy)
    out[:3, 3] = xyz
    return out


# ---------------------------------------------------------------- the tree

_FIXED, _REVOLUTE, _PRISMATIC, _UNSUPPORTED = 0, 1, 2, 3


@dataclass(frozen=True)
class JointMotion:
    """How the joint into a link moves it: the parent-to-joint ``origin`` (4x4), then, for
    ``kind`` "revolute" or "prismatic", a turn or slide along the unit ``axis`` by
    ``gain * q[column] + offset`` (mimic joints have their leader's column). "fixed" otherwise.
    """

    kind: str
    origin: np.ndarray
    axis: np.ndarray
    column: int
    gain: float
    offset: float


@dataclass(frozen=True)
class TFTree:
    """A robot compiled for kinematics: links in topological order (root first).

    ``parent[i]`` is the index of link i's parent (-1 for the root); ``joints[i]`` the joint
    into link i (None for the root). ``dof`` lists the movable joints, the columns of a
    configuration vector.
    """

    robot: Robot
    links: tuple[str, ...]
    parent: tuple[int, ...]
    joints: tuple[Joint | None, ...]
    dof: tuple[str, ...]
    _kind: tuple[int, ...]
    _origin: tuple[np.ndarray, ...]
    _axis: tuple[np.ndarray, ...]
    _source: tuple[int, ...]  # column of the configuration driving the joint (-1: none)
    _gain: tuple[float, ...]
    _offset: tuple[float, ...]

    @property
    def root(self) -> str:
        return self.links[0]

    @property
    def unsupported_joints(self) -> list[str]:
        """Floating and planar joints: kept at their origin, never moved."""
        return [j.name or "?" for j, k in zip(self.joints, self._kind) if j is not None and k == _UNSUPPORTED]

    def joint_motion(self, i: int) -> JointMotion:
        """How link ``i`` moves relative to its parent (see :class:`JointMotion`)."""
        kind = {_REVOLUTE: "revolute", _PRISMATIC: "prismatic"}.get(self._kind[i], "fixed")
        return JointMotion(kind, self._origin[i], self._axis[i], self._source[i], self._gain[i], self._offset[i])

    def index(self, link: str) -> int:
        try:
            return self._index[link]  # type: ignore[attr-defined]
        except KeyError:
            raise ParameterError(
                M("unknown link '{link}'", link=link), hint=M("valid links: {names}", names=", ".join(self.links))
            ) from None

    def children(self, link: str) -> list[str]:
        i = self.index(link)
        return [self.links[k] for k, p in enumerate(self.parent) if p == i]

    def depth(self, link: str) -> int:
        depth, i = 0, self.index(link)
        while self.parent[i] >= 0:
            i, depth = self.parent[i], depth + 1
        return depth

    def dof_joints(self) -> list[Joint]:
        return [self.robot.joint(name) for name in self.dof]  # type: ignore[misc]

    def config_vector(self, config: Mapping[str, float] | None = None) -> np.ndarray:
        """A configuration vector from joint names; missing joints are 0, unknown names an error."""
        q = np.zeros(len(self.dof))
        for name, value in (config or {}).items():
            if name not in self._dof_index:  # type: ignore[attr-defined]
                joint = self.robot.joint(name)
                why = M("joint '{name}' is {type} and cannot be set", name=name, type=joint.type) if joint \
                    else M("unknown joint '{name}'", name=name)
                raise UnknownJointError(why, name, hint=movable_joints_hint(self.dof))
            q[self._dof_index[name]] = float(value)  # type: ignore[attr-defined]
        return q

    def out_of_limits(self, config: Mapping[str, float]) -> list[tuple[str, float, float, float]]:
        """(joint, value, lower, upper) for each value outside its joint's limits."""
        out = []
        for name, value in config.items():
            joint = self.robot.joint(name)
            if joint is None:
                continue
            lower, upper = joint.bounds()
            if value < lower or value > upper:
                out.append((name, float(value), lower, upper))
        return out


def _unit(axis: Sequence[float]) -> np.ndarray:
    """The axis as a unit vector; NaN for a zero, unreadable or non-finite axis (never a default
    direction in place of the one written: a command refuses such a model first, BK204-BK207)."""
    vector = np.asarray(axis, dtype=float)
    norm = math.hypot(*vector.tolist())  # no overflow for 1e308, no underflow for denormals
    if norm == 0.0 or not math.isfinite(norm):
        return np.full(3, math.nan)
    return vector / norm


def tree_structure(robot: Robot) -> tuple[list[str], list[Joint | None], list[int], dict[str, int],
                                          list[tuple[int, float, float]]]:
    """The links in topological order, the joint into each (None for the root), each one's parent
    index, the index of each link's name, and what drives each link's joint (:func:`_driver`,
    the root's (-1, 0, 0)): all of :func:`tf_tree` but its numbers, without numpy (``validate``
    on a package asks only whether a formula's joint can move, BK623).

    Raises :class:`ModelError` (naming the elements and lines) when the links do not form
    one tree: no links, unknown parent or child, a link with two parents, a cycle, several roots,
    or a mimic joint following an unknown joint or a loop of them.
    """
    where = robot.path
    names = robot.link_names
    if not names:
        raise ModelError(M("the robot has no <link>"), path=where, line=robot.line,
                         hint=M("add at least one <link name=\"...\">"))
    known = set(names)
    parent_of: dict[str, Joint] = {}
    for joint in robot.joints:
        for role, link in (("parent", joint.parent), ("child", joint.child)):
            if link is None or link not in known:
                raise ModelError(
                    M("joint '{joint}' names parent link '{link}', which does not exist", joint=joint.name, link=link)
                    if role == "parent" else
                    M("joint '{joint}' names child link '{link}', which does not exist", joint=joint.name, link=link),
                    path=where, line=joint.line, element="joint",
                    hint=M("links: {names}", names=", ".join(names)))
        if joint.child in parent_of:
            first = parent_of[joint.child]
            raise ModelError(
                M("link '{link}' has two parents: joints '{first}' (line {line}) and '{second}'",
                  link=joint.child, first=first.name, line=first.line, second=joint.name),
                path=where, line=joint.line, element="joint",
                hint=M("a URDF is a tree: each link is the child of at most one joint"))
        parent_of[joint.child] = joint  # type: ignore[index]
    roots = [n for n in dict.fromkeys(names) if n not in parent_of]
    if not roots:
        raise ModelError(M("every link has a parent: the joints form a loop"), path=where,
                         hint=M("one link (the base) must be the child of no joint"))
    if len(roots) > 1:
        raise ModelError(M("several root links: {names}", names=", ".join(roots)), path=where,
                         hint=M("connect them with joints so that one link is the root"))
    children: dict[str, list[Joint]] = {}
    for joint in robot.joints:
        children.setdefault(joint.parent, []).append(joint)  # type: ignore[arg-type]
    order: list[str] = [roots[0]]
    into: list[Joint | None] = [None]
    parents: list[int] = [-1]
    index = {roots[0]: 0}
    i = 0
    while i < len(order):
        for joint in children.get(order[i], []):
            index[joint.child] = len(order)  # type: ignore[index]
            order.append(joint.child)  # type: ignore[arg-type]
            into.append(joint)
            parents.append(i)
        i += 1
    if len(order) != len(set(names)):
        loop = sorted(set(names) - set(order))
        raise ModelError(M("links in a loop, not reachable from the root: {names}", names=", ".join(loop)),
                         path=where, hint=M("break the loop: one of these joints points back up the tree"))
    dof_index = {name: k for k, name in enumerate(movable_names(robot))}
    drivers = [(-1, 0.0, 0.0) if joint is None else _driver(robot, joint, dof_index) for joint in into]
    return order, into, parents, index, drivers


def movable_names(robot: Robot) -> list[str]:
    """The joints a configuration sets (a :class:`TFTree`'s ``dof``), in the URDF's order."""
    return [j.name for j in robot.joints if j.movable and j.name]


def tf_tree(robot: Robot) -> TFTree:
    """Compile the robot's links and joints into a :class:`TFTree`.

    Raises :class:`ModelError` (naming the elements and lines) when the links do not form
    one tree (:func:`tree_structure`).
    """
    order, into, parents, index, drivers = tree_structure(robot)
    movable = movable_names(robot)
    dof_index = {name: k for k, name in enumerate(movable)}
    kinds, origins, axes, sources, gains, offsets = [], [], [], [], [], []
    for incoming, (source, gain, offset) in zip(into, drivers):
        if incoming is None:
            kinds.append(_FIXED)
            origins.append(np.eye(4))
            axes.append(np.zeros(3))
            sources.append(-1)
            gains.append(0.0)
            offsets.append(0.0)
            continue
        origins.append(origin_matrix(incoming.origin.xyz, incoming.origin.rpy))
        axes.append(_unit(incoming.axis_or_default))
        kind = {"revolute": _REVOLUTE, "continuous": _REVOLUTE, "prismatic": _PRISMATIC,
                "fixed": _FIXED}.get(incoming.type or "", _UNSUPPORTED)
        if kind in (_REVOLUTE, _PRISMATIC) and source < 0:
            kind = _FIXED
        kinds.append(kind)
        sources.append(source)
        gains.append(gain)
        offsets.append(offset)
    tree = TFTree(robot, tuple(order), tuple(parents), tuple(into), tuple(movable), tuple(kinds),
                  tuple(origins), tuple(axes), tuple(sources), tuple(gains), tuple(offsets))
    object.__setattr__(tree, "_index", index)
    object.__setattr__(tree, "_dof_index", dof_index)
    return tree


def _driver(robot: Robot, joint: Joint, dof_index: dict[str, int]) -> tuple[int, float, float]:
    """Which configuration column moves ``joint``, with the mimic gain and offset."""
    if joint.type not in MOVABLE_TYPES:
        return -1, 0.0, 0.0
    gain, offset, seen = 1.0, 0.0, set()
    current: Joint | None = joint
    while current is not None and current.mimic is not None:
        if current.name in seen:
            raise ModelError(M("mimic joints follow each other in a loop at '{name}'", name=joint.name),
                             path=robot.path, line=joint.line, element="mimic")
        seen.add(current.name)
        leader = robot.joint(current.mimic.joint or "")
        if leader is None or leader.name is None:
            raise ModelError(M("joint '{name}' mimics unknown joint '{leader}'", name=current.name,
                               leader=current.mimic.joint),
                             path=robot.path, line=current.mimic.line, element="mimic",
                             hint=M("joints: {names}", names=", ".join(robot.joint_names)))
        offset = gain * current.mimic.offset + offset
        gain = gain * current.mimic.multiplier
        current = leader
    if current is None or current.name not in dof_index:
        return -1, 0.0, 0.0
    return dof_index[current.name], gain, offset


# ---------------------------------------------------------------- forward kinematics


def _skew(axis: np.ndarray) -> np.ndarray:
    x, y, z = axis
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def fk_batch(tree: TFTree, q: np.ndarray) -> np.ndarray:
    """World transforms of every link for every configuration.

    ``q`` has shape (N, len(tree.dof)) (or (len(dof),) for one pose); the result has shape
    (N, L, 4, 4) (or (L, 4, 4)), links in ``tree.links`` order, relative to the root.

    A rotation about a unit axis ``a`` by angle v is ``cos v (I - a a^T) + sin v K + a a^T``
    (Rodrigues), so a joint's rotation, pre-multiplied by anything constant, is a weighted sum
    of three fixed matrices: elementwise work, plus one batched product when the parent moves.
    """
    q = np.asarray(q, dtype=float)
    single = q.ndim == 1
    if single:
        q = q[None, :]
    if q.ndim != 2 or q.shape[-1] != len(tree.dof):
        raise ParameterError(M("expected {count} joint values ({names}), got {got}", count=len(tree.dof),
                               names=", ".join(tree.dof), got=q.shape[-1]))
    n, count = q.shape[0], len(tree.links)
    out = np.empty((n, count, 4, 4))
    out[:, :, 3, :3] = 0.0
    out[:, :, 3, 3] = 1.0
    # World transform of links that no joint value moves (4x4), else None (then read from `out`).
    constant: list[np.ndarray | None] = [np.eye(4)] + [None] * (count - 1)
    out[:, 0, :3, :] = np.eye(4)[:3]
    for i in range(1, count):
        p, origin, kind = tree.parent[i], tree._origin[i], tree._kind[i]
        parent_const = constant[p]
        if kind not in (_REVOLUTE, _PRISMATIC):
            if parent_const is not None:
                fixed = parent_const @ origin
                constant[i] = fixed
                out[:, i, :3, :] = fixed[:3]
            else:
                np.matmul(out[:, p], origin, out=out[:, i])
            continue
        value = q[:, tree._source[i]] * tree._gain[i] + tree._offset[i]
        axis = tree._axis[i]
        rot_out, pos_out = out[:, i, :3, :3], out[:, i, :3, 3]
        # `pre` is the constant factor in front of the joint motion: the origin, and the
        # parent's world transform too when the parent does not move.
        pre = parent_const @ origin if parent_const is not None else origin
        pre_rot = pre[:3, :3]
        if kind == _REVOLUTE:
            along = pre_rot @ np.outer(axis, axis)
            c, s = np.cos(value)[:, None, None], np.sin(value)[:, None, None]
            local = c * (pre_rot - along)
            local += s * (pre_rot @ _skew(axis))
            local += along
            if parent_const is not None:
                rot_out[...] = local
                pos_out[...] = pre[:3, 3]
            else:
                parent_rot = out[:, p, :3, :3]
                np.matmul(parent_rot, local, out=rot_out)
                np.matmul(parent_rot, pre[:3, 3], out=pos_out)
                pos_out += out[:, p, :3, 3]
        else:
            slide = value[:, None] * (pre_rot @ axis) + pre[:3, 3]
            if parent_const is not None:
                rot_out[...] = pre_rot
                pos_out[...] = slide
            else:
                parent_rot = out[:, p, :3, :3]
                np.matmul(parent_rot, pre_rot, out=rot_out)
                pos_out[...] = np.einsum("nij,nj->ni", parent_rot, slide) + out[:, p, :3, 3]
    return out[0] if single else out


def fk(tree: TFTree, config: Mapping[str, float] | None = None) -> dict[str, np.ndarray]:
    """World (root-relative) 4x4 transform of every link for one configuration given by joint names."""
    transforms = fk_batch(tree, tree.config_vector(config))
    return {name: transforms[i] for i, name in enumerate(tree.links)}


def relative_transform(tree: TFTree, config: Mapping[str, float] | None, source: str, target: str) -> np.ndarray:
    """Pose of ``target`` in the frame of ``source`` (what ``tf2_echo source target`` prints)."""
    transforms = fk_batch(tree, tree.config_vector(config))
    a, b = transforms[tree.index(source)], transforms[tree.index(target)]
    return np.linalg.inv(a) @ b


def describe_transform(matrix: np.ndarray) -> dict[str, list[float]]:
    """Translation, quaternion (x y z w) and roll-pitch-yaw of a transform, as plain lists."""
    def clean(values: Sequence[float] | np.ndarray) -> list[float]:
        return [float(v) + 0.0 for v in values]  # + 0.0 turns -0.0 into 0.0

    return {
        "xyz": clean(matrix[:3, 3]),
        "quat_xyzw": clean(matrix_to_quat_xyzw(matrix)),
        "rpy": clean(matrix_to_rpy(matrix)),
    }
