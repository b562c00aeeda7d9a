"""Where motions come from: the tutorial's node, formulas of t, a fixed pose, waypoint files.

Each source fills a layer of tracks; :func:`motion_from_specs` stacks layers and refuses a
joint driven twice.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
else:
    from ..core.lazy_numpy import np

from ..core.errors import ParameterError
from ..core.message import M, Message, number
from ..kinematics.frames import TFTree, tf_tree
from ..model.expr import compile_expression
from ..model.robot import Joint, Robot
from .core import JointStates, Motion, Track, check_joint
from .interpolation import interpolator
from .limits import joint_unit, speed_limit
from .specs import spec_kind, split_formula
from .waypoints import read_waypoints


@dataclass
class _Layer:
    """The tracks one source gives (a formula, a waypoint file, a recording), its length and notes."""

    tracks: dict[str, Track] = field(default_factory=dict)
    duration: float | None = None
    label: str = ""
    notes: list = field(default_factory=list)  # Messages about the input (a recording's gaps...)


def _formula_track(joint: str, formula: str, prefix: str = "") -> Track:
    expression = compile_expression(formula, prefix=prefix)
    return Track(joint, expression.evaluate, expression.text)


def _constant_track(joint: str, value: float) -> Track:
    def evaluate(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return np.full(t.shape, value), np.zeros(t.shape)

    return Track(joint, evaluate, M("held at {value:g}", value=value))


def _round_down(value: float, step: float = 0.01) -> float:
    return math.floor(value / step + 1e-9) * step


def _fitted_sine(joint: Joint, amplitude: float, omega: float, phase: str = "") -> str:
    """A sine formula kept inside the joint's position limits and 90% of its velocity limit."""
    lower, upper = joint.bounds()
    centre = 0.0
    if math.isfinite(lower) and math.isfinite(upper):
        span = upper - lower
        centre = round(min(max(0.0, lower + 0.4 * span), upper - 0.4 * span), 3)
        room = min(upper - centre, centre - lower)
        amplitude = min(amplitude, 0.8 * room)
    speed = speed_limit(joint)
    if speed is not None:
        amplitude = min(amplitude, 0.9 * speed / omega)
    amplitude = _round_down(max(amplitude, 0.0))
    wave = f"sin({number(omega)}*t{phase})" if omega != 1.0 else f"sin(t{phase})"
    if amplitude <= 0:
        return number(centre)
    text = f"{number(amplitude)}*{wave}"  # 0.69, never 0.6900000000000001
    return f"{number(centre)} + {text}" if centre else text


# The tutorial's node: epaule = 0.8 sin t, coude = 1.2 sin 0.7t, kept as written (even past
# narrower limits: that is the pitfall the limit check is for).
# The one definition of the tutorial's motion, used by the CLI, the scaffolded node (bras-kit
# new) and the lessons: joint -> (amplitude rad, angular frequency rad/s, phase rad). The wrist
# of the exercise moves faster than the elbow, so the three joints never line up for long.
TUTORIAL_WAVES: dict[str, tuple[float, float, float]] = {
    "epaule": (0.8, 1.0, 0.0),
    "coude": (1.2, 0.7, 0.0),
    "poignet": (1.0, 1.3, 0.0),
}


def wave_formula(amplitude: float, omega: float, phase: float = 0.0) -> str:
    """``amplitude*sin(omega*t + phase)`` written as a learner would: ``1.2*sin(0.7*t)``."""
    inner = "t" if omega == 1.0 else f"{omega!r}*t"
    if phase:
        inner += f" + {phase!r}"
    return f"{amplitude!r}*sin({inner})"


TUTORIAL_FORMULAS = {name: wave_formula(*wave) for name, wave in TUTORIAL_WAVES.items()}


def tutorial_motion(robot: Robot) -> Motion:
    """The tutorial's animation: epaule = 0.8 sin t, coude = 1.2 sin 0.7t.

    A wrist ``poignet`` follows 1.0 sin 1.3t (:data:`TUTORIAL_WAVES`; smaller if its limits are
    narrower); any other movable joint gets a gentle sine inside its limits, each at its own pace.
    """
    tree = tf_tree(robot)
    return _build(tree, [_tutorial_layer(tree)], label="tutorial")


def _tutorial_layer(tree: TFTree) -> _Layer:
    tracks: dict[str, Track] = {}
    others = 0
    for name, joint in zip(tree.dof, tree.dof_joints()):
        if name in ("epaule", "coude"):  # the tutorial's node, as written (limits are checked)
            formula = TUTORIAL_FORMULAS[name]
        elif name in TUTORIAL_WAVES:
            amplitude, omega, phase = TUTORIAL_WAVES[name]
            formula = _fitted_sine(joint, amplitude, omega, f" + {number(phase)}" if phase else "")
        else:
            cap = 0.1 if joint_unit(joint) == "m" else 0.8
            formula = _fitted_sine(joint, cap, 0.5 + 0.25 * others)
            others += 1
        tracks[name] = _formula_track(name, formula)
    return _Layer(tracks, None, "tutorial")


def _formula_layer(tree: TFTree, specs: Sequence[str]) -> _Layer:
    tracks: dict[str, Track] = {}
    for spec in specs:
        name, formula, prefix = split_formula(spec)
        check_joint(tree, name)
        if name in tracks:
            raise ParameterError(M("two formulas for joint '{name}'", name=name), hint=M("give each joint one formula"))
        tracks[name] = _formula_track(name, formula, prefix)
    return _Layer(tracks, None, "formulas")


def _pose_layer(tree: TFTree, config: Mapping[str, float]) -> _Layer:
    tree.config_vector(config)  # unknown or fixed joints: a clear error
    tracks = {}
    for name, value in config.items():
        number = float(value)
        if not math.isfinite(number):
            raise ParameterError(M("{name}={value}: the joint value is not a finite number", name=name, value=str(value)))
        tracks[name] = _constant_track(name, number)
    return _Layer(tracks, None, "pose")


def _build(tree: TFTree, layers: Sequence[_Layer], base: _Layer | None = None, label: str = "") -> Motion:
    """Joints take their track from the layers (the first that drives them), else ``base``, else 0."""
    tracks = []
    for name in tree.dof:
        track = next((layer.tracks[name] for layer in layers if name in layer.tracks), None)
        if track is None and base is not None:
            track = base.tracks.get(name)
        tracks.append(track or _constant_track(name, 0.0))
    durations = [layer.duration for layer in layers if layer.duration is not None]
    notes = [note for layer in layers for note in layer.notes]
    return Motion(list(tree.dof), tracks, max(durations) if durations else None,
                  label or " + ".join(layer.label for layer in layers if layer.label), notes)


def _base_layer(tree: TFTree, base: Mapping[str, float] | Motion | None) -> _Layer | None:
    if base is None:
        return None
    if isinstance(base, Motion):
        return _Layer({t.joint: t for t in base.tracks}, base.duration, base.label)
    return _pose_layer(tree, base)


def formula_motion(robot: Robot, specs: Sequence[str],
                   base: Mapping[str, float] | Motion | None = None) -> Motion:
    """One formula of ``t`` per joint (``"epaule=0.8*sin(t)"``); other joints follow ``base``.

    ``base`` is a pose (joint values by name) or another motion; without it they stay at 0.
    """
    tree = tf_tree(robot)
    return _build(tree, [_formula_layer(tree, specs)], _base_layer(tree, base))


def pose_motion(robot: Robot, config: Mapping[str, float] | None = None) -> Motion:
    """Every joint held still: the values of ``config``, 0 for joints it does not name."""
    tree = tf_tree(robot)
    return _build(tree, [_pose_layer(tree, config or {})], label="pose")


def waypoint_motion(robot: Robot, path: str, interpolation: str | None = None,
                    base: Mapping[str, float] | Motion | None = None) -> Motion:
    """Joint values through the waypoints of a CSV, JSON or YAML file.

    ``interpolation`` ("linear" or "cubic") overrides the file's own; the default is linear.
    Before the first waypoint and after the last, joints hold still. Joints the file does not
    name follow ``base`` (0 without it). The natural duration is the last waypoint's time.
    """
    tree = tf_tree(robot)
    return _build(tree, [_waypoint_layer(tree, path, interpolation)], _base_layer(tree, base))


def _waypoint_layer(tree: TFTree, path: str, interpolation: str | None) -> _Layer:
    points = read_waypoints(path, tree, interpolation)
    tracks = {}
    for k, joint in enumerate(points.joints):
        evaluate = interpolator(points.times, points.values[:, k], points.interpolation)
        tracks[joint] = Track(joint, evaluate, f"{os.path.basename(path)} ({points.interpolation})", points)
    return _Layer(tracks, points.duration, os.path.basename(path))


def _bag_layer(tree: TFTree, path: str, topic: str | None) -> _Layer:
    """A recorded JointState topic of a ROS 2 bag, linear between samples (see :mod:`bras_kit.motion.bags`)."""
    from .bags import recorded_tracks  # a feature above motion: only loaded for a bag

    tracks, duration, notes, label = recorded_tracks(tree.dof, lambda name: check_joint(tree, name), path, topic)
    return _Layer(tracks, duration, label, notes)


def _recorded_layer(tree: TFTree, states: JointStates, label: str) -> _Layer:
    """Joint states as a node published them (``--node``), linear between messages."""
    times = np.asarray(states.times, dtype=float)
    times, first = np.unique(times, return_index=True)
    times = times - times[0] if len(times) else times  # the motion starts with the first message
    tracks = {}
    for k, joint in enumerate(states.names):
        check_joint(tree, joint)
        values = np.asarray(states.positions, dtype=float)[first, k]
        tracks[joint] = Track(joint, interpolator(times, values, "linear"), label)
    return _Layer(tracks, float(times[-1]) if len(times) else 0.0, label)


def motion_from_specs(robot: Robot, specs: Sequence[str], set_values: Mapping[str, float] | None = None,
                      interpolation: str | None = None, topic: str | None = None,
                      recorded: tuple[str, JointStates] | None = None) -> Motion:
    """Combine motion specs: "tutorial", "JOINT=FORMULA", waypoint files and bags, plus fixed values.

    A ROS 2 bag (a folder with metadata.yaml, or its .mcap/.db3 file) drives the joints its
    ``topic`` (default /joint_states) records; what was odd in it is in ``motion.notes``.

    Formulas and files drive the joints they name (two specs for one joint are an error);
    ``set_values`` hold joints still; "tutorial" drives every joint left over. With no specs and
    no values this is the tutorial motion; with values only, a fixed pose. ``recorded`` is
    ``(label, JointStates)``: what a node published, taken directly (``--node``).
    """
    tree = tf_tree(robot)
    specs = list(specs)
    set_values = dict(set_values or {})
    if not specs and not set_values and recorded is None:
        return tutorial_motion(robot)
    layers: list[_Layer] = []
    if recorded is not None:
        layers.append(_recorded_layer(tree, recorded[1], recorded[0]))
    formulas: list[str] = []
    background: _Layer | None = None
    for spec in specs:
        kind = spec_kind(spec)
        if kind == "tutorial":
            background = _tutorial_layer(tree)
        elif kind == "file":
            layers.append(_waypoint_layer(tree, spec.strip(), interpolation))
        elif kind == "bag":
            layers.append(_bag_layer(tree, spec.strip(), topic))
        else:
            formulas.append(spec)
    if formulas:
        layers.append(_formula_layer(tree, formulas))
    if set_values:
        layers.append(_pose_layer(tree, set_values))
    owner: dict[str, str] = {}
    for layer in layers:
        for name in layer.tracks:
            if name in owner:
                raise ParameterError(M("joint '{name}' is driven twice: by {first} and by {second}", name=name,
                                       first=motion_title(owner[name]), second=motion_title(layer.label)),
                                     hint=M("give each joint one source (formula, waypoint file or --set)"))
            owner[name] = layer.label
    labels = [layer.label for layer in layers] + (["tutorial"] if background else [])
    return _build(tree, layers, background, " + ".join(labels))


# The words a motion's label is made of ("tutorial + formulas"); file names stay as they are.
_LABEL_WORDS = {"tutorial": M("tutorial"), "formulas": M("formulas"), "pose": M("pose"), "motion": M("motion")}


def motion_title(label: str | None) -> Message | str:
    """A motion's label (``Motion.label``, English words joined by " + ") as a message, worded
    where it is shown; an empty label is "motion"."""
    parts = [part for part in (label or "motion").split(" + ") if part]
    words: list[Message | str] = [_LABEL_WORDS.get(part, part) for part in parts]
    title = words[0]
    for word in words[1:]:
        title = M("{left} + {right}", left=title, right=word)
    return title
