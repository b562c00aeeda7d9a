"""bras-kit new: scaffold the tutorial's ROS 2 package (steps 2 to 7, ready to colcon build)."""

from __future__ import annotations

import argparse
import os

from ..i18n import say
from ..message import M
from ._common import add_force_argument, template_values


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("dir", nargs="?", metavar="DIR",
                        help="folder to create (default: ./PKG)")
    parser.add_argument("--name", default="bras_description", metavar="PKG",
                        help="ROS package name: lowercase letters, digits, _ (default: bras_description)")
    parser.add_argument("--wrist", action="store_true", help="add the wrist link and joint 'poignet'")
    parser.add_argument("--inertials", action="store_true", help="add mass and inertia to every link")
    parser.add_argument("--xacro", action="store_true",
                        help="describe the arm in urdf/bras.urdf.xacro, expanded by the launch file (instead of the "
                        "tutorial's hand-written urdf/bras.urdf)")
    parser.add_argument("--param", dest="params", action="append", default=[], metavar="NAME=VALUE",
                        help="change a template parameter (repeatable); 'bras-kit urdf --list-params' "
                        "shows them")
    parser.add_argument("--set", dest="old_params", action="append", default=[], metavar="NAME=VALUE",
                        help="deprecated spelling of --param (--set means joint values elsewhere)")
    parser.add_argument("--maintainer", metavar="NAME", help="maintainer in package.xml (default: your user name)")
    parser.add_argument("--email", metavar="EMAIL", help="maintainer e-mail, one colcon accepts (default: from NAME, e.g. jean.dupont@todo.todo)")
    parser.add_argument("--empty", action="store_true",
                        help="write only what 'ros2 pkg create --build-type ament_python PKG' writes (package.xml, "
                        "setup.py, setup.cfg, resource/PKG, PKG/__init__.py, test/): the tutorial's step 2, "
                        "the files of steps 3 to 7 yours to write")
    parser.add_argument("--license", dest="license_name", metavar="LICENSE",
                        help="with --empty: the license in package.xml and setup.py, as ros2 pkg create --license "
                        "(default: 'TODO: License declaration'; Apache-2.0 also writes LICENSE)")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..authoring import parse_assignments
    from ..errors import ParameterError
    from ..scaffold import check_package_name, scaffold_package

    check_package_name(args.name)
    if args.empty:
        return _empty(args)
    if args.license_name is not None:
        raise ParameterError(M("--license applies to --empty only"),
                             hint=M("the full package is Apache-2.0; add --empty for the files of ros2 pkg create"))
    params = template_values(args)
    dest = args.dir if args.dir is not None else os.path.join(".", args.name)
    made = scaffold_package(dest, args.name, wrist=args.wrist, inertials=args.inertials,
                            params=parse_assignments(params), force=args.force,
                            maintainer=args.maintainer, email=args.email, lang=args.lang, xacro=args.xacro)
    print(say(M("created the ROS 2 package '{name}' in {folder}:", name=args.name, folder=dest), args.lang))
    for path in made:
        print(f"  {os.path.relpath(path, dest)}")
    print("\n" + say(M("next: move it into the src/ folder of a colcon workspace, then"), args.lang))
    print(f"  colcon build --packages-select {args.name} && source install/setup.bash")
    print(f"  ros2 launch {args.name} affichage.launch.py")
    print(say(M("or here, without ROS:"), args.lang))
    here = ((f"bras-kit launch {dest}", M("its launch file, live in your browser")),
            (f"bras-kit run {dest} animation", M("its node, recorded and checked")))
    width = max(len(command) for command, _ in here)
    for command, what in here:
        print(f"  {command:<{width}}   {say(what, args.lang)}")
    return 0


def _empty(args: argparse.Namespace) -> int:
    """The tutorial's step 2 (``ros2 pkg create``): the package's frame, the learner's files to write."""
    from ..errors import ParameterError
    from ..scaffold import DEFAULT_LICENSE, scaffold_empty_package

    chosen = [flag for flag, on in (("--wrist", args.wrist), ("--inertials", args.inertials), ("--xacro", args.xacro),
                                    ("--param", bool(args.params or args.old_params))) if on]
    if chosen:
        raise ParameterError(M("{options}: not with --empty, which writes no robot", options=", ".join(chosen)),
                             hint=M("drop --empty for the tutorial's finished package, or drop {options}",
                                    options=", ".join(chosen)))
    dest = args.dir if args.dir is not None else os.path.join(".", args.name)
    made = scaffold_empty_package(dest, args.name, force=args.force, maintainer=args.maintainer, email=args.email,
                                  license_name=DEFAULT_LICENSE if args.license_name is None else args.license_name)
    print(say(M("created the ROS 2 package '{name}' in {folder}, as ros2 pkg create does:", name=args.name,
                folder=dest), args.lang))
    for path in made:
        print(f"  {os.path.relpath(path, dest)}")
    print("\n" + say(M("next (the tutorial's step 3): describe the arm in {file}, then check the package:",
                       file=os.path.join(dest, "urdf", "bras.urdf")), args.lang))
    print(f"  bras-kit validate {dest}")
    return 0
