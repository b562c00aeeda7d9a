"""bras-kit run: the learner's node, with no ROS install (the counterpart of ``ros2 run PKG EXE``)."""

from __future__ import annotations

import argparse
import os
import signal
import sys

from ..core.message import M
from ._common import add_force_argument, check_writable, warn

_EPILOG = """\
The node's main() runs in a child process, against bras-kit's stand-in for rclpy, on a
simulated clock: timers fire and time.sleep() waits in simulated time, so 10 s of node time
take a fraction of a second. Every message it publishes is recorded; what it published on
/joint_states is checked against the robot (names, limits, stamps, rate). The node's code
runs for real: it is limited in CPU time, memory and wall-clock time, in a temporary folder.
The real thing is 'ros2 run PKG EXE' on a ROS 2 machine.

PKG is a package of the colcon workspace the command is typed in (its root, e.g.
~/ros2_cellule_ws, or any folder below it), by the name in its package.xml; the workspace's other
packages are built beside it. A package folder or a node's .py file works too.

Beside a 'bras-kit launch' of the same user on the same ROS_DOMAIN_ID (default 0), a run with
none of -o, --gif, --json and --duration is live: it joins that launch, publishes on the wall
clock and moves its page until Ctrl-C, as 'ros2 run' beside 'ros2 launch'. Any of them makes it a
batch run: simulated time, as fast as it can, the page left alone.

examples (in ~/ros2_cellule_ws or a folder below it):
  bras-kit run bras_description animation            10 s of node time; beside a launch, live until Ctrl-C
  bras-kit run bras_description animation --duration 5 -o states.csv
  bras-kit run src/bras_description/bras_description/animation.py --gif arm.gif
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = _EPILOG
    parser.add_argument("target", nargs="?", default=".", metavar="PKG|PKG_DIR|FILE.py",
                        help="a package of the colcon workspace you are in, by name, a package folder (with "
                             "setup.py), or the node's .py file (default: .)")
    parser.add_argument("executable", nargs="?", metavar="EXECUTABLE",
                        help="a name of setup.py's console_scripts (default: the only one)")
    parser.add_argument("--duration", type=float, default=None, metavar="S",
                        help="of simulated time the node runs for (default: 10; beside a bras-kit launch, live until Ctrl-C)")
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="what /joint_states carried (.csv, .json or a ROS 2 bag .mcap, like bras-kit motion)")
    parser.add_argument("--gif", metavar="FILE", help="the arm moved by the node")
    parser.add_argument("--urdf", metavar="FILE",
                        help="the robot the node drives (default: the package's urdf/ file)")
    parser.add_argument("--quiet", action="store_true", help="do not show the node's logs and prints")
    parser.add_argument("-p", "--param", dest="params", action="append", default=[], metavar="NAME:=VALUE",
                        help="a parameter the node declares, as 'ros2 run ... --ros-args -p NAME:=VALUE' gives it")
    parser.add_argument("--json", action="store_true", help="the findings")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..core.i18n import current_language, say
    from ..findings.report import exit_code, format_json, format_text
    from ..motion.states_io import check_states_output
    from ..run.node import DEFAULT_DURATION, parse_parameters, run_node
    from ..run.report import failure_lines, summary
    from ..trust.contain import uncontained_note

    lang = args.lang
    args.typed = args.target
    beside = _resolve(args)
    if args.output is not None:
        check_states_output(args.output, args.force)
    if args.gif is not None:
        check_writable(args.gif, args.force, option="--gif")
    parameters = parse_parameters(args.params)
    robot = _robot(args)  # a wrong --urdf fails before the node runs
    note = uncontained_note()
    if note is not None:
        print(say(note, lang), file=sys.stderr)
    batch = args.output is not None or args.gif is not None or args.json or args.duration is not None
    bus = None if batch else _join(lang)
    if bus is not None:
        return _run_live(args, bus, parameters, robot, beside)
    if batch:
        _say_launch_left_alone(lang)
    duration = DEFAULT_DURATION if args.duration is None else args.duration
    recording = run_node(args.target, args.executable, duration=duration, echo=not args.quiet,
                         parameters=parameters, robot=robot, beside=beside)
    for message in summary(recording):
        print(say(message, lang), file=sys.stderr)
    for text in failure_lines(recording):
        print(text, file=sys.stderr)
    results = _results(recording, robot, args)
    if args.json:
        sys.stdout.write(format_json(results, lang=lang))
    else:
        sys.stdout.write(format_text(results, lang or current_language()))
    if args.output is not None:
        _write_states(recording, robot, args)
    if args.gif is not None:
        _write_gif(recording, robot, args)
    return exit_code(results)


def _resolve(args: argparse.Namespace) -> list[str]:
    """``args.target`` made the package folder it names (a node's .py file stays as it is): the
    other package folders of its workspace, built beside it, are returned."""
    if os.path.isfile(args.target):
        return []
    from ..ros.workspace import others, resolve_package

    args.target, workspace = resolve_package(args.target)
    return others(workspace, args.target)


def _join(lang: str | None):
    """The bus of the launches of this user on this ROS domain, or None when none is open (or
    Zenoh is missing: said, and the run is a batch run)."""
    from ..core.errors import BrasKitError, ParameterError
    from ..ros.bus import Bus

    try:
        return Bus.connect()
    except ParameterError:
        raise  # a ROS_DOMAIN_ID rcl refuses too
    except BrasKitError as exc:
        warn(exc, lang)
        return None


def _say_launch_left_alone(lang: str | None) -> None:
    """A batch run beside an open launch: said, so that a page that stays still is no surprise."""
    from ..core.errors import BrasKitError
    from ..core.i18n import say
    from ..ros.bus import listening

    try:
        open_now = listening()
    except BrasKitError:
        return  # a bad ROS_DOMAIN_ID does not concern a batch run
    if open_now:
        print(say(M("a bras-kit launch is open on this ROS domain: this run, with -o, --gif, --json or --duration, "
                    "runs in simulated time and leaves its page alone (without them it joins it, live)"), lang),
              file=sys.stderr, flush=True)


def _stop_on_sigterm():
    """SIGTERM ends a live run as Ctrl-C does (rclpy's signal handlers take both by default:
    rclpy/signals.py, SignalHandlerOptions.ALL); the handler it replaces is returned."""
    def interrupt(_number, _frame):
        raise KeyboardInterrupt

    return signal.signal(signal.SIGTERM, interrupt)


def _run_live(args: argparse.Namespace, bus, parameters, robot, beside: list[str]) -> int:
    """The node live beside the open launches, until Ctrl-C (or until it ends by itself), as
    ``ros2 run`` beside ``ros2 launch``: each JointState goes onto the bus as it is published; a
    joint the page's robot does not have is named once."""
    import time

    from ..core.i18n import say
    from ..ros.bus import domain_id, unknown_joints
    from ..run.node import MAX_DURATION, run_node
    from ..run.report import ending, failure_lines

    lang = args.lang
    robots = bus.robots()
    print(say(M("joined the running bras-kit launch (ROS domain {domain}): publishing /joint_states on the wall "
                "clock until Ctrl-C, as ros2 run", domain=domain_id()), lang), file=sys.stderr, flush=True)
    warned: set[tuple[object, tuple[str, ...]]] = set()
    from ..run.live_limits import LimitWatch

    watch = LimitWatch(robot)
    began = time.monotonic()

    def deliver(state) -> None:
        names = tuple(state.name)
        for violation in watch.see(names, [float(p) for p in state.position], time.monotonic() - began):
            # as RViz shows it: robot_state_publisher places the link at the angle sent, past the limit
            words = dict(joint=violation.joint, value=round(violation.value, 4), unit=violation.unit,
                         time=round(violation.time, 2), bound=violation.bound)
            warn(M("joint '{joint}' was sent {value} {unit} at t = {time} s, above its upper limit {bound} (BK649): "
                   "the summary at Ctrl-C says how often", **words) if violation.side == "upper" else
                 M("joint '{joint}' was sent {value} {unit} at t = {time} s, below its lower limit {bound} (BK649): "
                   "the summary at Ctrl-C says how often", **words), lang)
        for shown in robots:
            missing = unknown_joints(list(names), shown)
            if missing and (shown, names) not in warned:
                warned.add((shown, names))
                warn(M("the node publishes joints {names} that the robot of the launch of {package} does not have "
                       "(its joints: {joints}): its page does not move them", names=missing, package=shown.package,
                       joints=list(shown.joints)), lang)
        bus.publish_joint_state(state)

    built: list[int] = []  # the exit code setup.py's findings give (BK639), once the package is built

    def show_build(blocked) -> None:
        from ..core.i18n import current_language
        from ..findings.report import exit_code, format_text

        results = _file_results({}, blocked, args)
        built.append(exit_code(results) if results else 0)
        if results:  # before the node's own output, as a batch run lists them (at the end)
            sys.stdout.write(format_text(results, lang or current_language()))
            sys.stdout.flush()

    started = time.monotonic()
    previous = _stop_on_sigterm()
    try:
        recording = run_node(args.target, args.executable, duration=MAX_DURATION, echo=not args.quiet,
                             parameters=parameters, live=True, keep=False, on_joint_state=deliver, robot=robot,
                             beside=beside, on_built=show_build)
    except KeyboardInterrupt:
        print(say(M("stopped by Ctrl-C after {seconds} s", seconds=round(time.monotonic() - started, 1)), lang),
              file=sys.stderr, flush=True)
        return max(_say_past_limits(args, robot, watch), *built)
    finally:
        signal.signal(signal.SIGTERM, previous)
        bus.close()
    print(say(M("the node {ending}", ending=ending(recording)), lang), file=sys.stderr)
    for text in failure_lines(recording):
        print(text, file=sys.stderr)
    return max(1 if recording.failure is not None else 0, _say_past_limits(args, robot, watch), *built)


def _say_past_limits(args: argparse.Namespace, robot, watch) -> int:
    """A live run's summary of the angles past the limits, as BK649 findings at the line that sets
    msg.position (a batch run's words and place); its exit code (1 when there are any)."""
    from ..core.errors import BrasKitError
    from ..core.i18n import current_language
    from ..findings.data import finding
    from ..findings.registry import RULES
    from ..findings.report import exit_code, format_text
    from ..ros.locate import locate
    from ..validate.package.run_rules import field_line, past_limits_hits

    violations = watch.violations()
    if not violations:
        return 0
    try:
        target = locate(args.target, args.executable)
        path, root = target.path, target.root
    except BrasKitError:  # it ran, so it is found; never a traceback at Ctrl-C
        return 1
    shown = os.path.relpath(path, root)
    found = [finding(RULES["BK649"], hit) for hit in past_limits_hits(robot, violations, shown,
                                                                      field_line(path, root, "position"))]
    results = _file_results({shown: found}, [], args)
    sys.stdout.write(format_text(results, args.lang or current_language()))
    sys.stdout.flush()
    return exit_code(results)


def _robot(args: argparse.Namespace):
    """The robot the findings and the GIF use: --urdf, else the package's, else the built-in
    tutorial arm (a lone node file is written for it), said on stderr."""
    from ..model.authoring import arm
    from ..run.node import robot_of

    robot = robot_of(args.target, args.urdf)
    if robot is None:
        warn(M("no robot description beside the node: checked against the built-in tutorial arm "
               "(give yours with --urdf FILE)"))
        robot = arm()
    return robot


def _results(recording, robot, args):
    """The run rules' findings as the validator's per-file results, paths under the target; with
    them, what the package's setup.py tried that its walls stopped (BK639, as ``bras-kit build``
    shows it)."""
    from ..run.findings import run_findings

    by_file: dict[str, list] = {}
    target = os.path.abspath(args.target)
    for found in run_findings(recording, robot, lang=args.lang,
                              root=target if os.path.isdir(target) else os.path.dirname(target)):
        by_file.setdefault(str(found.data.get("file") or recording.source), []).append(found)
    if not by_file:
        by_file[recording.source] = []
    return _file_results(by_file, recording.build_blocked, args)


def _file_results(by_file, blocked, args):
    """``by_file`` (findings by file, under the target) with what setup.py tried that its walls
    stopped (``blocked``: BK639), as per-file results in name order."""
    from ..findings.data import FileResult, finding
    from ..findings.registry import RULES
    from ..validate.package.build_reach import setup_blocked_hits

    for hit in setup_blocked_hits(blocked):
        by_file.setdefault(str(hit.params["file"]), []).append(finding(RULES["BK639"], hit))
    base = args.target if os.path.isdir(args.target) else os.path.dirname(args.target)
    return [FileResult(os.path.join(base, file), findings) for file, findings in sorted(by_file.items())]


def _write_states(recording, robot, args) -> None:
    """What /joint_states carried, through the one joint-state writer (CSV, JSON or a ROS 2 bag;
    a bag holds the robot's joints in its order, as robot_state_publisher would have them)."""
    from ..core.errors import BrasKitError
    from ..core.i18n import say
    from ..motion.states_io import states_format, write_states
    from ..ros.recording import joint_states, states_for

    if states_format(args.output) == "bag":
        from ..kinematics.frames import tf_tree

        states = states_for(recording, tf_tree(robot).dof)
    else:
        states = joint_states(recording)
    if not len(states):
        raise BrasKitError(M("nothing was published on /joint_states: no joint states to write"))
    if states_format(args.output) == "bag" and robot is None:
        raise BrasKitError(M("a ROS 2 bag holds the robot (/robot_description, /tf): the package has no urdf/ file"),
                           hint=M("give one with --urdf FILE"))
    from ..ros.recording import sent_joint_states

    # the JSON and the bag hold /joint_states as the node sent it (no velocity filled in, its own stamps)
    written = write_states(robot, states, args.output, args.force, sent=sent_joint_states(recording))
    if written is not None:
        print(say(written, args.lang), file=sys.stderr)


def _write_gif(recording, robot, args) -> None:
    import numpy as np

    from ..core.i18n import say
    from ..core.message import Mn
    from ..kinematics.frames import tf_tree
    from ..motion.core import JointStates
    from ..render import render_motion
    from ..render.sequence import save_gif
    from ..ros.recording import states_for
    from ..trust.outputs import staged

    states = states_for(recording, tf_tree(robot).dof)
    if not len(states):  # one picture of the arm at rest, as RViz shows it with nothing on /joint_states
        warn(M("nothing was published on /joint_states: the GIF shows the arm at rest"))
        states = JointStates(np.zeros(1), states.names, np.zeros((1, len(states.names))),
                             np.zeros((1, len(states.names))))
    fps = _fps(states.times)
    frames = render_motion(robot, states, label="rendering")
    with frames, staged(args.gif, args.force, option="--gif") as temporary:
        count = save_gif(frames, temporary, fps)
    print(say(Mn("wrote {path}: {n} frame at {fps} fps", "wrote {path}: {n} frames at {fps} fps", count,
                 path=args.gif, fps=fps)), file=sys.stderr)


def _fps(times) -> float:
    import numpy as np

    if len(times) < 2:
        return 20.0
    step = float(np.median(np.diff(times)))
    return float(min(50.0, max(1.0, round(1.0 / step, 3)))) if step > 0 else 20.0
