"""bras-kit run: the learner's node, with no ROS install (the counterpart of ``ros2 run PKG EXE``)."""

from __future__ import annotations

import argparse
import os
import sys

from ..message import M
from ._common import add_force_argument, check_writable, warn

_EPILOG = """\
The node's main() runs in a child process, against bras-kit's stand-in for rclpy, on a
simulated clock: timers fire and time.sleep() waits in simulated time, so 10 s of node time
take a fraction of a second. Every message it publishes is recorded; what it published on
/joint_states is checked against the robot (names, limits, stamps, rate). The node's code
runs for real: it is limited in CPU time, memory and wall-clock time, in a temporary folder.
The real thing is 'ros2 run PKG EXE' on a ROS 2 machine.

examples:
  bras-kit run bras_description                      the package's only executable, 10 s
  bras-kit run bras_description animation --duration 5 -o states.csv
  bras-kit run bras_description/bras_description/animation.py --gif arm.gif
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = _EPILOG
    parser.add_argument("target", nargs="?", default=".", metavar="PKG_DIR|FILE.py",
                        help="the package folder (with setup.py), or the node's .py file (default: .)")
    parser.add_argument("executable", nargs="?", metavar="EXECUTABLE",
                        help="a name of setup.py's console_scripts (default: the only one)")
    parser.add_argument("--duration", type=float, default=10.0, metavar="S",
                        help="seconds of simulated time to run the node for (default: 10)")
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="write what /joint_states carried (.csv, .json or a ROS 2 bag .mcap, like bras-kit motion)")
    parser.add_argument("--gif", metavar="FILE", help="draw the arm moved by the node as a GIF")
    parser.add_argument("--urdf", metavar="FILE",
                        help="the robot the node drives (default: the package's urdf/ file)")
    parser.add_argument("--quiet", action="store_true", help="do not show the node's logs and prints")
    parser.add_argument("-p", "--param", dest="params", action="append", default=[], metavar="NAME:=VALUE",
                        help="a value for a parameter the node declares, as 'ros2 run ... --ros-args -p "
                        "NAME:=VALUE' gives it (repeatable)")
    parser.add_argument("--json", action="store_true", help="print the findings as JSON")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..i18n import current_language, say
    from ..motion.states_io import check_states_output
    from ..run import parse_parameters, run_node, uncontained_note
    from ..run.report import failure_lines, summary
    from ..validate.report import exit_code, format_json, format_text

    lang = args.lang
    if args.output is not None:
        check_states_output(args.output, args.force)
    if args.gif is not None:
        check_writable(args.gif, args.force, option="--gif")
    parameters = parse_parameters(args.params)
    robot = _robot(args)  # a wrong --urdf fails before the node runs
    note = uncontained_note()
    if note is not None:
        print(say(note, lang), file=sys.stderr)
    from ..ros.bus import listening

    live = listening()  # a bras-kit launch runs on this machine: publish into it, on the wall clock
    if live:
        print(say(M("publishing /joint_states to the running bras-kit launch, on the wall clock"), lang),
              file=sys.stderr, flush=True)
    recording = run_node(args.target, args.executable, duration=args.duration, echo=not args.quiet,
                         parameters=parameters, live=live, robot=robot)
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


def _robot(args: argparse.Namespace):  # type: ignore[no-untyped-def]
    """The robot the findings and the GIF use: --urdf, else the package's, else the built-in
    tutorial arm (a lone node file is written for it), said on stderr."""
    from ..authoring import arm
    from ..run.findings import robot_of

    robot = robot_of(args.target, args.urdf)
    if robot is None:
        warn(M("no robot description beside the node: checked against the built-in tutorial arm "
               "(give yours with --urdf FILE)"))
        robot = arm()
    return robot


def _results(recording, robot, args):  # type: ignore[no-untyped-def]
    """The run rules' findings as the validator's per-file results, paths under the target."""
    from ..run.findings import run_findings
    from ..validate.findings import FileResult

    base = args.target if os.path.isdir(args.target) else os.path.dirname(args.target)
    by_file: dict[str, list] = {}  # type: ignore[type-arg]
    for finding in run_findings(recording, robot, lang=args.lang):
        by_file.setdefault(str(finding.data.get("file") or recording.source), []).append(finding)
    if not by_file:
        by_file[recording.source] = []
    return [FileResult(os.path.join(base, file), findings) for file, findings in sorted(by_file.items())]


def _write_states(recording, robot, args) -> None:  # type: ignore[no-untyped-def]
    """What /joint_states carried, through the one joint-state writer (CSV, JSON or a ROS 2 bag;
    a bag holds the robot's joints in its order, as robot_state_publisher would have them)."""
    from ..errors import BrasKitError
    from ..i18n import say
    from ..motion.states_io import states_format, write_states
    from ..ros.recording import states_for
    from ..run import joint_states

    if states_format(args.output) == "bag":
        from ..kinematics import tf_tree

        states = states_for(recording, tf_tree(robot).dof)
    else:
        states = joint_states(recording)
    if not len(states):
        raise BrasKitError(M("nothing was published on /joint_states: no joint states to write"))
    if states_format(args.output) == "bag" and robot is None:
        raise BrasKitError(M("a ROS 2 bag holds the robot (/robot_description, /tf): the package has no urdf/ file"),
                           hint=M("give one with --urdf FILE"))
    written = write_states(robot, states, args.output, args.force)
    if written is not None:
        print(say(written, args.lang), file=sys.stderr)


def _write_gif(recording, robot, args) -> None:  # type: ignore[no-untyped-def]
    import numpy as np

    from ..i18n import say
    from ..kinematics import tf_tree
    from ..message import Mn
    from ..motion.core import JointStates
    from ..outputs import staged
    from ..render import render_motion
    from ..render.sequence import save_gif
    from ..ros.recording import states_for

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


def _fps(times) -> float:  # type: ignore[no-untyped-def]
    import numpy as np

    if len(times) < 2:
        return 20.0
    step = float(np.median(np.diff(times)))
    return float(min(50.0, max(1.0, round(1.0 / step, 3)))) if step > 0 else 20.0
