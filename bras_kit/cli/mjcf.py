"""bras-kit mjcf: write the MuJoCo model bras-kit builds from a URDF, to open in MuJoCo's own viewer.

Meshes are written next to the model in FILE_meshes/ (DAE converted to STL), so the folder is
self-contained: ``python -m mujoco.viewer --mjcf=arm.xml``.
"""

from __future__ import annotations

import argparse
import os
import sys

from ..core.errors import BrasKitError, os_reason
from ..core.i18n import labelled, say
from ..core.message import M, Mn
from ._common import add_force_argument, add_model_arguments, check_writable, write_text

_EPILOG = """\
examples:
  bras-kit mjcf --inertials                     print the tutorial arm's MJCF
  bras-kit mjcf --inertials -o arm.xml          then: python -m mujoco.viewer --mjcf=arm.xml
  bras-kit mjcf robot.urdf --package-path ws/src -o robot.xml
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = _EPILOG
    add_model_arguments(parser)
    parser.add_argument("--control", choices=("none", "pd", "pd+gravity"), default="pd",
                        help="none, PD servos (default) or PD servos with gravity compensation")
    parser.add_argument("--kp", type=float, default=None, metavar="GAIN")
    parser.add_argument("--kd", type=float, default=None, metavar="GAIN")
    parser.add_argument("-o", "--output", metavar="FILE", help="the MJCF to FILE (meshes in FILE_meshes/)")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..physics import mjcf
    from ..physics.controllers import gain_vector
    from ..physics.diagnostics import LEVELS, check_physics_ready, physics_notes

    lang = args.lang
    if args.output and args.output != "-":
        check_writable(args.output, args.force)
    robot = load_model(args)
    check_physics_ready(robot, lang)
    kp = mjcf.DEFAULT_KP if args.kp is None else float(gain_vector(args.kp, ["all"], mjcf.DEFAULT_KP, "kp")[0])
    kd = mjcf.DEFAULT_KD if args.kd is None else float(gain_vector(args.kd, ["all"], mjcf.DEFAULT_KD, "kd")[0])
    built = mjcf.build_mjcf(robot, package_paths=args.package_path, kp=kp, kd=kd, control=args.control)
    for note in physics_notes(robot, built, lang, args.package_path):
        print(labelled(LEVELS[note.level], note.worded(lang), lang), file=sys.stderr)
    if not args.output or args.output == "-":
        if built.assets:
            print(say(M("note: the meshes are not printed; write with -o FILE to get them in FILE_meshes/"), lang),
                  file=sys.stderr)
        write_text(None, built.xml, args.force)
        return 0
    stem = os.path.splitext(os.path.basename(args.output))[0]
    folder = f"{stem}_meshes"
    if built.assets:
        check_writable(os.path.join(os.path.dirname(args.output), folder), args.force)
    text = built.xml_with_meshdir(folder) if built.assets else built.xml
    write_text(args.output, text, args.force)
    if built.assets:
        target = os.path.join(os.path.dirname(args.output), folder)
        from ..trust.outputs import write_bytes

        if os.path.islink(target):
            raise BrasKitError(M("{path} is a symbolic link: refused", path=target),
                               hint=M("remove the link, or choose another -o"))
        try:
            os.makedirs(target, exist_ok=True)
        except OSError as exc:
            raise BrasKitError(M("cannot create {path}: {reason}", path=target, reason=os_reason(exc)),
                               hint=M("check the folder is writable and has space")) from None
        for asset in built.assets.values():  # each through the one safe write: no link followed
            write_bytes(os.path.join(target, asset.name), asset.data, args.force, announce=False)
        print(say(Mn("wrote {n} mesh in {folder}/", "wrote {n} meshes in {folder}/", len(built.assets), folder=target),
                  lang), file=sys.stderr)
    return 0


def load_model(args: argparse.Namespace):
    from ._common import load_model as load

    return load(args)
