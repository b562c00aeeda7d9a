"""The one entry point: :func:`solve_ik` picks the closed-form or the numeric solver for the chain."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ..core.errors import ParameterError
from ..core.message import M
from ..kinematics.frames import TFTree
from ..model.robot import Robot
from ._inputs import Vector, _as_tree, _joints_dict, _start_vector
from .analytic import _two_link_of, ik_2r
from .chain import serial_chain
from .numeric import MAX_ITERATIONS, SEEDS, solve_chain
from .results import IKResult


def solve_ik(model: TFTree | Robot, target: Vector, *, rotation: np.ndarray | None = None,
             tip_link: str | None = None, tip_offset: Vector | None = None,
             start: Mapping[str, float] | np.ndarray | None = None, method: str = "auto",
             elbow: str | None = None, seeds: int = SEEDS, max_iterations: int = MAX_ITERATIONS,
             tolerance: float = 1e-12, random_seed: int = 0) -> IKResult:
    """Joint values putting the tip at ``target`` (and, with ``rotation`` (3x3), the tip link's orientation).

    ``method``: "analytic" (two-joint planar arms, see :func:`ik_2r`), "numeric", or "auto"
    (analytic when the chain allows it and no orientation is asked). The numeric solver starts
    from ``start`` (zero pose by default), so a reachable target near it gives the solution
    nearest the start; when that descent gets stuck (a local minimum, often made by a joint
    limit) it restarts from random poses within the limits, up to ``seeds`` starts of at most
    ``max_iterations`` each (``random_seed`` makes them repeatable). Each descent is
    Levenberg-Marquardt on the geometric Jacobian with joints kept within their limits. When
    ten descents end on the same closest point, that point is the answer (the target is out
    of reach); when the target needs a joint past its limits, the message names the joint.
    """
    tree = _as_tree(model)
    chain = serial_chain(tree, tip_link, tip_offset)
    if method not in ("auto", "analytic", "numeric"):
        raise ParameterError(M("unknown method {method!r}", method=str(method)), hint=M("use auto, analytic or numeric"))
    analytic = method == "analytic" or (method == "auto" and rotation is None and _two_link_of(chain) is not None)
    if analytic:
        if rotation is not None:
            raise ParameterError(M("the closed-form solver places the tip only (no orientation)"),
                                 hint=M("use method='numeric' for an orientation target"))
        return ik_2r(tree, target, elbow=elbow, start=start if isinstance(start, Mapping) else
                     (None if start is None else _joints_dict(tree, _start_vector(tree, start))),
                     tip_link=chain.tip_link, tip_offset=chain.tip_offset)
    if elbow is not None and _two_link_of(chain) is not None:
        raise ParameterError(M("elbow up/down comes from the closed-form solver, which places the tip only"),
                             hint=M("leave out the orientation, or the elbow choice"))
    if elbow is not None:
        raise ParameterError(M("elbow up/down applies to two-joint planar arms; the chain to '{tip}' "
                               "has {count} joints ({names})", tip=chain.tip_link, count=len(chain.joints),
                               names=", ".join(chain.joints)),
                             hint=M("leave out the elbow choice: the numeric solver starts from the start pose"))
    return solve_chain(chain, target, rotation=rotation, start=start, seeds=seeds,
                       max_iterations=max_iterations, tolerance=tolerance, random_seed=random_seed)
