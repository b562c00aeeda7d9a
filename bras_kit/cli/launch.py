"""bras-kit launch: what ``ros2 launch PKG FILE`` does, on the package built as colcon builds it."""

from __future__ import annotations

import argparse
import os
import sys
from typing import Any

from ..core.message import M
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
    parser.add_argument("--json", action="store_true", help="the findings as JSON on standard output (what started goes to standard error)")
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


def run(args: argparse.Namespace) -> int:
    from ..core.i18n import current_language
    from ..launcher import Reporter, prepare

    lang = args.lang or current_language()
    launch_file, arguments = _split(args.items)
    # a folder, or a name in the workspace; the workspace's other packages are built beside it, as colcon builds them all
    request = prepare(args.target, launch_file, arguments, duration=args.duration, lang=lang)
    # --json: standard output is the report alone (what started goes to standard error)
    reporter = Reporter(lang, out=sys.stderr if args.json else None)
    if args.no_page:
        from ..launcher import launch

        return _report(args, launch(request, reporter=reporter).results, lang)
    from ..trust.contain import available as containable
    from ..trust.sandbox import children_from_a_server

    # With a page, threads run beside the package's children (the page's, viser's, Zenoh's): the
    # children that can be sent to it are forked by a server started now, before any thread exists
    # (a child forked while a thread imports a module could wait forever for its lock); its probe
    # too, a throwaway child, runs now.
    containable()
    from ..run.live import package_stamps

    # the files as the first build reads them: a save during that build (or its checks) is a save
    stamps = package_stamps(request.folder)
    shown: list[tuple[Any, Any]] = []  # (viewer, bus), once the page's address is printed
    with children_from_a_server():
        try:
            launched = _launch_with_page(args, request, reporter, shown)
            code = _report(args, launched.results, lang)
            if shown:  # the terminal first: a Ctrl-C as the page shows them loses nothing
                shown[0][0].show_checks()
            if launched.description is None:
                return code
            if not shown:  # no robot file the page could show
                return 0
            from ..launcher import live

            live(request, launched, shown[0][0], reporter, stamps)
            return 0
        except KeyboardInterrupt:
            if not shown:
                raise  # before the address: interrupted, as any command
            return 0  # Ctrl-C once the address is out (checks or a rebuild under way too): the stop it announced
        finally:
            if shown:
                _close(*shown[0])


def _launch_with_page(args: argparse.Namespace, request: Any, reporter: Any, shown: list[tuple[Any, Any]]) -> Any:
    """The launch, its page opened as soon as the robot is known (before the checks): (viewer,
    bus) is put in ``shown`` when its address is printed. viser is imported while the package
    builds (see run: children_from_a_server)."""
    from concurrent.futures import ThreadPoolExecutor

    from ..core import backends
    from ..launcher import launch

    pool = ThreadPoolExecutor(1, thread_name_prefix="bras-kit-page")
    pending = pool.submit(backends.viser)
    pool.shutdown(wait=False)  # the thread ends with its one task

    def open_when_evaluated(evaluation: Any, package_paths: tuple[str, ...]) -> None:
        pending.result()
        if evaluation.robot is not None:  # else no page: the terminal says why ROS shows no robot
            page = _open_page(args, evaluation, package_paths)
            _announce(args, page[0], request.typed)
            shown.append(page)

    return launch(request, reporter=reporter, on_evaluated=open_when_evaluated)


def _report(args: argparse.Namespace, results: list[Any], lang: str) -> int:
    """The findings printed (text or JSON); the exit code they give."""
    from ..findings.report import exit_code, format_json, format_text

    if args.json:
        sys.stdout.write(format_json(results, lang=lang))
    else:
        sys.stdout.write(format_text(results, lang))
    sys.stdout.flush()
    return exit_code(results)


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


def _announce(args: argparse.Namespace, viewer: Any, typed: str) -> None:
    """The page's address, and how to move its arm (``typed``: the package as the learner named it)."""
    from ..core.i18n import say

    print(say(M("bras-kit launch: {url} (Ctrl-C to stop)", url=viewer.url), args.lang), flush=True)
    print(say(M("'bras-kit run {folder}' in another terminal moves this arm, as ros2 run beside ros2 launch",
                folder=typed), args.lang), file=sys.stderr, flush=True)
    from ._common import open_page

    open_page(viewer.url, args)
