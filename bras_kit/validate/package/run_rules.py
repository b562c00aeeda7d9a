"""BK640-BK659: pitfalls seen for real, in the recording of a run of the learner's node.

``bras-kit run`` (and ``validate PKG --run``) runs the node against the stand-in for rclpy
and records every message (:mod:`bras_kit.run`); these rules read that recording and the
robot, the way robot_state_publisher and RViz would receive the messages. Each hit carries
``file``: the learner's file it points at (the node's module), with the line when known.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Iterable, Iterator
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ...findings.registry import ERROR, WARNING, Hit, hit, rule
from ...ros.topics import JOINT_STATE_TYPE, JOINT_STATES

if TYPE_CHECKING:  # the records are imported with a run: validate PKG_DIR without --run has none
    from ...ros.recording import Recording

RATE_TOLERANCE = 0.2  # a measured rate 20 % away from the timer's is "far"


@dataclass(frozen=True)
class RunContext:
    """What the run rules read: a run's recording and the robot it was run against."""

    recording: Recording
    robot: Any  # bras_kit.model.robot.Robot or None
    root: str | None = None  # the folder the recording's paths are relative to (None: not read)


RunCheck = Callable[[RunContext], Iterable[Hit]]
RUN_CHECKS: dict[str, RunCheck] = {}


def run_rule(code: str, name: str, severity: str) -> Callable[[RunCheck], RunCheck]:
    """Register a rule over a run's recording (never called on a robot file or a package)."""

    def decorate(check: RunCheck) -> RunCheck:
        def on_context(context: Any) -> Iterable[Hit]:
            return check(context) if isinstance(context, RunContext) else ()

        rule(code, name, severity)(on_context)
        RUN_CHECKS[code] = check
        return check

    return decorate


def _at(file: str, line: int | None, variant: str = "", **params: object) -> Hit:
    return hit("file", None, line or None, variant, file=file, **params)


def _publisher_line(run: RunContext, topic: str | None = None) -> tuple[str, int | None]:
    """Where the node creates its JointState publisher (on ``topic`` when given)."""
    r = run.recording
    for endpoint in r.publishers:
        if endpoint.type == JOINT_STATE_TYPE and (topic is None or endpoint.topic == topic) and endpoint.path:
            return endpoint.path, endpoint.line
    return r.source, None


def _field_line(run: RunContext, field: str) -> tuple[str, int | None]:
    """Where the node's JointState publisher's file sets ``msg.<field>`` (``msg.position = ...``,
    ``msg.position[k] = ...``, ``msg.position.append(...)``): the line a value past a limit comes
    from. None found (set elsewhere, or the file does not read): where the publisher is made."""
    path, line = _publisher_line(run, JOINT_STATES)
    if run.root is None or not path:
        return path, line
    return path, field_line(os.path.join(run.root, path), run.root, field) or line


def field_line(path: str, root: str, field: str) -> int | None:
    """The last line of the file ``path`` (under ``root``) that sets ``X.<field>``, or None."""
    import ast

    from ...trust.learner_files import read_text

    try:
        tree = ast.parse(read_text(path, (root,)))
    except (OSError, UnicodeDecodeError, SyntaxError, ValueError):
        return None

    def sets(target: ast.expr) -> bool:
        while isinstance(target, ast.Subscript):
            target = target.value
        return isinstance(target, ast.Attribute) and target.attr == field

    lines = []
    for node in ast.walk(tree):
        if isinstance(node, ast.Assign) and any(sets(t) for t in node.targets):
            lines.append(node.lineno)
        elif isinstance(node, (ast.AugAssign, ast.AnnAssign)) and sets(node.target):
            lines.append(node.lineno)
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) and \
                node.func.attr in ("append", "extend", "insert") and sets(node.func.value):
            lines.append(node.lineno)
    return max(lines) if lines else None  # the last write: the value published


def _movable(run: RunContext) -> list[str]:
    return [j.name for j in run.robot.movable_joints() if j.name] if run.robot is not None else []


# ---------------------------------------------------------------- how the node ended


@run_rule("BK640", "node-raised", ERROR)
def node_raised(run: RunContext) -> Iterator[Hit]:
    failure = run.recording.failure
    if failure is None or run.recording.ended != "error" or beginner_mistake(run.recording) is not None:
        return  # BK652 explains it
    frame = failure.frames[-1] if failure.frames else None
    yield _at(frame.path if frame else run.recording.source, frame.line if frame else None,
              kind=failure.kind, detail=_first_line(failure.detail),
              time=round(failure.time, 3))


def _first_line(text: str, limit: int = 160) -> str:
    line = text.strip().splitlines()[0] if text.strip() else "-"
    return line if len(line) <= limit else line[:limit] + "..."


@run_rule("BK641", "node-uses-unsimulated-ros", WARNING)
def node_uses_unsimulated(run: RunContext) -> Iterator[Hit]:
    failure = run.recording.failure
    if failure is None or run.recording.ended != "not_simulated":
        return
    frame = failure.frames[-1] if failure.frames else None
    yield _at(frame.path if frame else run.recording.source, frame.line if frame else None,
              what=failure.detail, time=round(failure.time, 3))


@run_rule("BK642", "node-publishes-without-time-passing", ERROR)
def node_storm(run: RunContext) -> Iterator[Hit]:
    r = run.recording
    if r.ended != "storm":
        return
    topics = list(dict.fromkeys(m.topic for m in r.messages if abs(m.time - r.end) < 1e-12))
    path, line = _publisher_line(run)
    yield _at(path, line, topics=topics or ["-"], time=round(r.end, 3))


@run_rule("BK643", "rate-sleep-without-spinning", WARNING)
def rate_sleep_without_spinning(run: RunContext) -> Iterator[Hit]:
    if run.recording.rate_sleeps:
        yield _at(run.recording.source, None, count=run.recording.rate_sleeps)


# ---------------------------------------------------------------- what /joint_states carried


@run_rule("BK644", "nothing-on-joint-states", ERROR)
def nothing_on_joint_states(run: RunContext) -> Iterator[Hit]:
    r = run.recording
    if r.ended in ("error", "not_simulated") and r.end == 0:
        return  # it never got going: BK640/BK641 say why
    mistake = beginner_mistake(r)
    if mistake is not None and mistake[0] not in ("shutdown_twice", "stamp_seconds"):
        return  # BK652 says why nothing came
    if r.joint_state_messages(JOINT_STATES):
        return
    elsewhere = list(dict.fromkeys(m.topic for m in r.messages if m.type == JOINT_STATE_TYPE))
    if elsewhere:
        path, line = _publisher_line(run, elsewhere[0])
        yield _at(path, line, "other", topics=elsewhere, count=len(r.on(elsewhere[0])))
        return
    other_types = list(dict.fromkeys(m.type for m in r.messages if m.topic == JOINT_STATES))
    if other_types:
        yield _at(r.source, None, "type", types=other_types)
        return
    made = [p for p in r.publishers if p.type == JOINT_STATE_TYPE]
    if made:
        yield _at(made[0].path or r.source, made[0].line, "silent", topic=made[0].topic, time=round(r.end, 3))
        return
    yield _at(r.source, None, "", topics=list(r.topics()) or ["-"], time=round(r.end, 3))


def _joint_state_messages(run: RunContext) -> list[Any]:
    return run.recording.joint_state_messages(JOINT_STATES)


def _split_names(run: RunContext) -> list[Any]:
    """msg.name given one string on /joint_states: sent as its letters (recording.SplitString)."""
    return [s for s in run.recording.split_strings if s.topic == JOINT_STATES and s.field == "name"]


@run_rule("BK645", "joint-state-lengths-differ", ERROR)
def joint_state_lengths_differ(run: RunContext) -> Iterator[Hit]:
    if _split_names(run):
        return  # BK646 names the cause: the letters of one string
    for message in _joint_state_messages(run):
        names, position = message.fields.get("name") or [], message.fields.get("position") or []
        if len(names) != len(position):
            bad = sum(1 for m in _joint_state_messages(run)
                      if len(m.fields.get("name") or []) != len(m.fields.get("position") or []))
            path, line = _publisher_line(run, JOINT_STATES)
            yield _at(path, line, names=len(names), positions=len(position), time=round(message.time, 3),
                      count=bad)
            return


@run_rule("BK646", "joint-state-unknown-names", ERROR)
def joint_state_unknown_names(run: RunContext) -> Iterator[Hit]:
    split = _split_names(run)
    if split:
        # rosidl_generator_py (Jazzy) _msg.py.em:440 keeps the str (no check) and the C
        # conversion iterates it (_msg_support.c.em, PySequence_Fast): one name per letter
        first = split[0]
        letters = len(first.value)
        yield _at(first.path or run.recording.source, first.line or None, "split", value=first.value,
                  letters=letters, count=first.count, names=repr([n for n in first.value.replace(",", " ").split()]))
        return
    movable = _movable(run)
    if run.robot is None:
        return
    named = list(dict.fromkeys(n for m in _joint_state_messages(run) for n in m.fields.get("name") or []))
    unknown = [n for n in named if n not in movable]
    if unknown:
        path, line = _publisher_line(run, JOINT_STATES)
        yield _at(path, line, "one" if len(unknown) == 1 else "", names=unknown, joints=movable or ["-"])


@run_rule("BK647", "joint-state-joints-never-named", ERROR)
def joint_state_joints_never_named(run: RunContext) -> Iterator[Hit]:
    messages = _joint_state_messages(run)
    if run.robot is None or not messages or _split_names(run):
        return
    named = {n for m in messages for n in m.fields.get("name") or []}
    missing = [n for n in _movable(run) if n not in named]
    if missing:
        path, line = _publisher_line(run, JOINT_STATES)
        yield _at(path, line, "one" if len(missing) == 1 else "", names=missing, published=sorted(named) or ["-"])


@run_rule("BK648", "joint-state-not-finite", ERROR)
def joint_state_not_finite(run: RunContext) -> Iterator[Hit]:
    seen: set[str] = set()
    for message in _joint_state_messages(run):
        for name, value in zip(message.fields.get("name") or [], message.fields.get("position") or []):
            if name not in seen and not math.isfinite(float(value)):
                seen.add(name)
                path, line = _publisher_line(run, JOINT_STATES)
                yield _at(path, line, joint=name, value=str(float(value)), time=round(message.time, 3))


@run_rule("BK649", "joint-state-past-limits", ERROR)
def joint_state_past_limits(run: RunContext) -> Iterator[Hit]:
    from ...motion import check_limits
    from ...ros.recording import joint_states

    robot = run.robot
    if robot is None:
        return
    states = joint_states(run.recording)
    if not len(states):
        return
    path, line = _field_line(run, "position")  # the value past the limit is set there
    yield from past_limits_hits(robot, check_limits(robot, states), path, line)


def past_limits_hits(robot: Any, violations: Iterable[Any], path: str, line: int | None) -> Iterator[Hit]:
    """BK649 for each position past a limit (motion.LimitViolation): a batch run's, and a live
    run's summary at Ctrl-C (bras_kit.run.live_limits)."""
    from ...motion import value_in_degrees

    for violation in violations:
        if violation.kind != "position":
            continue
        degrees = value_in_degrees(robot.joint(violation.joint), violation.value)
        yield _at(path, line, "degrees" if degrees else violation.side, joint=violation.joint,
                  value=round(violation.value, 4), time=round(violation.peak_time, 3), bound=violation.bound,
                  first=round(violation.time, 3), count=violation.samples, unit=violation.unit)


@run_rule("BK650", "joint-state-stamp-zero", WARNING)
def joint_state_stamp_zero(run: RunContext) -> Iterator[Hit]:
    from ...ros.recording import stamp_seconds

    messages = _joint_state_messages(run)
    zero = [m for m in messages if (stamp_seconds(m.fields) or 0.0) == 0.0]
    if zero:
        path, line = _publisher_line(run, JOINT_STATES)
        yield _at(path, line, count=len(zero), total=len(messages))


@run_rule("BK651", "publish-rate-off-timer", WARNING)
def publish_rate_off_timer(run: RunContext) -> Iterator[Hit]:
    r = run.recording
    messages = _joint_state_messages(run)
    publishers = [p for p in r.publishers if p.topic == JOINT_STATES and p.type == JOINT_STATE_TYPE]
    if len(messages) < 3 or not publishers:
        return
    timers = [t for t in r.timers if t.node == publishers[0].node and t.period > 0]
    if len(timers) != 1:
        return  # no timer, or several: which one publishes is not known
    times = [m.time for m in messages]
    span = times[-1] - times[0]
    if span <= 0:
        return
    measured = (len(times) - 1) / span
    declared = 1.0 / timers[0].period
    if abs(measured - declared) > RATE_TOLERANCE * declared:
        yield _at(timers[0].path or r.source, timers[0].line or None, rate=round(measured, 2),
                  expected=round(declared, 2), period=timers[0].period, count=len(messages))


# ---------------------------------------------------------------- the mistake behind a failure


def beginner_mistake(r: Recording) -> tuple[str, str, int | None, dict[str, Any]] | None:
    """(variant, file, line, parameters) of the beginner's mistake the run shows, if it is one
    of those rclpy Jazzy stops on with words that do not say the cause."""
    failure = r.failure
    context = failure.context if failure is not None else {}
    last = failure.frames[-1] if failure is not None and failure.frames else None
    here = (last.path, last.line) if last else (r.source, None)
    if failure is not None and r.ended == "error":
        detail = failure.detail
        if failure.kind == "ImportError" and context.get("homes") is not None:
            name, module = detail.split("'")[1], detail.split("'")[3] if detail.count("'") >= 4 else "?"
            homes = [home for home in context["homes"] if home != module]
            if homes:
                return "wrong_import", *here, {"type": name, "module": module, "home": homes[0]}
            near = context.get("near") or []
            if near:  # a misspelt type: JointSate, Jointstate
                home, _, close = near[0].rpartition(".")
                return "misspelt_import", *here, {"type": name, "module": module, "home": home, "close": close}
            return "unknown_import", *here, {"type": name, "module": module}
        if failure.kind == "ModuleNotFoundError" and context.get("near_packages") is not None:
            module = detail.split("'")[1] if detail.count("'") >= 2 else "?"
            near = context["near_packages"]
            if near:
                return "misspelt_package", *here, {"module": module, "close": near[0]}
            return "unknown_package", *here, {"module": module}
        if failure.kind == "RCLError" and "rcl_shutdown already called" in detail:
            return "shutdown_twice", *here, {"detail": detail}
        if failure.kind == "TypeError" and "does not support the context manager protocol" in detail:
            name = detail.split("'")[1] if "'" in detail else "Node"
            return "with_node", *here, {"cls": name}
        if failure.kind == "AttributeError" and context.get("node_class"):
            return "super_init", context.get("def_path", here[0]), context.get("def_line", here[1]), {
                "cls": context["node_class"], "detail": detail}
        if failure.kind == "Aborted" and context.get("held") == "rclpy.time.Time":
            return "now_not_msg", *here, {}
        if failure.kind == "Aborted" and context.get("field"):
            wanted = {"PyFloat_Check": "float", "PyLong_Check": "int", "PyBool_Check": "bool",
                      "PyUnicode_Check": "str"}
            kind = next((w for check, w in wanted.items() if check in detail), "other")
            return "field_type", *here, {"field": context["field"], "held": context.get("held", "?"), "wanted": kind}
        callback = context.get("callback", "")
        if failure.kind == "TypeError" and context.get("callback_kind") == "timer" and "NoneType" in detail:
            line_text = _source_line(r, context.get("made_path"), context.get("made_line"))
            short = line_text.split("self.", 2)[-1].split("(")[0] if "self." in line_text else "tick"
            return "callback_called", context.get("made_path", here[0]), context.get("made_line", here[1]), {
                "callback": f"self.{short}", "short": short}
        if (failure.kind == "TypeError" and context.get("bound") and "takes 0 positional arguments" in detail):
            short = callback.rsplit(".", 1)[-1]
            return "no_self", context.get("def_path", here[0]), context.get("def_line", here[1]), {
                "callback": callback, "short": short, "detail": "TypeError"}
        if failure.kind == "AttributeError" and detail.endswith(f"has no attribute '{r.function}'") \
                and not failure.frames:
            return "no_main", r.source, None, {"function": r.function}
    if r.ended == "returned" and r.end == 0 and r.timers and not r.messages:
        timer = r.timers[0]
        return "spin_forgotten", timer.path or r.source, timer.line or None, {}
    if r.timers and not r.messages and all(t.period >= 2.0 and t.period > r.duration for t in r.timers) \
            and r.ended in ("duration", "stopped"):
        timer = r.timers[0]
        period = int(timer.period) if timer.period == int(timer.period) else timer.period
        return "timer_period", timer.path or r.source, timer.line or None, {
            "period": period, "duration": r.duration, "hz": round(1 / timer.period, 4)}
    stamps = [m.fields.get("header", {}).get("stamp", {}) for m in r.joint_state_messages(JOINT_STATES)]
    if len(stamps) >= 10 and all(s.get("nanosec") == 0 and s.get("sec") for s in stamps):
        distinct = len({s["sec"] for s in stamps})
        if distinct < len(stamps) / 2:
            path, line = _publisher_line(RunContext(r, None), JOINT_STATES)
            return "stamp_seconds", path, line, {"distinct": distinct, "count": len(stamps)}
    return None


def _source_line(r: Recording, path: str | None, line: int | None) -> str:
    for frame in (r.failure.frames if r.failure else []):
        if frame.path == path and frame.line == line:
            return frame.text
    return ""


@run_rule("BK652", "node-beginner-mistake", ERROR)
def node_beginner_mistake(run: RunContext) -> Iterator[Hit]:
    found = beginner_mistake(run.recording)
    if found is not None:
        variant, path, line, params = found
        yield _at(path, line, variant, **params)


def run_hits(recording: Recording, robot: Any, codes: Iterable[str], root: str | None = None) -> Iterator[tuple[str, Hit]]:
    context = RunContext(recording, robot, root)
    for code in codes:
        check = RUN_CHECKS.get(code)
        if check is not None:
            for found in check(context):
                yield code, found
