"""Where the tool tip goes during a motion, and the plane the arm moves in."""

from __future__ import annotations

from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core.errors import ParameterError
from ..core.message import M
from ..kinematics.frames import TFTree, fk_batch, movable_joints_hint, tf_tree
from ..kinematics.tip import tool_tip
from ..model.robot import Robot
from ._labels import format_vector


def tip_point(robot: Robot) -> tuple[str, np.ndarray]:
    """The tool tip: the end link and the tip's offset in its frame (see :mod:`bras_kit.kinematics.tip`)."""
    return tool_tip(tf_tree(robot))


def states_matrix(tree: TFTree, states: Any) -> np.ndarray:
    """Joint positions as an (T, dof) array in ``tree.dof`` order.

    ``states`` is a JointStates (``names`` and ``positions``) or an array already in dof order.
    Joints missing from ``states`` stay at 0; unknown names raise ParameterError.
    """
    if isinstance(states, np.ndarray):
        q = np.atleast_2d(np.asarray(states, dtype=float))
        if q.shape[1] != len(tree.dof):
            raise ParameterError(M("expected {count} joint columns ({names}), got {got}", count=len(tree.dof),
                                   names=", ".join(tree.dof), got=q.shape[1]))
        return q
    positions = np.atleast_2d(np.asarray(states.positions, dtype=float))
    q = np.zeros((positions.shape[0], len(tree.dof)))
    columns = {name: k for k, name in enumerate(tree.dof)}
    for k, name in enumerate(states.names):
        if name not in columns:
            raise ParameterError(M("the motion drives '{name}', which is not a movable joint of this robot", name=name),
                                 hint=movable_joints_hint(tree.dof))
        q[:, columns[name]] = positions[:, k]
    return q


def tip_positions(transforms: np.ndarray, end: int, offset: np.ndarray) -> np.ndarray:
    """(T, 3) tip positions from (T, L, 4, 4) link transforms, the end link's index and the tip offset."""
    return transforms[:, end, :3, :3] @ offset + transforms[:, end, :3, 3]


def tip_path(robot: Robot, states: Any) -> np.ndarray:
    """World (root frame) positions of the tool tip for every sample: shape (T, 3)."""
    tree = tf_tree(robot)
    link, offset = tool_tip(tree)
    return tip_positions(fk_batch(tree, states_matrix(tree, states)), tree.index(link), offset)


@dataclass(frozen=True)
class MotionPlane:
    """The plane the arm moves in: its normal and two in-plane axes with their labels."""

    normal: np.ndarray
    u: np.ndarray
    v: np.ndarray
    u_label: str
    v_label: str
    common_axis: bool  # False: the revolute axes differ and this is a default side view


def motion_plane(robot: Robot) -> MotionPlane:
    """The plane normal to the revolute joints' common axis (at the zero pose).

    The tutorial arm turns about y, so it moves in x-z. When the axes are not all parallel
    (or there are none) the side view x-z is used and ``common_axis`` is False.
    """
    tree = tf_tree(robot)
    zero = fk_batch(tree, np.zeros(len(tree.dof)))
    axes = []
    for i in range(1, len(tree.links)):
        joint = tree.joints[i]
        if joint is not None and joint.type in ("revolute", "continuous"):
            axis = np.asarray(joint.axis_or_default, dtype=float)
            if np.linalg.norm(axis) > 0:
                axes.append(zero[i][:3, :3] @ (axis / np.linalg.norm(axis)))
    normal, common = np.array([0.0, 1.0, 0.0]), False
    if axes and all(np.linalg.norm(np.cross(axes[0], a)) < 1e-6 for a in axes):
        normal, common = axes[0] / np.linalg.norm(axes[0]), True
    named = {0: (np.array([0.0, 1, 0]), np.array([0.0, 0, 1]), "y", "z"),
             1: (np.array([1.0, 0, 0]), np.array([0.0, 0, 1]), "x", "z"),
             2: (np.array([1.0, 0, 0]), np.array([0.0, 1, 0]), "x", "y")}
    dominant = int(np.argmax(np.abs(normal)))
    if abs(normal[dominant]) > 1 - 1e-9:
        u, v, u_name, v_name = named[dominant]
    else:
        up = np.array([0.0, 0.0, 1.0]) - normal[2] * normal
        if np.linalg.norm(up) < 1e-6:
            up = np.array([0.0, 1.0, 0.0]) - normal[1] * normal
        v = up / np.linalg.norm(up)
        u = np.cross(v, normal)
        u_name, v_name = f"u = ({format_vector(u.tolist())})", f"v = ({format_vector(v.tolist())})"
    return MotionPlane(normal, u, v, f"{u_name} (m)", f"{v_name} (m)", common)
