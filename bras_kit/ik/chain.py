"""The chain from the root to the tip point: compiled once, then its Jacobian and tip positions."""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass

import numpy as np

from ..core.errors import ParameterError
from ..core.message import M
from ..kinematics.frames import TFTree, _skew, fk_batch
from ..kinematics.tip import end_link, tool_tip
from ..model.robot import Robot
from ._inputs import Vector, _as_tree, _point
from ._kernel import _flat, _forward, _jacobian_rows, _Kernel
from ._limits import _bounds


def resolve_tip(tree: TFTree, tip_link: str | None = None,
                tip_offset: Vector | None = None) -> tuple[str, np.ndarray]:
    """(link, point in the link's frame): defaults are those of :func:`bras_kit.kinematics.tip.tool_tip`."""
    if tip_offset is None:
        return tool_tip(tree, tip_link)
    return tree.links[tree.index(tip_link)] if tip_link else end_link(tree), _point(tip_offset, M("the tip offset"))


@dataclass(frozen=True)
class SerialChain:
    """The path from the root to a tip point, reduced to what moves it.

    Each moving joint k is reached through a constant transform (``pre_rot[k]``, ``pre_pos[k]``)
    from the previous moving joint's frame; ``end_point`` is the tip in the last moving joint's
    frame and ``end_rot`` the tip link's orientation there. ``variables`` are the configuration
    columns (``tree.dof`` indices) that move the chain, in chain order; ``joint_var[k]`` is the
    variable driving joint k (mimic joints share their leader's), with ``gains``/``offsets``.
    """

    tree: TFTree
    tip_link: str
    tip_offset: np.ndarray
    joints: tuple[str, ...]
    revolute: np.ndarray  # (m,) bool
    axes: np.ndarray  # (m, 3) unit, in the joint's frame
    pre_rot: np.ndarray  # (m, 3, 3)
    pre_pos: np.ndarray  # (m, 3)
    columns: np.ndarray  # (m,) configuration column of each joint
    gains: np.ndarray  # (m,)
    offsets: np.ndarray  # (m,)
    end_rot: np.ndarray  # (3, 3)
    end_point: np.ndarray  # (3,)
    variables: np.ndarray  # (k,) configuration columns
    joint_var: np.ndarray  # (m,) index into variables
    lower: np.ndarray  # (k,) bounds of the variables
    upper: np.ndarray  # (k,)
    kernel: _Kernel

    @property
    def variable_names(self) -> list[str]:
        return [self.tree.dof[c] for c in self.variables]


def _path_from_root(tree: TFTree, index: int) -> list[int]:
    """Link indices from the root (index 0) down to link ``index``, both included."""
    path = []
    while index >= 0:
        path.append(index)
        index = tree.parent[index]
    path.reverse()
    return path


def serial_chain(model: TFTree | Robot, tip_link: str | None = None,
                 tip_offset: Vector | None = None) -> SerialChain:
    """Compile the chain from the root to the tip (see :func:`resolve_tip` for the defaults).

    Chains are kept on the (immutable) tree, so solving many targets compiles once.
    """
    tree = _as_tree(model)
    cache = tree.__dict__.setdefault("_serial_chains", {})
    key = (tip_link, None if tip_offset is None else tuple(_point(tip_offset, M("the tip offset")).tolist()))
    if key not in cache:
        cache[key] = _compile_chain(tree, tip_link, tip_offset)
    return cache[key]


def _compile_chain(tree: TFTree, tip_link: str | None, tip_offset: Vector | None) -> SerialChain:
    link, offset = resolve_tip(tree, tip_link, tip_offset)
    path = _path_from_root(tree, tree.index(link))[1:]
    rot, pos = np.eye(3), np.zeros(3)
    names, revolute, axes, pre_rot, pre_pos, columns, gains, offsets = [], [], [], [], [], [], [], []
    for i in path:
        motion = tree.joint_motion(i)
        pos = pos + rot @ motion.origin[:3, 3]
        rot = rot @ motion.origin[:3, :3]
        if motion.kind == "fixed":
            continue
        names.append(str(tree.joints[i].name))  # type: ignore[union-attr]
        revolute.append(motion.kind == "revolute")
        axes.append(motion.axis)
        pre_rot.append(rot)
        pre_pos.append(pos)
        columns.append(motion.column)
        gains.append(motion.gain)
        offsets.append(motion.offset)
        rot, pos = np.eye(3), np.zeros(3)
    variables = list(dict.fromkeys(columns))
    joint_var = [variables.index(c) for c in columns]
    lower, upper = _bounds(tree)
    end_point = pos + rot @ offset
    kernel_parts: dict[str, list] = {"outer": [], "rest": [], "skew": [], "axis": []}
    for a, r in zip(axes, pre_rot):
        outer = np.outer(a, a)
        kernel_parts["outer"].append(_flat(r @ outer))
        kernel_parts["rest"].append(_flat(r @ (np.eye(3) - outer)))
        kernel_parts["skew"].append(_flat(r @ _skew(a)))
        kernel_parts["axis"].append(_flat(r @ a))
    kernel = _Kernel(
        revolute=tuple(revolute), var=tuple(joint_var), gain=tuple(float(g) for g in gains),
        offset=tuple(float(o) for o in offsets), pre_pos=tuple(_flat(p) for p in pre_pos),  # type: ignore[misc]
        pre_axis=tuple(kernel_parts["axis"]), pre_rot=tuple(_flat(r) for r in pre_rot),
        outer=tuple(kernel_parts["outer"]), rest=tuple(kernel_parts["rest"]), skew=tuple(kernel_parts["skew"]),
        end_point=_flat(end_point), end_rot=_flat(rot), size=len(variables),  # type: ignore[arg-type]
    )
    m = len(names)
    return SerialChain(
        tree=tree, tip_link=link, tip_offset=offset, joints=tuple(names),
        revolute=np.array(revolute, dtype=bool), axes=np.array(axes).reshape(m, 3),
        pre_rot=np.array(pre_rot).reshape(m, 3, 3), pre_pos=np.array(pre_pos).reshape(m, 3),
        columns=np.array(columns, dtype=int), gains=np.array(gains, dtype=float),
        offsets=np.array(offsets, dtype=float), end_rot=rot, end_point=end_point,
        variables=np.array(variables, dtype=int), joint_var=np.array(joint_var, dtype=int),
        lower=lower[variables], upper=upper[variables], kernel=kernel,
    )


def jacobian(model: TFTree | Robot, q: Mapping[str, float] | np.ndarray | Sequence[float] | None = None,
             tip_link: str | None = None, tip_offset: Vector | None = None, *,
             orientation: bool = True) -> np.ndarray:
    """The geometric Jacobian of the tip point, in the root frame.

    Rows: linear velocity (x, y, z), then, with ``orientation``, angular velocity. Columns:
    the movable joints in ``tree.dof`` order (zero for joints off the chain). ``q`` is a dict
    by joint name, a vector (dof,) -> result (6|3, dof), or a batch (N, dof) -> (N, 6|3, dof).
    """
    tree = _as_tree(model)
    chain = serial_chain(tree, tip_link, tip_offset)
    if q is None or isinstance(q, Mapping):
        q = tree.config_vector(q)
    q = np.asarray(q, dtype=float)
    single = q.ndim == 1
    batch = q[None, :] if single else q
    if batch.shape[-1] != len(tree.dof):
        raise ParameterError(M("expected {count} joint values ({names}), got {got}", count=len(tree.dof),
                               names=", ".join(tree.dof), got=batch.shape[-1]))
    out = np.zeros((batch.shape[0], 6 if orientation else 3, len(tree.dof)))
    for n, config in enumerate(batch):
        x = config[chain.variables].tolist()
        tip, _, origins, axes = _forward(chain.kernel, x)
        out[n][:, chain.variables] = _jacobian_rows(chain.kernel, tip, origins, axes, orientation)
    return out[0] if single else out


def tip_positions(model: TFTree | Robot, q: np.ndarray, tip_link: str | None = None,
                  tip_offset: Vector | None = None) -> np.ndarray:
    """World position of the tip for configurations q (N, dof) -> (N, 3) (or (dof,) -> (3,)), by :func:`fk_batch`."""
    tree = _as_tree(model)
    link, offset = resolve_tip(tree, tip_link, tip_offset)
    transforms = fk_batch(tree, np.asarray(q, dtype=float))[..., tree.index(link), :, :]
    return transforms[..., :3, :3] @ offset + transforms[..., :3, 3]
