"""bras-kit gazebo: what Gazebo's URDF reader (libsdformat 12) will load: links kept, merged, dropped,
frames lost, and why a model is refused; as text or JSON, and drawn (-o picture.png).

Its counterpart with Gazebo installed is ``gz sdf -p FILE`` (``ign sdf -p`` on Fortress) and the
Gazebo window. The prediction is :func:`bras_kit.validate.urdf2sdf.gazebo_model`; the reasons
are the BK7xx findings of ``bras-kit validate --target gazebo``.

Exit status: 0 Gazebo loads the model, 1 it refuses it, 2 the file cannot be read or the command
line is wrong.
"""

from __future__ import annotations

import argparse
import json
import sys

from ..core.message import M, Mn
from ._common import SEVERITY_WORDS, add_force_argument, add_model_arguments

EPILOG = """\
exit status: 0 Gazebo loads the model, 1 it refuses it, 2 the file cannot be read.
examples:
  bras-kit gazebo --wrist --inertials            the tutorial arm with both exercises done
  bras-kit gazebo my_robot.urdf --json           the same facts for a program
  bras-kit gazebo my_robot.urdf -o gazebo.png    the parts Gazebo loses drawn in red
  bras-kit validate my_robot.urdf --target gazebo    each problem, its line and its fix"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = EPILOG
    add_model_arguments(parser)
    parser.add_argument("--json", action="store_true", help="the facts")
    parser.add_argument("-o", "--output", metavar="PNG",
                        help="a picture of the robot as Gazebo loads it: the parts it loses in red")
    parser.add_argument("--only-kept", action="store_true", help="with -o: leave out the parts Gazebo loses")
    add_force_argument(parser)


def _names(items: list[str]) -> str:
    return ", ".join(items) if items else "-"


def _text(found, findings, robot_name: str | None, lang: str | None) -> str:
    from ..core.i18n import labelled, say

    name = robot_name or "?"
    lines = []

    def said(f) -> None:
        lines.append(f"{f.code} " + labelled(SEVERITY_WORDS[f.severity], f.text(lang), lang))
        if f.hint_text(lang):
            lines.append("  " + say(M("hint: {hint}", hint=f.hint_text(lang)), lang))

    # a refusal's reasons come right under it, before the facts: the first thing read is why
    reasons = [f for f in findings if f.severity == "error"] if found.refused else []
    if found.refused:
        lines.append(say(M("Gazebo refuses model '{name}'", name=name), lang))
        for f in reasons:
            said(f)
    else:
        lines.append(say(Mn("Gazebo loads model '{name}': {n} link", "Gazebo loads model '{name}': {n} links",
                            len(found.links), name=name), lang))
    lines.append(say(M("  kept:        {links}", links=_names(list(found.links))), lang))
    joints = [f"{j} ({found.joint_types[j]})" for j in found.joints]
    lines.append(say(M("  joints:      {joints}", joints=_names(joints)), lang))
    for m in found.merged:
        lines.append(say(M("  merged:      {link} -> {into} (fixed joint {joint}): the frame {link} is lost",
                           link=m.link, into=m.into, joint=m.joint), lang))
    for d in found.dropped:
        reason = M("no <inertial>") if d.reason == "no-inertial" else M("mass {mass:g} kg", mass=d.mass or 0.0)
        lines.append(say(M("  dropped:     {link} ({reason}): lost {links}; joints {joints}", link=d.link,
                           reason=reason, links=_names(list(d.lost_links)), joints=_names(list(d.lost_joints))),
                         lang))
    anchored = M("yes (the root is 'world')") if found.anchored else M("no: a free body, it falls")
    lines.append(say(M("  anchored:    {answer}", answer=anchored), lang))
    for f in findings:
        if not any(f is reason for reason in reasons):
            said(f)
    return "\n".join(lines) + "\n"


def run(args: argparse.Namespace) -> int:
    from ..core.errors import ParameterError
    from ..validate import validate
    from ..validate.urdf2sdf import as_data, as_gazebo_shows, gazebo_model
    from ._common import check_writable, load_model

    robot = load_model(args)
    found = gazebo_model(robot)
    if found is None:
        raise ParameterError(M("{path}: the links do not form one tree, so Gazebo's URDF reader refuses it",
                               path=robot.path or robot.name or "?"),
                             hint=M("run 'bras-kit validate' on it: the BK1xx findings say what to fix"))
    findings = validate(robot, select=["BK7"], target="gazebo")
    if args.output:
        check_writable(args.output, args.force)
    if args.json:
        data = as_data(found)
        data["findings"] = [f.as_dict(args.lang) for f in findings]
        sys.stdout.write(json.dumps(data, indent=2, ensure_ascii=False) + "\n")
    else:
        sys.stdout.write(_text(found, findings, robot.name, args.lang))
    if args.output:
        from ..render import render_pose, save_png

        save_png(render_pose(as_gazebo_shows(robot, found, only_kept=args.only_kept)), args.output)
    return 1 if found.refused else 0
