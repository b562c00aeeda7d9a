"""Closed-form inverse kinematics of two revolute joints on parallel axes (the tutorial arm)."""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np

from ..core.errors import ParameterError
from ..core.message import M, Message
from ..core.wording import joined
from ..kinematics.frames import TFTree
from ..model.robot import Robot
from ._inputs import Vector, _as_tree, _joints_dict, _point, _start_vector
from ._kernel import _forward
from ._limits import TWO_PI, _bounds, _fit_angle, _violations
from .chain import SerialChain, serial_chain
from .numeric import solve_chain
from .results import ElbowSolution, IKResult

PLANE_TOLERANCE = 1e-9  # m: a target this close to a planar arm's plane counts as in it
SINGULAR_TOLERANCE = 1e-9  # m: a target this close to the reach boundary is on it (singular pose)


@dataclass(frozen=True)
class PlanarTwoLink:
    """A chain with two revolute joints on parallel axes: the tutorial arm's structure.

    With W the world orientation of the shoulder frame and u its axis, the tip is
    ``shoulder + W Rot(u, q1) (elbow_offset + Rot(u, sign q2) forearm)``. In the plane normal to
    u, with basis (e1, e2), the upper arm has length ``upper`` and the forearm ``lower``; the tip
    stays at ``height`` along u. Angles ``phi_upper``/``phi_lower`` are the arm vectors' angles.
    """

    shoulder: str
    elbow: str
    columns: tuple[int, int]
    origin: np.ndarray  # shoulder position (world)
    frame: np.ndarray  # W (3, 3)
    axis: np.ndarray  # u in the shoulder frame
    e1: np.ndarray
    e2: np.ndarray
    height: float
    upper: float
    lower: float
    phi_upper: float
    phi_lower: float
    sign: float
    chain: SerialChain

    @property
    def normal(self) -> np.ndarray:
        """The joints' axis in the world: the normal of the arm's plane."""
        return self.frame @ self.axis

    @property
    def reach(self) -> tuple[float, float]:
        """Inner and outer radius of the reachable annulus (joint limits aside)."""
        return abs(self.upper - self.lower), self.upper + self.lower


def planar_two_link(model: TFTree | Robot | SerialChain, tip_link: str | None = None,
                    tip_offset: Vector | None = None) -> PlanarTwoLink | None:
    """Detect the two-joint planar structure on the chain to the tip; None if the chain is anything else."""
    chain = model if isinstance(model, SerialChain) else serial_chain(model, tip_link, tip_offset)
    if len(chain.joints) != 2 or not chain.revolute.all() or len(chain.variables) != 2:
        return None
    if not np.allclose(chain.gains, 1.0) or not np.allclose(chain.offsets, 0.0):
        return None
    axis = chain.axes[0]
    second = chain.pre_rot[1] @ chain.axes[1]
    dot = float(axis @ second)
    if abs(abs(dot) - 1.0) > 1e-9:
        return None
    link = chain.pre_pos[1]  # shoulder -> elbow, in the shoulder's rotating frame
    forearm = chain.pre_rot[1] @ chain.end_point  # elbow -> tip, same frame at q2 = 0
    link_plane = link - (link @ axis) * axis
    forearm_plane = forearm - (forearm @ axis) * axis
    upper, lower = float(np.linalg.norm(link_plane)), float(np.linalg.norm(forearm_plane))
    if upper < 1e-12 or lower < 1e-12:
        return None
    e1 = link_plane / upper
    e2 = np.cross(axis, e1)
    return PlanarTwoLink(
        shoulder=chain.joints[0], elbow=chain.joints[1],
        columns=(int(chain.columns[0]), int(chain.columns[1])),
        origin=chain.pre_pos[0].copy(), frame=chain.pre_rot[0].copy(), axis=axis.copy(), e1=e1, e2=e2,
        height=float(link @ axis + forearm @ axis), upper=upper, lower=lower,
        phi_upper=0.0, phi_lower=math.atan2(float(forearm_plane @ e2), float(forearm_plane @ e1)),
        sign=1.0 if dot > 0 else -1.0, chain=chain,
    )


def _two_link_of(chain: SerialChain) -> PlanarTwoLink | None:
    """:func:`planar_two_link`, detected once per compiled chain."""
    if "_two_link" not in chain.__dict__:
        chain.__dict__["_two_link"] = planar_two_link(chain)
    return chain.__dict__["_two_link"]


def _wrap(angle: np.ndarray) -> np.ndarray:
    return np.remainder(angle + math.pi, TWO_PI) - math.pi


@dataclass(frozen=True)
class _TwoLinkSolve:
    """Both elbow solutions for a batch of targets (arrays of shape (N,) unless said)."""

    q_up: np.ndarray  # (N, 2): shoulder, elbow
    q_down: np.ndarray  # (N, 2)
    distance: np.ndarray  # in-plane distance from the shoulder axis
    off_plane: np.ndarray  # signed distance from the plane


def _two_link_angles(arm: PlanarTwoLink, targets: np.ndarray) -> _TwoLinkSolve:
    local = (targets - arm.origin) @ arm.frame  # W^T (p - origin)
    off = local @ arm.axis - arm.height
    x, y = local @ arm.e1, local @ arm.e2
    distance = np.hypot(x, y)
    cosine = (distance ** 2 - arm.upper ** 2 - arm.lower ** 2) / (2.0 * arm.upper * arm.lower)
    gamma = np.arccos(np.clip(cosine, -1.0, 1.0))  # angle between upper arm and forearm (in plane)
    # on the boundary arccos is ill-conditioned (1 - 1e-16 -> 1e-8 rad): snap to stretched / folded
    inner, outer = arm.reach
    gamma = np.where(distance >= outer - SINGULAR_TOLERANCE, 0.0, gamma)
    gamma = np.where(distance <= inner + SINGULAR_TOLERANCE, math.pi, gamma)
    solutions = []
    for g in (gamma, -gamma):
        q2 = arm.sign * (g + arm.phi_upper - arm.phi_lower)
        vx = arm.upper * math.cos(arm.phi_upper) + arm.lower * np.cos(g + arm.phi_upper)
        vy = arm.upper * math.sin(arm.phi_upper) + arm.lower * np.sin(g + arm.phi_upper)
        q1 = np.arctan2(y, x) - np.arctan2(vy, vx)
        solutions.append(np.stack([_wrap(q1), _wrap(q2)], axis=-1))
    first, second = solutions
    # "up": the elbow on the +z side of the shoulder -> target line (ties: positive elbow angle)
    side = _elbow_side(arm, first[:, 0], x, y)
    first_is_up = np.where(np.abs(side) > 1e-12, side > 0, first[:, 1] >= 0)
    q_up = np.where(first_is_up[:, None], first, second)
    q_down = np.where(first_is_up[:, None], second, first)
    return _TwoLinkSolve(q_up, q_down, distance, off)


def _elbow_side(arm: PlanarTwoLink, q1: np.ndarray, x: np.ndarray, y: np.ndarray) -> np.ndarray:
    """World z of the elbow's offset from the shoulder -> target line, for shoulder angles q1."""
    c, s = np.cos(q1 + arm.phi_upper), np.sin(q1 + arm.phi_upper)
    ex, ey = arm.upper * c, arm.upper * s  # elbow in plane coordinates
    norm = np.hypot(x, y)
    safe = np.where(norm > 0, norm, 1.0)
    dx, dy = x / safe, y / safe
    along = ex * dx + ey * dy
    px, py = ex - along * dx, ey - along * dy  # perpendicular part
    world = arm.frame @ np.stack([arm.e1, arm.e2], axis=1)  # (3, 2): plane axes in the world
    return world[2, 0] * px + world[2, 1] * py


def ik_2r_batch(arm: PlanarTwoLink, targets: np.ndarray, elbow: str = "up") -> tuple[np.ndarray, np.ndarray]:
    """Closed-form solutions for many targets at once (joint limits not applied).

    Returns (q (N, 2) shoulder and elbow angles, ok (N,) bool: in the plane and within the
    annulus). Use :func:`ik_2r` for one target with limits and explanations.
    """
    targets = np.atleast_2d(np.asarray(targets, dtype=float))
    solve = _two_link_angles(arm, targets)
    inner, outer = arm.reach
    ok = ((np.abs(solve.off_plane) <= PLANE_TOLERANCE) & (solve.distance <= outer + SINGULAR_TOLERANCE)
          & (solve.distance >= inner - SINGULAR_TOLERANCE))
    return (solve.q_up if elbow == "up" else solve.q_down), ok


def _plane_description(arm: PlanarTwoLink) -> Message | str:
    normal = arm.normal
    axis = int(np.argmax(np.abs(normal)))
    level = float(arm.origin @ normal + arm.height)  # points p of the plane: normal . p = level
    if abs(abs(normal[axis]) - 1.0) < 1e-9:
        value = level * normal[axis]
        return f"{'xyz'[axis]} = {value + 0.0:.4g}"
    return M("the plane through ({point}) normal to ({normal})", point=", ".join(f"{v:.3g}" for v in arm.origin),
             normal=", ".join(f"{v:.3g}" for v in normal))


def _elbow_needs(solution: ElbowSolution) -> Message:
    """"elbow up: coude would need ..., ..." (the joints an elbow choice takes past their limits)."""
    needs = joined([v.describe() for v in solution.violations])
    if solution.elbow == "up":
        return M("elbow up: {needs}", needs=needs)
    return M("elbow down: {needs}", needs=needs)


def ik_2r(model: TFTree | Robot, target: Vector, *, elbow: str | None = None,
          start: Mapping[str, float] | None = None, tip_link: str | None = None,
          tip_offset: Vector | None = None) -> IKResult:
    """Closed-form inverse kinematics of a two-joint planar arm (the tutorial arm).

    ``elbow`` is "up", "down" or None (the solution within limits closest to ``start``).
    Raises :class:`ParameterError` when the chain to the tip is not two revolute joints with
    parallel axes (use :func:`solve_ik`). Both solutions are in ``result.solutions``.
    """
    tree = _as_tree(model)
    if elbow not in (None, "up", "down"):
        raise ParameterError(M("elbow must be 'up' or 'down', not {elbow!r}", elbow=str(elbow)))
    goal = _point(target, M("the target"))
    q_start = _start_vector(tree, start)
    chain = serial_chain(tree, tip_link, tip_offset)
    arm = _two_link_of(chain)
    if arm is None:
        raise ParameterError(
            M("the chain to '{tip}' is not two revolute joints with parallel axes (joints: {joints})",
              tip=chain.tip_link, joints=", ".join(chain.joints) or M("none")),
            hint=M("use the numeric solver (solve_ik)"))
    lower, upper = _bounds(tree)
    solve = _two_link_angles(arm, goal[None, :])
    distance, off = float(solve.distance[0]), float(solve.off_plane[0])
    inner, outer = arm.reach
    c1, c2 = arm.columns

    def failure(reason: str, message: Message, violations=(), solutions=()) -> IKResult:
        closest = solve_chain(chain, goal, start=q_start, explain=False)
        return IKResult(False, closest.joints, closest.tip, goal, closest.residual, message, "analytic",
                        reason=reason, iterations=closest.iterations, violations=list(violations),
                        solutions=list(solutions))

    if abs(off) > PLANE_TOLERANCE:
        return failure("off_plane", M("out of reach: the arm moves in a plane ({plane}) and the target is "
                                      "{off:.4g} m off it", plane=_plane_description(arm), off=abs(off)))
    if distance > outer + SINGULAR_TOLERANCE:
        return failure("too_far", M("out of reach: the target is {excess:.4g} m too far ({distance:.4g} m from the "
                                    "shoulder axis, the arm reaches {outer:.4g} m)", excess=distance - outer,
                                    distance=distance, outer=outer))
    if distance < inner - SINGULAR_TOLERANCE:
        return failure("too_close", M("out of reach: the target is {excess:.4g} m too close to the shoulder axis "
                                      "({distance:.4g} m; the arm cannot fold closer than {inner:.4g} m)",
                                      excess=inner - distance, distance=distance, inner=inner))
    singular: Message | None = None
    if distance < SINGULAR_TOLERANCE:
        singular = M("the target is on the shoulder axis: any shoulder angle works (singular pose)")
    elif abs(distance - outer) <= SINGULAR_TOLERANCE:
        singular = M("the arm is fully stretched (singular pose: the tip cannot move towards or away from the shoulder)")
    elif abs(distance - inner) <= SINGULAR_TOLERANCE:
        singular = M("the arm is fully folded (singular pose: the tip cannot move towards or away from the shoulder)")

    solutions = []
    for name, q in (("up", solve.q_up[0]), ("down", solve.q_down[0])):
        values = q_start.copy()
        q1 = float(q_start[c1]) if distance < SINGULAR_TOLERANCE else float(q[0])
        values[c1] = _fit_angle(q1, lower[c1], upper[c1], q_start[c1])
        values[c2] = _fit_angle(float(q[1]), lower[c2], upper[c2], q_start[c2])
        chosen = {tree.dof[c1]: float(values[c1]), tree.dof[c2]: float(values[c2])}
        solutions.append(ElbowSolution(name, _joints_dict(tree, values), _violations(tree, chosen, lower, upper)))
    if elbow is not None:
        pick = next(s for s in solutions if s.elbow == elbow)
    else:
        candidates = [s for s in solutions if s.within_limits] or solutions
        pick = min(candidates, key=lambda s: sum((s.joints[n] - q_start[tree.dof.index(n)]) ** 2
                                                   for n in (tree.dof[c1], tree.dof[c2])))
    if not pick.within_limits:
        other = next(s for s in solutions if s is not pick)
        details = [_elbow_needs(pick)]
        if other.within_limits:
            details.append(M("elbow up is within the limits") if other.elbow == "up" else
                           M("elbow down is within the limits"))
        elif elbow is None:
            details.append(_elbow_needs(other))
        message = M("reachable only past the limits ({details})", details=joined(details, "; "))
        return failure("limits", message, pick.violations, solutions)
    q = np.array([pick.joints[n] for n in tree.dof])
    tip = np.array(_forward(chain.kernel, q[chain.variables].tolist())[0])
    residual = float(np.linalg.norm(tip - goal))
    message = M("reached with elbow up") if pick.elbow == "up" else M("reached with elbow down")
    if singular is not None:
        message = M("{reached}; {singular}", reached=message, singular=singular)
    return IKResult(True, pick.joints, tip, goal, residual, message, "analytic", reason="singular" if singular else "ok",
                    elbow=pick.elbow, singular=bool(singular), solutions=solutions)
