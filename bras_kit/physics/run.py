"""A simulation run: the arm in MuJoCo, its motors following a motion program, sampled like /joint_states.

The physics steps at ``timestep``; the motors' PD law runs inside MuJoCo at every step, while
their set point moves at ``control_rate`` (like a ros2_control loop, 100 Hz by default, taken at
the middle of each control period); the states are kept at ``rate`` (20 Hz, like the tutorial's node) for files,
pictures and GIFs, while the per-joint figures (tracking error, peak torque, time at the limit)
use every control tick.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field

import numpy as np

from ..core import backends
from ..core.errors import ParameterError
from ..core.message import M, Message
from ..kinematics.frames import tf_tree
from ..model.robot import Robot
from ..motion import (
    DEFAULT_DURATION,
    DEFAULT_RATE,
    JointStates,
    Motion,
    motion_from_specs,
    sample_count,
    tutorial_motion,
)
from .controllers import check_control, gain_vector, servo_setpoints
from .mjcf import (
    DEFAULT_INTEGRATOR,
    DEFAULT_KD,
    DEFAULT_KP,
    DEFAULT_TIMESTEP,
    MjcfModel,
    build_mjcf,
    quiet_mujoco,
)

DEFAULT_CONTROL_RATE = 100.0  # Hz, the update rate ros2_control setups commonly use
AT_LIMIT = 1e-3  # a torque within 0.1 % of the effort counts as "at the limit"
SATURATED_SHARE, SATURATED_ERROR = 0.05, 0.1  # 5 % of the time at the limit and 0.1 rad (m) behind
MAX_TICKS = 5_000_000


@dataclass
class JointReport:
    """How one joint did: tracking error, torques, and whether its motor is strong enough."""

    joint: str
    effort: float  # inf when the URDF gives none
    error_mean: float
    error_max: float
    peak_torque: float
    share_at_limit: float  # 0..1 of the control ticks
    needed_peak: float  # inverse dynamics along the reference: what a perfect motor would give
    overshoot: float  # furthest past the joint range (rad or m), 0 when inside
    final_position: float
    lower: float
    upper: float
    weak: bool  # the motion needs more torque than <limit effort> allows
    saturated: bool = False  # at its limit and behind although the motion needs less: gains or time step


@dataclass(frozen=True)
class Divergence:
    """Where a run stopped being a number: the simulated time and the joint MuJoCo named."""

    time: float
    joint: str


@dataclass
class SimulatedStates(JointStates):
    """Joint states measured in the simulation, with the motor torques and the reference followed."""

    efforts: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))  # measured motor torques
    targets: np.ndarray = field(default_factory=lambda: np.zeros((0, 0)))  # the motion program's positions
    effort_limits: np.ndarray = field(default_factory=lambda: np.zeros(0))
    control: str = "pd"
    timestep: float = DEFAULT_TIMESTEP
    integrator: str = DEFAULT_INTEGRATOR
    control_rate: float = DEFAULT_CONTROL_RATE
    report: list[JointReport] = field(default_factory=list)
    contacts: list[tuple[str, str]] = field(default_factory=list)  # geoms touching at the end
    model: MjcfModel | None = field(default=None, repr=False)
    diverged: Divergence | None = None  # the run stopped there: NaN or a huge value (unstable)

    def joint_report(self, joint: str) -> JointReport:
        return self.report[self.column(joint)]

    @property
    def weak_joints(self) -> list[str]:
        return [r.joint for r in self.report if r.weak]


def _motion(robot: Robot, motion: Motion | Sequence[str] | None) -> Motion:
    if motion is None:
        return tutorial_motion(robot)
    if isinstance(motion, Motion):
        return motion
    if isinstance(motion, str):
        motion = [motion]
    return motion_from_specs(robot, list(motion))


def _check_positive(value: float, what: Message, hint: Message) -> float:
    value = float(value)
    if not math.isfinite(value) or value <= 0:
        raise ParameterError(M("{what} {value} is not above 0", what=what, value=value), hint=hint)
    return value


def simulate(robot: Robot, motion: Motion | Sequence[str] | None = None, *, control: str = "pd",
             kp: float | Mapping[str, float] = DEFAULT_KP, kd: float | Mapping[str, float] = DEFAULT_KD,
             duration: float | None = None, rate: float = DEFAULT_RATE, start: Mapping[str, float] | None = None,
             timestep: float = DEFAULT_TIMESTEP, integrator: str = DEFAULT_INTEGRATOR,
             control_rate: float = DEFAULT_CONTROL_RATE, damping: float | None = None,
             package_paths: Sequence[str] = (), lang: str = "en") -> SimulatedStates:
    """Simulate ``robot`` under gravity with its motors following ``motion``; return the measured states.

    ``motion``: a :class:`~bras_kit.motion.Motion`, motion specs (``["tutorial"]``,
    ``["coude=1.2*sin(0.7*t)"]``) or None for the tutorial's node. ``control``: ``none`` (motors
    off: the arm falls from ``start``), ``pd`` or ``pd+gravity``. ``start`` ({joint: value}) is the
    pose at t = 0 (default: the motion's first pose), at rest. Motor torques never exceed
    ``<limit effort>``. Joint damping and friction come from the URDF's ``<dynamics>`` (none
    when absent, as in Gazebo); ``damping`` (N.m.s/rad), when given, replaces the damping of
    every joint. A run that becomes unstable (NaN) stops there: ``diverged`` says when and where.
    ``lang`` (``en``/``fr``): the words of a model error.
    """
    mujoco = backends.mujoco()

    from .diagnostics import check_physics_ready

    check_control(control)
    check_physics_ready(robot, lang)
    timestep = _check_positive(timestep, M("time step"), M("give a time step in seconds, e.g. 0.002"))
    rate = _check_positive(rate, M("rate"), M("give samples per second, e.g. 20"))
    control_rate = _check_positive(control_rate, M("control rate"), M("give a control rate in Hz, e.g. 500"))
    if integrator not in ("Euler", "RK4", "implicit", "implicitfast"):
        raise ParameterError(M("unknown integrator '{name}'", name=integrator),
                             hint=M("use Euler, RK4, implicit or implicitfast"))
    if damping is not None and (not math.isfinite(damping) or damping < 0):
        raise ParameterError(M("damping {value} is not a number of 0 or more", value=damping),
                             hint=M("give a damping in N·m·s/rad, e.g. 0.05, or 0 for none"))
    tree = tf_tree(robot)
    names = list(tree.dof)
    program = _motion(robot, motion)
    if duration is None:
        duration = program.duration if program.duration is not None else DEFAULT_DURATION
    duration = float(duration)
    if not math.isfinite(duration) or duration < 0:
        raise ParameterError(M("duration {value} s is not a time", value=duration),
                             hint=M("give a duration of 0 s or more"))
    kp_v = gain_vector(kp, names, DEFAULT_KP, "kp")
    kd_v = gain_vector(kd, names, DEFAULT_KD, "kd")
    built = build_mjcf(robot, package_paths=package_paths, kp=dict(zip(names, kp_v)), kd=dict(zip(names, kd_v)),
                       timestep=timestep, integrator=integrator, control=control, damping=damping)
    model = built.compile()
    data = mujoco.MjData(model)

    joint_ids = [mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_JOINT, n) for n in names]
    qadr = np.array([model.jnt_qposadr[j] for j in joint_ids], dtype=int)
    vadr = np.array([model.jnt_dofadr[j] for j in joint_ids], dtype=int)
    act = np.array([mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_ACTUATOR, n) for n in names], dtype=int)
    efforts = np.array([next((a.effort for a in built.actuated if a.joint == n), math.inf) for n in names])

    steps = max(1, round(1.0 / (control_rate * timestep)))
    tick = steps * timestep
    ticks = math.ceil(duration / tick - 1e-9)
    if (ticks + 1) * max(1, len(names)) > MAX_TICKS:
        raise ParameterError(M("{count} control ticks is too many", count=ticks), hint=M("lower --duration"))
    times = np.arange(ticks + 1) * tick
    columns = [program.names.index(n) for n in names]
    with np.errstate(all="ignore"):
        q_ref, qd_ref = (a[:, columns] for a in program.evaluate(times))
        q_mid, qd_mid = (a[:, columns] for a in program.evaluate(times + tick / 2))
    if not (np.all(np.isfinite(q_ref)) and np.all(np.isfinite(qd_ref))):
        raise ParameterError(M("the motion is not a number at some time"),
                             hint=M("check the formulas with bras-kit motion"))
    setpoints = servo_setpoints(q_mid, qd_mid, kp_v, kd_v)

    first = q_ref[0].copy()
    if start:
        first = tree.config_vector({**dict(zip(names, first)), **start})
    data.qpos[qadr] = first
    driven = control != "none" and len(names) > 0
    if driven:
        data.ctrl[act] = setpoints[0]
    mujoco.mj_forward(model, data)
    positions = np.empty((ticks + 1, len(names)))
    velocities = np.empty_like(positions)
    torques = np.empty_like(positions)
    positions[0], velocities[0], torques[0] = first, 0.0, data.qfrc_actuator[vadr]
    diverged = None
    with quiet_mujoco():
        for k in range(ticks):
            if driven:
                data.ctrl[act] = setpoints[k]
            diverged = _steps(model, data, steps, float(times[k]), timestep)
            if diverged is not None:
                ticks = k  # keep what was a number; MuJoCo has reset the state
                break
            positions[k + 1] = data.qpos[qadr]
            velocities[k + 1] = data.qvel[vadr]
            torques[k + 1] = data.qfrc_actuator[vadr]
        contacts = sorted({(_geom_name(model, c.geom1), _geom_name(model, c.geom2))
                           for c in data.contact[:data.ncon]}) if diverged is None else []
        needed = _needed_torques(model, qadr, vadr, times, q_ref, qd_ref) if driven else np.zeros((1, len(names)))
    positions, velocities, torques = positions[:ticks + 1], velocities[:ticks + 1], torques[:ticks + 1]
    times, q_ref = times[:ticks + 1], q_ref[:ticks + 1]
    report = _reports(robot, names, positions, torques, q_ref, needed, efforts, control)
    kept = float(times[-1]) if diverged is not None else duration
    picks = np.unique(np.minimum(np.round(np.arange(sample_count(kept, rate)) / rate / tick).astype(int), ticks))
    return SimulatedStates(times[picks], names, positions[picks], velocities[picks], efforts=torques[picks],
                           targets=q_ref[picks], effort_limits=efforts, control=control, timestep=timestep,
                           integrator=integrator, control_rate=1.0 / tick, report=report, contacts=contacts,
                           model=built, diverged=diverged)


_UNSTABLE = ("mjWARN_BADQPOS", "mjWARN_BADQVEL", "mjWARN_BADQACC")


def _steps(model, data, steps: int, start: float, timestep: float) -> Divergence | None:
    """Step ``steps`` times; stop at the first step MuJoCo finds unstable (it then resets the state)."""
    mujoco = backends.mujoco()

    kinds = [int(getattr(mujoco.mjtWarning, name)) for name in _UNSTABLE]
    before = [int(data.warning[kind].number) for kind in kinds]
    for step in range(steps):
        mujoco.mj_step(model, data)
        for kind, count in zip(kinds, before):
            if int(data.warning[kind].number) > count:
                dof = int(data.warning[kind].lastinfo)
                joint = int(model.dof_jntid[dof]) if 0 <= dof < model.nv else -1
                name = mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_JOINT, joint) if joint >= 0 else None
                return Divergence(start + (step + 1) * timestep, name or "?")
        if not np.all(np.isfinite(data.qpos)):
            return Divergence(start + (step + 1) * timestep, "?")
    return None


def _geom_name(model, geom: int) -> str:
    mujoco = backends.mujoco()

    return mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_GEOM, geom) or f"geom {geom}"


def _needed_torques(model, qadr, vadr, times, q_ref, qd_ref) -> np.ndarray:
    """Inverse dynamics along the reference: the torque each joint would need to follow it exactly."""
    mujoco = backends.mujoco()

    data = mujoco.MjData(model)
    qdd = np.gradient(qd_ref, times, axis=0) if len(times) > 1 else np.zeros_like(qd_ref)
    # 50 evaluations per second catch the peak of a smooth motion; waypoint corners are sharper anyway
    stride = max(1, round(1.0 / (50.0 * (times[1] - times[0])))) if len(times) > 1 else 1
    picks = np.unique(np.append(np.arange(0, len(times), stride), len(times) - 1))
    out = np.zeros((len(picks), q_ref.shape[1]))
    for row, k in enumerate(picks):
        data.qpos[qadr], data.qvel[vadr], data.qacc[vadr] = q_ref[k], qd_ref[k], qdd[k]
        mujoco.mj_inverse(model, data)
        out[row] = data.qfrc_inverse[vadr]
    return out


def _reports(robot: Robot, names: list[str], positions: np.ndarray, torques: np.ndarray, q_ref: np.ndarray,
             needed: np.ndarray, efforts: np.ndarray, control: str) -> list[JointReport]:
    out = []
    for j, name in enumerate(names):
        joint = robot.joint(name)
        lower, upper = joint.bounds() if joint is not None else (-math.inf, math.inf)
        error = np.abs(positions[:, j] - q_ref[:, j])
        at_limit = np.abs(torques[:, j]) >= efforts[j] * (1 - AT_LIMIT) if math.isfinite(efforts[j]) \
            else np.zeros(len(torques), dtype=bool)
        share = float(at_limit.mean()) if len(at_limit) else 0.0
        past = np.maximum(lower - positions[:, j], positions[:, j] - upper)
        needed_peak = float(np.abs(needed[:, j]).max()) if len(needed) else 0.0
        driven = control != "none" and math.isfinite(efforts[j])
        # too weak: a perfect motor would need more than <limit effort> (inverse dynamics along
        # the reference). At its limit and behind while the motion needs less is not weakness:
        # the gains or the time step make the motor overshoot and chatter (reported apart).
        weak = driven and needed_peak > efforts[j]
        saturated = driven and not weak and share > SATURATED_SHARE and float(error.max()) > SATURATED_ERROR
        out.append(JointReport(name, float(efforts[j]), float(error.mean()), float(error.max()),
                               float(np.abs(torques[:, j]).max()), share, needed_peak,
                               float(max(0.0, past.max())), float(positions[-1, j]), lower, upper, bool(weak),
                               bool(saturated)))
    return out
