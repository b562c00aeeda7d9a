"""One build and launch of a package, as ``ros2 launch PKG FILE`` does after ``colcon build``.

The package is built (bras-kit's colcon, into a temporary install tree, the other packages of
its workspace beside it), its launch file evaluated once (:mod:`bras_kit.ros.evaluation`), what
started said as ros2 launch says it, and the package's own nodes run in simulated time for
their findings. A page (``bras-kit launch``'s, or a notebook's) is handed the evaluation as
soon as the launch is evaluated, before the checks (``on_evaluated``).
"""

from __future__ import annotations

import os
from collections.abc import Callable, Sequence
from dataclasses import dataclass, field
from typing import Any

from ..core.message import M, Message
from ..trust.inert import for_terminal
from .reporter import Reporter

DEFAULT_DURATION = 10.0  # s of simulated time the package's own nodes are first run for

COUNTERPARTS = {
    "robot_state_publisher": M("the model and its TF frames"),
    "joint_state_publisher": M("the viewer's joint sliders"),
    "joint_state_publisher_gui": M("the viewer's joint sliders"),
    "rviz2": M("the viewer"),
}


@dataclass(frozen=True)
class LaunchRequest:
    """What ``ros2 launch PKG FILE NAME:=VALUE`` names: the package's folder (``typed``: as the
    learner named it), its colcon workspace and the packages built beside it, the launch file
    (None: the package's first) and the launch arguments."""

    folder: str
    typed: str
    workspace: Any = None  # ros.workspace.Workspace, or None outside a workspace
    others: tuple[str, ...] = ()
    launch_file: str | None = None
    arguments: dict[str, str] = field(default_factory=dict)
    duration: float = DEFAULT_DURATION
    lang: str | None = None


def prepare(target: str, launch_file: str | None = None, arguments: dict[str, str] | None = None, *,
            duration: float = DEFAULT_DURATION, lang: str | None = None) -> LaunchRequest:
    """The request for ``target``: a package folder, or a package's name in the colcon workspace
    of the current folder (its root or below), as ``ros2 launch`` takes it after sourcing."""
    from ..ros.workspace import others, resolve_package

    folder, workspace = resolve_package(target)
    return LaunchRequest(folder, target, workspace, tuple(others(workspace, folder)), launch_file,
                         dict(arguments or {}), duration, lang)


class Launched:
    """One build and launch of the package: its evaluation (what the terminal prints and a page
    shows), the package's own nodes among those started, the findings."""

    def __init__(self, package: Any, evaluation: Any, nodes: list[Any]) -> None:
        self.package, self.evaluation, self.nodes = package, evaluation, nodes
        self.result = evaluation.launched
        self.results = evaluation.results
        self.plan = self.result.plan
        self.description = self.result.description

    @property
    def started(self) -> bool:
        """Whether the package built and its launch file started (then its own nodes can run live)."""
        return self.result.build.failure is None and self.plan is not None and self.plan.failure is None


class Superseded(Exception):
    """A file of the package saved while it was built and launched again: that build is dropped
    (neither printed nor shown) and the next one reads the files as they are now."""


OnEvaluated = Callable[[Any, tuple[str, ...]], None]


def launch(target: str | LaunchRequest, launch_file: str | None = None, arguments: dict[str, str] | None = None, *,
           duration: float = DEFAULT_DURATION, lang: str | None = None, reporter: Reporter | None = None,
           on_evaluated: OnEvaluated | None = None, superseded: Callable[[], bool] | None = None) -> Launched:
    """Build the package, evaluate its launch file once, say what started, run its own nodes in
    simulated time for their findings. ``on_evaluated(evaluation, package_paths)`` is called
    once the launch is evaluated, before the checks (a page shows its robot at once). ``superseded`` (a
    rebuild) is asked once the build is evaluated and once the checks are in: true,
    :class:`Superseded`. Raises :class:`~bras_kit.core.errors.ParameterError` for a launch file
    the package does not install, as ros2 launch refuses it."""
    import tempfile

    from ..findings.data import merge_results
    from ..ros.evaluation import evaluate_launch
    from ..ros.workspace import build_others
    from ..validate.package import Package
    from ..validate.package.launch_check import check_launch

    request = target if isinstance(target, LaunchRequest) else prepare(
        target, launch_file, arguments, duration=duration, lang=lang)
    if reporter is None:
        from ..core.i18n import current_language

        reporter = Reporter(request.lang or current_language())
    package = Package(request.folder)
    with tempfile.TemporaryDirectory(prefix="bras-kit-launch-") as base:
        install = os.path.join(base, "install")
        prefixes, unbuilt = build_others(list(request.others), install)
        for name in unbuilt:
            reporter.warn(M("the package {name} of the workspace does not build: launch files cannot find it "
                            "(bras-kit build says why)", name=name))
        evaluation = evaluate_launch(request.folder, install, request.launch_file, request.arguments, package,
                                     prefixes=tuple(prefixes))
        learners = learners_install(install, request.workspace)
        if superseded is not None and superseded():
            raise Superseded  # built from files that are no longer the learner's: nothing said of it
        result = evaluation.launched
        if result.build.failure is None and request.launch_file is not None and result.plan is None:
            _refuse_launch_file(result.build, request.launch_file, learners)
        nodes = _say_started(request, evaluation, reporter, learners)
        if result.build.failure is None:  # at each build: a save the learner's colcon build has not seen
            evaluation.stale_install = stale_install_notice(request.workspace, result.build)
            if evaluation.stale_install is not None:
                reporter.warn(evaluation.stale_install)
        reporter.flush()
        # the install tree's share folder: the robot's package:// meshes, as robot_state_publisher's
        package_paths = (os.path.join(result.build.prefix, "share"), os.path.dirname(os.path.abspath(request.folder)))
        if on_evaluated is not None:  # the page first, the checks after
            on_evaluated(evaluation, package_paths)
        check_launch(evaluation, package, package_paths)
        evaluation.results = sorted(merge_results(evaluation.results,
                                                  node_results(request, nodes, evaluation.robot, evaluation.package,
                                                               reporter)),
                                    key=lambda r: r.path)
        if superseded is not None and superseded():
            raise Superseded  # the page waits ("checking") for the build of the files as saved now
        evaluation.checked = True  # a page shows them once the terminal has said them
    return Launched(package, evaluation, nodes)


def _refuse_launch_file(build: Any, launch_file: str, learners: Callable[[str], str]) -> None:
    """ros2 launch's refusal of a launch file the package does not install, or installs twice."""
    from ..core.errors import ParameterError
    from ..ros.launched import launch_sources, share_files_named

    share = os.path.join(build.prefix, "share", build.package)
    found = share_files_named(build, launch_file)
    if len(found) > 1:  # ros2launch's MultipleLaunchFilesError (ros2launch/api/api.py, Jazzy 58-63)
        raise ParameterError(
            M("file '{file}' was found more than once in the share directory of package '{package}': "
              "{paths}", file=launch_file, package=build.package, paths=found),
            hint=M("give each launch file of the package its own name"))
    raise ParameterError(
        M("file '{file}' was not found in the share directory of package '{package}' which is at '{share}'",
          file=launch_file, package=build.package, share=learners(share)),
        hint=M("the installed launch files are {names}; a new one needs colcon build (data_files)",
               names=[os.path.basename(f) for f in launch_sources(build)] or "-"))


def _say_started(request: LaunchRequest, evaluation: Any, reporter: Reporter,
                 learners: Callable[[str], str]) -> list[Any]:
    """What ros2 launch prints as it starts the plan's nodes, each with what stands for it here;
    the package's own nodes among them (run for their findings)."""
    result = evaluation.launched
    plan = result.plan
    nodes: list[Any] = []
    if result.build.failure is not None or plan is None:
        return nodes
    reporter.line(M("ros2 launch {package} {file}", package=result.build.package,
                    file=os.path.basename(result.launch_file)))
    for _delay, text, *_where in plan.logs:  # LogInfo actions, as ros2 launch prints them
        reporter.line(f"[INFO] [launch.user]: {for_terminal(learners(str(text)))}")  # the learner's text, made inert
    for node in plan.nodes:
        counterpart = COUNTERPARTS.get(node.package or "")
        if counterpart is not None:
            reporter.line(M("[INFO] started {node} ({what}) -> {counterpart}", node=node.full_name,
                            what=node.shown, counterpart=reporter.say(counterpart)))
        elif node.package == result.build.package:
            reporter.line(M("[INFO] started {node} ({what}) -> your node, run for {duration} s",
                            node=node.full_name, what=node.shown, duration=request.duration))
            nodes.append(node)
        else:
            reporter.line(M("[INFO] started {node} ({what}): not simulated, nothing is shown for it",
                            node=node.full_name, what=node.shown))
    if plan.failure is not None:
        reporter.error(for_terminal(learners(plan.ros2_launch_error)))
    for _node, problem in result.problems:
        for line in problem.ros:
            reporter.error(for_terminal(learners(line)))
    return nodes


def learners_install(install: str, workspace: Any) -> Callable[[str], str]:
    """A text naming bras-kit's own install tree (a temporary folder) made to name the one the
    learner's colcon build makes: the workspace's install/, or install/ where colcon build is
    typed (ros2 launch's words, on the learner's machine)."""
    mine = install.rstrip(os.sep)
    theirs = workspace.install if workspace is not None else "install"
    return lambda text: text.replace(mine + os.sep, theirs + os.sep).replace(mine, theirs)


def stale_install_notice(workspace: Any, build: Any) -> Message | None:
    """The workspace's install/ built before the last changes: ros2 launch reads that tree, never
    the sources, so it would still run the old files until colcon build is run again (the
    tutorial's "recompilez"); bras-kit launch builds them as they are now. None when the install
    is current, or there is none."""
    from ..ros.workspace import stale_install

    differ = stale_install(workspace, build.package, build.prefix)
    if not differ or workspace is None:
        return None
    shown = [os.path.join("install", build.package, f) for f in differ[:3]] + (["..."] if len(differ) > 3 else [])
    return M("{install} was built before your last changes ({files}): ros2 launch would still use that old install "
             "until you run colcon build again in {root} (bras-kit launch builds the sources as they are now)",
             install=os.path.join(workspace.install, build.package), files=", ".join(shown), root=workspace.root)


def node_results(request: LaunchRequest, nodes: Sequence[Any], robot: Any, package: str,
                 reporter: Reporter) -> list[Any]:
    """Each of the package's own nodes run as bras-kit run runs it, in simulated time, against the
    robot robot_state_publisher loads: what it published, and its findings."""
    from ..core.errors import BrasKitError
    from ..core.i18n import current_language
    from ..findings.data import FileResult
    from ..run.findings import run_findings
    from ..run.live import executables_of
    from ..run.node import run_node
    from ..run.report import summary

    lang = reporter.lang or current_language()
    out = []
    executables, parameters = executables_of(nodes, package)
    for executable in executables:
        try:
            recording = run_node(request.folder, executable, duration=request.duration, echo=False,
                                 parameters=parameters[executable], robot=robot, beside=request.others)
        except BrasKitError as exc:
            reporter.error(for_terminal(str(exc)))
            continue
        for message in summary(recording):
            reporter.line("  " + reporter.say(message))
        by_file: dict[str, list[Any]] = {}
        for found in run_findings(recording, robot, lang=lang, root=os.path.abspath(request.folder)):
            by_file.setdefault(str(found.data.get("file", "")), []).append(found)
        out += [FileResult(os.path.join(request.folder, file), found) for file, found in by_file.items()]
    return out
