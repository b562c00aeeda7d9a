"""bras-kit simulate: the arm under gravity in MuJoCo, motors limited by <limit effort>.

Prints, per joint, the tracking error, the peak torque, the share of time at the torque limit
and, in plain words, which motor is too weak. Writes the measured joint states (CSV/JSON with an
``effort`` column), a GIF drawn by bras-kit's own renderer and a torque/tracking plot.
"""

from __future__ import annotations

import argparse
import sys

from ..core.errors import BrasKitError, ParameterError, os_reason
from ..core.i18n import labelled, say
from ..core.message import M
from ._common import (
    add_force_argument,
    add_model_arguments,
    add_topic_argument,
    check_writable,
    joint_values,
    load_model,
    warn_motion_notes,
)

NUDGE = 0.05  # rad: the upright arm is balanced at 0; motors off, it needs a push to fall

_EPILOG = """\
control:
  none         motors off: the arm falls from --set and comes to rest on its limits (or the floor)
  pd           motors follow the motion: torque = kp (target - q) + kd (target speed - speed),
               clipped to each joint's <limit effort>
  pd+gravity   the same plus gravity compensation (inside the same effort clip)

examples:
  bras-kit simulate --inertials                                 track the tutorial's sine
  bras-kit simulate --inertials --control none --gif fall.gif   drop the arm
  bras-kit simulate --inertials --param epaule_effort=2          the shoulder is too weak
  bras-kit simulate --inertials --control pd+gravity -o states.csv --plot torques.png
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = _EPILOG
    add_model_arguments(parser)
    parser.add_argument("-m", "--motion", action="append", default=[], metavar="SPEC",
                        help="a waypoint file; default: tutorial")
    add_topic_argument(parser)
    parser.add_argument("--control", choices=("none", "pd", "pd+gravity"), default="pd",
                        help="default: pd")
    parser.add_argument("--kp", type=float, default=None, metavar="GAIN")
    parser.add_argument("--kd", type=float, default=None, metavar="GAIN")
    parser.add_argument("--set", "--start", dest="start", action="append", default=[], metavar="JOINT=VALUE",
                        help="pose at t=0, at rest (default: the motion's first pose; "
                             f"with --control none, {NUDGE:g} rad on every joint); --start is the old name")
    parser.add_argument("--duration", type=float, metavar="S",
                        help="simulated (default: the last waypoint's time, else 10)")
    parser.add_argument("--rate", type=float, default=20.0, metavar="HZ",
                        help="kept for files and the GIF (default: 20)")
    parser.add_argument("--timestep", type=float, default=None, metavar="S", help="physics time step (default: 0.002)")
    parser.add_argument("--integrator", choices=("implicitfast", "implicit", "RK4", "Euler"), default=None,
                        help="MuJoCo integrator (default: implicitfast)")
    parser.add_argument("--damping", type=float, default=None, metavar="B",
                        help="joint damping on every joint, N·m·s/rad (default: each joint's <dynamics damping>, "
                             "none when absent, as in Gazebo)")
    parser.add_argument("--gif", metavar="FILE", help="the simulated motion (bras-kit's renderer)")
    parser.add_argument("-o", "--output", metavar="FILE",
                        help="the measured joint states: .csv (time,name,position,velocity,effort), .json, or .mcap/.db3 for a ROS 2 bag (/robot_description, /tf, /joint_states with effort)")
    parser.add_argument("--plot", metavar="FILE", help="plot positions and torques with the effort limits (.png/.svg/.pdf)")
    parser.add_argument("--strict", action="store_true", help="a motor too weak")
    add_force_argument(parser)


def _output_format(path: str) -> str:
    from ..motion.states_io import states_format

    fmt = states_format(path)
    if fmt is None:
        raise ParameterError(M("cannot tell the format of '{path}'", path=path),
                             hint=M("end the file name in .csv, .json or .mcap (a ROS 2 bag)"))
    return fmt


def run(args: argparse.Namespace) -> int:
    from ..motion import motion_from_specs
    from ..physics import mjcf
    from ..physics.diagnostics import (
        DIVERGENCE_HINT,
        LEVELS,
        check_physics_ready,
        divergence_message,
        physics_notes,
        report_text,
    )
    from ..physics.run import simulate

    lang = args.lang
    fmt = _output_format(args.output) if args.output else None
    if args.plot:
        from ..diagrams.output import FIGURE_FORMATS, output_suffix

        output_suffix(args.plot, FIGURE_FORMATS)
    if args.gif and not args.gif.lower().endswith(".gif"):
        raise ParameterError(M("cannot write '{path}' as a GIF", path=args.gif), hint=M("end the file name in .gif"))
    if args.output and args.output != "-":
        from ..motion.states_io import check_states_output

        check_states_output(args.output, args.force, fmt)
    for path in (args.plot, args.gif):
        if path and path != "-":
            check_writable(path, args.force)
    robot = load_model(args)
    check_physics_ready(robot, lang)
    motion = motion_from_specs(robot, args.motion, topic=args.topic)
    warn_motion_notes(motion)
    start = joint_values(args.start)
    if args.control == "none" and not start:
        from ..kinematics.frames import tf_tree

        start = dict.fromkeys(tf_tree(robot).dof, NUDGE)
    states = simulate(robot, motion, control=args.control,
                      kp=mjcf.DEFAULT_KP if args.kp is None else args.kp,
                      kd=mjcf.DEFAULT_KD if args.kd is None else args.kd,
                      duration=args.duration, rate=args.rate, start=start or None,
                      timestep=mjcf.DEFAULT_TIMESTEP if args.timestep is None else args.timestep,
                      integrator=args.integrator or mjcf.DEFAULT_INTEGRATOR,
                      damping=args.damping, package_paths=args.package_path)
    for note in physics_notes(robot, states.model, lang, args.package_path):  # type: ignore[arg-type]
        print(labelled(LEVELS[note.level], note.worded(lang), lang), file=sys.stderr)
    print(report_text(robot, states, lang))
    diverged = divergence_message(states)
    if diverged is not None:  # a failure: no file is written from numbers that stopped being numbers
        print("bras-kit simulate: " + labelled(M("error"), say(diverged, lang), lang) + "\n  "
              + labelled(M("hint"), say(DIVERGENCE_HINT, lang), lang), file=sys.stderr)
        return 1
    try:
        if fmt is not None:
            from ..motion.states_io import write_states

            written = write_states(robot, states, args.output, args.force, fmt)
            if written is not None:
                print(say(written), file=sys.stderr)
        if args.plot:
            from ..physics.plot import save_torque_plot

            save_torque_plot(robot, states, args.plot, lang)
            print(say(M("wrote {path}", path=args.plot), lang), file=sys.stderr)
        if args.gif:
            from ..render import render_motion, save_gif

            with render_motion(robot, states, package_paths=tuple(args.package_path)) as frames:
                count = save_gif(frames, args.gif, fps=args.rate)
            print(say(M("wrote {path}: {count} frames at {fps} fps", path=args.gif, count=count, fps=args.rate),
                      lang), file=sys.stderr)
    except OSError as exc:
        raise BrasKitError(M("cannot write {path}: {reason}", path=exc.filename or M("the output"),
                             reason=os_reason(exc)),
                           hint=M("check the folder exists, is writable and has space")) from None
    return 1 if args.strict and states.weak_joints else 0
