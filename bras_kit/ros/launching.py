"""A launch file evaluated into a plan, as ``ros2 launch`` evaluates it before starting anything.

The launch file (Python, XML or YAML) is loaded in the sandbox child against the stand-in of
``launch``, ``launch_ros``, ``ament_index_python`` and ``xacro`` (``standin/``), with
``AMENT_PREFIX_PATH`` naming the built packages and a simulated ROS install (the programs a
beginner's launch file starts: robot_state_publisher, joint_state_publisher(_gui), rviz2,
xacro). The launch description is visited (launch's shape: actions and substitutions evaluated
against a LaunchContext) and every Node it would start is recorded: :class:`LaunchPlan`.
An exception stops the visit as it stops ``ros2 launch`` ("Caught exception in launch"), and
comes back as data with the learner's file and line.
"""

from __future__ import annotations

import os
import re
from dataclasses import dataclass, field
from typing import Any

from ..core.errors import BrasKitError
from ..model.robot import robot_from_xml  # robot_state_publisher's description, read as it reads it
from ..model.xmlio import parse_xml
from ..trust import scratch
from .attempts import Attempt

PLAN_CPU_SECONDS = 20
PLAN_WALL_SECONDS = 40.0
MAX_LAUNCH_NODES = 256  # the stand-in's bound (launch/_plan.py MAX_NODES): the nodes of one launch evaluated
PLAN_MEMORY_BYTES = 1 << 30

# the simulated ROS install: package -> its executables (what `apt install` gave the tutorial)
ROS_INSTALL: dict[str, tuple[str, ...]] = {
    "robot_state_publisher": ("robot_state_publisher",),
    "joint_state_publisher": ("joint_state_publisher",),
    "joint_state_publisher_gui": ("joint_state_publisher_gui",),
    "rviz2": ("rviz2",),
    "xacro": ("xacro",),
    "tf2_ros": ("static_transform_publisher",),
    "urdf": (),
    "launch": (),
    "launch_ros": (),
    "ament_index_python": (),
}


@dataclass(frozen=True)
class PlannedNode:
    """A node a launch file starts (a launch_ros Node action), as ros2 launch would start it."""

    package: str | None
    executable: str
    name: str | None
    namespace: str | None
    parameters: dict[str, Any]
    parameter_files: list[str]
    remappings: list[tuple[str, str]]
    arguments: list[str]
    delay: float
    file: str  # where the Node(...) was written (absolute, as loaded)
    line: int
    ros_arguments: list[str] = field(default_factory=list)
    argv: list[str] = field(default_factory=list)  # the node's command line after the program (node.py:201-212)

    @property
    def shown(self) -> str:
        return f"{self.package} {self.executable}" if self.package else self.executable

    @property
    def full_name(self) -> str:
        name = self.name or self.executable
        return (self.namespace.rstrip("/") + "/" + name) if self.namespace else "/" + name

    def resolve(self, topic: str) -> str:
        """The topic this node really uses for ``topic``, as rcl resolves it: expanded in the node's
        namespace, then remapped by its ``-r`` rules (names.py)."""
        from .names import InvalidROSArgs, parse_ros_arguments, resolve_topic_name

        try:
            rules = parse_ros_arguments(self.argv).remaps
        except InvalidROSArgs:
            rules = []
        return resolve_topic_name(topic, self.name or self.executable, self.namespace or "/", rules)


@dataclass(frozen=True)
class LaunchFailure:
    """Why the launch stopped: the exception, and the learner's line it came through."""

    type: str  # the exception's class, e.g. PackageNotFoundError
    message: str  # str(exception), as ros2 launch prints it
    file: str  # the learner's file the exception came through (absolute), "" if none
    line: int
    text: str  # that line


@dataclass
class LaunchPlan:
    """What evaluating a launch file gave: the nodes and processes it starts, its logs, or its failure."""

    launch_file: str
    nodes: list[PlannedNode] = field(default_factory=list)
    processes: list[dict[str, Any]] = field(default_factory=list)
    logs: list[tuple[float, str, str, int]] = field(default_factory=list)
    warnings: list[str] = field(default_factory=list)
    failure: LaunchFailure | None = None
    included: list[str] = field(default_factory=list)  # the launch files it included (absolute, installed)
    unfired: list[dict[str, Any]] = field(default_factory=list)  # OnProcessStart whose target never started
    # what the launch file tried that its walls stopped; ``path`` relative to the watched root
    # (the package's install prefix: map it back with BuildRecord.source_of)
    blocked: list[Attempt] = field(default_factory=list)

    @property
    def ros2_launch_error(self) -> str:
        """What ros2 launch prints when the launch stops (launch_service.py)."""
        if self.failure is None:
            return ""
        return f"[ERROR] [launch]: Caught exception in launch (see debug for traceback): {self.failure.message}"


def simulated_ros_prefix(base: str) -> str:
    """An install prefix holding the ROS packages of ROS_INSTALL, found through the ament index."""
    prefix = os.path.join(base, "ros")
    index = os.path.join(prefix, "share", "ament_index", "resource_index", "packages")
    os.makedirs(index, exist_ok=True)
    for package, executables in ROS_INSTALL.items():
        open(os.path.join(index, package), "w").close()
        os.makedirs(os.path.join(prefix, "share", package), exist_ok=True)
        for executable in executables:
            path = os.path.join(prefix, "lib", package, executable)
            os.makedirs(os.path.dirname(path), exist_ok=True)
            with open(path, "w") as handle:
                handle.write(f"#!/bin/sh\n# {package} {executable}, started by bras-kit as its counterpart\n")
            os.chmod(path, 0o755)
    return prefix


def plan_launch(launch_file: str, prefixes: list[str], arguments: dict[str, str] | None = None, *,
                learner_roots: tuple[str, ...] = ()) -> LaunchPlan:
    """Evaluate ``launch_file`` (from an install tree) with the packages at ``prefixes``."""
    from ..trust.sandbox import ResourceLimitError, run_limited

    with scratch.folder("bras-kit-launch-") as workdir:
        ros, cwd = _planning_folders(workdir)
        from ..trust.contain import containment

        roots = tuple(os.path.abspath(r) for r in learner_roots) + tuple(prefixes)
        # the launch file reads its packages' install trees and writes only in its own folder
        walls = containment("auto", workdir, (*roots, os.path.dirname(os.path.abspath(launch_file))))
        try:
            return run_limited(_plan_here, os.path.abspath(launch_file), [*prefixes, ros], dict(arguments or {}),
                               cwd, roots, walls, cpu_seconds=PLAN_CPU_SECONDS, memory_bytes=PLAN_MEMORY_BYTES,
                               wall_seconds=PLAN_WALL_SECONDS, what=f"the launch file {launch_file}", contain=walls)
        except ResourceLimitError as exc:  # a launch file that never ends: as data
            return _stopped(launch_file, exc)


def _planning_folders(workdir: str) -> tuple[str, str]:
    """In a launch child's working folder: the simulated ROS install prefix, and the folder the
    launch file runs in (``ros2 launch`` from a workspace)."""
    ros = simulated_ros_prefix(workdir)
    cwd = os.path.join(workdir, "ws")
    os.makedirs(cwd)
    return ros, cwd


def _stopped(launch_file: str, exc: Any) -> LaunchPlan:
    """A launch file the sandbox stopped (a limit), as the plan's failure."""
    return LaunchPlan(launch_file, failure=LaunchFailure(
        "ResourceLimitError", f"the launch file was stopped ({exc.kind} limit of the sandbox)", "", 0, ""))


class PlanAhead:
    """A launch file's child forked and walled in before the package is built (:func:`begin_plan`):
    it waits, contained, for what to evaluate, while setup.py's child runs beside it.

    Only this process writes to the child's pipe: the launch file's path in the fresh install
    tree, the prefixes and arguments, all bras-kit's own data. The child reads them, then runs the
    launch file exactly as :func:`plan_launch`'s child does (:func:`_plan_here`)."""

    def __init__(self, pending: Any, write: int, folder: Any, ros: str, cwd: str, roots: tuple[str, ...]) -> None:
        self._pending, self._write, self._folder = pending, write, folder
        self._ros, self._cwd, self._roots = ros, cwd, roots

    def plan(self, launch_file: str, prefixes: list[str], arguments: dict[str, str] | None = None) -> LaunchPlan:
        """The evaluation of ``launch_file`` (under the install base given to :func:`begin_plan`)."""
        import pickle

        from ..trust.sandbox import ResourceLimitError

        told = (os.path.abspath(launch_file), [*prefixes, self._ros], dict(arguments or {}), self._cwd,
                (*self._roots, *prefixes))
        try:
            with os.fdopen(self._write, "wb") as pipe:
                self._write = -1
                pipe.write(pickle.dumps(told, protocol=pickle.HIGHEST_PROTOCOL))
        except OSError:  # the child is gone: its end is reported by result()
            pass
        try:
            return self._pending.result()
        except ResourceLimitError as exc:  # a launch file that never ends: as data
            return _stopped(launch_file, exc)
        finally:
            self._folder.cleanup()

    def cancel(self) -> None:
        """Nothing to evaluate (the build failed, no launch file): the child ends without running any."""
        if self._write >= 0:
            os.close(self._write)
            self._write = -1
        self._pending.close()
        self._folder.cleanup()


def begin_plan(install_base: str, prefixes: list[str], *, learner_roots: tuple[str, ...] = ()) -> PlanAhead | None:
    """The child of :func:`plan_launch` for a package about to be built into ``install_base``,
    forked and contained now: its namespaces, mounts and imports are made while setup.py runs.
    It may read ``install_base`` (where the build lays the package out), the other ``prefixes``
    and ``learner_roots``; ``install_base`` must be a folder of bras-kit's own holding nothing else
    (validate's throwaway install tree). None where children come from a fork server."""
    from dataclasses import replace

    from ..trust import sandbox
    from ..trust.contain import containment

    if sandbox.children_from_the_server():  # a process with threads: plan_launch's child, after the build
        return None
    os.makedirs(install_base, exist_ok=True)
    folder = scratch.folder("bras-kit-launch-")
    ros, cwd = _planning_folders(folder.name)
    roots = tuple(os.path.abspath(r) for r in learner_roots)
    walls = containment("auto", folder.name, (*roots, *prefixes, os.path.abspath(install_base)))
    read, write = os.pipe()
    what = f"the launch file of {', '.join(learner_roots) or install_base}"
    try:
        kept = replace(walls, keep=(*walls.keep, read)) if walls is not None else None
        pending = sandbox.start_limited(_plan_when_told, read, write, walls, cpu_seconds=PLAN_CPU_SECONDS,
                                        memory_bytes=PLAN_MEMORY_BYTES, wall_seconds=PLAN_WALL_SECONDS + WAIT_SECONDS,
                                        what=what, contain=kept)
    except BaseException:
        os.close(write)
        folder.cleanup()
        raise
    finally:
        os.close(read)
    return PlanAhead(pending, write, folder, ros, cwd, roots)


WAIT_SECONDS = 30.0  # how long the child of begin_plan may wait for the build (setup.py's own limit is 20 s)


def _plan_when_told(read: int, write: int, walls: Any = None) -> LaunchPlan | None:
    """In :func:`begin_plan`'s child: what to evaluate, from the pipe (None: nothing, the child ends).
    Walled in, the child kept only the pipe's reading end; without walls it closes the writing end
    it inherited, or it would wait for itself."""
    import pickle

    if walls is None:
        os.close(write)
    _install_launch()  # while setup.py runs: what is left once told is the launch file's own work
    chunks = []
    while chunk := os.read(read, 1 << 16):
        chunks.append(chunk)
    os.close(read)
    if not chunks:
        return None
    launch_file, prefixes, arguments, cwd, roots = pickle.loads(b"".join(chunks))  # noqa: S301 - this process's parent wrote it
    return _plan_here(launch_file, prefixes, arguments, cwd, tuple(roots), walls, installed=True)


def preload_planning() -> None:
    """Import, in this process, what every launch file's child imports before it installs the
    stand-in (its import hook): children forked afterwards start with it. What only some launch
    files need (the real xacro, PyYAML) each child imports when it does."""
    from . import finder  # noqa: F401


def _install_launch() -> None:
    """The stand-in installed in this (launch file's) child, and the modules every evaluation runs
    imported: launch's, ament_index_python's (``ros2 launch`` imports both before any launch file,
    ros2launch/api/api.py) and launch_ros's, which nearly every launch file imports. None of them
    reads the environment or the current folder at import."""
    from .finder import install

    install()
    import ament_index_python.packages  # noqa: F401
    import launch._actions  # noqa: F401
    import launch._core  # noqa: F401
    import launch._events  # noqa: F401
    import launch._plan  # noqa: F401
    import launch._sources  # noqa: F401
    import launch_ros  # noqa: F401


def _plan_here(launch_file: str, prefixes: list[str], arguments: dict[str, str], cwd: str,
               roots: tuple[str, ...], walls: Any = None, installed: bool = False) -> LaunchPlan:
    """In the child: the stand-in installed (already, where ``installed``: :func:`_install_launch`),
    the launch description visited; contained (``walls``), what the walls stopped is watched from
    the first prefix (the package's)."""
    import sys
    import traceback
    import warnings

    os.environ["AMENT_PREFIX_PATH"] = os.pathsep.join(prefixes)
    os.chdir(cwd)
    if not installed:
        _install_launch()
    import launch._plan as record
    from launch._actions import IncludeLaunchDescription
    from launch._core import LaunchContext, LaunchDescription, visit_all
    from launch._events import fire_pending, unfired_start_handlers
    from launch._sources import AnyLaunchDescriptionSource

    record.reset()
    record.ROOTS = tuple(roots)
    plan = LaunchPlan(launch_file)
    context = LaunchContext(argv=[f"{k}:={v}" for k, v in arguments.items()])
    context.launch_configurations.update(arguments)
    context.extend_locals({"current_launch_file_path": launch_file,
                           "current_launch_file_directory": os.path.dirname(launch_file)})
    sys.argv = ["ros2", "launch", launch_file]
    watcher = None
    if walls is not None:
        from .attempts import Watcher

        read, write = walls.granted()
        watcher = Watcher(prefixes[0] if prefixes else os.path.dirname(launch_file), tuple(write), tuple(read))
        watcher.install()
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        try:
            # ros2launch/api/api.py:168: the file is included, as ros2 launch includes it
            visit_all(LaunchDescription([IncludeLaunchDescription(
                AnyLaunchDescriptionSource(launch_file), launch_arguments=list(arguments.items()))]), context)
            fire_pending(context, visit_all)  # what event handlers start once their event happened
            record.UNFIRED.extend(unfired_start_handlers(context))
        except BaseException as exc:  # noqa: BLE001 - the learner's launch file, as data
            first = (getattr(exc, "_likely_errors", None) or [exc])[0]  # InvalidLaunchFileError: the first loader's
            if hasattr(first, "what"):  # NotSimulated: what bras-kit does not simulate, not what launch says
                exc = first
            frames = [f for f in traceback.extract_tb(first.__traceback__)
                      if os.path.abspath(f.filename).startswith(roots)]
            if isinstance(first, SyntaxError) and first.filename:
                where = (os.path.abspath(first.filename), first.lineno or 0, (first.text or "").strip())
            elif frames:
                where = (os.path.abspath(frames[-1].filename), frames[-1].lineno or 0, (frames[-1].line or "").strip())
            elif record.CURRENT:
                where = (*record.CURRENT, "")
            else:
                where = ("", 0, "")
            message = exc.what if hasattr(exc, "what") else str(exc)  # NotSimulated
            plan.failure = LaunchFailure(type(exc).__name__, message, *where)
    plan.warnings = [str(w.message) for w in caught]
    plan.nodes = [PlannedNode(
        package=n["package"], executable=n["executable"], name=n["name"], namespace=n["namespace"],
        parameters={k: _plain(v) for k, v in n["parameters"].items()}, parameter_files=list(n["parameter_files"]),
        remappings=[tuple(r) for r in n["remappings"]], arguments=list(n["arguments"]), delay=n["delay"],
        file=n["file"], line=n["line"], ros_arguments=list(n.get("ros_arguments", [])),
        argv=list(n.get("argv", []))) for n in record.NODES]
    plan.processes = [dict(p) for p in record.PROCESSES]
    plan.included = [f for f in record.INCLUDED if f != launch_file]
    plan.unfired = [dict(u) for u in record.UNFIRED]
    plan.logs = list(record.LOGS)
    if watcher is not None:
        plan.blocked = watcher.finish()
    return plan


def _plain(value: Any) -> Any:
    if isinstance(value, tuple):
        return [_plain(v) for v in value]
    if isinstance(value, (str, int, float, bool, bytes)) or value is None:
        return value
    return str(value)


# ---------------------------------------------------------------- robot_state_publisher


@dataclass(frozen=True)
class StartProblem:
    """Why a node's counterpart cannot start, in its program's own words (``ros``) and a kind
    the feature above words for the learner."""

    kind: str  # "empty", "file_fallback", "file_missing", "file_refused", "path", "xacro", "not_urdf",
    # "too_large", "too_many" (past what bras-kit parses: MAX_DESCRIPTION_CHARS, MAX_DESCRIPTION_ELEMENTS)
    ros: tuple[str, ...]
    detail: str = ""


# the programs of the simulated install written in C++ (rclcpp): their words for an unknown ROS argument
CPP_PROGRAMS = ("robot_state_publisher", "rviz2", "static_transform_publisher")


def ros_arguments_start(node: PlannedNode) -> list[StartProblem]:
    """What rcl makes of the node's command line (rcl/src/rcl/arguments.c): an argument after
    ``--ros-args`` that is not a ROS flag ('--log-level warn' as one word) kills the node at
    rclcpp::init / rclpy.init with UnknownROSArgsError (rclcpp context.cpp:240, rclpy utils.cpp:277);
    a ROS flag with a wrong value stops it too (RCL_RET_INVALID_ROS_ARGS)."""
    from .names import InvalidROSArgs, parse_ros_arguments, unknown_ros_args_error

    cpp = node.executable in CPP_PROGRAMS
    process = f"{node.executable}-1"
    try:
        parsed = parse_ros_arguments(node.argv)
    except InvalidROSArgs as exc:
        return [StartProblem("invalid_ros_args", (f"[ERROR] [{process}]: {exc}",), str(exc))]
    if not parsed.unknown:
        return []
    words = unknown_ros_args_error(parsed.unknown, cpp=cpp)
    said: tuple[str, ...]
    if cpp:
        said = (f"[{process}] terminate called after throwing an instance of 'rclcpp::exceptions::UnknownROSArgsError'",
                f"[{process}]   what():  {words}",
                f"[ERROR] [{process}]: process has died [exit code -6]")
    else:
        said = (f"[{process}] rclpy._rclpy_pybind11.UnknownROSArgsError: {words}",
                f"[ERROR] [{process}]: process has died [exit code 1]")
    return [StartProblem("unknown_ros_args", said, ", ".join(parsed.unknown))]


RSP_EMPTY = "robot_description parameter must not be empty"
# the robot_description bras-kit parses and holds (the tutorial's arm: 5 kB, 3 links): as much
# text as the one reader reads from a file, and no more links and joints than the page can show
MAX_DESCRIPTION_CHARS = 8 << 20
MAX_DESCRIPTION_ELEMENTS = 20_000
_ELEMENT = re.compile(r"<(?:link|joint)[\s/>]")
RSP_INIT = "Unable to initialize urdf::model from robot description"
RSP_FALLBACK = ("No robot_description parameter, but command-line argument available.  Assuming argument is "
                "name of URDF file.  This backwards compatibility fallback will be removed in the future.")


def description_too_large(text: str, most_chars: int = MAX_DESCRIPTION_CHARS) -> StartProblem | None:
    """"too_large" (its MiB in ``detail``) or "too_many" (its links and joints) for a description
    bras-kit will not parse: counted on the text, before any parser holds it."""
    if len(text) > most_chars:
        return StartProblem("too_large", (), str(round(len(text) / (1 << 20), 1)))
    count = 0
    for _ in _ELEMENT.finditer(text):
        count += 1
        if count > MAX_DESCRIPTION_ELEMENTS:
            return StartProblem("too_many", (), str(MAX_DESCRIPTION_ELEMENTS))
    return None


def robot_state_publisher_start(node: PlannedNode, roots: tuple[str, ...] = ()) -> tuple[str | None, list[StartProblem]]:
    """The URDF robot_state_publisher 3.3 (Jazzy) would load, and what it says on the way
    (robot_state_publisher.cpp: the constructor, lines 81-113; parseURDF, lines 164-176). A URDF
    file named by the launch file is read only through :mod:`bras_kit.trust.learner_files`, inside
    ``roots`` (the package, its install tree): never a device, a pipe, or a file elsewhere
    ("file_refused", and nothing of it is quoted)."""
    text = node.parameters.get("robot_description", "")
    problems: list[StartProblem] = []
    if not isinstance(text, str):
        text = str(text)
    if text == "":
        if node.arguments:
            problems.append(StartProblem("file_fallback", (f"[WARN] [robot_state_publisher]: {RSP_FALLBACK}",),
                                         node.arguments[0]))
            from ..trust.learner_files import Unreadable, read_text

            try:
                text = read_text(node.arguments[0], roots)
            except Unreadable as exc:
                if exc.kind == "too_large":  # past the reader's 8 MiB: the same bound as a parameter's text
                    return None, [*problems, StartProblem("too_large", (), f"> {MAX_DESCRIPTION_CHARS >> 20}")]
                # a path that names nothing is what robot_state_publisher says; any other refusal is ours
                if exc.kind != "missing" and os.path.lexists(os.path.join(roots[0] if roots else "", node.arguments[0])):
                    return None, [*problems, StartProblem("file_refused", (), str(node.arguments[0])[:200])]
                return None, [*problems, StartProblem(
                    "file_missing", (f"[FATAL] [robot_state_publisher]: Failed to open URDF file: "
                                     f"{node.arguments[0]}: No such file or directory",), node.arguments[0])]
            except (OSError, UnicodeDecodeError):
                return None, [*problems, StartProblem(
                    "file_missing", (f"[FATAL] [robot_state_publisher]: Failed to open URDF file: "
                                     f"{node.arguments[0]}: No such file or directory",), node.arguments[0])]
        else:
            return None, [StartProblem("empty", (f"[FATAL] [robot_state_publisher]: {RSP_EMPTY}",))]
    too_large = description_too_large(text)
    if too_large is not None:
        return None, [*problems, too_large]
    stripped = text.strip()
    fatal = (f"[FATAL] [robot_state_publisher]: {RSP_INIT}",)
    if not stripped.startswith("<"):
        kind = "path" if stripped.endswith((".urdf", ".xacro", ".xml")) or os.sep in stripped else "not_urdf"
        return None, [*problems, StartProblem(kind, fatal, stripped[:200])]
    if "xmlns:xacro" in stripped or "<xacro:" in stripped or "${" in stripped:
        return None, [*problems, StartProblem("xacro", fatal)]
    try:
        robot_from_xml(parse_xml(text, "robot_description"), "robot_description", text)
    except BrasKitError as exc:
        return None, [*problems, StartProblem("not_urdf", fatal, str(exc.message))]
    return text, problems
