"""One joint's formula of t followed against that joint's position limits with Python floats.

The package rule BK623 asks, for each formula a node publishes, what
``check_limits(robot, sample(motion_from_specs(robot, ["JOINT=FORMULA"]), duration, rate))``
says of that joint's position. This module answers the same, step for step, without numpy
(whose import is a quarter of ``bras-kit validate PKG_DIR``, issue 43): the same refusals (a
robot that is not a tree, a joint that cannot be driven, a formula the evaluator refuses, a
value that is not a number), the same times ``k / rate``, the same first and worst samples. The
values come from :meth:`bras_kit.model.expr.Expression.at`, which follows numpy's IEEE results; a
transcendental function may differ from numpy's in the last bit, far below what BK623 shows.
Checked against the numpy path on the formulas of tests/motion/test_formula_limits.py.
"""

from __future__ import annotations

import math

from ..core.errors import ParameterError
from ..core.message import M
from ..kinematics.frames import movable_names, tree_structure
from ..model.expr import compile_expression
from ..model.robot import Robot
from .core import DEFAULT_RATE, check_joint_of, checked_count
from .limits import TOLERANCE, LimitViolation, joint_unit
from .specs import spec_kind, split_formula


def formula_position_violations(robot: Robot, joint: str, formula: str, duration: float,
                                rate: float = DEFAULT_RATE, tolerance: float = TOLERANCE) -> list[LimitViolation]:
    """The position limits ``formula`` takes ``joint`` past over ``duration`` seconds sampled at
    ``rate`` (at most one per side, as :func:`~bras_kit.motion.limits.check_limits` gives them).

    Raises what :func:`~bras_kit.motion.sources.motion_from_specs` and
    :func:`~bras_kit.motion.core.sample` raise for that formula (:class:`BrasKitError`).
    """
    spec = f"{joint}={formula}"
    tree_structure(robot)  # ModelError where tf_tree would raise one
    if spec_kind(spec) != "formula":  # read as a waypoint file or a bag, as motion_from_specs reads it
        raise ParameterError(M("'{spec}' is not a motion", spec=spec))
    name, text, prefix = split_formula(spec)
    dof = movable_names(robot)
    check_joint_of(robot, dof, name)
    expression = compile_expression(text, prefix=prefix)
    count, rate = checked_count(duration, rate, len(dof))
    times = [k / rate for k in range(count)]
    values = [expression.at(t) for t in times]
    at = next((k for k, value in enumerate(values) if not math.isfinite(value)), None)
    if at is not None:
        raise ParameterError(M("the motion of {joint} ({source}) is not a number at t={time:g} s", joint=name,
                               source=expression.text, time=times[at]))
    driven = robot.joint(name)
    if driven is None:
        return []
    lower, upper = driven.bounds()
    out = []
    for side, bound, past in (("upper", upper, [v - upper for v in values]),
                              ("lower", lower, [lower - v for v in values])):
        if not math.isfinite(bound):
            continue
        first = next((k for k, p in enumerate(past) if p > tolerance), None)
        if first is None:
            continue
        worst = max(range(count), key=past.__getitem__)  # the first of the largest, as numpy's argmax
        out.append(LimitViolation(name, "position", times[first], values[worst], float(bound), past[worst],
                                  times[worst], side, sum(p > tolerance for p in past), joint_unit(driven)))
    return out
