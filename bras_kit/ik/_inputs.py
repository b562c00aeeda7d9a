"""What the IK functions accept, checked and turned into arrays: models, points, poses."""

from __future__ import annotations

from collections.abc import Mapping, Sequence

import numpy as np

from ..core.errors import ParameterError
from ..core.message import M, Message
from ..kinematics.frames import TFTree, tf_tree
from ..model.robot import Robot
from ..motion import joint_unit

Vector = Sequence[float] | np.ndarray  # three numbers: a point, an offset


def _as_tree(model: TFTree | Robot) -> TFTree:
    return model if isinstance(model, TFTree) else tf_tree(model)


def _point(values: Vector, what: Message) -> np.ndarray:
    try:
        point = np.asarray(values, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ParameterError(M("{what} {values} is not three numbers", what=what, values=repr(values)),
                             hint=M("give X Y Z in metres")) from None
    if point.shape != (3,):
        raise ParameterError(M("{what} needs three numbers (x y z), got {count}", what=what, count=point.size),
                             hint=M("give X Y Z in metres"))
    if not np.all(np.isfinite(point)):
        raise ParameterError(M("{what} ({values}) is not finite", what=what, values=", ".join(f"{v:g}" for v in point)),
                             hint=M("give finite numbers in metres (no nan or inf)"))
    return point


def _start_vector(tree: TFTree, start: Mapping[str, float] | np.ndarray | None) -> np.ndarray:
    if start is None:
        return np.zeros(len(tree.dof))
    if isinstance(start, Mapping):
        q = tree.config_vector(start)
    else:
        q = np.asarray(start, dtype=float).reshape(-1)
        if q.shape != (len(tree.dof),):
            raise ParameterError(M("the start pose needs {count} values ({names})", count=len(tree.dof),
                                   names=", ".join(tree.dof)))
    if not np.all(np.isfinite(q)):
        raise ParameterError(M("the start pose holds a value that is not finite"),
                             hint=M("give numbers (no nan or inf)"))
    return q


def _joints_dict(tree: TFTree, q: np.ndarray) -> dict[str, float]:
    return {name: float(q[i]) for i, name in enumerate(tree.dof)}


def _unit_of(tree: TFTree, name: str) -> str:
    return joint_unit(tree.robot.joint(name))
