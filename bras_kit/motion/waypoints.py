"""Waypoint files (CSV, JSON, YAML) read with their line numbers, and segments too fast for a joint."""

from __future__ import annotations

import math
import os
from dataclasses import dataclass
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
else:
    from ..core.lazy_numpy import np

from ..core.errors import ParameterError, os_reason
from ..core.message import M, Message
from ..kinematics.frames import TFTree, movable_joints_hint, tf_tree
from ..model.robot import Robot
from .core import Motion, Waypoints, check_joint
from .interpolation import INTERPOLATIONS, segment_peaks
from .limits import TOLERANCE, joint_unit, speed_limit
from .specs import WAYPOINT_SUFFIXES


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
        raise ParameterError(M("unknown interpolation '{name}'", name=interpolation), hint=M("use linear or cubic"))
    suffix = os.path.splitext(path)[1].lower()
    if suffix not in WAYPOINT_SUFFIXES:
        raise ParameterError(M("{path}: not a waypoint file", path=path), path=None,
                             hint=M("waypoint files end in .csv, .json, .yaml or .yml"))
    try:
        with open(path, encoding="utf-8-sig") as handle:
            text = handle.read()
    except FileNotFoundError:
        raise ParameterError(M("no such waypoint file"), path=path,
                             hint=M("check the path (relative paths start from the current folder)")) from None
    except OSError as exc:
        raise ParameterError(M("cannot read the waypoint file: {reason}", reason=os_reason(exc)), path=path,
                             hint=M("waypoint files are UTF-8 text")) from None
    except UnicodeDecodeError as exc:
        raise ParameterError(M("cannot read the waypoint file: {reason}", reason=str(exc)), path=path,
                             hint=M("waypoint files are UTF-8 text")) from None
    states = _joint_states_in(text, path, suffix)
    if states is not None:  # a file written by bras-kit motion/simulate, or a recorded /joint_states
        for name in states.names:
            check_joint(tree, name, path)
        times = [float(t) - float(states.times[0]) for t in states.times]
        _check_times(times, [None] * len(times), path)
        return Waypoints(np.asarray(times), list(states.names), np.asarray(states.positions, dtype=float),
                         interpolation or "linear", path, tuple([None] * len(times)))
    if suffix == ".csv":
        times, joints, values, lines, written = _parse_csv(text, path, tree)
    else:
        times, joints, values, lines, written = _parse_structured(text, path, tree, suffix == ".json")
    _check_times(times, lines, path)
    return Waypoints(np.asarray(times, dtype=float), joints, np.asarray(values, dtype=float).reshape(len(times), len(joints)),
                     interpolation or written or "linear", path, tuple(lines))


TIME_COLUMNS = ("time", "temps")  # the time column, in English or French


def _joint_states_in(text: str, path: str, suffix: str):
    """The joint states when the file holds messages (time, name, position...), else None."""
    from .states_io import _states_from_csv, _states_from_json

    if suffix == ".csv":
        lines = text.splitlines()
        at = next((k for k, line in enumerate(lines) if line.strip() and not line.lstrip().startswith("#")), None)
        if at is None:
            return None
        cells = [c.strip().lower() for c in lines[at].split(",")]
        if len(cells) >= 3 and cells[0] in TIME_COLUMNS and cells[1:3] == ["name", "position"]:
            header = ",".join(["time", *cells[1:]])  # temps,name,position,... reads as time,...
            return _states_from_csv("\n".join([header, *lines[at + 1:]]), path)
        return None
    if suffix == ".json":
        import json

        try:
            data = json.loads(text)
        except json.JSONDecodeError:
            return None
        if isinstance(data, list) and data and isinstance(data[0], dict) and "name" in data[0]:
            return _states_from_json(text, path)
    return None


def _number(text: str, decimal_comma: bool = False) -> float | None:
    """The one parser of joint values (``0.5``, ``1,5``, ``pi/2``, ``90deg``), None if not one."""
    from ..core.errors import BrasKitError
    from ..model.expr import parse_joint_value

    try:
        return parse_joint_value(text.replace(",", ".") if decimal_comma else text)
    except BrasKitError:
        return None


def _parse_csv(text: str, path: str, tree: TFTree):
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
            raise ParameterError(M("row has {count} values, the header has {wanted} ({names})", count=len(cells),
                                   wanted=len(header), names=", ".join(header)), path=path, line=number,
                                 hint=M("give a time and one value per joint on every row"))
        values = []
        for column, cell in zip(header, cells):
            value = _number(cell, decimal_comma)
            if value is None:
                raise ParameterError(M("{column}: '{cell}' is not a number", column=column, cell=cell),
                                     path=path, line=number,
                                     hint=M("write times in seconds and joint values in radians (metres "
                                            "for prismatic joints), e.g. 0.5"))
            values.append(value)
        times.append(values[0])
        rows.append(values[1:])
        lines.append(number)
    if header is None:
        raise ParameterError(M("the waypoint file is empty"), path=path,
                             hint=M("start with a header such as time,epaule,coude"))
    if not rows:
        raise ParameterError(M("no waypoints after the header"), path=path,
                             hint=M("add rows such as 0,0,0 then 2,0.5,1.0 (time, then one value per joint)"))
    return times, header[1:], rows, lines, None


def _check_header(header: list[str], path: str, line: int, tree: TFTree) -> None:
    if header[0].lower() not in TIME_COLUMNS:
        raise ParameterError(M("the first column is '{name}', not 'time'", name=header[0]), path=path, line=line,
                             hint=M("start the file with a header such as time,{names}", names=",".join(tree.dof)))
    if len(header) < 2:
        raise ParameterError(M("the header names no joint"), path=path, line=line,
                             hint=M("name the joint columns after time, e.g. time,{names}", names=",".join(tree.dof)))
    seen = set()
    for name in header[1:]:
        if not name:
            raise ParameterError(M("a column of the header has no name"), path=path, line=line,
                                 hint=movable_joints_hint(tree.dof))
        if name in seen:
            raise ParameterError(M("the column '{name}' appears twice", name=name), path=path, line=line,
                                 hint=M("give each joint one column"))
        seen.add(name)
        check_joint(tree, name, path, line)


_TOP_KEYS = ("waypoints", "interpolation", "joints")
_POINT_KEYS = ("time", "positions")


def _parse_structured(text: str, path: str, tree: TFTree, is_json: bool):
    if is_json:
        import json

        try:
            data = json.loads(text)
        except json.JSONDecodeError as exc:
            raise ParameterError(M("not valid JSON: {problem} (column {column})", problem=exc.msg, column=exc.colno),
                                 path=path, line=exc.lineno,
                                 hint=M("check commas, quotes and brackets near that line")) from None
    else:
        import yaml

        from ..trust import yaml_gate

        try:
            data = yaml_gate.load(text, loader=yaml.SafeLoader)  # PyYAML's own words in errors
        except yaml.YAMLError as exc:
            mark = getattr(exc, "problem_mark", None)
            problem = getattr(exc, "problem", None)  # PyYAML's own words, quoted in French
            raise ParameterError(M("not valid YAML: {problem}", problem=problem) if problem else
                                 M("not valid YAML: cannot be read"), path=path,
                                 line=mark.line + 1 if mark is not None else None,
                                 hint=M("check the indentation and the ':' after each key near that line")) from None
    lines = _waypoint_lines(text)
    written = None
    names: list[str] | None = None
    if isinstance(data, dict):
        unknown = [k for k in data if k not in _TOP_KEYS]
        if unknown:
            raise ParameterError(M("unknown key '{key}'", key=unknown[0]), path=path,
                                 hint=M("the keys are {keys}", keys=", ".join(_TOP_KEYS)))
        if "waypoints" not in data:
            raise ParameterError(M("no 'waypoints' in the {kind} file", kind="JSON" if is_json else "YAML"),
                                 path=path, hint=M("write {example}", example='{"interpolation": "linear", '
                                                   '"waypoints": [{"time": 0, "positions": {"epaule": 0}}, ...]}'))
        written = data.get("interpolation")
        if written is not None and written not in INTERPOLATIONS:
            raise ParameterError(M("unknown interpolation {name!r}", name=written), path=path,
                                 hint=M("use linear or cubic"))
        if "joints" in data:
            names = data["joints"]
            if not isinstance(names, list) or not all(isinstance(n, str) for n in names):
                raise ParameterError(M("'joints' must be a list of joint names"), path=path,
                                     hint=movable_joints_hint(tree.dof))
            for name in names:
                check_joint(tree, name, path)
        data = data["waypoints"]
    if not isinstance(data, list) or not data:
        raise ParameterError(M("the waypoints must be a non-empty list"), path=path,
                             hint=M("each waypoint is {example}",
                                    example='{"time": 0.0, "positions": {"epaule": 0.0, "coude": 0.0}}'))
    times: list[float] = []
    rows: list[dict[str, float]] = []
    for index, point in enumerate(data):
        line = lines[index] if index < len(lines) else None
        where = M("waypoint {number}", number=index + 1)
        if not isinstance(point, dict):
            raise ParameterError(M("{where} is not a mapping with 'time' and 'positions'", where=where), path=path,
                                 line=line, hint=M("write {example}", example='{"time": 0.5, "positions": {"epaule": 0.3}}'))
        unknown = [k for k in point if k not in _POINT_KEYS]
        missing = [k for k in _POINT_KEYS if k not in point]
        if unknown or missing:
            what = M("unknown key '{key}'", key=unknown[0]) if unknown else M("no '{key}'", key=missing[0])
            raise ParameterError(M("{where}: {what}", where=where, what=what), path=path, line=line,
                                 hint=M("each waypoint has exactly 'time' (seconds) and 'positions'"))
        time = _structured_number(point["time"])
        if time is None:
            raise ParameterError(M("{where}: time {value} is not a number", where=where, value=repr(point["time"])),
                                 path=path, line=line, hint=M("give the time in seconds, e.g. 1.5"))
        positions = point["positions"]
        if isinstance(positions, list):
            if names is None:
                raise ParameterError(M("{where}: positions is a list but the file has no 'joints'", where=where),
                                     path=path, line=line,
                                     hint=M("add \"joints\": [...] naming the columns, or give positions by name: "
                                            "{example}", example='{"epaule": 0.3}'))
            if len(positions) != len(names):
                raise ParameterError(M("{where}: {count} positions for {joints} joints ({names})", where=where,
                                       count=len(positions), joints=len(names), names=", ".join(names)),
                                     path=path, line=line, hint=M("give one value per joint named in 'joints'"))
            positions = dict(zip(names, positions))
        if not isinstance(positions, dict) or not positions:
            raise ParameterError(M("{where}: positions must map joint names to values", where=where), path=path,
                                 line=line, hint=M("write {example}", example='"positions": {"epaule": 0.3, "coude": -0.2}'))
        row = {}
        for name, raw in positions.items():
            check_joint(tree, str(name), path, line)
            value = _structured_number(raw)
            if value is None:
                raise ParameterError(M("{where}: {name} = {value} is not a number", where=where, name=str(name),
                                       value=repr(raw)), path=path, line=line,
                                     hint=M("joint values are radians (metres for prismatic joints)"))
            row[str(name)] = value
        times.append(time)
        rows.append(row)
    joints = list(dict.fromkeys(name for row in rows for name in row))
    for index, row in enumerate(rows):
        absent = [name for name in joints if name not in row]
        if absent:
            line = lines[index] if index < len(lines) else None
            raise ParameterError(M("waypoint {number} has no value for {names}", number=index + 1,
                                   names=", ".join(absent)), path=path,
                                 line=line, hint=M("give every joint of the file a value in every waypoint"))
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

    from ..trust import yaml_gate

    try:
        node = yaml_gate.compose(text)
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
            raise ParameterError(M("waypoint time {time:g} is negative", time=time), path=path, line=line,
                                 hint=M("times are seconds from the start of the motion, from 0"))
        if index and time <= times[index - 1]:
            raise ParameterError(M("waypoint time {time:g} does not come after the previous one ({previous:g})",
                                   time=time, previous=times[index - 1]), path=path, line=line,
                                 hint=M("list waypoints in increasing time order, each at a later time"))


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


def waypoint_speeds(robot: Robot, motion: Motion, tolerance: float = TOLERANCE) -> list[SegmentSpeed]:
    """Waypoint segments where a joint would need more than its velocity limit.

    The speed is the segment's peak: |change / time| for linear interpolation, the largest
    speed of the cubic (at a segment end or where the acceleration is zero) for cubic.
    """
    out = []
    for track in motion.tracks:
        points = track.waypoints
        joint = robot.joint(track.joint)
        limit = speed_limit(joint)
        if points is None or limit is None or len(points.times) < 2:
            continue
        column = points.values[:, points.joints.index(track.joint)]
        for i, speed in enumerate(segment_peaks(points.times, column, points.interpolation)):
            if speed > limit + tolerance:
                lines = (points.lines[i] if i < len(points.lines) else None,
                         points.lines[i + 1] if i + 1 < len(points.lines) else None)
                out.append(SegmentSpeed(track.joint, float(points.times[i]), float(points.times[i + 1]),
                                        float(speed), limit, points.path, lines, joint_unit(joint),
                                        points.interpolation))
    return out


def describe_segment(segment: SegmentSpeed) -> Message:
    """One line for people naming the segment, the joint, the speed it needs and the fix."""
    s = segment
    spread = (s.end - s.start) * s.speed / s.limit
    text = M("{joint} needs {speed:.4g} {unit}/s between t={start:g} s and t={end:g} s ({interpolation}), "
             "above its velocity limit {limit:g} {unit}/s; space these waypoints about {spread:.3g} s apart",
             joint=s.joint, speed=s.speed, unit=s.unit, start=s.start, end=s.end, interpolation=s.interpolation,
             limit=s.limit, spread=spread)
    if not s.path:
        return text
    name = os.path.basename(s.path)
    if s.lines[0] is not None and s.lines[1] is not None:
        return M("{file} lines {first}-{last}: {text}", file=name, first=s.lines[0], last=s.lines[1], text=text)
    return M("{file}: {text}", file=name, text=text)

