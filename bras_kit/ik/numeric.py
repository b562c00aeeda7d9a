"""Numeric inverse kinematics for any serial chain: damped least squares within the joint limits."""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from operator import mul

import numpy as np

from ..core.errors import ParameterError
from ..core.message import M, Message, Mn
from ..core.wording import joined
from ._inputs import Vector, _joints_dict, _point, _start_vector, _unit_of
from ._kernel import _flat, _forward, _jacobian_rows, _Kernel, _product
from ._limits import _bounds, _fit_angle, _violations
from .chain import SerialChain
from .results import IKResult

SEEDS = 100  # starting poses at most: the start pose, then random ones
MAX_ITERATIONS = 100  # per starting pose
SAME_MINIMUM = 10  # descents ending on the best minimum so far before it is taken as the closest
ACCEPT = 1e-9  # m and rad: a descent stopped (slow convergence near a singularity) this close counts


def _rotation_error(target: Sequence[float], rot: Sequence[float]) -> tuple[float, float, float]:
    """Rotation vector e (world frame) with ``target = exp([e]) rot``; rotations as row-major 9-tuples."""
    m = _product(target, (rot[0], rot[3], rot[6], rot[1], rot[4], rot[7], rot[2], rot[5], rot[8]))
    vx, vy, vz = (m[7] - m[5]) / 2.0, (m[2] - m[6]) / 2.0, (m[3] - m[1]) / 2.0
    sine = math.sqrt(vx * vx + vy * vy + vz * vz)
    cosine = min(max((m[0] + m[4] + m[8] - 1.0) / 2.0, -1.0), 1.0)
    angle = math.atan2(sine, cosine)
    if sine > 1e-6 or cosine > 0.0:
        scale = angle / sine if sine > 1e-12 else 1.0
        return vx * scale, vy * scale, vz * scale
    # near a half turn the skew part vanishes: (m + I) / 2 is then the axis' outer product
    i = max(range(3), key=lambda j: m[4 * j])
    column = [(m[3 * j + i] + (1.0 if j == i else 0.0)) / 2.0 for j in range(3)]
    norm = math.sqrt(sum(c * c for c in column))
    return column[0] / norm * angle, column[1] / norm * angle, column[2] / norm * angle


def _solve_symmetric(a: list[list[float]], b: list[float]) -> list[float]:
    """Solve a x = b for a small symmetric positive definite a (Cholesky)."""
    n = len(b)
    low = [[0.0] * n for _ in range(n)]
    for i in range(n):
        row = low[i]
        for j in range(i + 1):
            s = a[i][j] - sum(map(mul, row[:j], low[j][:j]))
            if i == j:
                row[i] = math.sqrt(s) if s > 1e-300 else 1e-150
            else:
                row[j] = s / low[j][j]
    y = [0.0] * n
    for i in range(n):
        y[i] = (b[i] - sum(map(mul, low[i][:i], y[:i]))) / low[i][i]
    x = [0.0] * n
    for i in reversed(range(n)):
        x[i] = (y[i] - sum(low[j][i] * x[j] for j in range(i + 1, n))) / low[i][i]
    return x


def _damped_step(columns: list[tuple[float, ...]], error: Sequence[float], free: list[int],
                 damping: float, size: int) -> list[float]:
    """(J^T J + damping I)^-1 J^T e over the ``free`` variables; the others do not move."""
    step = [0.0] * size
    if not free:
        return step
    normal = [[sum(map(mul, columns[i], columns[j])) + (damping if i == j else 0.0) for j in free] for i in free]
    rhs = [sum(map(mul, columns[i], error)) for i in free]
    for i, value in zip(free, _solve_symmetric(normal, rhs)):
        step[i] = value
    return step


def _close_enough(error: Sequence[float]) -> bool:
    position = error[0] ** 2 + error[1] ** 2 + error[2] ** 2
    rotation = sum(e * e for e in error[3:])
    return position <= ACCEPT ** 2 and rotation <= ACCEPT ** 2


@dataclass
class _Descent:
    x: list[float]
    error: list[float]
    cost: float
    tip: tuple[float, float, float]
    iterations: int
    converged: bool


def _descend(kernel: _Kernel, x: list[float], goal: Sequence[float], goal_rot: Sequence[float] | None,
             lower: list[float], upper: list[float], tolerance: float, rotation_tolerance: float,
             budget: int) -> _Descent:
    """Levenberg-Marquardt from ``x``, never leaving [lower, upper]; stops converged, stuck or out of budget.

    A joint on a bound that the gradient pushes outwards is left out of the step; a joint a
    step would carry past a bound stops on it while the others re-solve for what is left.
    """
    orientation = goal_rot is not None
    gx, gy, gz = goal

    def evaluate(values: list[float]):
        tip, rot, origins, axes = _forward(kernel, values, orientation)
        error = [gx - tip[0], gy - tip[1], gz - tip[2]]
        if orientation:
            error.extend(_rotation_error(goal_rot, rot))  # type: ignore[arg-type]
        return error, tip, origins, axes

    def reached(error: list[float]) -> bool:
        if error[0] ** 2 + error[1] ** 2 + error[2] ** 2 > tolerance ** 2:
            return False
        return not orientation or error[3] ** 2 + error[4] ** 2 + error[5] ** 2 <= rotation_tolerance ** 2

    size = kernel.size
    error, tip, origins, axes = evaluate(x)
    cost = sum(e * e for e in error)
    damping, stale = 1e-3, 0
    for iteration in range(budget + 1):
        if reached(error):
            return _Descent(x, error, cost, tip, iteration, True)
        if iteration == budget:
            break
        columns = list(zip(*_jacobian_rows(kernel, tip, origins, axes, orientation)))
        grad = [sum(map(mul, column, error)) for column in columns]  # descent direction J^T e
        free = [i for i in range(size)
                if not ((x[i] <= lower[i] and grad[i] < 0) or (x[i] >= upper[i] and grad[i] > 0))]
        step = _damped_step(columns, error, free, damping, size)
        leaving = {i: min(max(x[i] + step[i], lower[i]), upper[i]) - x[i]
                   for i in free if not lower[i] <= x[i] + step[i] <= upper[i]}
        if leaving:
            rest = [e - sum(columns[i][r] * d for i, d in leaving.items()) for r, e in enumerate(error)]
            step = _damped_step(columns, rest, [i for i in free if i not in leaving], damping, size)
            for i, d in leaving.items():
                step[i] = d
        trial = [min(max(v + d, lo), hi) for v, d, lo, hi in zip(x, step, lower, upper)]
        t_error, t_tip, t_origins, t_axes = evaluate(trial)
        t_cost = sum(e * e for e in t_error)
        if t_cost < cost:
            stale = 0 if t_cost < cost * (1.0 - 1e-6) else stale + 1
            x, error, cost, tip, origins, axes = trial, t_error, t_cost, t_tip, t_origins, t_axes
            damping = max(damping * 0.3, 1e-9)
        else:
            damping *= 10.0
            stale += 1
        if damping > 1e4 or stale >= 8:  # a local minimum, or the closest the limits allow
            return _Descent(x, error, cost, tip, iteration + 1, False)
    return _Descent(x, error, cost, tip, budget, False)


def solve_chain(chain: SerialChain, target: Vector, *, rotation: np.ndarray | Sequence[float] | None = None,
                start: Mapping[str, float] | np.ndarray | None = None, seeds: int = SEEDS,
                max_iterations: int = MAX_ITERATIONS, tolerance: float = 1e-12,
                rotation_tolerance: float = 1e-12, limits: bool = True, random_seed: int = 0,
                explain: bool = True) -> IKResult:
    """Numeric inverse kinematics on a compiled chain (see :func:`solve_ik`).

    Descents stop at ``tolerance`` (m) / ``rotation_tolerance`` (rad); a result counts as
    reached within :data:`ACCEPT` of the target. ``limits=False`` lets joints turn freely;
    ``explain`` re-solves without limits after a failure, to name the joints in the way.
    """
    tree = chain.tree
    goal = _point(target, M("the target"))
    goal_rot = None if rotation is None else _flat(np.asarray(rotation, dtype=float).reshape(3, 3))
    q_start = _start_vector(tree, start)
    if chain.kernel.size == 0:
        raise ParameterError(M("no movable joint moves '{tip}'", tip=chain.tip_link),
                             hint=M("choose a link further down the arm (--link)"))
    lower = chain.lower if limits else np.full(chain.kernel.size, -np.inf)
    upper = chain.upper if limits else np.full(chain.kernel.size, np.inf)
    low, high = lower.tolist(), upper.tolist()
    goal_list = goal.tolist()
    rng = None
    best: _Descent | None = None
    iterations = repeats = 0
    for attempt in range(max(seeds, 1)):
        if attempt == 0:
            x = np.clip(q_start[chain.variables], lower, upper).tolist()
        else:  # repeatable random restarts within the limits (a full turn where there is none)
            rng = rng or np.random.default_rng(random_seed)
            x = rng.uniform(np.where(np.isfinite(lower), lower, -math.pi),
                            np.where(np.isfinite(upper), upper, math.pi)).tolist()
        descent = _descend(chain.kernel, x, goal_list, goal_rot, low, high, tolerance, rotation_tolerance,
                           max_iterations)
        iterations += descent.iterations
        if best is not None and abs(descent.cost - best.cost) <= 1e-6 * best.cost:
            repeats += 1
        elif best is None or descent.cost < best.cost:
            repeats = 1
        if best is None or descent.converged or descent.cost < best.cost:
            best = descent
        if descent.converged or _close_enough(best.error) or repeats >= SAME_MINIMUM:
            break
    assert best is not None
    q = q_start.copy()
    q[chain.variables] = best.x
    residual = math.sqrt(sum(e * e for e in best.error[:3]))
    rotation_residual = math.sqrt(sum(e * e for e in best.error[3:])) if goal_rot is not None else None
    joints = _joints_dict(tree, q)
    tip_point = np.array(best.tip)
    if best.converged or _close_enough(best.error):
        return IKResult(True, joints, tip_point, goal, residual,
                        Mn("reached in {n} iteration", "reached in {n} iterations", iterations),
                        "numeric", iterations=iterations, rotation_residual=rotation_residual)
    reason, violations = "out_of_reach", []
    message: Message | None = None
    if explain and limits:
        free = solve_chain(chain, goal, rotation=goal_rot, start=q_start, seeds=seeds,
                           max_iterations=max_iterations, tolerance=tolerance,
                           rotation_tolerance=rotation_tolerance, limits=False,
                           random_seed=random_seed, explain=False)
        if free.reachable:
            values = {}
            for j, column in enumerate(chain.variables):
                name = tree.dof[column]
                value = free.joints[name]
                if _unit_of(tree, name) == "rad":
                    value = _fit_angle(value, chain.lower[j], chain.upper[j], q_start[column])
                values[name] = value
            violations = _violations(tree, values, *_bounds(tree))
            if violations:
                reason = "limits"
                message = M("reachable only past the limits: {needs}",
                            needs=joined([v.describe() for v in violations], "; "))
    if message is None:
        where = ", ".join(f"{v:.4f}" for v in tip_point)
        if goal_rot is not None:
            message = M("out of reach: the tip gets no closer than {residual:.4g} m to the target "
                        "(closest pose at {where}), orientation off by {angle:.4g} rad",
                        residual=residual, where=where, angle=rotation_residual)
        else:
            message = M("out of reach: the tip gets no closer than {residual:.4g} m to the target "
                        "(closest point at {where})", residual=residual, where=where)
    else:
        message = M("{message}; within the limits the tip gets no closer than {residual:.4g} m",
                    message=message, residual=residual)
    return IKResult(False, joints, tip_point, goal, residual, message, "numeric", reason=reason,
                    iterations=iterations, rotation_residual=rotation_residual, violations=violations)
