"""Joint states to and from files: /joint_states-like CSV (long form), JSON messages, ROS 2 bags.

:func:`write_states` is the one writer every command uses (``motion``, ``simulate``,
``render --record``, ``run``): the format follows the file name.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

if TYPE_CHECKING:
    import numpy as np
else:
    from ..core.lazy_numpy import np

from ..core.errors import ParameterError, os_reason
from ..core.message import M, Message
from ..model.robot import Robot
from .core import JointStates


def _efforts(states: JointStates):
    """Measured motor torques when the states come from a simulation (``bras-kit simulate``), else None."""
    efforts = getattr(states, "efforts", None)
    return efforts if efforts is not None and len(efforts) == len(states.times) else None


def states_to_messages(states: JointStates) -> list[dict]:
    """One dict per sample, shaped like a sensor_msgs/JointState message (with "effort" when simulated)."""
    messages = [{"time": float(t), "name": list(states.names), "position": [float(v) for v in p],
                 "velocity": [float(v) for v in w]}
                for t, p, w in zip(states.times, states.positions, states.velocities)]
    efforts = _efforts(states)
    if efforts is not None:
        for message, row in zip(messages, efforts):
            message["effort"] = [float(v) for v in row]
    return messages


def states_to_json(states: JointStates) -> str:
    """A JSON list of messages {"time", "name", "position", "velocity"}, one per line."""
    import json

    body = ",\n".join(json.dumps(message) for message in states_to_messages(states))
    return "[\n" + body + "\n]\n" if body else "[]\n"


def states_to_csv(states: JointStates) -> str:
    """Long form, like a recorded /joint_states: ``time,name,position,velocity``, one row per joint per sample.

    Simulated states (with measured torques) get a fifth column, ``effort``. The joint names are
    the URDF's, so a stranger's: text cells through bras_kit.trust.inert.csv_text (never a formula),
    the numbers as numbers.
    """
    from ..trust.inert import csv_text

    efforts = _efforts(states)
    names = [str(name) for name in states.names]
    if efforts is not None:
        return csv_text([("time", "name", "position", "velocity", "effort"),
                         *((float(t), name, float(p), float(v), float(e))
                           for t, position, velocity, effort in zip(states.times, states.positions,
                                                                    states.velocities, efforts)
                           for name, p, v, e in zip(names, position, velocity, effort))])
    return csv_text([("time", "name", "position", "velocity"),
                     *((float(t), name, float(p), float(v))
                       for t, position, velocity in zip(states.times, states.positions, states.velocities)
                       for name, p, v in zip(names, position, velocity))])


STATES_SUFFIXES = (".csv", ".json", ".mcap", ".db3")


def states_format(path: str) -> str | None:
    """"csv", "json" or "bag" (``.mcap``, ``.db3`` or a folder name ending in /) from a file name; None if unknown.

    ``-`` (standard output) is CSV.
    """
    if path == "-":
        return "csv"
    suffix = os.path.splitext(path)[1].lower()
    if suffix in (".csv", ".json"):
        return suffix[1:]
    if suffix in (".mcap", ".db3") or (path.endswith(("/", os.sep)) and path.strip("/" + os.sep)):
        return "bag"
    return None


def check_states_output(path: str, force: bool, fmt: str | None = None, option: str = "-o") -> str:
    """Raise unless joint states may be written to ``path`` (before any work is done); returns the format."""
    fmt = fmt or states_format(path)
    if fmt is None:
        raise ParameterError(M("cannot tell the format of '{path}'", path=path),
                             hint=M("end the file name in .csv, .json or .mcap (a ROS 2 bag)"))
    if fmt == "bag":
        from .bags.writer import check_bag_output  # a feature above motion: loaded for bags only

        check_bag_output(path, force, option)
    elif path != "-":
        from ..trust.outputs import check_output

        check_output(path, force, option=option)
    return fmt


def write_states(robot: Robot, states: JointStates, path: str, force: bool = False, fmt: str | None = None,
                 option: str = "-o", sent: list[dict] | None = None) -> Message | None:
    """Write joint states to ``path`` in the format its name says (or ``fmt``): CSV, JSON or a ROS 2 bag.

    Returns what was written, for the command to show (the bag folder and its topics, or the
    file); None for standard output (``-``).
    """
    fmt = check_states_output(path, force, fmt, option)
    if fmt == "bag":
        from .bags import write_bag

        summary = write_bag(robot, states, path, force=force, option=option, sent=sent)
        return M("wrote the ROS 2 bag {folder} ({storage}: {messages} messages on /robot_description, /tf_static, "
                 "/tf, /joint_states; {duration} s): ros2 bag play {folder}", folder=summary.folder,
                 storage=summary.storage_file, messages=summary.messages, duration=summary.duration)
    from ..trust.outputs import write_text

    if fmt == "json" and sent is not None:  # messages as a node sent them (bras-kit run -o)
        import json

        body = ",\n".join(json.dumps(message) for message in sent)
        text = "[\n" + body + "\n]\n" if body else "[]\n"
    else:
        text = states_to_json(states) if fmt == "json" else states_to_csv(states)
    write_text(path, text, force, announce=False)
    return None if path == "-" else M("wrote {path}", path=path)


def read_states(path: str) -> JointStates:
    """Read back a joint-state file written by ``bras-kit motion`` (CSV long form or JSON)."""
    suffix = os.path.splitext(path)[1].lower()
    try:
        with open(path, encoding="utf-8-sig") as handle:
            text = handle.read()
    except (OSError, UnicodeDecodeError) as exc:
        reason = os_reason(exc) if isinstance(exc, OSError) else str(exc)
        raise ParameterError(M("cannot read the joint states: {reason}", reason=reason), path=path,
                             hint=M("give a .csv or .json file written by bras-kit motion")) from None
    if suffix == ".json":
        return _states_from_json(text, path)
    if suffix == ".csv":
        return _states_from_csv(text, path)
    raise ParameterError(M("joint states are read from .csv or .json files"), path=path,
                         hint=M("write them with bras-kit motion -o states.csv"))


def _states_from_json(text: str, path: str) -> JointStates:
    import json

    try:
        data = json.loads(text)
    except json.JSONDecodeError as exc:
        raise ParameterError(M("not valid JSON: {problem}", problem=exc.msg), path=path, line=exc.lineno) from None
    hint = M("a list of {example}", example='{"time": t, "name": [...], "position": [...], "velocity": [...]}')
    if not isinstance(data, list) or not data:
        raise ParameterError(M("expected a non-empty list of joint-state messages"), path=path, hint=hint)
    names = None
    times, positions, velocities = [], [], []
    for index, message in enumerate(data):
        try:
            if names is None:
                names = [str(n) for n in message["name"]]
            if list(message["name"]) != names:
                raise ParameterError(M("message {number} names other joints than the first", number=index + 1),
                                     path=path, hint=hint)
            position = [float(v) for v in message["position"]]
            velocity = [float(v) for v in message.get("velocity") or [0.0] * len(names)]
            if len(position) != len(names) or len(velocity) != len(names):
                raise ValueError
            times.append(float(message["time"]))
        except (KeyError, TypeError, ValueError):
            raise ParameterError(M("message {number} is not a joint state", number=index + 1), path=path,
                                 hint=hint) from None
        positions.append(position)
        velocities.append(velocity)
    return JointStates(np.array(times), names or [], np.array(positions), np.array(velocities))


def _states_from_csv(text: str, path: str) -> JointStates:
    import csv
    import io

    from ..trust.inert import from_spreadsheet

    # csv's reader: a joint name may hold a comma, a quote or a line break, which csv_text quoted
    reader = csv.reader(io.StringIO(text, newline=""))
    try:
        rows = [(reader.line_num, row) for row in reader]
    except csv.Error as exc:  # a NUL on Python 3.10
        raise ParameterError(M("not a CSV file: {reason}", reason=str(exc)), path=path, line=reader.line_num,
                             hint=M("write the file with bras-kit motion -o states.csv")) from None
    header = [c.strip() for c in rows[0][1]] if rows else []
    if header not in (["time", "name", "position", "velocity"], ["time", "name", "position", "velocity", "effort"]):
        raise ParameterError(M("the header is not time,name,position,velocity"), path=path, line=1,
                             hint=M("write the file with bras-kit motion -o states.csv"))
    names: list[str] = []
    times: list[float] = []
    positions: list[list[float]] = []
    velocities: list[list[float]] = []
    for number, cells in rows[1:]:
        if not any(cell.strip() for cell in cells):
            continue
        try:
            time, name, position, velocity = (float(cells[0]), from_spreadsheet(cells[1]).strip(), float(cells[2]),
                                              float(cells[3]))
        except (IndexError, ValueError):
            raise ParameterError(M("expected time,name,position,velocity"), path=path, line=number) from None
        if not times or time != times[-1]:
            if times and len(positions[-1]) != len(names):
                raise ParameterError(M("the sample at t={time:g} s does not list every joint", time=times[-1]),
                                     path=path, line=number)
            times.append(time)
            positions.append([])
            velocities.append([])
        if len(times) == 1 and name not in names:
            names.append(name)
        k = len(positions[-1])
        if k >= len(names) or names[k] != name:
            raise ParameterError(M("joint '{name}' is out of order (expected the order {names})", name=name,
                                   names=", ".join(names)),
                                 path=path, line=number)
        positions[-1].append(position)
        velocities[-1].append(velocity)
    if not times or len(positions[-1]) != len(names):
        raise ParameterError(M("no complete joint state in the file"), path=path)
    return JointStates(np.array(times), names, np.array(positions), np.array(velocities))
