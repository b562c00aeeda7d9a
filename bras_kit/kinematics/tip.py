"""The tool tip: which link ends the arm, and where on that link the tip is.

One definition serves inverse kinematics, plots and the workspace. The end link is the deepest
leaf of the tree (ties: farthest from the root at the zero pose, then last in file order). The
tip on a link is the centre of the face of its visual primitives (box, cylinder, sphere) that
reaches farthest along the chain's direction: the direction from the nearest ancestor at a
different place to the link, at the zero pose. For the tutorial arm that is the far end of the forearm: (0, 0, 0.5) in
``avant_bras``. Meshes are not loaded here; a link with no primitive gives its origin.
"""

from __future__ import annotations

import math

import numpy as np

from ..model.robot import Geometry
from .frames import TFTree, fk_batch, origin_matrix


def support_point(visual_matrix: np.ndarray, geometry: Geometry, direction: np.ndarray) -> np.ndarray | None:
    """The centre of the primitive's face that reaches farthest along ``direction`` (link frame).

    A face centre, not the extreme corner: a segment's tip is the middle of its end face even
    when the chain runs a little askew of the segment (a mimic offset, a small tilt).
    """
    rotation, centre = visual_matrix[:3, :3], visual_matrix[:3, 3]
    local = rotation.T @ direction
    if geometry.kind == "box" and geometry.size is not None:
        half = np.asarray(geometry.size, dtype=float) / 2
        axis = int(np.argmax(np.abs(local) * half))
        offset = np.zeros(3)
        offset[axis] = math.copysign(half[axis], local[axis])
    elif geometry.kind == "cylinder" and geometry.radius is not None and geometry.length is not None:
        radial = np.array([local[0], local[1], 0.0])
        norm = float(np.linalg.norm(radial))
        if abs(local[2]) * geometry.length / 2 >= norm * geometry.radius:
            offset = np.array([0.0, 0.0, math.copysign(geometry.length / 2, local[2])])
        else:
            offset = radial / norm * geometry.radius
    elif geometry.kind == "sphere" and geometry.radius is not None:
        offset = local * geometry.radius
    else:  # meshes are not loaded here: their extent is unknown
        return None
    return centre + rotation @ offset


def end_link(tree: TFTree) -> str:
    """The link that ends the longest chain (deepest leaf; ties: farthest from the root, then last)."""
    count = len(tree.links)
    depth = [0] * count
    has_child = [False] * count
    for i, p in enumerate(tree.parent):
        if p >= 0:
            depth[i] = depth[p] + 1
            has_child[p] = True
    zero = fk_batch(tree, np.zeros(len(tree.dof)))
    leaves = [i for i in range(count) if not has_child[i]]
    end = max(leaves, key=lambda i: (depth[i], round(float(np.linalg.norm(zero[i][:3, 3])), 12), i))
    return tree.links[end]


def link_tip(tree: TFTree, link: str) -> np.ndarray:
    """The point of ``link``'s visual primitives farthest along the chain, in the link's frame."""
    index = tree.index(link)
    zero = fk_batch(tree, np.zeros(len(tree.dof)))
    rotation, position = zero[index][:3, :3], zero[index][:3, 3]
    direction = np.array([0.0, 0.0, 1.0])
    ancestor = tree.parent[index]
    while ancestor >= 0:
        step = position - zero[ancestor][:3, 3]
        if np.linalg.norm(step) > 1e-9:
            direction = rotation.T @ (step / np.linalg.norm(step))
            break
        ancestor = tree.parent[ancestor]
    model = tree.robot.link(link)
    best, best_reach = np.zeros(3), -math.inf
    for visual in (model.visuals if model is not None else []):
        if visual.geometry is None:
            continue
        point = support_point(origin_matrix(visual.origin.xyz, visual.origin.rpy), visual.geometry, direction)
        if point is not None and float(direction @ point) > best_reach + 1e-12:
            best, best_reach = point, float(direction @ point)
    return best


def tool_tip(tree: TFTree, link: str | None = None) -> tuple[str, np.ndarray]:
    """(link, tip point in that link's frame); the end link of the arm when ``link`` is None."""
    name = end_link(tree) if link is None else tree.links[tree.index(link)]
    return name, link_tip(tree, name)
