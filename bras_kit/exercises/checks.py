"""The checks an exercise names in its manifest, each judging what the learner's file DOES with
the project's own machinery, never its text:

========== ================================================================================
kind       judged by
========== ================================================================================
findings   the validator (:mod:`bras_kit.validate`): no finding above ``allow`` (default
           ``info``) and none of the ``gone`` codes (among the ``only`` codes when given,
           never the ``ignore`` ones; codes or prefixes such as ``BK1``); a folder is judged as a ROS 2 package
           (its package rules, and its robot files)
frame      the model and forward kinematics: with ``pose``, the ``point`` fixed in ``link``
           (default its origin) is ``at`` (metres, within ``tol``)
tip        the tool tip as drawn (:func:`bras_kit.kinematics.tip.tool_tip`: the farthest point of the end
           link's visual, or of ``link``'s) is ``at`` with ``pose``
joint      the model: a joint ``name`` exists, of ``type``, from ``parent`` to ``child``
parent     the TF tree: ``link``'s parent is ``parent``
limits     the validator's pose check (BK303): ``inside`` poses are within the limits, every
           ``outside`` pose is past them
node       ``bras-kit run`` (:func:`bras_kit.run.run_node`) for ``duration`` simulated seconds:
           the run rules find nothing above ``allow`` (nothing on /joint_states, unknown names,
           joints never named, past the limits, stamps at zero...; ``only``, ``gone``, ``ignore``
           as for ``findings``)
node_names the names the node publishes on /joint_states are ``names``
node_rate  it publishes at ``hz`` (within ``tol``, relative)
node_stamps header.stamp follows the simulated clock (not zero, increasing, at publication time)
node_tip   robot_state_publisher's view of what it publishes (each message's joints set, the
           others kept) puts ``point`` of ``link`` at ``at``: in ``when`` = ``all`` messages
           from ``after`` seconds, the ``first`` or the ``last``
node_still the published positions do not change from ``after`` seconds on
node_speed the published motion within the joint limits and velocities (BK304, BK305)
========== ================================================================================

A check that fails says why in the machinery's own words (a finding, a position) and names the
hint (1 to 3) that fits. A file that cannot be read at all (not well-formed, a Python syntax
error, missing) is BROKEN, a state with its message, never an exception.
"""

from __future__ import annotations

import math
import os
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..core.errors import BrasKitError
from ..core.message import M, Message

PASSED, FAILED, BROKEN = "passed", "failed", "broken"
DEFAULT_TOLERANCE = 0.002  # metres
DEFAULT_DURATION = 2.0  # simulated seconds a node runs for
SEVERITY_RANK = {"info": 0, "warning": 1, "error": 2}


@dataclass(frozen=True)
class Outcome:
    state: str  # PASSED, FAILED or BROKEN
    reason: Message | str | None = None  # why it is not passing (a Message, or a finding's worded text)
    hint: int = 1  # the hint that fits (1..3)
    file: str = ""  # the learner's file it points at
    line: int | None = None
    detail: Message | str | None = None  # a second line: the machinery's own hint


class Broken(Exception):
    """The learner's file cannot be read at all (a state, not an error)."""

    def __init__(self, reason: Message | str, file: str = "", line: int | None = None) -> None:
        super().__init__(str(reason))
        self.reason, self.file, self.line = reason, file, line


class Failed(Exception):
    def __init__(self, reason: Message | str, *, file: str = "", line: int | None = None,
                 detail: Message | str | None = None) -> None:
        super().__init__(str(reason))
        self.reason, self.file, self.line, self.detail = reason, file, line, detail


@dataclass
class Session:
    """One pass over an exercise: robots and node runs made once, shared by its checks."""

    folder: Path
    lang: str
    robots: dict[tuple[str, tuple[tuple[str, str], ...]], Any] = field(default_factory=dict)
    runs: dict[tuple[str, float], Any] = field(default_factory=dict)

    def path(self, name: str) -> Path:
        path = self.folder / name
        if not path.exists():
            raise Broken(M("the file is missing: 'bras-kit exercises reset' lays it out again"), name)
        return path

    def robot(self, name: str, args: Mapping[str, str] | None = None) -> Any:
        key = (name, tuple(sorted((args or {}).items())))
        if key not in self.robots:
            # the track is learner data: its robot, includes and meshes are read inside it, never through a link out
            self.robots[key] = _load_robot(self.path(name), name, args, (str(self.folder.parent.absolute()),))
        return self.robots[key]

    def run(self, name: str, duration: float) -> Any:
        key = (name, duration)
        if key not in self.runs:
            self.runs[key] = _run(self.path(name), name, duration)
        return self.runs[key]


def _load_robot(path: Path, name: str, args: Mapping[str, str] | None, roots: tuple[str, ...] | None = None) -> Any:
    from ..model.authoring import load
    from ..validate import UNREADABLE_CODES, validate_path

    unreadable = [f for f in validate_path(path, mappings=args, roots=roots) if f.code in UNREADABLE_CODES]
    if unreadable:
        raise Broken(unreadable[0].message, name, unreadable[0].line)
    try:
        return load(path, mappings=args, roots=roots)
    except BrasKitError as exc:
        raise Broken(exc.message, name, exc.line) from None


def _run(path: Path, name: str, duration: float) -> Any:
    from ..run.node import NodeRunError, run_node

    try:
        recording = run_node(str(path), duration=duration, wall_seconds=20.0, cpu_seconds=10)
    except NodeRunError as exc:
        raise Failed(exc.message, file=name) from None
    except BrasKitError as exc:  # no main(), not a Python file...
        raise Broken(exc.message, name, exc.line) from None
    failure = recording.failure
    if failure is not None and failure.kind in ("SyntaxError", "IndentationError", "TabError"):
        line = failure.frames[-1].line if failure.frames else None
        raise Broken(M("Python cannot read it: {detail}", detail=failure.detail), name, line)
    return recording


# ------------------------------------------------------------------------------- the checks

def _findings_above(findings: list[Any], allow: str, gone: list[str], ignore: list[str],
                    only: list[str] | None = None) -> Any:
    rank = SEVERITY_RANK.get(allow, 0)

    def among(code: str, prefixes: list[str]) -> bool:
        return any(code.startswith(prefix) for prefix in prefixes)

    for found in findings:
        if among(found.code, ignore) or (only and not among(found.code, only)):
            continue
        if among(found.code, gone) or SEVERITY_RANK.get(found.severity, 2) > rank:
            return found
    return None


def check_findings(session: Session, spec: Mapping[str, Any]) -> None:
    from ..validate import UNREADABLE_CODES, validate_path

    name = spec["file"]
    path = session.path(name)
    allow, gone, ignore = spec.get("allow", "info"), list(spec.get("gone", [])), list(spec.get("ignore", []))
    if spec.get("target") != "gazebo":  # the track is the RViz tutorial: what Gazebo will make of the
        ignore.append("BK7")            # arm (BK7xx) is for a learner heading there (validate --target gazebo)
    if path.is_dir():
        results = _package_results(path)
    else:
        results = [(name, validate_path(path, mappings=spec.get("args"),
                                        roots=(str(session.folder.parent.absolute()),)))]
    for file, findings in results:
        for found in findings:
            if found.code in UNREADABLE_CODES:
                raise Broken(found.message, file, found.line)
        worst = _findings_above(findings, allow, gone, ignore, spec.get("only"))
        if worst is not None:
            raise Failed(M("{code} {text}", code=worst.code, text=worst.message), file=file, line=worst.line,
                         detail=worst.hint)


def _package_results(path: Path) -> list[tuple[str, list[Any]]]:
    """The package rules' findings and those of its robot files, by file (relative to the exercise)."""
    from ..validate import validate_path
    from ..validate.package import validate_package

    out = []
    base = path.parent
    # built and launched as colcon and ros2 launch would (BK630-BK639): the learner's setup.py and
    # launch files run, contained, and what they tried is judged with the rest
    for result in validate_package(str(path), launch=True):
        out.append((os.path.relpath(result.path, base), list(result.findings)))
    from ..trust.learner_files import is_file, walk

    roots = (str(base),)  # listed through the one reader: no link followed out of the exercise's folder
    for folder, dirs, files in walk(str(path), roots):
        dirs[:] = sorted(d for d in dirs if not d.startswith("."))
        for file in sorted(files):
            full = os.path.join(folder, file)
            if file.endswith((".urdf", ".xacro")) and is_file(full, roots):
                out.append((os.path.relpath(full, base), validate_path(full, roots=(os.path.abspath(base),))))
    return out


def _vector(values: Any) -> tuple[float, float, float]:
    return (float(values[0]), float(values[1]), float(values[2]))


def _where(tree: Any, q: Any, link: str, point: Any) -> Any:
    import numpy as np

    from ..kinematics.frames import fk_batch

    index = tree.index(link)
    matrix = fk_batch(tree, q)[index]
    return matrix[:3, :3] @ np.asarray(_vector(point)) + matrix[:3, 3]


def _tree(robot: Any, name: str) -> Any:
    from ..kinematics.frames import tf_tree

    try:
        return tf_tree(robot)
    except BrasKitError as exc:
        raise Failed(exc.message, file=name, detail=exc.hint) from None


def _link(tree: Any, link: str, name: str) -> None:
    if link not in tree.links:
        raise Failed(M("there is no link named '{link}' in the robot's tree (links: {names})",
                       link=link, names=list(tree.links)), file=name)


def _shown(values: Any) -> str:
    return "(" + ", ".join(f"{float(v):.3f}" for v in values) + ")"


def check_frame(session: Session, spec: Mapping[str, Any]) -> None:
    import numpy as np

    name, link = spec["file"], spec["link"]
    robot = session.robot(name, spec.get("args"))
    tree = _tree(robot, name)
    _link(tree, link, name)
    pose = dict(spec.get("pose", {}))
    try:
        q = tree.config_vector(pose)
    except BrasKitError as exc:
        raise Failed(exc.message, file=name, detail=exc.hint) from None
    found = _where(tree, q, link, spec.get("point", (0, 0, 0)))
    expected = np.asarray(_vector(spec["at"]))
    if float(np.linalg.norm(found - expected)) > float(spec.get("tol", DEFAULT_TOLERANCE)):
        what = _point_words(link, spec)
        if pose:
            raise Failed(M("with {pose}, {what} is at {found}: it must be at {expected}", pose=_pose_words(pose),
                           what=what, found=_shown(found), expected=_shown(expected)), file=name)
        raise Failed(M("at rest, {what} is at {found}: it must be at {expected}", what=what, found=_shown(found),
                       expected=_shown(expected)), file=name)


def check_tip(session: Session, spec: Mapping[str, Any]) -> None:
    import numpy as np

    from ..kinematics.tip import tool_tip

    name = spec["file"]
    tree = _tree(session.robot(name, spec.get("args")), name)
    if "link" in spec:
        _link(tree, spec["link"], name)
    pose = dict(spec.get("pose", {}))
    try:
        q = tree.config_vector(pose)
    except BrasKitError as exc:
        raise Failed(exc.message, file=name, detail=exc.hint) from None
    link, point = tool_tip(tree, spec.get("link"))
    found = _where(tree, q, link, point)
    expected = np.asarray(_vector(spec["at"]))
    if float(np.linalg.norm(found - expected)) > float(spec.get("tol", DEFAULT_TOLERANCE)):
        what = M("the tip of the arm (the end of '{link}' as drawn)", link=link)
        if pose:
            raise Failed(M("with {pose}, {what} is at {found}: it must be at {expected}", pose=_pose_words(pose),
                           what=what, found=_shown(found), expected=_shown(expected)), file=name)
        raise Failed(M("at rest, {what} is at {found}: it must be at {expected}", what=what, found=_shown(found),
                       expected=_shown(expected)), file=name)


def _pose_words(pose: Mapping[str, float]) -> str:
    from ..core.message import number

    return ", ".join(f"{k}={number(float(v))}" for k, v in pose.items())


def _point_words(link: str, spec: Mapping[str, Any]) -> Message:
    point = spec.get("point")
    if point is None or not any(float(v) for v in point):
        return M("the frame of '{link}'", link=link)
    return M("the point {point} of '{link}'", point=_shown(point), link=link)


def check_parent(session: Session, spec: Mapping[str, Any]) -> None:
    name, link, parent = spec["file"], spec["link"], spec["parent"]
    tree = _tree(session.robot(name, spec.get("args")), name)
    _link(tree, link, name)
    index = tree.parent[tree.index(link)]
    found = tree.links[index] if index >= 0 else None
    if found != parent:
        if found is None:
            raise Failed(M("'{link}' is the root of the TF tree: its parent must be '{parent}'", link=link,
                           parent=parent), file=name)
        raise Failed(M("the parent of '{link}' in the TF tree is '{found}': it must be '{parent}'", link=link,
                       found=found, parent=parent), file=name)


def check_joint(session: Session, spec: Mapping[str, Any]) -> None:
    name, joint_name = spec["file"], spec["name"]
    robot = session.robot(name, spec.get("args"))
    joint = robot.joint(joint_name)
    if joint is None:
        raise Failed(M("the robot has no joint named '{joint}' (joints: {names})", joint=joint_name,
                       names=[j.name for j in robot.joints]), file=name)
    for key in ("type", "parent", "child"):
        wanted, found = spec.get(key), getattr(joint, key, None)
        if wanted is not None and found != wanted:
            raise Failed(M("the joint '{joint}' has {key} '{found}': it must be '{wanted}'", joint=joint_name,
                           key=key, found=found, wanted=wanted), file=name, line=joint.line)


def check_limits(session: Session, spec: Mapping[str, Any]) -> None:
    from ..validate import validate

    name = spec["file"]
    robot = session.robot(name, spec.get("args"))

    def past(pose: Mapping[str, float]) -> bool:
        try:
            return any(f.code == "BK303" for f in validate(robot, pose=dict(pose), select=["BK303"]))
        except BrasKitError as exc:
            raise Failed(exc.message, file=name, detail=exc.hint) from None

    for inside in spec.get("inside", []):
        if past(inside):
            raise Failed(M("the pose {pose} must be within the limits: the robot refuses it",
                           pose=_pose_words(inside)), file=name)
    for pose in spec.get("outside", []):
        if not past(pose):
            raise Failed(M("the pose {pose} must be past the limits: the robot accepts it", pose=_pose_words(pose)),
                         file=name)


def _node_robot(session: Session, spec: Mapping[str, Any]) -> Any:
    return session.robot(spec["robot"], spec.get("args"))


def _messages(session: Session, spec: Mapping[str, Any]) -> tuple[Any, list[Any]]:
    from ..ros.topics import JOINT_STATES

    recording = session.run(spec["file"], float(spec.get("duration", DEFAULT_DURATION)))
    messages = recording.joint_state_messages(JOINT_STATES)
    if not messages:
        topics = list(recording.topics())
        raise Failed(M("nothing was published on /joint_states (published on: {topics})", topics=topics)
                     if topics else M("nothing was published on /joint_states"), file=spec["file"])
    return recording, messages


def check_node(session: Session, spec: Mapping[str, Any]) -> None:
    from ..run.findings import run_findings

    name = spec["file"]
    recording = session.run(name, float(spec.get("duration", DEFAULT_DURATION)))
    robot = _node_robot(session, spec)
    worst = _findings_above(run_findings(recording, robot), spec.get("allow", "info"), list(spec.get("gone", [])),
                            list(spec.get("ignore", [])), spec.get("only"))
    if worst is not None:
        raise Failed(M("{code} {text}", code=worst.code, text=worst.message),
                     file=str(worst.data.get("file") or name), line=worst.line, detail=worst.hint)


def check_node_names(session: Session, spec: Mapping[str, Any]) -> None:
    _, messages = _messages(session, spec)
    expected = sorted(spec["names"])
    for message in messages:
        names = list(message.fields.get("name") or [])
        if sorted(names) != expected:
            raise Failed(M("at t={time:.2f} s the node names {names}: the joints are {expected}",
                           time=message.time, names=names, expected=expected), file=spec["file"])


def check_node_rate(session: Session, spec: Mapping[str, Any]) -> None:
    _, messages = _messages(session, spec)
    wanted, tol = float(spec["hz"]), float(spec.get("tol", 0.05))
    span = messages[-1].time - messages[0].time
    rate = (len(messages) - 1) / span if span > 0 else math.inf
    if not abs(rate - wanted) <= tol * wanted:
        raise Failed(M("the node publishes at {rate:.3g} Hz: it must publish at {wanted:.3g} Hz",
                       rate=rate, wanted=wanted), file=spec["file"])


def check_node_stamps(session: Session, spec: Mapping[str, Any]) -> None:
    from ..ros.recording import stamp_seconds

    recording, messages = _messages(session, spec)
    start = recording.start_ns * 1e-9
    previous = -math.inf
    for message in messages:
        stamp = stamp_seconds(message.fields)
        if not stamp:
            raise Failed(M("at t={time:.2f} s header.stamp is zero: robot_state_publisher cannot place it in time",
                           time=message.time), file=spec["file"])
        if stamp <= previous:
            raise Failed(M("at t={time:.2f} s header.stamp does not move forward", time=message.time),
                         file=spec["file"])
        if abs(stamp - (start + message.time)) > float(spec.get("tol", 0.1)):
            raise Failed(M("at t={time:.2f} s header.stamp is {off:.3g} s away from the clock's time",
                           time=message.time, off=stamp - (start + message.time)), file=spec["file"])
        previous = stamp


def check_node_tip(session: Session, spec: Mapping[str, Any]) -> None:
    import numpy as np

    from ..ros.recording import states_for

    recording, _ = _messages(session, spec)
    robot = _node_robot(session, spec)
    tree = _tree(robot, spec["robot"])
    link = spec["link"]
    _link(tree, link, spec["robot"])
    states = states_for(recording, tree.dof)
    rows = [i for i, t in enumerate(states.times) if t >= float(spec.get("after", 0.0)) - 1e-9]
    when = spec.get("when", "all")
    if when == "first":
        rows = rows[:1]
    elif when == "last":
        rows = rows[-1:]
    expected = np.asarray(_vector(spec["at"]))
    tol = float(spec.get("tol", DEFAULT_TOLERANCE))
    what = _point_words(link, spec)
    for i in rows:
        found = _where(tree, states.positions[i], link, spec.get("point", (0, 0, 0)))
        if float(np.linalg.norm(found - expected)) > tol:
            raise Failed(M("at t={time:.2f} s {what} is at {found}: it must be at {expected}",
                           time=float(states.times[i]), what=what, found=_shown(found), expected=_shown(expected)),
                         file=spec["file"])


def check_node_still(session: Session, spec: Mapping[str, Any]) -> None:
    _, messages = _messages(session, spec)
    after = float(spec.get("after", 0.0))
    held = [m for m in messages if m.time >= after - 1e-9]
    first = [float(v) for v in held[0].fields.get("position") or []] if held else []
    for message in held[1:]:
        position = [float(v) for v in message.fields.get("position") or []]
        if len(position) != len(first) or any(abs(a - b) > 1e-6 for a, b in zip(position, first)):
            raise Failed(M("the arm still moves: at t={time:.2f} s the node publishes {now}, at t={start:.2f} s it "
                           "published {then}", time=message.time, now=position, start=held[0].time, then=first),
                         file=spec["file"])


def check_node_speed(session: Session, spec: Mapping[str, Any]) -> None:
    from ..ros.recording import states_for
    from ..validate import validate

    recording, _ = _messages(session, spec)
    robot = _node_robot(session, spec)
    states = states_for(recording, _tree(robot, spec["robot"]).dof)
    for found in validate(robot, states=states, select=["BK304", "BK305"]):
        raise Failed(M("{code} {text}", code=found.code, text=found.message), file=spec["file"], detail=found.hint)


Check = Callable[[Session, Mapping[str, Any]], None]
CHECKS: dict[str, tuple[Check, tuple[str, ...]]] = {
    # kind -> (check, required keys)
    "findings": (check_findings, ("file",)),
    "frame": (check_frame, ("file", "link", "at")),
    "tip": (check_tip, ("file", "at")),
    "joint": (check_joint, ("file", "name")),
    "parent": (check_parent, ("file", "link", "parent")),
    "limits": (check_limits, ("file",)),
    "node": (check_node, ("file", "robot")),
    "node_names": (check_node_names, ("file", "names")),
    "node_rate": (check_node_rate, ("file", "hz")),
    "node_stamps": (check_node_stamps, ("file",)),
    "node_tip": (check_node_tip, ("file", "robot", "link", "at")),
    "node_still": (check_node_still, ("file",)),
    "node_speed": (check_node_speed, ("file", "robot")),
}


def validate_check(spec: Mapping[str, Any], path: Path) -> None:
    """A manifest's check: a known kind, its keys, a hint number (errors name the manifest)."""
    kind = spec.get("kind")
    if kind not in CHECKS:
        raise BrasKitError(M("unknown check kind '{kind}'", kind=str(kind)), path=str(path),
                           hint=M("the kinds are {kinds}", kinds=sorted(CHECKS)))
    missing = [key for key in CHECKS[kind][1] if key not in spec]
    if missing:
        raise BrasKitError(M("the check '{kind}' needs {keys}", kind=kind, keys=missing), path=str(path))
    if spec.get("hint", 1) not in (1, 2, 3):
        raise BrasKitError(M("a check's hint is 1, 2 or 3"), path=str(path))


def run_checks(folder: Path, checks: tuple[Mapping[str, Any], ...], lang: str) -> Outcome:
    """The exercise's checks in order; the first that fails decides the outcome."""
    session = Session(folder, lang)
    for spec in checks:
        hint = int(spec.get("hint", 1))
        try:
            CHECKS[spec["kind"]][0](session, spec)
        except Broken as exc:
            return Outcome(BROKEN, exc.reason, 1, exc.file, exc.line)
        except Failed as exc:
            return Outcome(FAILED, exc.reason, hint, exc.file or str(spec.get("file", "")), exc.line, exc.detail)
        except BrasKitError as exc:
            return Outcome(BROKEN, exc.message, 1, str(spec.get("file", "")), exc.line)
        except (OSError, UnicodeError, ValueError, RecursionError, MemoryError) as exc:
            # a file half-written by an editor can be anything: a state, never a traceback
            return Outcome(BROKEN, M("the file cannot be read now ({reason})", reason=str(exc) or type(exc).__name__),
                           1, str(spec.get("file", "")))
    return Outcome(PASSED)
