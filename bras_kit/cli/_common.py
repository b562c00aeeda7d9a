"""Options and helpers shared by several commands."""

from __future__ import annotations

import argparse
import os
import sys
from collections.abc import Callable, Iterable, Mapping
from typing import Any

from ..core.errors import BrasKitError, ParameterError, TimeInJointValueError
from ..core.message import M, Message, Mn

# A finding's or a note's severity, as it is shown
SEVERITY_WORDS = {"error": M("error"), "warning": M("warning"), "info": M("info")}


def add_model_arguments(parser: argparse.ArgumentParser, *, variants: bool = True) -> None:
    """FILE (optional: the tutorial arm), xacro args and package paths, and the arm's variants."""
    parser.add_argument("file", nargs="?", metavar="FILE",
                        help="a .urdf or .xacro file (default: the built-in tutorial arm)")
    parser.add_argument("--package-path", action="append", default=[], metavar="DIR",
                        help="folder holding ROS packages, for $(find pkg) and package:// (repeatable)")
    parser.add_argument("--xacro-arg", action="append", default=[], metavar="NAME:=VALUE",
                        help="xacro argument when FILE is a .xacro (repeatable)")
    add_cache_argument(parser)
    if variants:
        parser.add_argument("--wrist", action="store_true",
                            help="built-in arm: add the wrist joint 'poignet' (the tutorial's exercise)")
        parser.add_argument("--inertials", action="store_true",
                            help="built-in arm: add <inertial> mass and inertia to every link")
        parser.add_argument("--collisions", action="store_true",
                            help="built-in arm: add <collision> shapes equal to the visuals (on with --inertials)")
        parser.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                            help="a template parameter of the built-in arm (e.g. bras_length=0.8)")


def add_cache_argument(parser: argparse.ArgumentParser) -> None:
    """``--no-cache``: decode every mesh file again, neither reading nor writing the cache."""
    parser.add_argument("--no-cache", action="store_true",
                        help="decode mesh files again, without the cache of decoded meshes")


def xacro_mappings(items: Iterable[str]) -> dict[str, str]:
    out = {}
    for item in items:
        name, sep, value = item.partition(":=")
        if not sep or not name:
            raise ParameterError(M("'{item}' is not NAME:=VALUE", item=item),
                                 hint=M("write xacro arguments as name:=value"))
        out[name] = value
    return out


def load_model(args: argparse.Namespace):
    """The robot named by the model arguments (the tutorial arm when FILE is absent), refused with
    the validator's findings when it holds a value the command would compute with but the reader
    could not use (see :func:`check_usable`)."""
    from ..model.authoring import arm, load, parse_assignments

    if args.file is None:
        robot = arm(wrist=getattr(args, "wrist", False), inertials=getattr(args, "inertials", False),
                    params=parse_assignments(getattr(args, "param", [])),
                    collisions=getattr(args, "collisions", False))
    elif getattr(args, "wrist", False) or getattr(args, "inertials", False) or getattr(args, "param", []) \
            or getattr(args, "collisions", False):
        raise ParameterError(M("--wrist, --inertials, --collisions and --param apply to the built-in arm only"),
                             hint=M("drop FILE to use the built-in arm, or edit your file"))
    else:
        robot = load(args.file, mappings=xacro_mappings(args.xacro_arg), package_paths=args.package_path)
    check_usable(robot, args)
    return robot


# What each command computes with (bras_kit.model.robot.PARTS): a validator error about any other part
# (a NaN inertia for fk, a text colour for motion) does not stop it.
_KINEMATICS, _LIMITS = "kinematics", "limits"
USES: dict[str, tuple[str, ...]] = {
    "fk": (_KINEMATICS,),
    "frames": (_KINEMATICS, _LIMITS),  # the joint labels show the limits
    "motion": (_LIMITS,),
    "render": (_KINEMATICS, _LIMITS, "visual"),  # the camera is framed over the joints' range
    "plot": (_KINEMATICS, _LIMITS),
    "reach": (_KINEMATICS, _LIMITS),
    "workspace": (_KINEMATICS, _LIMITS),
    "view": (_KINEMATICS, _LIMITS, "visual", "collision"),
    "mjcf": (_KINEMATICS, _LIMITS, "dynamics", "visual", "collision", "inertial"),
    "simulate": (_KINEMATICS, _LIMITS, "dynamics", "visual", "collision", "inertial"),
    "grade": (_KINEMATICS, "visual"),  # the picture of each arm
}
MAX_SHOWN_FINDINGS = 10


def parts_used(args: argparse.Namespace) -> tuple[str, ...]:
    """The parts of the model the command of ``args`` computes with."""
    parts = USES.get(getattr(args, "command", None) or "", ())
    if getattr(args, "geometry", "visual") in ("collision", "both") and "collision" not in parts:
        parts = (*parts, "collision")
    return parts


def check_usable(robot: Any, args: argparse.Namespace) -> None:
    """Refuse ``robot`` when the validator reports an error about a value the command uses (a NaN
    axis for fk, an unreadable limit for motion...): the command would compute with a value the
    reader could not use. The error lists the validator's findings as ``bras-kit validate`` prints
    them; the command exits 1."""
    parts = parts_used(args)
    if not parts:
        return
    from ..core.errors import UnusableModelError
    from ..validate.usable import blocking_findings

    findings = blocking_findings(robot, parts, getattr(args, "package_path", ()))
    if findings:
        command = getattr(args, "command", None) or "bras-kit"
        raise UnusableModelError(
            Mn("the robot holds {n} value that {command} needs but cannot use as written "
               "(bras-kit validate reports the same):\n{findings}",
               "the robot holds {n} values that {command} needs but cannot use as written "
               "(bras-kit validate reports the same):\n{findings}",
               len(findings), command=command, findings=_findings_text(robot.path or "<robot>", findings)),
            findings)


def _findings_text(path: str, findings: list[Any]) -> Message:
    """The findings as ``bras-kit validate`` prints them, one message worded where it is shown."""
    from ..findings.report import element_text

    lines: list[Message] = []
    for finding in findings[:MAX_SHOWN_FINDINGS]:
        where = f"{path}:{finding.line}:" if finding.line else f"{path}:"
        head = M("{where} {code} {severity} {element} {message}", where=where, code=finding.code,
                 severity=SEVERITY_WORDS[finding.severity], element=element_text(finding), message=finding.message)
        lines.append(head if finding.hint is None else M("{head}\n  hint: {hint}", head=head, hint=finding.hint))
    if len(findings) > MAX_SHOWN_FINDINGS:
        lines.append(M("... and {count} more (bras-kit validate {path} lists them all)",
                       count=len(findings) - MAX_SHOWN_FINDINGS, path=path))
    text = lines[-1]
    for line in reversed(lines[:-1]):
        text = M("{first}\n{rest}", first=line, rest=text)
    return text


def joint_values(items: Iterable[str]) -> dict[str, float]:
    """``["epaule=0.5", "coude=pi/2", "poignet=90deg"]`` -> radians by joint name, with a clear
    error for a bad value (the one parser of joint values: --set, --pose, --from, --start)."""
    from ..model.authoring import parse_assignments
    from ..model.expr import parse_joint_value

    values = {}
    for name, text in parse_assignments(items, M("joint value")).items():
        try:
            values[name] = parse_joint_value(text)
        except BrasKitError as exc:
            detail = getattr(exc, "reason", exc.message)  # the formula's error without its caret lines
            why = detail if isinstance(exc, TimeInJointValueError) else \
                M("the joint value is not a number ({detail})", detail=detail)
            raise ParameterError(M("{name}={text!r}: {why}", name=name, text=text, why=why),
                                 hint=M("give radians for revolute joints and metres for prismatic ones: "
                                        "0.5, 1,5, pi/2, -0.5*pi, or degrees said explicitly: 90deg")) from None
    return values


def add_topic_argument(parser: argparse.ArgumentParser) -> None:
    """``--topic``: which JointState topic a ROS 2 bag given to --motion is read from."""
    parser.add_argument("--topic", metavar="NAME", default=None,
                        help="with a ROS 2 bag as --motion: the JointState topic to replay (default: /joint_states)")


def warn_motion_notes(motion: Any) -> None:
    """What was odd in the motion's input (a recording's gaps, unknown joints...), one warning each."""
    for note in getattr(motion, "notes", ()):
        warn(note)


def add_force_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--force", action="store_true", help="overwrite files that already exist")


def check_writable(path: str, force: bool, *, make_parents: bool = False, option: str = "-o") -> None:
    """Refuse a path that exists (even a dangling link) unless ``force``, a folder, or a missing parent."""
    from ..trust.outputs import check_output

    check_output(path, force, make_parents=make_parents, option=option)


def write_text(path: str | None, text: str, force: bool, **options: Any) -> None:
    """Write ``text`` to ``path`` (stdout when None or '-') through the one safe write function."""
    from ..trust.outputs import write_text as write

    write(path, text, force, **options)


def save_with(path: str, force: bool, writer: Callable[[str], Any], **options: Any) -> Any:
    """``writer(temporary_path)`` then moved onto ``path``: see :func:`bras_kit.trust.outputs.write_to`."""
    from ..trust.outputs import write_to

    return write_to(path, force, writer, **options)


def warn(message: Message | BrasKitError, lang: str | None = None) -> None:
    """``warning: ...`` on stderr, worded in the command's language."""
    from ..core.i18n import labelled, say

    print(labelled(M("warning"), say(message, lang), lang), file=sys.stderr)


def warn_out_of_limits(tree: Any, config: Mapping[str, float], consequence: Message | None = None,
                       lang: str | None = None) -> None:
    """One warning per value past its joint's limits; a value that reads as degrees says so."""
    from ..motion import value_in_degrees

    for name, value, lower, upper in tree.out_of_limits(config):
        if value > upper:
            text = M("{name}={value:g} is above its upper limit {limit:g} by {excess:.4g}",
                     name=name, value=value, limit=upper, excess=value - upper)
        else:
            text = M("{name}={value:g} is below its lower limit {limit:g} by {excess:.4g}",
                     name=name, value=value, limit=lower, excess=lower - value)
        if value_in_degrees(tree.robot.joint(name), value):
            text = M("{text}; it looks like degrees: write {name}={value:g}deg", text=text, name=name, value=value)
        if consequence is not None:
            text = M("{text} ({consequence})", text=text, consequence=consequence)
        warn(text, lang)


def template_values(args: argparse.Namespace) -> list[str]:
    """``--param`` items, plus the old ``--set`` spelling of ``urdf`` and ``new`` with a note;
    a joint name given there is pointed to ``--set`` of the other commands."""
    from ..model.authoring import template_parameters

    old = list(getattr(args, "old_params", []) or [])
    if old:
        warn(M("--set is deprecated for template parameters: use --param (--set gives joint values in the other commands)"),
             getattr(args, "lang", None))
    items = list(args.params) + old
    known = template_parameters()
    for item in items:
        name = item.partition("=")[0].strip()
        if name and name not in known and name in ("epaule", "coude", "poignet"):
            raise ParameterError(M("'{name}' is a joint, not a template parameter", name=name),
                                 hint=M("joint values go to --set in render, fk, tree, plot and validate; "
                                        "template parameters are listed by bras-kit urdf --list-params"))
    return items


def joint_name_hint(name: str, hint: Message | str | None) -> Message | str | None:
    """What a name given as a joint is instead: a template parameter, the wrist of the exercise."""
    from ..model.authoring import template_parameters

    if name in template_parameters():
        return M("'{name}' is a template parameter of the built-in arm, not a joint: use --param {name}=VALUE",
                 name=name)
    if name == "poignet":
        return M("'poignet' is the wrist of the tutorial's exercise: add --wrist to use the arm that has it")
    return hint


def format_config(config: Mapping[str, float]) -> Message | str:
    """``epaule=0.5, coude=1.2`` (names and numbers: the same in every language), or "zero pose"."""
    if not config:
        return M("zero pose")
    return ", ".join(f"{k}={v:g}" for k, v in config.items())


def add_node_argument(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("--node", metavar="PKG_DIR[:EXE]",
                        help="the motion is what your node publishes on /joint_states (run with bras-kit run's "
                             "stand-in for rclpy, simulated time); the robot is the package's URDF unless FILE is given")


def apply_node(args: argparse.Namespace, duration: float | None) -> None:
    """``--node PKG_DIR[:EXE]``: run the node (as ``bras-kit run`` does) and make what it published
    on /joint_states the motion (``args.recorded``, taken directly by the motion sources);
    FILE defaults to the package's robot description."""
    from ..core.message import M

    args.recorded = None
    spec = getattr(args, "node", None)
    if not spec:
        return
    if args.motion:
        raise ParameterError(M("--node and --motion both say how the arm moves"), hint=M("give one of them"))
    where, executable = _node_spec(spec)
    if args.file is None and os.path.isdir(where):
        from ..ros.package import Package

        source = Package(where).description_source()
        if source is not None:
            args.file = os.path.join(where, source)
            args.package_path = [*args.package_path, os.path.dirname(os.path.abspath(where))]
    from ..ros.recording import states_for
    from ..run.node import run_node

    robot = load_model(args)
    recording = run_node(where, executable, duration=duration or 10.0, robot=robot)
    from ..kinematics.frames import tf_tree

    states = states_for(recording, tf_tree(robot).dof)
    if not len(states):
        raise ParameterError(M("the node published nothing on /joint_states in {time} s", time=recording.end),
                             hint=M("run it with 'bras-kit run {spec}' to see what it did", spec=spec))
    args.recorded = (os.path.basename(recording.source), states)


def _node_spec(spec: str) -> tuple[str, str | None]:
    """``PKG_DIR``, ``PKG_DIR:EXE`` or ``node.py``."""
    if os.path.exists(spec):
        return spec, None
    where, sep, executable = spec.rpartition(":")
    if sep and where and os.path.isdir(where):
        return where, executable or None
    return spec, None


def add_no_browser_argument(parser: argparse.ArgumentParser) -> None:
    """``--no-browser``: the page is served and its address printed; no browser is opened (see _options)."""
    parser.add_argument("--no-browser", action="store_true")


def has_screen() -> bool:
    """A graphical browser can open: a desktop session (not SSH into a server)."""
    if sys.platform in ("darwin", "win32"):
        return True
    return bool(os.environ.get("DISPLAY") or os.environ.get("WAYLAND_DISPLAY"))


def open_page(url: str, args: argparse.Namespace) -> None:
    """The page in the user's browser, unless ``--no-browser`` or there is no screen to show it on
    (view, view --ros and launch alike)."""
    if not args.no_browser and has_screen():
        import webbrowser

        webbrowser.open(url)
