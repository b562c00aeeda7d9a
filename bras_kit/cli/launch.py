"""bras-kit launch: what ``ros2 launch PKG FILE`` does, on the package built as colcon builds it."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable

from ..core.message import M, Mn
from ..ros.evaluation import rviz_fixed_frame
from ..trust.inert import for_terminal
from ._common import add_no_browser_argument

_EPILOG = """\
The package is built (bras-kit build, into a temporary install tree), the launch file (Python,
XML or YAML) is evaluated as ros2 launch evaluates it, against a stand-in of launch, launch_ros
and ament_index_python, and each Node it returns is started as its counterpart:
robot_state_publisher loads its robot_description, joint_state_publisher(_gui) and rviz2 are
the viewer, and the package's own executables run as 'bras-kit run' runs them.

The other packages of the colcon workspace are built beside it (as colcon builds them all), so
FindPackageShare, get_package_share_directory and launch includes across packages find them.

examples (in ~/ros2_cellule_ws or a folder below it, as after 'source install/setup.bash'):
  bras-kit launch bras_description affichage.launch.py
  bras-kit launch bras_description affichage.launch.py --no-page --duration 5
  bras-kit launch bras_description affichage.launch.py animation:=true --no-page
  bras-kit launch bras_description affichage.launch.py --no-browser   (over SSH: the page's address only)
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = _EPILOG
    parser.add_argument("target", nargs="?", default=".", metavar="PKG|PKG_DIR",
                        help="a package of the colcon workspace you are in (its root or below), by name, "
                             "or a package folder (default: .)")
    parser.add_argument("items", nargs="*", metavar="FILE|NAME:=VALUE",
                        help="the launch file, by its name in the package's share folder (default: the "
                             "package's first), and launch arguments")
    parser.add_argument("--no-page", action="store_true",
                        help="no page: print what started, what each node published and the findings, then exit")
    add_no_browser_argument(parser)
    parser.add_argument("--duration", type=float, default=10.0, metavar="S",
                        help="of simulated time the package's own nodes are first run for, for their findings (default: 10); in the browser they then run live")
    parser.add_argument("--json", action="store_true", help="the findings")
    parser.add_argument("--port", type=int, default=8080,
                        help="port of the page (default 8080; the next free one if taken)")
    parser.set_defaults(keeps_assignments="items")


def _split(items: list[str]) -> tuple[str | None, dict[str, str]]:
    from ..core.errors import ParameterError

    launch_file, arguments = None, {}
    for item in items:
        name, sep, value = item.partition(":=")
        if sep and name:
            arguments[name] = value
        elif launch_file is None and not sep:
            launch_file = item
        else:
            raise ParameterError(M("'{item}' is not a launch file nor NAME:=VALUE", item=item),
                                 hint=M("write launch arguments as NAME:=VALUE, as after ros2 launch PKG FILE"))
    return launch_file, arguments


COUNTERPARTS = {
    "robot_state_publisher": M("the model and its TF frames"),
    "joint_state_publisher": M("the viewer's joint sliders"),
    "joint_state_publisher_gui": M("the viewer's joint sliders"),
    "rviz2": M("the viewer"),
}


def run(args: argparse.Namespace) -> int:
    from ..core.i18n import current_language

    lang = args.lang or current_language()
    from ..ros.workspace import others, resolve_package

    args.typed, (args.target, workspace) = args.target, resolve_package(args.target)  # a folder, or a name in the workspace
    args.workspace = workspace
    args.others = others(workspace, args.target)  # built beside it, as colcon builds the whole workspace
    launch_file, arguments = _split(args.items)
    if args.no_page:
        return _report(args, _launch(args, launch_file, arguments, lang), lang)
    from ..trust.contain import available as containable
    from ..trust.sandbox import children_from_a_server

    # With a page, threads run beside the package's children (the page's, viser's, Zenoh's): the
    # children that can be sent to it are forked by a server started now, before any thread exists
    # (a child forked while a thread imports a module could wait forever for its lock); its probe
    # too, a throwaway child, runs now.
    containable()
    from ..run.live import package_stamps

    # the files as the first build reads them: a save during that build (or its checks) is a save
    args.stamps = package_stamps(args.target)
    shown: list[tuple[object, object]] = []  # (viewer, bus), once the page's address is printed
    with children_from_a_server():
        try:
            launched = _launch(args, launch_file, arguments, lang, page_shown=shown)
            code = _report(args, launched, lang)
            if launched.page is not None:  # the terminal first: a Ctrl-C as the page shows them loses nothing
                launched.page[0].show_checks()
            if launched.description is None:
                return code
            if launched.page is None:  # no robot file the page could show
                return 0
            return _live(args, launch_file, arguments, lang, launched, launched.page[0])
        except KeyboardInterrupt:
            if not shown:
                raise  # before the address: interrupted, as any command
            return 0  # Ctrl-C once the address is out (checks or a rebuild under way too): the stop it announced
        finally:
            if shown:
                _close(*shown[0])


def _report(args: argparse.Namespace, launched: _Launched, lang: str) -> int:
    """The findings printed (text or JSON); the exit code they give."""
    from ..findings.report import exit_code, format_json, format_text

    if args.json:
        sys.stdout.write(format_json(launched.results, lang=lang))
    else:
        sys.stdout.write(format_text(launched.results, lang))
    sys.stdout.flush()
    return exit_code(launched.results)


class _Launched:
    """One build and launch of the package: its evaluation (what the terminal prints and the page
    shows), the package's own nodes, the page."""

    def __init__(self, package, evaluation, nodes, page) -> None:
        self.package, self.evaluation, self.nodes = package, evaluation, nodes
        self.result = evaluation.launched
        self.results = evaluation.results
        self.page = page  # (viewer, bus) when a page was asked for and robot_state_publisher got a robot
        self.plan = self.result.plan
        self.description = self.result.description


class _Superseded(Exception):
    """A file of the package saved while it was built and launched again: that build is dropped
    (neither printed nor shown) and the next one reads the files as they are now."""


def _launch(args: argparse.Namespace, launch_file: str | None, arguments: dict[str, str], lang: str,
            page_shown: list[tuple[object, object]] | None = None, viewer=None,
            superseded: Callable[[], bool] | None = None) -> _Launched:
    """Build the package, evaluate its launch file once (:mod:`bras_kit.ros.evaluation`), say what
    started, run its own nodes in simulated time for their findings. The page reads that same
    evaluation: given ``page_shown``, it is opened as soon as the robot is known (before the
    checks), and (viewer, bus) is put in ``page_shown`` when its address is printed; given
    ``viewer`` (a rebuild), the open page shows the new evaluation. ``superseded`` (a rebuild) is
    asked once the build is evaluated and once the checks are in: true, :class:`_Superseded`."""
    import tempfile

    from ..core.errors import ParameterError
    from ..core.i18n import say
    from ..findings.data import merge_results
    from ..ros.evaluation import evaluate_launch
    from ..validate.package import Package
    from ..validate.package.launch_check import check_launch

    package = Package(args.target)
    pending, page = None, None
    if page_shown is not None:  # viser is imported while the package builds (see run: children_from_a_server)
        from concurrent.futures import ThreadPoolExecutor

        from ..core import backends

        pool = ThreadPoolExecutor(1, thread_name_prefix="bras-kit-page")
        pending = pool.submit(backends.viser)
        pool.shutdown(wait=False)  # the thread ends with its one task
    with tempfile.TemporaryDirectory(prefix="bras-kit-launch-") as base:
        from ..ros.workspace import build_others

        prefixes, unbuilt = build_others(getattr(args, "others", []), os.path.join(base, "install"))
        for name in unbuilt:
            from ._common import warn

            warn(M("the package {name} of the workspace does not build: launch files cannot find it "
                   "(bras-kit build says why)", name=name), lang)
        evaluation = evaluate_launch(args.target, os.path.join(base, "install"), launch_file, arguments, package,
                                     prefixes=tuple(prefixes))
        learners = _learners_install(os.path.join(base, "install"), getattr(args, "workspace", None))
        if superseded is not None and superseded():
            raise _Superseded  # built from files that are no longer the learner's: nothing said of it
        result = evaluation.launched
        plan = result.plan
        if result.build.failure is None and launch_file is not None and plan is None:
            from ..ros.launched import launch_sources, share_files_named

            share = os.path.join(result.build.prefix, "share", result.build.package)
            found = share_files_named(result.build, launch_file)
            if len(found) > 1:  # ros2launch's MultipleLaunchFilesError (ros2launch/api/api.py, Jazzy 58-63)
                raise ParameterError(
                    M("file '{file}' was found more than once in the share directory of package '{package}': "
                      "{paths}", file=launch_file, package=result.build.package, paths=found),
                    hint=M("give each launch file of the package its own name"))
            raise ParameterError(
                M("file '{file}' was not found in the share directory of package '{package}' which is at '{share}'",
                  file=launch_file, package=result.build.package, share=learners(share)),
                hint=M("the installed launch files are {names}; a new one needs colcon build (data_files)",
                       names=[os.path.basename(f) for f in launch_sources(result.build)] or "-"))
        nodes = []
        if result.build.failure is None and plan is not None:
            shown = result.launch_file
            print(say(M("ros2 launch {package} {file}", package=result.build.package,
                        file=os.path.basename(shown)), lang))
            for _delay, text, *_where in plan.logs:  # LogInfo actions, as ros2 launch prints them
                print(f"[INFO] [launch.user]: {for_terminal(learners(str(text)))}")  # the learner's text, made inert
            for node in plan.nodes:
                counterpart = COUNTERPARTS.get(node.package or "")
                if counterpart is not None:
                    print(say(M("[INFO] started {node} ({what}) -> {counterpart}", node=node.full_name,
                                what=node.shown, counterpart=say(counterpart, lang)), lang))
                elif node.package == result.build.package:
                    print(say(M("[INFO] started {node} ({what}) -> your node, run for {duration} s",
                                node=node.full_name, what=node.shown, duration=args.duration), lang))
                    nodes.append(node)
                else:
                    print(say(M("[INFO] started {node} ({what}): not simulated, nothing is shown for it",
                                node=node.full_name, what=node.shown), lang))
            if plan.failure is not None:
                print(for_terminal(learners(plan.ros2_launch_error)), file=sys.stderr)
            for _node, problem in result.problems:
                for line in problem.ros:
                    print(for_terminal(learners(line)), file=sys.stderr)
        if result.build.failure is None:  # at each build: a save the learner's colcon build has not seen
            _say_stale_install(args, result.build, lang)
        sys.stdout.flush()
        # the install tree's share folder: the robot's package:// meshes, as robot_state_publisher's
        package_paths = (os.path.join(result.build.prefix, "share"), os.path.dirname(os.path.abspath(args.target)))
        if pending is not None and page_shown is not None:  # the page first, the checks after
            pending.result()
            if evaluation.robot is not None:  # else no page: the terminal says why ROS shows no robot
                page = _open_page(args, evaluation, package_paths)
                _announce(args, page[0])
                page_shown.append(page)
        elif viewer is not None:
            viewer.show_launch(evaluation, package_paths)
        check_launch(evaluation, package, package_paths)
        evaluation.results = sorted(merge_results(evaluation.results, _node_results(args, nodes, evaluation.robot, evaluation.package)),
                                    key=lambda r: r.path)
        if superseded is not None and superseded():
            raise _Superseded  # the page waits ("checking") for the build of the files as saved now
        evaluation.checked = True  # the page shows them once the terminal has said them (run, _live)
    return _Launched(package, evaluation, nodes, page)


def _learners_install(install: str, workspace) -> Callable[[str], str]:
    """A text naming bras-kit's own install tree (a temporary folder) made to name the one the
    learner's colcon build makes: the workspace's install/, or install/ where colcon build is
    typed (ros2 launch's words, on the learner's machine)."""
    mine = install.rstrip(os.sep)
    theirs = workspace.install if workspace is not None else "install"
    return lambda text: text.replace(mine + os.sep, theirs + os.sep).replace(mine, theirs)


def _say_stale_install(args: argparse.Namespace, build, lang: str) -> None:
    """The workspace's install/ built before the last changes: ros2 launch reads that tree, never
    the sources, so it would still run the old files until colcon build is run again (the
    tutorial's "recompilez"); bras-kit launch builds them as they are now."""
    from ..ros.workspace import stale_install
    from ._common import warn

    workspace = getattr(args, "workspace", None)
    differ = stale_install(workspace, build.package, build.prefix)
    if not differ or workspace is None:
        return
    shown = [os.path.join("install", build.package, f) for f in differ[:3]] + (["..."] if len(differ) > 3 else [])
    warn(M("{install} was built before your last changes ({files}): ros2 launch would still use that old install "
           "until you run colcon build again in {root} (bras-kit launch builds the sources as they are now)",
           install=os.path.join(workspace.install, build.package), files=", ".join(shown), root=workspace.root), lang)


def _node_results(args: argparse.Namespace, nodes: list, robot, package: str):
    """Each of the package's own nodes run as bras-kit run runs it, in simulated time, against the
    robot robot_state_publisher loads: what it published, and its findings."""
    from ..core.errors import BrasKitError
    from ..core.i18n import current_language, say
    from ..findings.data import FileResult
    from ..run.findings import run_findings
    from ..run.node import run_node
    from ..run.report import summary

    lang = args.lang or current_language()
    from ..run.live import executables_of

    out = []
    executables, parameters = executables_of(nodes, package)
    for executable in executables:
        try:
            recording = run_node(args.target, executable, duration=args.duration, echo=False,
                                 parameters=parameters[executable], robot=robot, beside=getattr(args, "others", ()))
        except BrasKitError as exc:
            print(for_terminal(str(exc)), file=sys.stderr)
            continue
        for message in summary(recording):
            print("  " + say(message, lang))
        by_file: dict[str, list] = {}
        for found in run_findings(recording, robot, lang=lang, root=os.path.abspath(args.target)):
            by_file.setdefault(str(found.data.get("file", "")), []).append(found)
        out += [FileResult(os.path.join(args.target, file), found) for file, found in by_file.items()]
    return out


_rviz_fixed_frame = rviz_fixed_frame  # the evaluation's reading (kept under its old name)


def _open_page(args: argparse.Namespace, evaluation, package_paths: tuple[str, ...]):
    """The launch in the browser: the evaluation's robot (robot_state_publisher's), findings, Fixed
    Frame and slider window, and the bus open for 'bras-kit run' beside it. Returns (viewer, bus).
    Nothing is said yet (:func:`_announce`)."""
    from ..core.errors import BrasKitError
    from ..ros.bus import Bus
    from ..view import Source, Viewer

    viewer = Viewer(Source(robot=evaluation.robot, package_paths=package_paths), port=args.port, lang=args.lang,
                    watch=False, launch=evaluation)
    if viewer.rviz_state is not None:  # Save Config in the page: the terminal says what makes the launch use it
        viewer.rviz_state.on_saved = lambda relative, package: _print_rviz_lines(relative, package, args.lang)
    viewer.on_publishing = lambda publishing: _print_publishing(publishing, args.lang)
    try:
        bus: Bus | None = Bus.listen()
    except BrasKitError as exc:  # no Zenoh: the launch is shown, bras-kit run cannot publish into it
        from ._common import warn

        warn(exc, args.lang)
        bus = None
    if bus is not None:
        from ..ros.bus import LaunchRobot

        bus.on_joint_state(lambda state: viewer.show_joint_state(state.name, state.position))
        # a run asks which joints the page moves, and names those it publishes that are not among them
        bus.offer_robot(lambda: LaunchRobot(evaluation.package, tuple(viewer.model.tree.dof)))
    return viewer, bus


def _print_rviz_lines(relative: str, package: str, lang: str | None) -> None:
    """After Save Config: the data_files entry that installs the file, and the rviz2 argument that
    loads it (RViz reads -d, rviz2's --display-config)."""
    from ..core.i18n import say

    name = os.path.basename(relative)
    print(say(M("{file} saved. For ros2 launch to open RViz with it, add to setup.py's data_files:",
                file=relative), lang), file=sys.stderr)
    print("    (os.path.join('share', package_name, 'rviz'), glob('rviz/*.rviz')),", file=sys.stderr)
    print(say(M("and to the rviz2 Node of the launch file:"), lang), file=sys.stderr)
    print(f"    arguments=['-d', os.path.join(get_package_share_directory('{for_terminal(package)}'), 'rviz', "
          f"'{for_terminal(name)}')],", file=sys.stderr)
    print(say(M("then build again (colcon build) and launch again."), lang), file=sys.stderr, flush=True)


def _print_publishing(publishing: bool, lang: str | None) -> None:
    """A node beside the launch (bras-kit run, as ros2 run) started or stopped publishing
    /joint_states: the page lists BK620 only while none does, and the terminal says so."""
    from ..core.i18n import say

    print(say(M("BK620 does not hold while it runs: a node beside the launch publishes /joint_states (the page "
                "no longer lists it)") if publishing else
              M("BK620 holds again: nothing publishes /joint_states any more (the page lists it again)"), lang),
          file=sys.stderr, flush=True)


def _close(viewer, bus) -> None:
    if bus is not None:
        bus.close()
    viewer.stop()


def _announce(args: argparse.Namespace, viewer) -> None:
    from ..core.i18n import say

    print(say(M("bras-kit launch: {url} (Ctrl-C to stop)", url=viewer.url), args.lang), flush=True)
    print(say(M("'bras-kit run {folder}' in another terminal moves this arm, as ros2 run beside ros2 launch",
                folder=getattr(args, "typed", args.target)), args.lang), file=sys.stderr, flush=True)
    from ._common import open_page

    open_page(viewer.url, args)


def _live(args: argparse.Namespace, launch_file: str | None, arguments: dict[str, str], lang: str,
          launched: _Launched, viewer) -> int:
    """The package's own nodes live in the page until Ctrl-C; a file of the package saved: built
    and launched again, one evaluation printed and shown (robot, Fixed Frame, sliders, checks, nodes)."""
    from ..core.errors import BrasKitError
    from ..core.i18n import say
    from ..findings.report import format_text
    from ..run.live import LiveNodes, changed_files, executables_of, package_stamps

    nodes = LiveNodes(args.target, [], viewer.show_joint_state)

    def start(current: _Launched) -> None:
        nonlocal nodes
        started = current.result.build.failure is None and current.plan is not None and current.plan.failure is None
        names, parameters = executables_of(current.nodes, current.result.build.package) if started else ([], {})
        nodes = LiveNodes(args.target, names, viewer.show_joint_state, parameters, lang,
                          beside=getattr(args, "others", ()))
        nodes.start()  # a Ctrl-C while they start still finds them in ``nodes``

    stamps = getattr(args, "stamps", None) or package_stamps(args.target)
    saved: list[str] = []

    def changed() -> bool:
        """Whether a file of the package was saved since ``stamps`` (then ``saved`` names them and
        ``stamps`` is what the next build reads). Save Config's own file is no save."""
        nonlocal stamps
        now = package_stamps(args.target, before=stamps)
        written = viewer.rviz_state.written if viewer.rviz_state is not None else set()
        files = changed_files(stamps, now)
        saved[:] = [p for p in files if os.path.abspath(p) not in written]
        written.difference_update(os.path.abspath(p) for p in files)
        stamps = now
        return bool(saved)

    def say_saved(message) -> None:
        names = ", ".join(os.path.relpath(p, args.target) for p in saved[:3])
        print(say(message(names, min(len(saved), 3)), lang), file=sys.stderr, flush=True)

    try:
        start(launched)
        while True:
            saved.clear()
            viewer.wait(until=changed)
            if not saved:  # Ctrl-C
                break
            nodes.stop()
            say_saved(lambda files, n: Mn("{files} saved: the package is built and launched again",
                                          "{files} saved: the package is built and launched again", n, files=files))
            relaunched = None
            while relaunched is None:
                try:
                    # a save while it builds: that build is dropped and the package built again,
                    # so the last save always wins (stamps are never taken after the build: what
                    # was saved during it is a save)
                    relaunched = _launch(args, launch_file, arguments, lang, viewer=viewer, superseded=changed)
                except _Superseded:
                    say_saved(lambda files, n: Mn(
                        "{files} saved during the build: the package is built and launched again",
                        "{files} saved during the build: the package is built and launched again", n, files=files))
                except BrasKitError as exc:
                    print(say(exc.message, lang), file=sys.stderr, flush=True)
                    break
            if relaunched is None:
                nodes = LiveNodes(args.target, [], viewer.show_joint_state)
                continue
            sys.stdout.write(format_text(relaunched.results, lang))
            sys.stdout.flush()
            viewer.show_checks()  # once the terminal has said them, as the first time
            start(relaunched)
    except KeyboardInterrupt:  # during a rebuild: the same stop as during the wait
        pass
    finally:
        nodes.stop()  # the page is closed by run
    return 0
