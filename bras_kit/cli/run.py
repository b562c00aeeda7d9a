"""bras-kit run: the learner's node, with no ROS install (the counterpart of ``ros2 run PKG EXE``)."""

from __future__ import annotations

import argparse
import os
import sys

from ._common import add_force_argument, check_writable, warn, write_text

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
                        help="write what /joint_states carried (.csv or .json, like bras-kit motion)")
    parser.add_argument("--gif", metavar="FILE", help="draw the arm moved by the node as a GIF")
    parser.add_argument("--urdf", metavar="FILE",
                        help="the robot the node drives (default: the package's urdf/ file)")
    parser.add_argument("--quiet", action="store_true", help="do not show the node's logs and prints")
    parser.add_argument("--json", action="store_true", help="print the findings as JSON")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..errors import ParameterError
    from ..i18n import say
    from ..run import run_node
    from ..run.report import failure_lines, summary

    lang = args.lang
    if args.output is not None and os.path.splitext(args.output)[1].lower() not in (".csv", ".json"):
        raise ParameterError(f"-o: cannot tell the format of '{args.output}'",
                             hint="end the file name in .csv or .json")
    for path, option in ((args.output, "-o"), (args.gif, "--gif")):
        if path is not None:
            check_writable(path, args.force, option=option)
    recording = run_node(args.target, args.executable, duration=args.duration, echo=not args.quiet)
    for message in summary(recording):
        print(say(message, lang), file=sys.stderr)
    for text in failure_lines(recording):
        print(text, file=sys.stderr)
    robot = _robot(args)
    findings = _findings(recording, robot, lang)
    _print_findings(findings, recording, args)
    if args.output is not None:
        _write_states(recording, robot, args)
    if args.gif is not None:
        _write_gif(recording, robot, args)
    return 1 if any(f.severity == "error" for f in findings) else 0


def _robot(args: argparse.Namespace):  # type: ignore[no-untyped-def]
    from ..run.findings import robot_of

    return robot_of(args.target, args.urdf)


def _findings(recording, robot, lang):  # type: ignore[no-untyped-def]
    from ..run.findings import run_findings

    return run_findings(recording, robot, lang=lang)


def _print_findings(findings, recording, args) -> None:  # type: ignore[no-untyped-def]
    import json

    if args.json:
        print(json.dumps([f.as_dict() | {"path": f.data.get("file") or recording.source} for f in findings],
                         ensure_ascii=False, indent=1))
        return
    for finding in findings:
        where = str(finding.data.get("file") or recording.source) + (f":{finding.line}" if finding.line else "")
        print(f"{where}: {finding.code} {finding.severity}: {finding.message}")
        if finding.hint:
            print(f"    {finding.hint}")


def _write_states(recording, robot, args) -> None:  # type: ignore[no-untyped-def]
    from ..errors import BrasKitError
    from ..message import M
    from ..motion.states_io import states_to_csv, states_to_json
    from ..run import joint_states

    states = joint_states(recording)
    if not len(states):
        raise BrasKitError(M("nothing was published on /joint_states: no joint states to write"))
    text = states_to_json(states) if args.output.lower().endswith(".json") else states_to_csv(states)
    write_text(args.output, text, args.force)


def _write_gif(recording, robot, args) -> None:  # type: ignore[no-untyped-def]
    from ..errors import BrasKitError
    from ..i18n import say
    from ..kinematics import tf_tree
    from ..message import M
    from ..outputs import staged
    from ..render import render_motion
    from ..render.sequence import save_gif
    from ..run.recording import states_for

    if robot is None:
        raise BrasKitError(M("no robot to draw: the package has no urdf/ file"), hint=M("give one with --urdf FILE"))
    states = states_for(recording, tf_tree(robot).dof)
    if not len(states):
        warn(M("nothing was published on /joint_states: the GIF shows the arm at rest"))
    fps = _fps(states.times)
    frames = render_motion(robot, states if len(states) else None, label="rendering")
    with frames, staged(args.gif, args.force, option="--gif") as temporary:
        count = save_gif(frames, temporary, fps)
    print(say(M("wrote {path}: {n} frames at {fps} fps", path=args.gif, n=count, fps=fps)), file=sys.stderr)


def _fps(times) -> float:  # type: ignore[no-untyped-def]
    import numpy as np

    if len(times) < 2:
        return 20.0
    step = float(np.median(np.diff(times)))
    return float(min(50.0, max(1.0, round(1.0 / step, 3)))) if step > 0 else 20.0
