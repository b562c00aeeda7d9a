"""Inverse kinematics: joint values that put a point of the arm (the tip) at a target.

Two solvers share one result type, :class:`IKResult`:

- :func:`ik_2r`, closed form, for chains whose structure is the tutorial arm's: two revolute
  joints with parallel axes and a tip offset. The structure is read from the model
  (:func:`planar_two_link`), never hard-coded: shoulder position from the first joint's origin,
  upper-arm length from the second joint's origin, forearm length from the tip offset. It gives
  both elbow solutions and says why a target fails (too far, too close, off the arm's plane,
  or a joint past its limit, named, with the excess).
- :func:`solve_chain` / :func:`solve_ik`, numeric, for any serial chain (position, and
  orientation if asked): Levenberg-Marquardt on the geometric Jacobian, joints kept within
  their limits (a joint meeting a bound stops there while the others re-solve), from the start
  pose first, then from repeatable random poses when a descent gets stuck. The inner loop runs
  on plain floats (see :class:`_Kernel`): about ten times ikpy's speed on the wrist arm.

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
from operator import mul
from typing import Any

import numpy as np

from .errors import ParameterError
from .kinematics import TFTree, fk_batch, tf_tree
from .model import Robot
from .tip import end_link, tool_tip

Vector = Sequence[float] | np.ndarray  # three numbers: a point, an offset

TWO_PI = 2.0 * math.pi
PLANE_TOLERANCE = 1e-9  # m: a target this close to a planar arm's plane counts as in it
SINGULAR_TOLERANCE = 1e-9  # m: a target this close to the reach boundary is on it (singular pose)
QUINTIC_PEAK = 15.0 / 8.0  # peak of d/dtau of 10 tau^3 - 15 tau^4 + 6 tau^5, at tau = 1/2

# ---------------------------------------------------------------- inputs


def _as_tree(model: TFTree | Robot) -> TFTree:
    return model if isinstance(model, TFTree) else tf_tree(model)


def _point(values: Vector, what: str) -> np.ndarray:
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


def resolve_tip(tree: TFTree, tip_link: str | None = None,
                tip_offset: Vector | None = None) -> tuple[str, np.ndarray]:
    """(link, point in the link's frame): defaults are those of :func:`bras_kit.tip.tool_tip`."""
    if tip_offset is None:
        return tool_tip(tree, tip_link)
    return tree.links[tree.index(tip_link)] if tip_link else end_link(tree), _point(tip_offset, "the tip offset")


# ---------------------------------------------------------------- the serial chain


@dataclass(frozen=True)
class _Kernel:
    """The chain's constants as plain Python floats, for the solver's inner loop.

    On 3x3 matrices numpy spends more time per call than on arithmetic: the unrolled float
    products below run several times faster than the same products as small numpy arrays.
    Rotations are row-major 9-tuples. Before joint k: ``pre_pos[k]``, ``pre_axis[k]`` (the
    joint's axis in the previous moving joint's frame); Rodrigues, premultiplied by the
    constant rotation: pre_rot Rot(a, t) = outer + cos t rest + sin t skew.
    """

    revolute: tuple[bool, ...]
    var: tuple[int, ...]  # variable driving each joint
    gain: tuple[float, ...]
    offset: tuple[float, ...]
    pre_pos: tuple[tuple[float, float, float], ...]
    pre_axis: tuple[tuple[float, float, float], ...]
    pre_rot: tuple[tuple[float, ...], ...]
    outer: tuple[tuple[float, ...], ...]
    rest: tuple[tuple[float, ...], ...]
    skew: tuple[tuple[float, ...], ...]
    end_point: tuple[float, float, float]
    end_rot: tuple[float, ...]
    size: int  # number of variables


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


def _flat(matrix: np.ndarray) -> tuple[float, ...]:
    return tuple(float(v) for v in np.asarray(matrix).reshape(-1))


def serial_chain(model: TFTree | Robot, tip_link: str | None = None,
                 tip_offset: Vector | None = None) -> SerialChain:
    """Compile the chain from the root to the tip (see :func:`resolve_tip` for the defaults).

    Chains are kept on the (immutable) tree, so solving many targets compiles once.
    """
    tree = _as_tree(model)
    cache = tree.__dict__.setdefault("_serial_chains", {})
    key = (tip_link, None if tip_offset is None else tuple(_point(tip_offset, "the tip offset").tolist()))
    if key not in cache:
        cache[key] = _compile_chain(tree, tip_link, tip_offset)
    return cache[key]


def _compile_chain(tree: TFTree, tip_link: str | None, tip_offset: Vector | None) -> SerialChain:
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
        skew = np.array([[0.0, -a[2], a[1]], [a[2], 0.0, -a[0]], [-a[1], a[0], 0.0]])
        kernel_parts["outer"].append(_flat(r @ outer))
        kernel_parts["rest"].append(_flat(r @ (np.eye(3) - outer)))
        kernel_parts["skew"].append(_flat(r @ skew))
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


def _product(a: Sequence[float], b: Sequence[float]) -> tuple[float, ...]:
    """Row-major 3x3 product a b."""
    a0, a1, a2, a3, a4, a5, a6, a7, a8 = a
    b0, b1, b2, b3, b4, b5, b6, b7, b8 = b
    return (a0 * b0 + a1 * b3 + a2 * b6, a0 * b1 + a1 * b4 + a2 * b7, a0 * b2 + a1 * b5 + a2 * b8,
            a3 * b0 + a4 * b3 + a5 * b6, a3 * b1 + a4 * b4 + a5 * b7, a3 * b2 + a4 * b5 + a5 * b8,
            a6 * b0 + a7 * b3 + a8 * b6, a6 * b1 + a7 * b4 + a8 * b7, a6 * b2 + a7 * b5 + a8 * b8)


def _forward(kernel: _Kernel, x: Sequence[float], with_rotation: bool = False):  # type: ignore[no-untyped-def]
    """Tip point, tip rotation (9-tuple, or None), joint origins and world axes for variables x."""
    r: Sequence[float] = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
    px = py = pz = 0.0
    origins, axes = [], []
    for k, revolute in enumerate(kernel.revolute):
        value = x[kernel.var[k]] * kernel.gain[k] + kernel.offset[k]
        r0, r1, r2, r3, r4, r5, r6, r7, r8 = r
        bx, by, bz = kernel.pre_pos[k]
        px, py, pz = px + r0 * bx + r1 * by + r2 * bz, py + r3 * bx + r4 * by + r5 * bz, pz + r6 * bx + r7 * by + r8 * bz
        ax, ay, az = kernel.pre_axis[k]
        wx, wy, wz = r0 * ax + r1 * ay + r2 * az, r3 * ax + r4 * ay + r5 * az, r6 * ax + r7 * ay + r8 * az
        if revolute:
            c, s = math.cos(value), math.sin(value)
            local = [o + c * e + s * w for o, e, w in zip(kernel.outer[k], kernel.rest[k], kernel.skew[k])]
        else:
            local = kernel.pre_rot[k]  # type: ignore[assignment]
            px, py, pz = px + value * wx, py + value * wy, pz + value * wz
        r = _product(r, local)
        origins.append((px, py, pz))
        axes.append((wx, wy, wz))
    r0, r1, r2, r3, r4, r5, r6, r7, r8 = r
    ex, ey, ez = kernel.end_point
    tip = (px + r0 * ex + r1 * ey + r2 * ez, py + r3 * ex + r4 * ey + r5 * ez, pz + r6 * ex + r7 * ey + r8 * ez)
    return tip, (_product(r, kernel.end_rot) if with_rotation else None), origins, axes


def _jacobian_rows(kernel: _Kernel, tip, origins, axes, orientation: bool) -> list[list[float]]:  # type: ignore[no-untyped-def]
    """Geometric Jacobian as rows (3 or 6) of ``kernel.size`` columns, world frame."""
    rows = [[0.0] * kernel.size for _ in range(6 if orientation else 3)]
    tx, ty, tz = tip
    for k, revolute in enumerate(kernel.revolute):
        column, g = kernel.var[k], kernel.gain[k]
        ax, ay, az = axes[k]
        if revolute:
            ox, oy, oz = origins[k]
            dx, dy, dz = tx - ox, ty - oy, tz - oz
            rows[0][column] += g * (ay * dz - az * dy)
            rows[1][column] += g * (az * dx - ax * dz)
            rows[2][column] += g * (ax * dy - ay * dx)
            if orientation:
                rows[3][column] += g * ax
                rows[4][column] += g * ay
                rows[5][column] += g * az
        else:
            rows[0][column] += g * ax
            rows[1][column] += g * ay
            rows[2][column] += g * az
    return rows


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
        raise ParameterError(f"expected {len(tree.dof)} joint values ({', '.join(tree.dof)}), got {batch.shape[-1]}")
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
    """``value`` + 2 pi k: within [lower, upper] and nearest ``reference`` if possible, else least outside."""
    base = math.remainder(value, TWO_PI)
    if not (math.isfinite(lower) and math.isfinite(upper)):
        return base + TWO_PI * round((reference - base) / TWO_PI)
    first = math.ceil((lower - base) / TWO_PI - 1e-12)  # turns that land inside the range
    last = math.floor((upper - base) / TWO_PI + 1e-12)
    if first <= last:
        return base + TWO_PI * min(max(round((reference - base) / TWO_PI), first), last)
    below, above = base + TWO_PI * last, base + TWO_PI * first
    return below if lower - below <= above - upper else above


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


def _plane_description(arm: PlanarTwoLink) -> str:
    normal = arm.normal
    axis = int(np.argmax(np.abs(normal)))
    level = float(arm.origin @ normal + arm.height)  # points p of the plane: normal . p = level
    if abs(abs(normal[axis]) - 1.0) < 1e-9:
        value = level * normal[axis]
        return f"{'xyz'[axis]} = {value + 0.0:.4g}"
    return f"the plane through ({', '.join(f'{v:.3g}' for v in arm.origin)}) normal to ({', '.join(f'{v:.3g}' for v in normal)})"


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
        raise ParameterError(f"elbow must be 'up' or 'down', not {elbow!r}")
    goal = _point(target, "the target")
    q_start = _start_vector(tree, start)
    chain = serial_chain(tree, tip_link, tip_offset)
    arm = _two_link_of(chain)
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
        closest = solve_chain(chain, goal, start=q_start, explain=False)
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
    tip = np.array(_forward(chain.kernel, q[chain.variables].tolist())[0])
    residual = float(np.linalg.norm(tip - goal))
    message = f"reached with elbow {pick.elbow}" + (f"; {singular}" if singular else "")
    return IKResult(True, pick.joints, tip, goal, residual, message, "analytic", reason="singular" if singular else "ok",
                    elbow=pick.elbow, singular=bool(singular), solutions=solutions)


# ---------------------------------------------------------------- numeric: damped least squares


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


SEEDS = 100  # starting poses at most: the start pose, then random ones
MAX_ITERATIONS = 100  # per starting pose
SAME_MINIMUM = 10  # descents ending on the best minimum so far before it is taken as the closest
ACCEPT = 1e-9  # m and rad: a descent stopped (slow convergence near a singularity) this close counts


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

    def evaluate(values: list[float]):  # type: ignore[no-untyped-def]
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
    goal = _point(target, "the target")
    goal_rot = None if rotation is None else _flat(np.asarray(rotation, dtype=float).reshape(3, 3))
    q_start = _start_vector(tree, start)
    if chain.kernel.size == 0:
        raise ParameterError(f"no movable joint moves '{chain.tip_link}'",
                             hint="choose a link further down the arm (--link)")
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
        raise ParameterError(f"unknown method {method!r}", hint="use auto, analytic or numeric")
    analytic = method == "analytic" or (method == "auto" and rotation is None and _two_link_of(chain) is not None)
    if analytic:
        if rotation is not None:
            raise ParameterError("the closed-form solver places the tip only (no orientation)",
                                 hint="use method='numeric' for an orientation target")
        return ik_2r(tree, target, elbow=elbow, start=start if isinstance(start, Mapping) else
                     (None if start is None else _joints_dict(tree, _start_vector(tree, start))),
                     tip_link=chain.tip_link, tip_offset=chain.tip_offset)
    if elbow is not None and _two_link_of(chain) is not None:
        raise ParameterError("elbow up/down comes from the closed-form solver, which places the tip only",
                             hint="leave out the orientation, or the elbow choice")
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

    def evaluate(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Positions and velocities, as :meth:`bras_kit.motion.Motion.evaluate` (so ``sample`` takes it)."""
        return self.positions(t), self.velocities(t)

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
                     tip_link: str | None = None, tip_offset: Vector | None = None,
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
                     tip_offset: Vector | None = None, size: tuple[float, float] = (7.0, 6.0),
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
    last = zero[chain_links[-1]]
    arm_points = np.array([zero[j][:3, 3] for j in chain_links] + [last[:3, :3] @ offset + last[:3, 3]])
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
    handles: list[Any] = [Patch(facecolor=free_colour, label="reachable if joints turned freely"),
               Patch(facecolor=bounded_colour, label="reachable within the joint limits")]
    handles += axes.get_legend_handles_labels()[0]
    axes.legend(handles=handles, loc="lower left", fontsize=8, framealpha=0.9)
    figure.tight_layout()
    summary = WorkspaceSummary((names[h], names[v]), float(bounded_cells.sum() * cell_area),
                               float(free_cells.sum() * cell_area), reach, samples)
    return figure, axes, summary
