"""Motion programs: joint positions as functions of time, sampled like recorded /joint_states.

A :class:`Motion` gives every movable joint of a robot (``tree.dof`` order) a position and a
velocity at any time. Motions come from the tutorial's animation node (:func:`tutorial_motion`),
per-joint formulas (:func:`formula_motion`, checked by :mod:`bras_kit.expr`), a fixed pose
(:func:`pose_motion`) or a waypoint file (:func:`waypoint_motion`: CSV, JSON or YAML).

:func:`sample` turns a motion into :class:`JointStates` at a fixed rate: samples at
``k / rate`` for ``k = 0 .. floor(duration * rate)``, so 10 s at 20 Hz is 201 samples, both ends
included. Velocities are the exact time derivatives of the positions (formulas are
differentiated along with their evaluation, splines analytically), not finite differences.

:func:`check_limits` reports where positions leave ``[lower, upper]`` and speeds exceed the
joint's velocity limit (the tutorial's pitfall "les articulations dépassent");
:func:`clamp` keeps positions inside; :func:`waypoint_speeds` names the waypoint segments that
would need a joint to move faster than its limit.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field, replace

import numpy as np

from .errors import ParameterError
from .expr import compile_expression
from .kinematics import TFTree, tf_tree
from .model import Joint, Robot

DEFAULT_RATE = 20.0  # Hz, like the tutorial's animation node (a 0.05 s timer)
DEFAULT_DURATION = 10.0  # seconds, for motions without a natural end
WAYPOINT_SUFFIXES = (".csv", ".json", ".yaml", ".yml")
INTERPOLATIONS = ("linear", "cubic")
MAX_VALUES = 20_000_000  # samples x joints kept in memory
TOLERANCE = 1e-9  # how far past a limit still counts as on it (rounding)

_Evaluate = Callable[[np.ndarray], "tuple[np.ndarray, np.ndarray]"]


# ---------------------------------------------------------------- data


@dataclass
class JointStates:
    """A sequence of joint states, like the messages recorded on /joint_states.

    ``positions`` and ``velocities`` have shape (len(times), len(names)); names follow
    ``tree.dof``.
    """

    times: np.ndarray
    names: list[str]
    positions: np.ndarray
    velocities: np.ndarray

    def __len__(self) -> int:
        return len(self.times)

    def column(self, joint: str) -> int:
        try:
            return self.names.index(joint)
        except ValueError:
            raise ParameterError(f"unknown joint '{joint}'", hint="joints: " + ", ".join(self.names)) from None

    def config(self, index: int) -> dict[str, float]:
        """The joint values of sample ``index`` by name."""
        return {name: float(v) for name, v in zip(self.names, self.positions[index])}


@dataclass(frozen=True)
class Waypoints:
    """Times and joint values read from a waypoint file (``lines``: where each waypoint is)."""

    times: np.ndarray  # (K,)
    joints: list[str]
    values: np.ndarray  # (K, J)
    interpolation: str = "linear"
    path: str | None = None
    lines: tuple[int | None, ...] = ()

    @property
    def duration(self) -> float:
        return float(self.times[-1])


@dataclass(frozen=True)
class Track:
    """How one joint moves: ``evaluate(t)`` gives its positions and velocities at the times ``t``."""

    joint: str
    evaluate: _Evaluate
    source: str  # what drives it, for people: "0.8*sin(t)", "held at 0", "waypoints.csv (cubic)"
    waypoints: Waypoints | None = None


@dataclass
class Motion:
    """Every movable joint's position as a function of time.

    ``duration`` is the natural length (the last waypoint's time) or None for endless motions.
    """

    names: list[str]
    tracks: list[Track]
    duration: float | None = None
    label: str = ""

    def evaluate(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Positions and velocities, each of shape (len(t), len(names))."""
        times = np.atleast_1d(np.asarray(t, dtype=float))
        positions = np.zeros((times.size, len(self.names)))
        velocities = np.zeros_like(positions)
        for k, track in enumerate(self.tracks):
            positions[:, k], velocities[:, k] = track.evaluate(times)
        return positions, velocities

    def positions(self, t: np.ndarray | float) -> np.ndarray:
        return self.evaluate(t)[0]

    def velocities(self, t: np.ndarray | float) -> np.ndarray:
        return self.evaluate(t)[1]

    def sources(self) -> dict[str, str]:
        return {track.joint: track.source for track in self.tracks}


@dataclass(frozen=True)
class LimitViolation:
    """A joint past a limit: first at ``time``; worst ``value`` at ``peak_time``, ``excess`` beyond ``bound``.

    ``kind`` is "position" (``side`` "upper" or "lower") or "velocity" (``bound`` is the speed
    limit, ``value`` the signed velocity). ``samples`` counts the samples past the limit.
    """

    joint: str
    kind: str
    time: float
    value: float
    bound: float
    excess: float
    peak_time: float = 0.0
    side: str = "upper"
    samples: int = 1
    unit: str = "rad"


@dataclass(frozen=True)
class SegmentSpeed:
    """A waypoint segment that needs ``joint`` to move at ``speed``, above its velocity ``limit``."""

    joint: str
    start: float
    end: float
    speed: float
    limit: float
    path: str | None = None
    lines: tuple[int | None, int | None] = (None, None)
    unit: str = "rad"
    interpolation: str = "linear"


@dataclass
class _Layer:
    tracks: dict[str, Track] = field(default_factory=dict)
    duration: float | None = None
    label: str = ""


# ---------------------------------------------------------------- building motions


def joint_unit(joint: Joint | None) -> str:
    """"m" for prismatic joints, "rad" for the others."""
    return "m" if joint is not None and joint.type == "prismatic" else "rad"


def _formula_track(joint: str, formula: str, prefix: str = "") -> Track:
    expression = compile_expression(formula, prefix=prefix)
    return Track(joint, expression.evaluate, expression.text)


def _constant_track(joint: str, value: float) -> Track:
    def evaluate(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        return np.full(t.shape, value), np.zeros(t.shape)

    return Track(joint, evaluate, f"held at {value:g}")


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
    speed = joint.limit.velocity if joint.limit is not None and joint.limit.velocity else 0.0
    if speed > 0:
        amplitude = min(amplitude, 0.9 * speed / omega)
    amplitude = _round_down(max(amplitude, 0.0))
    wave = f"sin({omega!r}*t{phase})" if omega != 1.0 else f"sin(t{phase})"
    if amplitude <= 0:
        return repr(centre)
    text = f"{amplitude!r}*{wave}"
    return f"{centre!r} + {text}" if centre else text


# The tutorial's node: epaule = 0.8 sin t, coude = 1.2 sin 0.7t, kept as written (even past
# narrower limits: that is the pitfall the limit check is for).
TUTORIAL_FORMULAS = {"epaule": "0.8*sin(t)", "coude": "1.2*sin(0.7*t)"}


def tutorial_motion(robot: Robot) -> Motion:
    """The tutorial's animation: epaule = 0.8 sin t, coude = 1.2 sin 0.7t.

    A wrist ``poignet`` follows 0.9 sin(1.3t + pi/3) (smaller if its limits are narrower); any
    other movable joint gets a gentle sine inside its limits, each at its own pace.
    """
    tree = tf_tree(robot)
    return _build(tree, [_tutorial_layer(tree)], label="tutorial")


def _tutorial_layer(tree: TFTree) -> _Layer:
    tracks: dict[str, Track] = {}
    others = 0
    for name in tree.dof:
        joint = tree.robot.joint(name)
        if name in TUTORIAL_FORMULAS:
            formula = TUTORIAL_FORMULAS[name]
        elif name == "poignet":
            formula = _fitted_sine(joint, 0.9, 1.3, " + pi/3")  # type: ignore[arg-type]
        else:
            cap = 0.1 if joint_unit(joint) == "m" else 0.8
            formula = _fitted_sine(joint, cap, 0.5 + 0.25 * others)  # type: ignore[arg-type]
            others += 1
        tracks[name] = _formula_track(name, formula)
    return _Layer(tracks, None, "tutorial")


def _check_joint(tree: TFTree, name: str, path: str | None = None, line: int | None = None) -> None:
    if name in tree.dof:
        return
    joint = tree.robot.joint(name)
    if joint is None:
        why = f"unknown joint '{name}'"
    elif joint.mimic is not None:
        why = f"joint '{name}' mimics '{joint.mimic.joint}' and follows it: it cannot be driven"
    else:
        why = f"joint '{name}' is {joint.type} and cannot move"
    raise ParameterError(why, path=path, line=line, hint="movable joints: " + (", ".join(tree.dof) or "none"))


def _split_formula(spec: str) -> tuple[str, str, str]:
    """``"epaule = 0.8*sin(t)"`` -> (joint, formula, the text before the formula)."""
    name, sep, formula = spec.partition("=")
    if not sep or not name.strip():
        raise ParameterError(f"'{spec}' is not JOINT=FORMULA",
                             hint="write e.g. epaule=0.8*sin(t) (the time is t, in seconds)")
    return name.strip(), formula, spec[: len(name) + 1]


def _formula_layer(tree: TFTree, specs: Sequence[str]) -> _Layer:
    tracks: dict[str, Track] = {}
    for spec in specs:
        name, formula, prefix = _split_formula(spec)
        _check_joint(tree, name)
        if name in tracks:
            raise ParameterError(f"two formulas for joint '{name}'", hint="give each joint one formula")
        tracks[name] = _formula_track(name, formula, prefix)
    return _Layer(tracks, None, "formulas")


def _pose_layer(tree: TFTree, config: Mapping[str, float]) -> _Layer:
    tree.config_vector(config)  # unknown or fixed joints: a clear error
    tracks = {}
    for name, value in config.items():
        number = float(value)
        if not math.isfinite(number):
            raise ParameterError(f"{name}={value}: the joint value is not a finite number")
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
    return Motion(list(tree.dof), tracks, max(durations) if durations else None,
                  label or " + ".join(layer.label for layer in layers if layer.label))


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
        evaluate = _interpolator(points.times, points.values[:, k], points.interpolation)
        tracks[joint] = Track(joint, evaluate, f"{os.path.basename(path)} ({points.interpolation})", points)
    return _Layer(tracks, points.duration, os.path.basename(path))


def spec_kind(spec: str) -> str:
    """"tutorial", "file" (a waypoint file) or "formula"; anything else is a ParameterError."""
    text = spec.strip()
    if text.lower() == "tutorial":
        return "tutorial"
    if text.lower().endswith(WAYPOINT_SUFFIXES):
        return "file"
    if "=" in text:
        return "formula"
    raise ParameterError(f"'{spec}' is not a motion",
                         hint="give 'tutorial', JOINT=FORMULA (e.g. epaule=0.8*sin(t)) "
                              "or a waypoint file (.csv, .json, .yaml)")


def motion_from_specs(robot: Robot, specs: Sequence[str], set_values: Mapping[str, float] | None = None,
                      interpolation: str | None = None) -> Motion:
    """Combine motion specs: "tutorial", "JOINT=FORMULA" and waypoint files, plus fixed values.

    Formulas and files drive the joints they name (two specs for one joint are an error);
    ``set_values`` hold joints still; "tutorial" drives every joint left over. With no specs and
    no values this is the tutorial motion; with values only, a fixed pose.
    """
    tree = tf_tree(robot)
    specs = list(specs)
    set_values = dict(set_values or {})
    if not specs and not set_values:
        return tutorial_motion(robot)
    layers: list[_Layer] = []
    formulas: list[str] = []
    background: _Layer | None = None
    for spec in specs:
        kind = spec_kind(spec)
        if kind == "tutorial":
            background = _tutorial_layer(tree)
        elif kind == "file":
            layers.append(_waypoint_layer(tree, spec.strip(), interpolation))
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
                raise ParameterError(f"joint '{name}' is driven twice: by {owner[name]} and by {layer.label}",
                                     hint="give each joint one source (formula, waypoint file or --set)")
            owner[name] = layer.label
    labels = [layer.label for layer in layers] + (["tutorial"] if background else [])
    return _build(tree, layers, background, " + ".join(labels))


# ---------------------------------------------------------------- interpolation


def _interpolator(times: np.ndarray, values: np.ndarray, interpolation: str) -> _Evaluate:
    """Positions and velocities through (times, values); held still outside the waypoints."""
    if len(times) == 1:
        value = float(values[0])
        return lambda t: (np.full(t.shape, value), np.zeros(t.shape))
    slopes = _cubic_slopes(times, values) if interpolation == "cubic" else None

    def evaluate(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
        t = np.asarray(t, dtype=float)
        index = np.clip(np.searchsorted(times, t, side="right") - 1, 0, len(times) - 2)
        start, width = times[index], times[index + 1] - times[index]
        u = (t - start) / width
        y0, y1 = values[index], values[index + 1]
        if slopes is None:
            position = (1.0 - u) * y0 + u * y1  # exact at both ends of a segment
            velocity = (y1 - y0) / width
        else:
            position, velocity = _hermite(u, width, y0, y1, slopes[index], slopes[index + 1])
        before, after = t < times[0], t > times[-1]
        position = np.where(before, values[0], np.where(after, values[-1], position))
        velocity = np.where(before | after, 0.0, velocity)
        return position, velocity

    return evaluate


def _hermite(u: np.ndarray, width: np.ndarray, y0: np.ndarray, y1: np.ndarray,
             s0: np.ndarray, s1: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Cubic Hermite segment: position and time derivative at fraction ``u`` of the segment."""
    u2, u3 = u * u, u * u * u
    position = ((2 * u3 - 3 * u2 + 1) * y0 + (u3 - 2 * u2 + u) * width * s0
                + (-2 * u3 + 3 * u2) * y1 + (u3 - u2) * width * s1)
    velocity = ((6 * u2 - 6 * u) * y0 + (3 * u2 - 4 * u + 1) * width * s0
                + (-6 * u2 + 6 * u) * y1 + (3 * u2 - 2 * u) * width * s1) / width
    return position, velocity


def _cubic_slopes(times: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Knot velocities of the shape-preserving cubic (PCHIP, Fritsch-Butland) through the values.

    Zero at the first and last waypoint (start and end at rest) and at every interior waypoint
    where the motion turns back; elsewhere a weighted harmonic mean of the neighbouring slopes.
    The curve is C1 and never overshoots: between two waypoints it stays between their values.
    """
    slopes = np.zeros(len(times))
    if len(times) < 3:
        return slopes
    h = np.diff(times)
    d = np.diff(values) / h
    h0, h1, d0, d1 = h[:-1], h[1:], d[:-1], d[1:]
    w0, w1 = 2 * h1 + h0, h1 + 2 * h0
    same = d0 * d1 > 0
    with np.errstate(all="ignore"):
        mean = (w0 + w1) / (w0 / d0 + w1 / d1)
    slopes[1:-1] = np.where(same, mean, 0.0)
    return slopes


# ---------------------------------------------------------------- waypoint files


def read_waypoints(path: str, tree: TFTree | Robot, interpolation: str | None = None) -> Waypoints:
    """Read a waypoint file (.csv, .json, .yaml/.yml) and check it against the robot's joints.

    CSV: a header ``time,JOINT,...`` then one row per waypoint (';' or tab separators with
    decimal commas also work; blank lines and lines starting with '#' are skipped).
    JSON/YAML: ``{"interpolation": "cubic", "waypoints": [{"time": 0, "positions": {"epaule": 0}}]}``,
    or just the list of waypoints; ``positions`` may be a list when ``"joints"`` names the columns.
    Times are seconds, increasing, from 0; values are radians (metres for prismatic joints).
    """
    if isinstance(tree, Robot):
        tree = tf_tree(tree)
    if interpolation is not None and interpolation not in INTERPOLATIONS:
        raise ParameterError(f"unknown interpolation '{interpolation}'", hint="use linear or cubic")
    suffix = os.path.splitext(path)[1].lower()
    if suffix not in WAYPOINT_SUFFIXES:
        raise ParameterError(f"{path}: not a waypoint file", path=None,
                             hint="waypoint files end in .csv, .json, .yaml or .yml")
    try:
        with open(path, encoding="utf-8-sig") as handle:
            text = handle.read()
    except FileNotFoundError:
        raise ParameterError("no such waypoint file", path=path,
                             hint="check the path (relative paths start from the current folder)") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise ParameterError(f"cannot read the waypoint file: {exc}", path=path,
                             hint="waypoint files are UTF-8 text") from None
    if suffix == ".csv":
        times, joints, values, lines, written = _parse_csv(text, path, tree)
    else:
        times, joints, values, lines, written = _parse_structured(text, path, tree, suffix == ".json")
    _check_times(times, lines, path)
    return Waypoints(np.asarray(times, dtype=float), joints, np.asarray(values, dtype=float).reshape(len(times), len(joints)),
                     interpolation or written or "linear", path, tuple(lines))


def _number(text: str, decimal_comma: bool = False) -> float | None:
    try:
        value = float(text.replace(",", ".") if decimal_comma else text)
    except ValueError:
        return None
    return value if math.isfinite(value) else None


def _parse_csv(text: str, path: str, tree: TFTree):  # type: ignore[no-untyped-def]
    import csv

    header: list[str] | None = None
    delimiter, decimal_comma = ",", False
    times: list[float] = []
    rows: list[list[float]] = []
    lines: list[int | None] = []
    for number, line in enumerate(text.splitlines(), start=1):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        if header is None:
            if "," not in line and (";" in line or "\t" in line):
                delimiter = ";" if ";" in line else "\t"
                decimal_comma = True
            header = [cell.strip() for cell in next(csv.reader([line], delimiter=delimiter))]
            _check_header(header, path, number, tree)
            continue
        cells = [cell.strip() for cell in next(csv.reader([line], delimiter=delimiter))]
        if len(cells) != len(header):
            raise ParameterError(f"row has {len(cells)} values, the header has {len(header)} "
                                 f"({', '.join(header)})", path=path, line=number,
                                 hint="give a time and one value per joint on every row")
        values = []
        for column, cell in zip(header, cells):
            value = _number(cell, decimal_comma)
            if value is None:
                raise ParameterError(f"{column}: '{cell}' is not a number", path=path, line=number,
                                     hint="write times in seconds and joint values in radians (metres "
                                          "for prismatic joints), e.g. 0.5")
            values.append(value)
        times.append(values[0])
        rows.append(values[1:])
        lines.append(number)
    if header is None:
        raise ParameterError("the waypoint file is empty", path=path,
                             hint="start with a header such as time,epaule,coude")
    if not rows:
        raise ParameterError("no waypoints after the header", path=path,
                             hint="add rows such as 0,0,0 then 2,0.5,1.0 (time, then one value per joint)")
    return times, header[1:], rows, lines, None


def _check_header(header: list[str], path: str, line: int, tree: TFTree) -> None:
    if header[0].lower() != "time":
        raise ParameterError(f"the first column is '{header[0]}', not 'time'", path=path, line=line,
                             hint="start the file with a header such as time," + ",".join(tree.dof))
    if len(header) < 2:
        raise ParameterError("the header names no joint", path=path, line=line,
                             hint="name the joint columns after time, e.g. time," + ",".join(tree.dof))
    seen = set()
    for name in header[1:]:
        if not name:
            raise ParameterError("a column of the header has no name", path=path, line=line,
                                 hint="movable joints: " + ", ".join(tree.dof))
        if name in seen:
            raise ParameterError(f"the column '{name}' appears twice", path=path, line=line,
                                 hint="give each joint one column")
        seen.add(name)
        _check_joint(tree, name, path, line)


_TOP_KEYS = ("waypoints", "interpolation", "joints")
_POINT_KEYS = ("time", "positions")


def _parse_structured(text: str, path: str, tree: TFTree, is_json: bool):  # type: ignore[no-untyped-def]
    kind = "JSON" if is_json else "YAML"
    if is_json:
        import json

        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise ParameterError(f"not valid JSON: {exc.msg} (column {exc.colno})", path=path, line=exc.lineno,
                                 hint="check commas, quotes and brackets near that line") from None
    else:
        import yaml

        try:
            data = yaml.safe_load(text)
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            problem = getattr(exc, "problem", None) or "cannot be read"
            raise ParameterError(f"not valid YAML: {problem}", path=path,
                                 line=mark.line + 1 if mark is not None else None,
                                 hint="check the indentation and the ':' after each key near that line") from None
    lines = _waypoint_lines(text)
    written = None
    names: list[str] | None = None
    if isinstance(data, dict):
        unknown = [k for k in data if k not in _TOP_KEYS]
        if unknown:
            raise ParameterError(f"unknown key '{unknown[0]}'", path=path,
                                 hint="the keys are " + ", ".join(_TOP_KEYS))
        if "waypoints" not in data:
            raise ParameterError(f"no 'waypoints' in the {kind} file", path=path,
                                 hint='write {"interpolation": "linear", "waypoints": [{"time": 0, '
                                      '"positions": {"epaule": 0}}, ...]}')
        written = data.get("interpolation")
        if written is not None and written not in INTERPOLATIONS:
            raise ParameterError(f"unknown interpolation {written!r}", path=path, hint="use linear or cubic")
        if "joints" in data:
            names = data["joints"]
            if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
                raise ParameterError("'joints' must be a list of joint names", path=path,
                                     hint="movable joints: " + ", ".join(tree.dof))
            for name in names:
                _check_joint(tree, name, path)
        data = data["waypoints"]
    if not isinstance(data, list) or not data:
        raise ParameterError("the waypoints must be a non-empty list", path=path,
                             hint='each waypoint is {"time": 0.0, "positions": {"epaule": 0.0, "coude": 0.0}}')
    times: list[float] = []
    rows: list[dict[str, float]] = []
    for index, point in enumerate(data):
        line = lines[index] if index < len(lines) else None
        where = f"waypoint {index + 1}"
        if not isinstance(point, dict):
            raise ParameterError(f"{where} is not a mapping with 'time' and 'positions'", path=path, line=line,
                                 hint='write {"time": 0.5, "positions": {"epaule": 0.3}}')
        unknown = [k for k in point if k not in _POINT_KEYS]
        missing = [k for k in _POINT_KEYS if k not in point]
        if unknown or missing:
            what = f"unknown key '{unknown[0]}'" if unknown else f"no '{missing[0]}'"
            raise ParameterError(f"{where}: {what}", path=path, line=line,
                                 hint="each waypoint has exactly 'time' (seconds) and 'positions'")
        time = _structured_number(point["time"])
        if time is None:
            raise ParameterError(f"{where}: time {point['time']!r} is not a number", path=path, line=line,
                                 hint="give the time in seconds, e.g. 1.5")
        positions = point["positions"]
        if isinstance(positions, list):
            if names is None:
                raise ParameterError(f"{where}: positions is a list but the file has no 'joints'", path=path,
                                     line=line, hint='add "joints": [...] naming the columns, or give '
                                                     'positions by name: {"epaule": 0.3}')
            if len(positions) != len(names):
                raise ParameterError(f"{where}: {len(positions)} positions for {len(names)} joints "
                                     f"({', '.join(names)})", path=path, line=line,
                                     hint="give one value per joint named in 'joints'")
            positions = dict(zip(names, positions))
        if not isinstance(positions, dict) or not positions:
            raise ParameterError(f"{where}: positions must map joint names to values", path=path, line=line,
                                 hint='write "positions": {"epaule": 0.3, "coude": -0.2}')
        row = {}
        for name, raw in positions.items():
            _check_joint(tree, str(name), path, line)
            value = _structured_number(raw)
            if value is None:
                raise ParameterError(f"{where}: {name} = {raw!r} is not a number", path=path, line=line,
                                     hint="joint values are radians (metres for prismatic joints)")
            row[str(name)] = value
        times.append(time)
        rows.append(row)
    joints = list(dict.fromkeys(name for row in rows for name in row))
    for index, row in enumerate(rows):
        absent = [name for name in joints if name not in row]
        if absent:
            line = lines[index] if index < len(lines) else None
            raise ParameterError(f"waypoint {index + 1} has no value for {', '.join(absent)}", path=path,
                                 line=line, hint="give every joint of the file a value in every waypoint")
    values = [[row[name] for name in joints] for row in rows]
    return times, joints, values, [lines[i] if i < len(lines) else None for i in range(len(rows))], written


def _structured_number(raw: object) -> float | None:
    if isinstance(raw, bool):
        return None
    if isinstance(raw, (int, float)):
        try:
            value = float(raw)
        except OverflowError:
            return None
        return value if math.isfinite(value) else None
    if isinstance(raw, str):  # YAML 1.1 reads 1e-3 as text
        return _number(raw.strip())
    return None


def _waypoint_lines(text: str) -> list[int | None]:
    """The line of each waypoint, found by composing the text as YAML (JSON is YAML too)."""
    import yaml

    try:
        node = yaml.compose(text, Loader=yaml.SafeLoader)
    except yaml.YAMLError:
        return []
    if isinstance(node, yaml.MappingNode):
        node = next((value for key, value in node.value if getattr(key, "value", None) == "waypoints"), None)
    if not isinstance(node, yaml.SequenceNode):
        return []
    return [item.start_mark.line + 1 for item in node.value]


def _check_times(times: list[float], lines: list[int | None], path: str) -> None:
    for index, time in enumerate(times):
        line = lines[index] if index < len(lines) else None
        if time < 0:
            raise ParameterError(f"waypoint time {time:g} is negative", path=path, line=line,
                                 hint="times are seconds from the start of the motion, from 0")
        if index and time <= times[index - 1]:
            raise ParameterError(f"waypoint time {time:g} does not come after the previous one "
                                 f"({times[index - 1]:g})", path=path, line=line,
                                 hint="list waypoints in increasing time order, each at a later time")


# ---------------------------------------------------------------- sampling


def sample_count(duration: float, rate: float) -> int:
    """Samples at k/rate for k = 0..floor(duration*rate): duration*rate + 1 when that is whole."""
    return int(math.floor(duration * rate + 1e-9)) + 1


def sample(motion: Motion, duration: float | None = None, rate: float = DEFAULT_RATE) -> JointStates:
    """The motion at ``k / rate`` seconds for k = 0 .. floor(duration * rate) (both ends included).

    ``duration`` defaults to the motion's natural duration, else :data:`DEFAULT_DURATION`.
    Raises :class:`ParameterError` when a position is not a finite number (say ``log(t)`` at 0).
    """
    if duration is None:
        duration = motion.duration if motion.duration is not None else DEFAULT_DURATION
    duration, rate = float(duration), float(rate)
    if not math.isfinite(duration) or duration < 0:
        raise ParameterError(f"duration {duration:g} s is not a time", hint="give a duration of 0 s or more")
    if not math.isfinite(rate) or rate <= 0:
        raise ParameterError(f"rate {rate:g} Hz is not a rate", hint="give samples per second above 0, e.g. 20")
    count = sample_count(duration, rate)
    if count * max(len(motion.names), 1) > MAX_VALUES:
        raise ParameterError(f"{count} samples of {len(motion.names)} joints is too many",
                             hint="lower --duration or --rate")
    times = np.arange(count) / rate
    with np.errstate(all="ignore"):
        positions, velocities = motion.evaluate(times)
    bad = ~np.isfinite(positions)
    if bad.any():
        k, j = np.argwhere(bad)[0]
        track = motion.tracks[j]
        raise ParameterError(f"the motion of {track.joint} ({track.source}) is not a number at t={times[k]:g} s",
                             hint="log, sqrt, asin, acos and division are undefined for some values; "
                                  "keep their arguments in range (e.g. sqrt(abs(...)), log(1 + t))")
    steep = ~np.isfinite(velocities)
    if steep.any():  # e.g. sqrt(t) at 0: fall back on the slope between neighbouring samples
        slope = np.gradient(positions, times, axis=0) if count > 1 else np.zeros_like(positions)
        velocities = np.where(steep, slope, velocities)
    return JointStates(times, list(motion.names), positions, velocities)


def sample_loop(motion: Motion, duration: float | None = None, fps: float = DEFAULT_RATE) -> JointStates:
    """``round(duration * fps)`` frames at ``k / fps``: an animation loop whose end is the next start.

    Unlike :func:`sample`, the last instant is left out, so a GIF of 9 s at 20 fps has 180 frames.
    """
    if duration is None:
        duration = motion.duration if motion.duration is not None else DEFAULT_DURATION
    count = round(float(duration) * float(fps)) if math.isfinite(duration) and math.isfinite(fps) else 0
    if count < 1:
        raise ParameterError(f"{duration:g} s at {fps:g} fps is less than one frame",
                             hint="raise --duration or --fps")
    return sample(motion, (count - 1) / fps, fps)


# ---------------------------------------------------------------- limits


def _speed_limit(joint: Joint | None) -> float | None:
    if joint is None or joint.limit is None or not joint.limit.velocity or joint.limit.velocity <= 0:
        return None
    return float(joint.limit.velocity)


def check_limits(robot: Robot, states: JointStates, tolerance: float = TOLERANCE) -> list[LimitViolation]:
    """Positions past lower/upper and speeds past the velocity limit, per joint.

    For each joint, at most one violation per kind and side: ``time`` is the first sample past
    the limit, ``value``/``peak_time``/``excess`` the worst one.
    """
    out = []
    for k, name in enumerate(states.names):
        joint = robot.joint(name)
        if joint is None:
            continue
        lower, upper = joint.bounds()
        unit = joint_unit(joint)
        position = states.positions[:, k]
        for side, bound, past in (("upper", upper, position - upper), ("lower", lower, lower - position)):
            if math.isfinite(bound):
                violation = _violation(states.times, past, position, name, "position", bound, side, unit, tolerance)
                if violation:
                    out.append(violation)
        limit = _speed_limit(joint)
        if limit is not None:
            velocity = states.velocities[:, k]
            violation = _violation(states.times, np.abs(velocity) - limit, velocity, name, "velocity",
                                   limit, "speed", unit, tolerance)
            if violation:
                out.append(violation)
    return out


def _violation(times: np.ndarray, past: np.ndarray, values: np.ndarray, joint: str, kind: str,
               bound: float, side: str, unit: str, tolerance: float) -> LimitViolation | None:
    mask = past > tolerance
    if not mask.any():
        return None
    first, worst = int(np.argmax(mask)), int(np.argmax(past))
    return LimitViolation(joint, kind, float(times[first]), float(values[worst]), float(bound),
                          float(past[worst]), float(times[worst]), side, int(mask.sum()), unit)


def describe_violation(violation: LimitViolation) -> str:
    """One line for people, e.g. "coude goes past its upper limit 2 by 0.5 rad at t=1.55 s (...)"."""
    v = violation
    span = f"first at t={v.time:.4g} s, {v.samples} sample{'s' if v.samples != 1 else ''}"
    if v.kind == "velocity":
        return (f"{v.joint} moves at {abs(v.value):.4g} {v.unit}/s at t={v.peak_time:.4g} s, "
                f"{v.excess:.3g} {v.unit}/s over its velocity limit {v.bound:g} {v.unit}/s ({span})")
    return (f"{v.joint} goes past its {v.side} limit {v.bound:g} by {v.excess:.3g} {v.unit} "
            f"at t={v.peak_time:.4g} s ({span})")


def clamp(robot: Robot, states: JointStates) -> JointStates:
    """Positions held inside each joint's limits; where a position was moved, its velocity is 0."""
    positions = states.positions.copy()
    velocities = states.velocities.copy()
    for k, name in enumerate(states.names):
        joint = robot.joint(name)
        if joint is None:
            continue
        lower, upper = joint.bounds()
        outside = (positions[:, k] < lower) | (positions[:, k] > upper)
        positions[:, k] = np.clip(positions[:, k], lower, upper)
        velocities[outside, k] = 0.0
    return replace(states, positions=positions, velocities=velocities)


def waypoint_speeds(robot: Robot, motion: Motion, tolerance: float = TOLERANCE) -> list[SegmentSpeed]:
    """Waypoint segments where a joint would need more than its velocity limit.

    The speed is the segment's peak: |change / time| for linear interpolation, the largest
    speed of the cubic (at a segment end or where the acceleration is zero) for cubic.
    """
    out = []
    for track in motion.tracks:
        points = track.waypoints
        joint = robot.joint(track.joint)
        limit = _speed_limit(joint)
        if points is None or limit is None or len(points.times) < 2:
            continue
        column = points.values[:, points.joints.index(track.joint)]
        for i, speed in enumerate(_segment_peaks(points.times, column, points.interpolation)):
            if speed > limit + tolerance:
                lines = (points.lines[i] if i < len(points.lines) else None,
                         points.lines[i + 1] if i + 1 < len(points.lines) else None)
                out.append(SegmentSpeed(track.joint, float(points.times[i]), float(points.times[i + 1]),
                                        float(speed), limit, points.path, lines, joint_unit(joint),
                                        points.interpolation))
    return out


def _segment_peaks(times: np.ndarray, values: np.ndarray, interpolation: str) -> np.ndarray:
    h = np.diff(times)
    if interpolation != "cubic":
        return np.abs(np.diff(values) / h)
    s = _cubic_slopes(times, values)
    y0, y1, s0, s1 = values[:-1], values[1:], s[:-1], s[1:]
    # acceleration is linear in u: a*u + b; the speed peaks at u = -b/a when inside the segment
    a = 12 * y0 + 6 * h * s0 - 12 * y1 + 6 * h * s1
    b = -6 * y0 - 4 * h * s0 + 6 * y1 - 2 * h * s1
    with np.errstate(all="ignore"):
        vertex = np.where(a != 0, -b / a, 0.0)
    vertex = np.clip(np.nan_to_num(vertex), 0.0, 1.0)
    peaks = np.zeros_like(h)
    for u in (np.zeros_like(h), np.ones_like(h), vertex):
        peaks = np.maximum(peaks, np.abs(_hermite(u, h, y0, y1, s0, s1)[1]))
    return peaks


def describe_segment(segment: SegmentSpeed) -> str:
    """One line for people naming the segment, the joint, the speed it needs and the fix."""
    s = segment
    where = ""
    if s.path:
        where = os.path.basename(s.path)
        if s.lines[0] is not None and s.lines[1] is not None:
            where += f" lines {s.lines[0]}-{s.lines[1]}"
        where += ": "
    spread = (s.end - s.start) * s.speed / s.limit
    return (f"{where}{s.joint} needs {s.speed:.4g} {s.unit}/s between t={s.start:g} s and t={s.end:g} s "
            f"({s.interpolation}), above its velocity limit {s.limit:g} {s.unit}/s; "
            f"space these waypoints about {spread:.3g} s apart")


# ---------------------------------------------------------------- joint-state files


def states_to_messages(states: JointStates) -> list[dict]:
    """One dict per sample, shaped like a sensor_msgs/JointState message."""
    return [{"time": float(t), "name": list(states.names), "position": [float(v) for v in p],
             "velocity": [float(v) for v in w]}
            for t, p, w in zip(states.times, states.positions, states.velocities)]


def states_to_json(states: JointStates) -> str:
    """A JSON list of messages {"time", "name", "position", "velocity"}, one per line."""
    import json

    body = ",\n".join(json.dumps(message) for message in states_to_messages(states))
    return "[\n" + body + "\n]\n" if body else "[]\n"


def states_to_csv(states: JointStates) -> str:
    """Long form, like a recorded /joint_states: ``time,name,position,velocity``, one row per joint per sample."""
    rows = ["time,name,position,velocity"]
    for t, position, velocity in zip(states.times, states.positions, states.velocities):
        time = repr(float(t))
        rows.extend(f"{time},{name},{float(p)!r},{float(v)!r}"
                    for name, p, v in zip(states.names, position, velocity))
    return "\n".join(rows) + "\n"


def read_states(path: str) -> JointStates:
    """Read back a joint-state file written by ``bras-kit motion`` (CSV long form or JSON)."""
    suffix = os.path.splitext(path)[1].lower()
    try:
        with open(path, encoding="utf-8-sig") as handle:
            text = handle.read()
    except (OSError, UnicodeDecodeError) as exc:
        raise ParameterError(f"cannot read the joint states: {exc}", path=path,
                             hint="give a .csv or .json file written by bras-kit motion") from None
    if suffix == ".json":
        return _states_from_json(text, path)
    if suffix == ".csv":
        return _states_from_csv(text, path)
    raise ParameterError("joint states are read from .csv or .json files", path=path,
                         hint="write them with bras-kit motion -o states.csv")


def _states_from_json(text: str, path: str) -> JointStates:
    import json

    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ParameterError(f"not valid JSON: {exc.msg}", path=path, line=exc.lineno) from None
    hint = 'a list of {"time": t, "name": [...], "position": [...], "velocity": [...]}'
    if not isinstance(data, list) or not data:
        raise ParameterError("expected a non-empty list of joint-state messages", path=path, hint=hint)
    names = None
    times, positions, velocities = [], [], []
    for index, message in enumerate(data):
        try:
            if names is None:
                names = [str(n) for n in message["name"]]
            if list(message["name"]) != names:
                raise ParameterError(f"message {index + 1} names other joints than the first", path=path, hint=hint)
            position = [float(v) for v in message["position"]]
            velocity = [float(v) for v in message.get("velocity") or [0.0] * len(names)]
            if len(position) != len(names) or len(velocity) != len(names):
                raise ValueError
            times.append(float(message["time"]))
        except (KeyError, TypeError, ValueError):
            raise ParameterError(f"message {index + 1} is not a joint state", path=path, hint=hint) from None
        positions.append(position)
        velocities.append(velocity)
    return JointStates(np.array(times), names or [], np.array(positions), np.array(velocities))


def _states_from_csv(text: str, path: str) -> JointStates:
    lines = text.splitlines()
    if not lines or [c.strip() for c in lines[0].split(",")] != ["time", "name", "position", "velocity"]:
        raise ParameterError("the header is not time,name,position,velocity", path=path, line=1,
                             hint="write the file with bras-kit motion -o states.csv")
    names: list[str] = []
    times: list[float] = []
    positions: list[list[float]] = []
    velocities: list[list[float]] = []
    for number, line in enumerate(lines[1:], start=2):
        if not line.strip():
            continue
        cells = line.split(",")
        try:
            time, name, position, velocity = float(cells[0]), cells[1].strip(), float(cells[2]), float(cells[3])
        except (IndexError, ValueError):
            raise ParameterError("expected time,name,position,velocity", path=path, line=number) from None
        if not times or time != times[-1]:
            if times and len(positions[-1]) != len(names):
                raise ParameterError(f"the sample at t={times[-1]:g} s does not list every joint",
                                     path=path, line=number)
            times.append(time)
            positions.append([])
            velocities.append([])
        if len(times) == 1 and name not in names:
            names.append(name)
        k = len(positions[-1])
        if k >= len(names) or names[k] != name:
            raise ParameterError(f"joint '{name}' is out of order (expected the order {', '.join(names)})",
                                 path=path, line=number)
        positions[-1].append(position)
        velocities[-1].append(velocity)
    if not times or len(positions[-1]) != len(names):
        raise ParameterError("no complete joint state in the file", path=path)
    return JointStates(np.array(times), names, np.array(positions), np.array(velocities))
