"""Inverse kinematics: joint values that put a point of the arm (the tip) at a target.

Two solvers share one result type, :class:`IKResult`:

- :func:`ik_2r`, closed form, for chains whose structure is the tutorial arm's: two revolute
  joints with parallel axes and a tip offset. The structure is read from the model
  (:func:`planar_two_link`), never hard-coded: shoulder position from the first joint's origin,
  upper-arm length from the second joint's origin, forearm length from the tip offset. It gives
  both elbow solutions and says why a target fails (too far, too close, off the arm's plane,
  or a joint past its limit, named, with the excess).
- :func:`solve_chain` / :func:`solve_ik`, numeric, for any serial chain: damped least squares
  with Levenberg-Marquardt damping on the geometric Jacobian, joint limits enforced by
  projection, several seeds solved at once as one numpy batch (deterministic random seeds).

:func:`jacobian` gives the geometric Jacobian on its own. :func:`reach_motion` builds the
joint-space motion from a start pose to a solution, slow enough for every velocity limit, and
:func:`workspace_points` / :func:`workspace_figure` sample and draw the region the tip can reach.

The tip is a point fixed in a link: by default the deepest link of the tree, at the far end of
its visual geometry along its local z (for the tutorial arm: 0.5 m up ``avant_bras``).
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from .errors import ParameterError
from .kinematics import _PRISMATIC, _REVOLUTE, TFTree, fk_batch, rpy_to_matrix, tf_tree
from .model import Geometry, Robot

TWO_PI = 2.0 * math.pi
PLANE_TOLERANCE = 1e-9  # m: a target this close to a planar arm's plane counts as in it
SINGULAR_TOLERANCE = 1e-9  # m: a target this close to the reach boundary is on it (singular pose)
QUINTIC_PEAK = 15.0 / 8.0  # peak of d/dtau of 10 tau^3 - 15 tau^4 + 6 tau^5, at tau = 1/2

# ---------------------------------------------------------------- inputs


def _as_tree(model: TFTree | Robot) -> TFTree:
    return model if isinstance(model, TFTree) else tf_tree(model)


def _point(values: Sequence[float], what: str) -> np.ndarray:
    try:
        point = np.asarray(values, dtype=float).reshape(-1)
    except (TypeError, ValueError):
        raise ParameterError(f"{what} {values!r} is not three numbers", hint="give X Y Z in metres") from None
    if point.shape != (3,):
        raise ParameterError(f"{what} needs three numbers (x y z), got {point.size}", hint="give X Y Z in metres")
    if not np.all(np.isfinite(point)):
        raise ParameterError(f"{what} ({', '.join(f'{v:g}' for v in point)}) is not finite",
                             hint="give finite numbers in metres (no nan or inf)")
    return point


def _start_vector(tree: TFTree, start: Mapping[str, float] | np.ndarray | None) -> np.ndarray:
    if start is None:
        return np.zeros(len(tree.dof))
    if isinstance(start, Mapping):
        q = tree.config_vector(start)
    else:
        q = np.asarray(start, dtype=float).reshape(-1)
        if q.shape != (len(tree.dof),):
            raise ParameterError(f"the start pose needs {len(tree.dof)} values ({', '.join(tree.dof)})")
    if not np.all(np.isfinite(q)):
        raise ParameterError("the start pose holds a value that is not finite", hint="give numbers (no nan or inf)")
    return q


def _bounds(tree: TFTree) -> tuple[np.ndarray, np.ndarray]:
    pairs = [joint.bounds() for joint in tree.dof_joints()]
    lower = np.array([p[0] for p in pairs], dtype=float)
    upper = np.array([p[1] for p in pairs], dtype=float)
    return lower, upper


# ---------------------------------------------------------------- the tip


def _far_end_along_z(geometry: Geometry | None, rotation: np.ndarray) -> float | None:
    """How far the geometry reaches along the link's z from the visual origin (None: unknown)."""
    if geometry is None:
        return None
    row = np.abs(rotation[2])  # how the geometry's own axes project on the link's z
    if geometry.kind == "box" and geometry.size is not None:
        return float(row @ np.asarray(geometry.size, dtype=float)) / 2.0
    if geometry.kind == "cylinder" and geometry.length is not None and geometry.radius is not None:
        return float(row[2] * geometry.length / 2.0 + geometry.radius * math.hypot(row[0], row[1]))
    if geometry.kind == "sphere" and geometry.radius is not None:
        return float(geometry.radius)
    return None  # meshes: the extent is unknown without loading the file


def link_tip_offset(robot: Robot, link_name: str) -> np.ndarray:
    """The far end of a link's visual geometry along its local z, as a point (0, 0, z) in its frame.

    For a segment drawn from its frame up z (the tutorial's boxes), z is the segment's length.
    Links without a visual, or whose geometry is a mesh, give (0, 0, 0): the frame origin.
    """
    link = robot.link(link_name)
    top = 0.0
    for visual in link.visuals if link is not None else []:
        half = _far_end_along_z(visual.geometry, rpy_to_matrix(visual.origin.rpy))
        if half is not None:
            top = max(top, visual.origin.xyz[2] + half)
    return np.array([0.0, 0.0, top])


def default_tip_link(tree: TFTree) -> str:
    """The end of the longest chain: the deepest link (the first one met, on a tie)."""
    depth = [0] * len(tree.links)
    for i in range(1, len(tree.links)):
        depth[i] = depth[tree.parent[i]] + 1
    return tree.links[int(np.argmax(depth))]


def resolve_tip(tree: TFTree, tip_link: str | None = None,
                tip_offset: Sequence[float] | None = None) -> tuple[str, np.ndarray]:
    """(link, point in the link's frame): defaults are the deepest link and its far end along z."""
    link = default_tip_link(tree) if tip_link is None else tree.links[tree.index(tip_link)]
    if tip_offset is None:
        return link, link_tip_offset(tree.robot, link)
    return link, _point(tip_offset, "the tip offset")


# ---------------------------------------------------------------- the serial chain


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
    # Rodrigues split, premultiplied by the constant rotation before each joint:
    # pre_rot Rot(a, t) = outer + cos t * rest + sin t * skew, and pre_rot a = pre_axis
    outer: np.ndarray  # (m, 3, 3) pre_rot a a^T
    rest: np.ndarray  # (m, 3, 3) pre_rot (I - a a^T)
    skew: np.ndarray  # (m, 3, 3) pre_rot [a]x
    pre_axis: np.ndarray  # (m, 3)

    @property
    def variable_names(self) -> list[str]:
        return [self.tree.dof[c] for c in self.variables]


def serial_chain(model: TFTree | Robot, tip_link: str | None = None,
                 tip_offset: Sequence[float] | None = None) -> SerialChain:
    """Compile the chain from the root to the tip (see :func:`resolve_tip` for the defaults)."""
    tree = _as_tree(model)
    link, offset = resolve_tip(tree, tip_link, tip_offset)
    path = []
    i = tree.index(link)
    while i > 0:
        path.append(i)
        i = tree.parent[i]
    path.reverse()
    rot, pos = np.eye(3), np.zeros(3)
    names, revolute, axes, pre_rot, pre_pos, columns, gains, offsets = [], [], [], [], [], [], [], []
    for i in path:
        origin = tree._origin[i]
        pos = pos + rot @ origin[:3, 3]
        rot = rot @ origin[:3, :3]
        if tree._kind[i] not in (_REVOLUTE, _PRISMATIC):
            continue
        names.append(tree.joints[i].name)  # type: ignore[union-attr]
        revolute.append(tree._kind[i] == _REVOLUTE)
        axes.append(tree._axis[i])
        pre_rot.append(rot)
        pre_pos.append(pos)
        columns.append(tree._source[i])
        gains.append(tree._gain[i])
        offsets.append(tree._offset[i])
        rot, pos = np.eye(3), np.zeros(3)
    variables = list(dict.fromkeys(columns))
    lower, upper = _bounds(tree)
    m = len(names)
    unit = np.array(axes).reshape(m, 3)
    outer = unit[:, :, None] * unit[:, None, :]
    skew = np.zeros((m, 3, 3))
    skew[:, 0, 1], skew[:, 0, 2], skew[:, 1, 2] = -unit[:, 2], unit[:, 1], -unit[:, 0]
    skew -= np.swapaxes(skew, 1, 2)
    chain_rot = np.array(pre_rot).reshape(m, 3, 3)
    return SerialChain(
        tree=tree, tip_link=link, tip_offset=offset, joints=tuple(names),
        revolute=np.array(revolute, dtype=bool), axes=np.array(axes).reshape(m, 3),
        pre_rot=np.array(pre_rot).reshape(m, 3, 3), pre_pos=np.array(pre_pos).reshape(m, 3),
        columns=np.array(columns, dtype=int), gains=np.array(gains, dtype=float),
        offsets=np.array(offsets, dtype=float), end_rot=rot, end_point=pos + rot @ offset,
        variables=np.array(variables, dtype=int),
        joint_var=np.array([variables.index(c) for c in columns], dtype=int),
        lower=lower[variables], upper=upper[variables],
        outer=chain_rot @ outer, rest=chain_rot @ (np.eye(3)[None] - outer), skew=chain_rot @ skew,
        pre_axis=np.einsum("kij,kj->ki", chain_rot, unit),
    )


def _chain_forward(chain: SerialChain, q: np.ndarray):  # type: ignore[no-untyped-def]
    """Tip position (B,3), tip rotation (B,3,3), joint origins and world axes (B,m,3) for configs q (B,dof)."""
    count = q.shape[0]
    m = len(chain.joints)
    rot: np.ndarray | None = None  # None: identity, so the first joint skips a product
    pos: np.ndarray = np.zeros(3)
    origins = np.empty((count, m, 3))
    axes = np.empty((count, m, 3))
    for k in range(m):
        value = q[:, chain.columns[k]] * chain.gains[k] + chain.offsets[k]
        if rot is None:
            pos, axis = pos + chain.pre_pos[k], chain.pre_axis[k]
        else:
            pos, axis = pos + rot @ chain.pre_pos[k], rot @ chain.pre_axis[k]
        if chain.revolute[k]:
            local = (chain.outer[k] + np.cos(value)[:, None, None] * chain.rest[k]
                     + np.sin(value)[:, None, None] * chain.skew[k])
        else:
            local = chain.pre_rot[k]
            pos = pos + value[:, None] * axis
        rot = local if rot is None else rot @ local
        origins[:, k] = pos
        axes[:, k] = axis
    if rot is None:
        rot = np.eye(3)
    tip = np.broadcast_to(pos + rot @ chain.end_point, (count, 3)).copy()
    tip_rot = np.broadcast_to(rot @ chain.end_rot, (count, 3, 3))
    return tip, tip_rot, origins, axes


def _chain_jacobian(chain: SerialChain, tip: np.ndarray, origins: np.ndarray, axes: np.ndarray,
                    orientation: bool) -> np.ndarray:
    """Geometric Jacobian (B, 3 or 6, k) over the chain's variables, world frame."""
    arm = tip[:, None, :] - origins
    cross = np.empty_like(arm)
    cross[..., 0] = axes[..., 1] * arm[..., 2] - axes[..., 2] * arm[..., 1]
    cross[..., 1] = axes[..., 2] * arm[..., 0] - axes[..., 0] * arm[..., 2]
    cross[..., 2] = axes[..., 0] * arm[..., 1] - axes[..., 1] * arm[..., 0]
    linear = np.where(chain.revolute[None, :, None], cross, axes) * chain.gains[None, :, None]
    columns = linear
    if orientation:
        angular = np.where(chain.revolute[None, :, None], axes, 0.0) * chain.gains[None, :, None]
        columns = np.concatenate([linear, angular], axis=2)
    columns = np.swapaxes(columns, 1, 2)  # (B, rows, m)
    k = len(chain.variables)
    if k == len(chain.joints):  # one joint per variable, in chain order
        return columns
    out = np.zeros(columns.shape[:2] + (k,))
    for j, var in enumerate(chain.joint_var):
        out[:, :, var] += columns[:, :, j]
    return out


def jacobian(model: TFTree | Robot, q: Mapping[str, float] | np.ndarray | Sequence[float] | None = None,
             tip_link: str | None = None, tip_offset: Sequence[float] | None = None, *,
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
        raise ParameterError(f"expected {len(tree.dof)} joint values ({', '.join(tree.dof)}), got {batch.shape[-1]}")
    rows = 6 if orientation else 3
    out = np.zeros((batch.shape[0], rows, len(tree.dof)))
    if len(chain.joints):
        tip, _, origins, axes = _chain_forward(chain, batch)
        out[:, :, chain.variables] = _chain_jacobian(chain, tip, origins, axes, orientation)
    return out[0] if single else out


def tip_positions(model: TFTree | Robot, q: np.ndarray, tip_link: str | None = None,
                  tip_offset: Sequence[float] | None = None) -> np.ndarray:
    """World position of the tip for configurations q (N, dof) -> (N, 3) (or (dof,) -> (3,))."""
    chain = serial_chain(model, tip_link, tip_offset)
    q = np.asarray(q, dtype=float)
    batch = q[None, :] if q.ndim == 1 else q
    tip = np.array(_chain_forward(chain, batch)[0])
    return tip[0] if q.ndim == 1 else tip


# ---------------------------------------------------------------- results


@dataclass(frozen=True)
class LimitExcess:
    """A joint value a solution needs beyond the joint's limit."""

    joint: str
    value: float
    bound: float
    side: str  # "lower" or "upper"
    unit: str = "rad"

    @property
    def excess(self) -> float:
        return abs(self.value - self.bound)

    def describe(self) -> str:
        return (f"{self.joint} would need {self.value:.4f} {self.unit}, {self.excess:.4f} {self.unit} "
                f"past its {self.side} limit {self.bound:g}")


@dataclass
class ElbowSolution:
    """One of the two closed-form solutions of a two-joint planar arm."""

    elbow: str  # "up" or "down"
    joints: dict[str, float]
    violations: list[LimitExcess] = field(default_factory=list)

    @property
    def within_limits(self) -> bool:
        return not self.violations


@dataclass
class IKResult:
    """What a solver found.

    ``reachable`` is True when ``joints`` put the tip on the target (within the solver's
    tolerance) and within every limit. Otherwise ``joints`` is the closest pose found within
    the limits, ``reason`` says why (``too_far``, ``too_close``, ``off_plane``, ``limits``,
    ``out_of_reach``) and ``message`` says it in words. ``singular`` marks a reachable target on
    a singular pose (fully stretched or folded arm, tip on the shoulder axis).
    """

    reachable: bool
    joints: dict[str, float]
    tip: np.ndarray
    target: np.ndarray
    residual: float  # m, distance from tip to target
    message: str
    method: str  # "analytic" or "numeric"
    reason: str = "ok"
    iterations: int = 0
    elbow: str | None = None
    singular: bool = False
    rotation_residual: float | None = None  # rad, when an orientation was asked
    violations: list[LimitExcess] = field(default_factory=list)
    solutions: list[ElbowSolution] = field(default_factory=list)

    def as_dict(self) -> dict[str, object]:
        out: dict[str, object] = {
            "reachable": bool(self.reachable),
            "joints": {k: float(v) for k, v in self.joints.items()},
            "tip": [float(v) for v in self.tip],
            "target": [float(v) for v in self.target],
            "residual": float(self.residual),
            "message": self.message,
            "method": self.method,
            "reason": self.reason,
            "singular": bool(self.singular),
            "iterations": int(self.iterations),
        }
        if self.elbow is not None:
            out["elbow"] = self.elbow
        if self.rotation_residual is not None:
            out["rotation_residual"] = float(self.rotation_residual)
        if self.violations:
            out["violations"] = [{"joint": v.joint, "value": v.value, "bound": v.bound, "side": v.side,
                                  "excess": v.excess} for v in self.violations]
        if self.solutions:
            out["solutions"] = [{"elbow": s.elbow, "joints": s.joints, "within_limits": s.within_limits}
                                for s in self.solutions]
        return out


def _unit_of(tree: TFTree, name: str) -> str:
    joint = tree.robot.joint(name)
    return "m" if joint is not None and joint.type == "prismatic" else "rad"


def _fit_angle(value: float, lower: float, upper: float, reference: float) -> float:
    """``value`` + 2 pi k: within [lower, upper] and closest to ``reference`` if possible, else least outside."""
    base = math.remainder(value, TWO_PI)
    candidates = [base + TWO_PI * k for k in range(-3, 4)]

    def outside(v: float) -> float:
        return max(lower - v, v - upper, 0.0)

    return min(candidates, key=lambda v: (outside(v) > 1e-12, outside(v), abs(v - reference)))


def _violations(tree: TFTree, values: Mapping[str, float], lower: np.ndarray, upper: np.ndarray,
                tolerance: float = 1e-12) -> list[LimitExcess]:
    out = []
    for name, value in values.items():
        i = tree.dof.index(name)
        if value < lower[i] - tolerance:
            out.append(LimitExcess(name, value, float(lower[i]), "lower", _unit_of(tree, name)))
        elif value > upper[i] + tolerance:
            out.append(LimitExcess(name, value, float(upper[i]), "upper", _unit_of(tree, name)))
    return out


def _joints_dict(tree: TFTree, q: np.ndarray) -> dict[str, float]:
    return {name: float(q[i]) for i, name in enumerate(tree.dof)}


# ---------------------------------------------------------------- closed form: two-joint planar arm


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


def planar_two_link(model: TFTree | Robot, tip_link: str | None = None,
                    tip_offset: Sequence[float] | None = None) -> PlanarTwoLink | None:
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


def _plane_description(arm: PlanarTwoLink) -> str:
    normal = arm.normal
    axis = int(np.argmax(np.abs(normal)))
    level = float(arm.origin @ normal + arm.height)  # points p of the plane: normal . p = level
    if abs(abs(normal[axis]) - 1.0) < 1e-9:
        value = level * normal[axis]
        return f"{'xyz'[axis]} = {value + 0.0:.4g}"
    return f"the plane through ({', '.join(f'{v:.3g}' for v in arm.origin)}) normal to ({', '.join(f'{v:.3g}' for v in normal)})"


def ik_2r(model: TFTree | Robot, target: Sequence[float], *, elbow: str | None = None,
          start: Mapping[str, float] | None = None, tip_link: str | None = None,
          tip_offset: Sequence[float] | None = None) -> IKResult:
    """Closed-form inverse kinematics of a two-joint planar arm (the tutorial arm).

    ``elbow`` is "up", "down" or None (the solution within limits closest to ``start``).
    Raises :class:`ParameterError` when the chain to the tip is not two revolute joints with
    parallel axes (use :func:`solve_ik`). Both solutions are in ``result.solutions``.
    """
    tree = _as_tree(model)
    if elbow not in (None, "up", "down"):
        raise ParameterError(f"elbow must be 'up' or 'down', not {elbow!r}")
    goal = _point(target, "the target")
    q_start = _start_vector(tree, start)
    chain = serial_chain(tree, tip_link, tip_offset)
    arm = planar_two_link(chain)
    if arm is None:
        raise ParameterError(
            f"the chain to '{chain.tip_link}' is not two revolute joints with parallel axes "
            f"(joints: {', '.join(chain.joints) or 'none'})", hint="use the numeric solver (solve_ik)")
    lower, upper = _bounds(tree)
    solve = _two_link_angles(arm, goal[None, :])
    distance, off = float(solve.distance[0]), float(solve.off_plane[0])
    inner, outer = arm.reach
    c1, c2 = arm.columns

    def failure(reason: str, message: str, violations=(), solutions=()) -> IKResult:  # type: ignore[no-untyped-def]
        closest = solve_chain(chain, goal, start=q_start, seeds=8, explain=False)
        return IKResult(False, closest.joints, closest.tip, goal, closest.residual, message, "analytic",
                        reason=reason, iterations=closest.iterations, violations=list(violations),
                        solutions=list(solutions))

    if abs(off) > PLANE_TOLERANCE:
        return failure("off_plane", f"out of reach: the arm moves in a plane ({_plane_description(arm)}) "
                       f"and the target is {abs(off):.4g} m off it")
    if distance > outer + SINGULAR_TOLERANCE:
        return failure("too_far", f"out of reach: the target is {distance - outer:.4g} m too far "
                       f"({distance:.4g} m from the shoulder axis, the arm reaches {outer:.4g} m)")
    if distance < inner - SINGULAR_TOLERANCE:
        return failure("too_close", f"out of reach: the target is {inner - distance:.4g} m too close to "
                       f"the shoulder axis ({distance:.4g} m; the arm cannot fold closer than {inner:.4g} m)")
    singular = ""
    if distance < SINGULAR_TOLERANCE:
        singular = "the target is on the shoulder axis: any shoulder angle works (singular pose)"
    elif abs(distance - outer) <= SINGULAR_TOLERANCE:
        singular = "the arm is fully stretched (singular pose: the tip cannot move towards or away from the shoulder)"
    elif abs(distance - inner) <= SINGULAR_TOLERANCE:
        singular = "the arm is fully folded (singular pose: the tip cannot move towards or away from the shoulder)"

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
        details = [f"elbow {pick.elbow}: " + ", ".join(v.describe() for v in pick.violations)]
        if other.within_limits:
            details.append(f"elbow {other.elbow} is within the limits")
        elif elbow is None:
            details.append(f"elbow {other.elbow}: " + ", ".join(v.describe() for v in other.violations))
        message = "reachable only past the limits (" + "; ".join(details) + ")"
        return failure("limits", message, pick.violations, solutions)
    q = np.array([pick.joints[n] for n in tree.dof])
    tip = np.array(_chain_forward(chain, q[None, :])[0][0])
    residual = float(np.linalg.norm(tip - goal))
    message = f"reached with elbow {pick.elbow}" + (f"; {singular}" if singular else "")
    return IKResult(True, pick.joints, tip, goal, residual, message, "analytic", reason="singular" if singular else "ok",
                    elbow=pick.elbow, singular=bool(singular), solutions=solutions)


# ---------------------------------------------------------------- numeric: damped least squares


def _rotation_error(target: np.ndarray, rot: np.ndarray) -> np.ndarray:
    """Rotation vectors e (B, 3) with ``target = exp([e]) rot`` (world frame)."""
    m = target[None] @ np.swapaxes(rot, 1, 2)
    v = 0.5 * np.stack([m[:, 2, 1] - m[:, 1, 2], m[:, 0, 2] - m[:, 2, 0], m[:, 1, 0] - m[:, 0, 1]], axis=1)
    sine = np.linalg.norm(v, axis=1)
    cosine = np.clip((np.trace(m, axis1=1, axis2=2) - 1.0) / 2.0, -1.0, 1.0)
    angle = np.arctan2(sine, cosine)
    scale = np.where(sine > 1e-12, angle / np.where(sine > 1e-12, sine, 1.0), 1.0)
    out = v * scale[:, None]
    flip = (sine <= 1e-6) & (cosine < 0)  # near a half turn the skew part vanishes: use the diagonal
    for b in np.flatnonzero(flip):
        sym = (m[b] + np.eye(3)) / 2.0
        column = sym[:, int(np.argmax(np.diag(sym)))]
        out[b] = column / np.linalg.norm(column) * angle[b]
    return out


def _residuals(chain: SerialChain, q: np.ndarray, goal: np.ndarray, goal_rot: np.ndarray | None):
    tip, tip_rot, origins, axes = _chain_forward(chain, q)
    error = goal[None, :] - tip
    if goal_rot is not None:
        error = np.concatenate([error, _rotation_error(goal_rot, tip_rot)], axis=1)
    return error, tip, origins, axes


def solve_chain(chain: SerialChain, target: Sequence[float], *, rotation: np.ndarray | None = None,
                start: Mapping[str, float] | np.ndarray | None = None, seeds: int = 8,
                max_iterations: int = 200, tolerance: float = 1e-12, rotation_tolerance: float = 1e-10,
                limits: bool = True, random_seed: int = 0, explain: bool = True) -> IKResult:
    """Numeric inverse kinematics on a compiled chain (see :func:`solve_ik`)."""
    tree = chain.tree
    goal = _point(target, "the target")
    goal_rot = None if rotation is None else np.asarray(rotation, dtype=float).reshape(3, 3)
    q_start = _start_vector(tree, start)
    k = len(chain.variables)
    if k == 0:
        raise ParameterError(f"no movable joint moves '{chain.tip_link}'",
                             hint="choose a link further down the arm (--link)")
    lower = chain.lower if limits else np.where(np.isfinite(chain.lower), -np.inf, chain.lower)
    upper = chain.upper if limits else np.where(np.isfinite(chain.upper), np.inf, chain.upper)
    rng = np.random.default_rng(random_seed)
    sample_low = np.where(np.isfinite(lower), lower, -math.pi)
    sample_high = np.where(np.isfinite(upper), upper, math.pi)

    def draw(count: int) -> np.ndarray:
        return rng.uniform(sample_low, sample_high, size=(count, k))

    x = np.vstack([np.clip(q_start[chain.variables], lower, upper)[None, :], draw(max(seeds, 1) - 1)])
    full = np.repeat(q_start[None, :], len(x), axis=0)
    full[:, chain.variables] = x
    error, tip, origins, axes = _residuals(chain, full, goal, goal_rot)
    cost = np.einsum("ij,ij->i", error, error)
    damping = np.full(len(x), 1e-3)
    stale = np.zeros(len(x), dtype=int)
    best_cost, best_x = np.inf, x[0].copy()
    eye = np.eye(k)
    iterations = 0

    def converged(err: np.ndarray) -> np.ndarray:
        ok = np.einsum("ij,ij->i", err[:, :3], err[:, :3]) <= tolerance ** 2
        if goal_rot is not None:
            ok &= np.einsum("ij,ij->i", err[:, 3:], err[:, 3:]) <= rotation_tolerance ** 2
        return ok

    done = converged(error)
    while not done.any() and iterations < max_iterations:
        iterations += 1
        jac = _chain_jacobian(chain, tip, origins, axes, goal_rot is not None)
        grad = np.einsum("brk,br->bk", jac, error)  # descent direction J^T e
        blocked = ((x <= lower) & (grad < 0)) | ((x >= upper) & (grad > 0))
        jac = jac * ~blocked[:, None, :]
        grad = grad * ~blocked
        normal = np.einsum("brk,brl->bkl", jac, jac) + damping[:, None, None] * eye
        step = np.linalg.solve(normal, grad[:, :, None])[:, :, 0]
        leaving = (x + step < lower) | (x + step > upper)
        if leaving.any():
            # joints that would leave their range stop on the bound; the others re-solve for what is left
            fixed = np.where(leaving, np.clip(x + step, lower, upper) - x, 0.0)
            rest = error - np.einsum("brk,bk->br", jac, fixed)
            free_jac = jac * ~leaving[:, None, :]
            normal = np.einsum("brk,brl->bkl", free_jac, free_jac) + damping[:, None, None] * eye
            moved = np.linalg.solve(normal, np.einsum("brk,br->bk", free_jac, rest)[:, :, None])[:, :, 0]
            step = np.where(leaving, fixed, moved)
        trial = np.clip(x + step, lower, upper)
        full[:, chain.variables] = trial
        t_error, t_tip, t_origins, t_axes = _residuals(chain, full, goal, goal_rot)
        t_cost = np.einsum("ij,ij->i", t_error, t_error)
        better = t_cost < cost
        progress = better & (t_cost < cost * (1.0 - 1e-6))
        x = np.where(better[:, None], trial, x)
        error = np.where(better[:, None], t_error, error)
        tip = np.where(better[:, None], t_tip, tip)
        origins = np.where(better[:, None, None], t_origins, origins)
        axes = np.where(better[:, None, None], t_axes, axes)
        cost = np.where(better, t_cost, cost)
        damping = np.where(better, np.maximum(damping * 0.3, 1e-12), damping * 10.0)
        stale = np.where(progress, 0, stale + 1)
        done = converged(error)
        stuck = ~done & ((damping > 1e4) | (stale >= 8))
        if stuck.any():  # a local minimum (or the closest point): remember it, restart from a new seed
            worst = int(np.argmin(np.where(stuck, cost, np.inf)))
            if cost[worst] < best_cost:
                best_cost, best_x = float(cost[worst]), x[worst].copy()
            rows = np.flatnonzero(stuck)
            x[rows] = draw(len(rows))
            full[:, chain.variables] = x
            r_error, r_tip, r_origins, r_axes = _residuals(chain, full[rows], goal, goal_rot)
            error[rows], tip[rows], origins[rows], axes[rows] = r_error, r_tip, r_origins, r_axes
            cost[rows] = np.einsum("ij,ij->i", r_error, r_error)
            damping[rows], stale[rows] = 1e-3, 0
    if done.any():
        rows = np.flatnonzero(done)
        distance = np.linalg.norm(x[rows] - q_start[chain.variables], axis=1)
        best_x = x[rows[int(np.argmin(distance))]]
    elif cost.min() < best_cost:
        best_x = x[int(np.argmin(cost))]
    q = q_start.copy()
    q[chain.variables] = best_x
    final_error, final_tip, _, _ = _residuals(chain, q[None, :], goal, goal_rot)
    residual = float(np.linalg.norm(final_error[0, :3]))
    rotation_residual = float(np.linalg.norm(final_error[0, 3:])) if goal_rot is not None else None
    joints = _joints_dict(tree, q)
    tip_point = np.array(final_tip[0])
    if done.any():
        return IKResult(True, joints, tip_point, goal, residual, f"reached in {iterations} iterations",
                        "numeric", iterations=iterations, rotation_residual=rotation_residual)
    reason, message, violations = "out_of_reach", "", []
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
                message = "reachable only past the limits: " + "; ".join(v.describe() for v in violations)
    what = "pose" if goal_rot is not None else "point"
    if not message:
        message = (f"out of reach: the tip gets no closer than {residual:.4g} m to the target "
                   f"(closest {what} at {', '.join(f'{v:.4f}' for v in tip_point)})")
        if goal_rot is not None:
            message += f", orientation off by {rotation_residual:.4g} rad"
    else:
        message += f"; within the limits the tip gets no closer than {residual:.4g} m"
    return IKResult(False, joints, tip_point, goal, residual, message, "numeric", reason=reason,
                    iterations=iterations, rotation_residual=rotation_residual, violations=violations)


def solve_ik(model: TFTree | Robot, target: Sequence[float], *, rotation: np.ndarray | None = None,
             tip_link: str | None = None, tip_offset: Sequence[float] | None = None,
             start: Mapping[str, float] | np.ndarray | None = None, method: str = "auto",
             elbow: str | None = None, seeds: int = 8, max_iterations: int = 200,
             tolerance: float = 1e-12, random_seed: int = 0) -> IKResult:
    """Joint values putting the tip at ``target`` (and, with ``rotation`` (3x3), the tip link's orientation).

    ``method``: "analytic" (two-joint planar arms, see :func:`ik_2r`), "numeric", or "auto"
    (analytic when the chain allows it and no orientation is asked). The numeric solver starts
    from ``start`` (zero pose by default) plus ``seeds - 1`` random poses within the limits
    (``random_seed`` makes them repeatable), iterates damped least squares on all of them at
    once, and keeps the converged solution closest to ``start``. The result never leaves the
    joint limits; when the target needs a joint past its limits, the message names it.
    """
    tree = _as_tree(model)
    chain = serial_chain(tree, tip_link, tip_offset)
    if method not in ("auto", "analytic", "numeric"):
        raise ParameterError(f"unknown method {method!r}", hint="use auto, analytic or numeric")
    analytic = method == "analytic" or (method == "auto" and rotation is None and planar_two_link(chain) is not None)
    if analytic:
        if rotation is not None:
            raise ParameterError("the closed-form solver places the tip only (no orientation)",
                                 hint="use method='numeric' for an orientation target")
        return ik_2r(tree, target, elbow=elbow, start=start if isinstance(start, Mapping) else
                     (None if start is None else _joints_dict(tree, _start_vector(tree, start))),
                     tip_link=chain.tip_link, tip_offset=chain.tip_offset)
    if elbow is not None:
        raise ParameterError(f"elbow up/down applies to two-joint planar arms; the chain to '{chain.tip_link}' "
                             f"has {len(chain.joints)} joints ({', '.join(chain.joints)})",
                             hint="leave out the elbow choice: the numeric solver starts from the start pose")
    return solve_chain(chain, target, rotation=rotation, start=start, seeds=seeds,
                       max_iterations=max_iterations, tolerance=tolerance, random_seed=random_seed)


# ---------------------------------------------------------------- reaching motion


def _velocity_limits(tree: TFTree) -> np.ndarray:
    """Velocity limit per dof (inf when absent or not positive)."""
    out = []
    for joint in tree.dof_joints():
        v = joint.limit.velocity if joint.limit is not None else None
        out.append(float(v) if v is not None and v > 0 and math.isfinite(v) else math.inf)
    return np.array(out)


def minimum_duration(model: TFTree | Robot, start: np.ndarray, goal: np.ndarray) -> float:
    """Shortest quintic move from start to goal whose peak speed stays within every velocity limit.

    The quintic's peak speed is 15/8 |dq| / T, so T = 15/8 max_i |dq_i| / v_i (at least the
    plain max_i |dq_i| / v_i of a constant-speed move).
    """
    limits = _velocity_limits(_as_tree(model))
    delta = np.abs(np.asarray(goal, dtype=float) - np.asarray(start, dtype=float))
    ratio = np.where(np.isfinite(limits), delta / np.where(np.isfinite(limits), limits, 1.0), 0.0)
    return float(QUINTIC_PEAK * ratio.max(initial=0.0))


@dataclass(frozen=True)
class ReachMotion:
    """A joint-space move with quintic time scaling: zero speed and acceleration at both ends.

    Same shape as :class:`bras_kit.motion.Motion`: ``names``, ``positions(t)``, ``duration``.
    """

    names: tuple[str, ...]
    start: np.ndarray
    goal: np.ndarray
    duration: float

    def _phase(self, t: np.ndarray) -> np.ndarray:
        if self.duration <= 0:
            return np.ones_like(t)
        return np.clip(np.asarray(t, dtype=float) / self.duration, 0.0, 1.0)

    def positions(self, t: np.ndarray | float) -> np.ndarray:
        tau = self._phase(np.atleast_1d(np.asarray(t, dtype=float)))
        s = tau ** 3 * (10.0 - 15.0 * tau + 6.0 * tau ** 2)
        return self.start[None, :] + s[:, None] * (self.goal - self.start)[None, :]

    def velocities(self, t: np.ndarray | float) -> np.ndarray:
        times = np.atleast_1d(np.asarray(t, dtype=float))
        if self.duration <= 0:
            return np.zeros((len(times), len(self.names)))
        tau = self._phase(times)
        inside = (times >= 0) & (times <= self.duration)
        ds = np.where(inside, 30.0 * tau ** 2 * (1.0 - tau) ** 2 / self.duration, 0.0)
        return ds[:, None] * (self.goal - self.start)[None, :]

    def peak_velocities(self) -> np.ndarray:
        if self.duration <= 0:
            return np.zeros(len(self.names))
        return QUINTIC_PEAK * np.abs(self.goal - self.start) / self.duration

    def times(self, rate: float = 20.0) -> np.ndarray:
        count = max(int(math.ceil(self.duration * rate - 1e-9)), 1) + 1
        return np.linspace(0.0, self.duration, count)


def reach_motion(model: TFTree | Robot, start: Mapping[str, float] | np.ndarray | None,
                 goal: Mapping[str, float] | np.ndarray, duration: float | None = None) -> ReachMotion:
    """The move from ``start`` to ``goal`` (dicts by joint name or dof vectors).

    ``duration`` defaults to :func:`minimum_duration`; a shorter one is refused, naming the
    joint that would be too fast and the shortest duration that works.
    """
    tree = _as_tree(model)
    q0, q1 = _start_vector(tree, start), _start_vector(tree, goal)
    shortest = minimum_duration(tree, q0, q1)
    if duration is None:
        duration = shortest
    elif not math.isfinite(duration) or duration < 0:
        raise ParameterError(f"the duration {duration:g} s is not a positive number")
    elif duration < shortest * (1.0 - 1e-12):
        limits = _velocity_limits(tree)
        speeds = QUINTIC_PEAK * np.abs(q1 - q0) / max(duration, 1e-300)
        i = int(np.argmax(np.where(np.isfinite(limits), speeds / np.where(np.isfinite(limits), limits, 1), 0)))
        raise ParameterError(
            f"a {duration:g} s move is too fast: {tree.dof[i]} would turn at {speeds[i]:.3g} "
            f"{_unit_of(tree, tree.dof[i])}/s, above its velocity limit {limits[i]:g}",
            hint=f"give a duration of at least {math.ceil(shortest * 1000) / 1000:g} s, or leave it out")
    return ReachMotion(tuple(tree.dof), q0, q1, float(duration))


def motion_violations(model: TFTree | Robot, motion: ReachMotion) -> list[LimitExcess]:
    """Exact limit check of a reach motion: positions lie between start and goal, peak speeds are known."""
    tree = _as_tree(model)
    lower, upper = _bounds(tree)
    out = []
    for point in (motion.start, motion.goal):
        out += _violations(tree, _joints_dict(tree, point), lower, upper, tolerance=1e-9)
    limits = _velocity_limits(tree)
    for i, speed in enumerate(motion.peak_velocities()):
        if speed > limits[i] * (1.0 + 1e-9):
            out.append(LimitExcess(tree.dof[i], float(speed), float(limits[i]), "velocity",
                                   _unit_of(tree, tree.dof[i]) + "/s"))
    return out


# ---------------------------------------------------------------- workspace


def workspace_points(model: TFTree | Robot, samples: int = 100_000, *, limits: bool = True,
                     tip_link: str | None = None, tip_offset: Sequence[float] | None = None,
                     random_seed: int = 0) -> np.ndarray:
    """Tip positions (samples, 3) for configurations drawn uniformly within the joint limits.

    With ``limits=False`` revolute joints turn all the way round (-pi..pi); prismatic joints
    keep their limits. Forward kinematics runs in batches through :func:`fk_batch`.
    """
    tree = _as_tree(model)
    link, offset = resolve_tip(tree, tip_link, tip_offset)
    if samples < 1:
        raise ParameterError(f"--samples must be at least 1, not {samples}")
    lower, upper = _bounds(tree)
    revolute = np.array([j.type in ("revolute", "continuous") for j in tree.dof_joints()], dtype=bool)
    if not limits:
        lower = np.where(revolute, -math.pi, lower)
        upper = np.where(revolute, math.pi, upper)
    lower = np.where(np.isfinite(lower), lower, -math.pi)
    upper = np.where(np.isfinite(upper), upper, math.pi)
    rng = np.random.default_rng(random_seed)
    q = rng.uniform(lower, upper, size=(samples, len(tree.dof)))
    index = tree.index(link)
    out = np.empty((samples, 3))
    for begin in range(0, samples, 50_000):
        transforms = fk_batch(tree, q[begin:begin + 50_000])[:, index]
        out[begin:begin + 50_000] = transforms[:, :3, :3] @ offset + transforms[:, :3, 3]
    return out


def _occupancy(points: np.ndarray, x_edges: np.ndarray, y_edges: np.ndarray) -> np.ndarray:
    """Cells holding at least one point, with one-cell holes closed (dilate then erode)."""
    counts, _, _ = np.histogram2d(points[:, 0], points[:, 1], bins=(x_edges, y_edges))
    cells = counts > 0

    def shift_any(grid: np.ndarray) -> np.ndarray:
        padded = np.pad(grid, 1)
        out = np.zeros_like(grid)
        for dx in (0, 1, 2):
            for dy in (0, 1, 2):
                out |= padded[dx:dx + grid.shape[0], dy:dy + grid.shape[1]]
        return out

    dilated = shift_any(cells)
    return cells | ~shift_any(~dilated)


@dataclass
class WorkspaceSummary:
    """Figures of a drawn workspace: plane axes, areas (m^2) and the reach (m) from the first joint."""

    axes: tuple[str, str]
    area_within_limits: float
    area_without_limits: float
    max_reach: float
    samples: int


def _plane_axes(points: np.ndarray) -> tuple[int, int]:
    """Two world axes to draw: the widest spreads; z, if kept, is vertical."""
    spread = np.ptp(points, axis=0)
    keep = sorted(np.argsort(spread)[-2:].tolist())
    if 2 in keep:
        other = keep[0] if keep[1] == 2 else keep[1]
        return other, 2
    return keep[0], keep[1]


def workspace_figure(model: TFTree | Robot, samples: int = 100_000, *, tip_link: str | None = None,
                     tip_offset: Sequence[float] | None = None, size: tuple[float, float] = (7.0, 6.0),
                     dpi: int = 100):  # type: ignore[no-untyped-def]
    """A matplotlib figure of the region the tip reaches, in the arm's plane.

    Faint: every joint turning freely; solid: within the limits; the base and the arm at its
    zero pose on top. Returns (figure, axes, :class:`WorkspaceSummary`).
    """
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch, Rectangle

    tree = _as_tree(model)
    link, offset = resolve_tip(tree, tip_link, tip_offset)
    free = workspace_points(tree, samples, limits=False, tip_link=link, tip_offset=offset)
    bounded = workspace_points(tree, samples, limits=True, tip_link=link, tip_offset=offset, random_seed=1)
    h, v = _plane_axes(free)
    names = ("x", "y", "z")
    zero = fk_batch(tree, np.zeros(len(tree.dof)))
    chain_links = []
    i = tree.index(link)
    while i >= 0:
        chain_links.append(i)
        i = tree.parent[i]
    chain_links.reverse()
    arm_points = [zero[j][:3, 3] for j in chain_links] + [zero[chain_links[-1]][:3, :3] @ offset + zero[chain_links[-1]][:3, 3]]
    arm_points = np.array(arm_points)
    every = np.vstack([free, arm_points])
    low, high = every.min(axis=0), every.max(axis=0)
    span = max(float(np.max(high[[h, v]] - low[[h, v]])), 1e-3)
    margin = 0.08 * span
    cells = int(np.clip(math.sqrt(samples) / 2.5, 40, 250))
    x_edges = np.linspace(low[h] - margin, high[h] + margin, cells + 1)
    y_edges = np.linspace(low[v] - margin, high[v] + margin, cells + 1)
    free_cells = _occupancy(free[:, [h, v]], x_edges, y_edges)
    bounded_cells = _occupancy(bounded[:, [h, v]], x_edges, y_edges) & free_cells
    cell_area = float((x_edges[1] - x_edges[0]) * (y_edges[1] - y_edges[0]))

    figure = Figure(figsize=size, dpi=dpi)
    FigureCanvasAgg(figure)
    axes = figure.add_subplot(1, 1, 1)
    extent = (x_edges[0], x_edges[-1], y_edges[0], y_edges[-1])
    free_colour, bounded_colour = (0.55, 0.65, 0.85, 0.35), (0.15, 0.35, 0.80, 1.0)
    centres_x, centres_y = (x_edges[:-1] + x_edges[1:]) / 2, (y_edges[:-1] + y_edges[1:]) / 2
    for cells_on, colour, order in ((free_cells, free_colour, 1), (bounded_cells, bounded_colour, 2)):
        if cells_on.any():  # contour at half a cell: smooth edges, no blocky pixels
            axes.contourf(centres_x, centres_y, cells_on.T.astype(float), levels=[0.5, 1.5],
                          colors=[colour], antialiased=True, zorder=order)
    base = tree.robot.link(tree.root)
    for visual in base.visuals if base is not None else []:
        g = visual.geometry
        centre = np.asarray(visual.origin.xyz)
        if g is None:
            continue
        if g.kind == "box" and g.size:
            w, hh = g.size[h], g.size[v]
        elif g.kind == "cylinder" and g.radius is not None and g.length is not None:
            dims = (2 * g.radius, 2 * g.radius, g.length)
            w, hh = dims[h], dims[v]
        elif g.kind == "sphere" and g.radius is not None:
            w = hh = 2 * g.radius
        else:
            continue
        axes.add_patch(Rectangle((centre[h] - w / 2, centre[v] - hh / 2), w, hh, facecolor=(0.5, 0.5, 0.5),
                                 edgecolor="black", linewidth=0.8, zorder=3, label="base"))
    axes.plot(arm_points[:, h], arm_points[:, v], "-", color=(0.95, 0.5, 0.1), linewidth=3, zorder=4,
              label="arm at zero pose")
    axes.plot(arm_points[1:-1, h], arm_points[1:-1, v], "o", color="black", markersize=5, zorder=5)
    axes.plot(arm_points[-1, h], arm_points[-1, v], "*", color="black", markersize=9, zorder=5)
    shoulder = arm_points[1] if len(arm_points) > 2 else arm_points[0]
    reach = float(np.max(np.linalg.norm(free - shoulder, axis=1)))
    axes.set_xlim(extent[0], extent[1])
    axes.set_ylim(extent[2], extent[3])
    axes.set_aspect("equal")
    axes.set_xlabel(f"{names[h]} (m)")
    axes.set_ylabel(f"{names[v]} (m)")
    axes.grid(True, linewidth=0.3, alpha=0.5, zorder=0)
    tip_text = f"{link} + ({', '.join(f'{c:g}' for c in offset)})"
    axes.set_title(f"Workspace of {tree.robot.name or 'robot'}: tip {tip_text}", fontsize=10)
    handles = [Patch(facecolor=free_colour, label="reachable if joints turned freely"),
               Patch(facecolor=bounded_colour, label="reachable within the joint limits")]
    handles += axes.get_legend_handles_labels()[0]
    axes.legend(handles=handles, loc="lower left", fontsize=8, framealpha=0.9)
    figure.tight_layout()
    summary = WorkspaceSummary((names[h], names[v]), float(bounded_cells.sum() * cell_area),
                               float(free_cells.sum() * cell_area), reach, samples)
    return figure, axes, summary
