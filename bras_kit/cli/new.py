"""bras-kit new: scaffold the tutorial's ROS 2 package (steps 2 to 7, ready to colcon build)."""

from __future__ import annotations

import argparse
import os

from ..core.i18n import say
from ..core.message import M
from ._common import add_force_argument, template_values


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("dir", nargs="?", metavar="DIR",
                        help="folder to create (default: ./PKG); with --empty, as ros2 pkg create's package_name, "
                        "its last part names the package unless --name is given")
    parser.add_argument("--name", default=None, metavar="PKG",
                        help="ROS package name: lowercase letters, digits, _ (default: bras_description)")
    parser.add_argument("--wrist", action="store_true")
    parser.add_argument("--inertials", action="store_true")
    parser.add_argument("--xacro", action="store_true",
                        help="describe the arm in urdf/bras.urdf.xacro, expanded by the launch file (instead of the "
                        "tutorial's hand-written urdf/bras.urdf)")
    parser.add_argument("--param", dest="params", action="append", default=[], metavar="NAME=VALUE",
                        help="a template parameter of the built-in arm; 'bras-kit urdf --list-params' shows them")
    parser.add_argument("--set", dest="old_params", action="append", default=[], metavar="NAME=VALUE",
                        help=argparse.SUPPRESS)
    parser.add_argument("--maintainer", "--maintainer-name", metavar="NAME",
                        help="maintainer in package.xml (default: your user name)")
    parser.add_argument("--email", "--maintainer-email", metavar="EMAIL",
                        help="maintainer e-mail, one colcon accepts (default: from NAME, e.g. jean.dupont@todo.todo)")
    parser.add_argument("--empty", action="store_true",
                        help="write only what 'ros2 pkg create --build-type ament_python PKG' writes (package.xml, "
                        "setup.py, setup.cfg, resource/PKG, PKG/__init__.py, test/): the tutorial's step 2, "
                        "the files of steps 3 to 7 yours to write")
    parser.add_argument("--license", dest="license_name", metavar="LICENSE",
                        help="with --empty: the license in package.xml and setup.py, as ros2 pkg create --license "
                        "(default: 'TODO: License declaration'; Apache-2.0 also writes LICENSE)")
    ros2 = parser.add_argument_group("ros2 pkg create's options (with --empty, but --build-type ament_python)")
    ros2.add_argument("--build-type", choices=BUILD_TYPES, default=None,
                      help="ament_python, the only build type of the tutorial's packages (ros2 pkg create's "
                      "ament_cmake and cmake packages are C++)")
    ros2.add_argument("--dependencies", nargs="+", action="extend", default=[], metavar="PKG",
                      help="packages written as <depend> in package.xml")
    ros2.add_argument("--node-name", metavar="NODE",
                      help="an empty node, PKG/NODE.py, and its console_scripts entry in setup.py")
    ros2.add_argument("--library-name", metavar="LIB", help="an empty Python package, PKG/LIB/__init__.py")
    ros2.add_argument("--description", metavar="TEXT",
                      help="the description in package.xml and setup.py (default: 'TODO: Package description')")
    ros2.add_argument("--destination-directory", metavar="DIR",
                      help="the folder the package's folder is made in (default: the current folder)")
    ros2.add_argument("--package-format", "--package_format", type=int, choices=(2, 3), default=None,
                      help="the package.xml format (default: 3)")
    add_force_argument(parser)


# ros2pkg/verb/create.py's --build-type choices: bras-kit writes the one the tutorial uses
BUILD_TYPES = ("ament_python", "ament_cmake", "cmake")
_EMPTY_ONLY = ("--dependencies", "--node-name", "--library-name", "--description", "--destination-directory",
               "--package-format")


def _given(args: argparse.Namespace) -> list[str]:
    """The ros2 pkg create options of the command line that only --empty takes."""
    values = {"--dependencies": args.dependencies, "--node-name": args.node_name, "--library-name": args.library_name,
              "--description": args.description, "--destination-directory": args.destination_directory,
              "--package-format": args.package_format}
    return [option for option in _EMPTY_ONLY if values[option] not in (None, [])]


def run(args: argparse.Namespace) -> int:
    from ..core.errors import ParameterError
    from ..model.authoring import parse_assignments
    from ..scaffold.package import DEFAULT_PACKAGE, check_package_name, scaffold_package

    if args.build_type not in (None, "ament_python"):  # ros2 pkg create's ament_cmake or cmake: C++
        raise ParameterError(M("--build-type {type}: bras-kit makes ament_python packages only, the build type of "
                               "the tutorial's package", type=args.build_type),
                             hint=M("write --build-type ament_python, as the tutorial does; an {type} package is "
                                    "built from C++ with CMake, which bras-kit does not build", type=args.build_type))
    if args.empty:
        return _empty(args)
    args.name = args.name or DEFAULT_PACKAGE
    check_package_name(args.name)
    if args.license_name is not None:
        raise ParameterError(M("--license applies to --empty only"),
                             hint=M("the full package is Apache-2.0; add --empty for the files of ros2 pkg create"))
    if _given(args):
        raise ParameterError(M("{options}: ros2 pkg create's, with --empty only", options=", ".join(_given(args))),
                             hint=M("add --empty for the files of ros2 pkg create; the full package has its own"))
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
    from ..core.errors import ParameterError
    from ..scaffold.package import (
        DEFAULT_LICENSE,
        DEFAULT_PACKAGE,
        EMPTY_DESCRIPTION,
        check_package_name,
        scaffold_empty_package,
    )

    chosen = [flag for flag, on in (("--wrist", args.wrist), ("--inertials", args.inertials), ("--xacro", args.xacro),
                                    ("--param", bool(args.params or args.old_params))) if on]
    if chosen:
        raise ParameterError(M("{options}: not with --empty, which writes no robot", options=", ".join(chosen)),
                             hint=M("drop --empty for the tutorial's finished package, or drop {options}",
                                    options=", ".join(chosen)))
    if args.dependencies and args.dir is None:  # --dependencies took every word after it, the name too
        raise ParameterError(M("--dependencies {names}: no package name is left after the dependencies",
                               names=" ".join(args.dependencies)),
                             hint=M("write the package's name before --dependencies, or end the list with --: "
                                    "--dependencies rclpy -- bras_description (ros2 pkg create needs the same)"))
    # as ros2 pkg create: the package name is the positional argument, made in --destination-directory
    if args.name is None:
        args.name = os.path.basename(os.path.normpath(args.dir)) if args.dir is not None else DEFAULT_PACKAGE
    check_package_name(args.name)
    if args.destination_directory is not None:
        if args.dir is not None and os.path.basename(os.path.normpath(args.dir)) != args.dir:
            raise ParameterError(M("with --destination-directory, give the package's name, not a folder: {dir}",
                                   dir=args.dir), hint=M("e.g. --destination-directory src bras_description"))
        dest = os.path.join(args.destination_directory, args.name)
    else:
        dest = args.dir if args.dir is not None else os.path.join(".", args.name)
    made = scaffold_empty_package(dest, args.name, force=args.force, maintainer=args.maintainer, email=args.email,
                                  license_name=DEFAULT_LICENSE if args.license_name is None else args.license_name,
                                  description=EMPTY_DESCRIPTION if args.description is None else args.description,
                                  dependencies=args.dependencies, node_name=args.node_name,
                                  library_name=args.library_name, package_format=args.package_format or 3)
    print(say(M("created the ROS 2 package '{name}' in {folder}, as ros2 pkg create does:", name=args.name,
                folder=dest), args.lang))
    for path in made:
        print(f"  {os.path.relpath(path, dest)}")
    print("\n" + say(M("next (the tutorial's step 3): describe the arm in {file}, then check the package:",
                       file=os.path.join(dest, "urdf", "bras.urdf")), args.lang))
    print(f"  bras-kit validate {dest}")
    return 0
