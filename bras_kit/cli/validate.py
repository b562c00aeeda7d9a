"""bras-kit validate: check URDF/xacro files (or the built-in arm) for defects and the tutorial's pitfalls.

Exit status: 0 no error (warnings and notes allowed), 1 errors (or warnings with --strict),
2 a file could not be read (not well-formed, unsafe XML, xacro failure, missing) or bad usage.
"""

from __future__ import annotations

import argparse
import os
import sys

from ..core.message import M

EPILOG = """\
exit status: 0 no errors (warnings allowed), 1 errors (or warnings with --strict),
2 a file could not be read or the command line is wrong.
examples:
  bras-kit validate                         the built-in tutorial arm
  bras-kit validate urdf/bras.urdf --lang fr
  bras-kit validate src/ --format json      every .urdf and .xacro below src/
  bras-kit validate bras_description/       a ROS 2 package: also setup.py, launch, RViz, nodes
  bras-kit validate bras.urdf --pose coude=2.5 --motion tutorial
  bras-kit validate bras.urdf --target gazebo    what Gazebo refuses or loses is an error
  bras-kit explain BK301                    what a code means and how to fix it"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = EPILOG
    parser.add_argument("files", nargs="*", metavar="FILE",
                        help=".urdf or .xacro files, or folders to search; a folder holding package.xml and setup.py "
                        "is also checked as a ROS 2 package (default: the built-in tutorial arm)")
    parser.add_argument("--format", choices=("text", "json"), default="text",
                        help="text for people (default), json for programs")
    parser.add_argument("--strict", action="store_true", help="warnings also fail")
    parser.add_argument("--target", choices=("gazebo",), default=None,
                        help="where the robot is heading: 'gazebo' makes every model Gazebo refuses and every "
                        "part it loses an error (BK7xx, see docs/gazebo.md)")
    parser.add_argument("--set", "--pose", dest="pose", action="append", default=[], metavar="JOINT=VALUE",
                        help="checked against its limits (or comma-separated: --pose epaule=0.5,coude=2.5)")
    parser.add_argument("--motion", action="append", default=[], metavar="SPEC",
                        help="checked against limits and velocities (e.g. coude=1.2*sin(0.7*t))")
    parser.add_argument("--duration", type=float, default=None, metavar="SECONDS",
                        help="of --motion sampled (default: the motion's own length, else 10 s)")
    parser.add_argument("--select", action="append", default=[], metavar="CODES",
                        help="only these rules: codes or prefixes, comma-separated (e.g. BK3,BK201)")
    parser.add_argument("--ignore", action="append", default=[], metavar="CODES",
                        help="skip these rules: codes or prefixes, comma-separated (e.g. BK505)")
    parser.add_argument("--package-path", action="append", default=[], metavar="DIR")
    parser.add_argument("--xacro-arg", action="append", default=[], metavar="NAME:=VALUE")
    parser.add_argument("--run", action="store_true",
                        help="ROS 2 packages: also run each node of console_scripts (bras-kit run's stand-in for "
                        "rclpy, simulated time, --duration seconds, default 10) and check what it published; "
                        "this executes the package's code, in a child process with CPU, memory and time limits")
    parser.add_argument("-v", "--verbose", action="store_true",
                        help="also say which folder each ROS package ($(find), package://) was taken from")
    parser.add_argument("--wrist", action="store_true")
    parser.add_argument("--inertials", action="store_true")
    parser.add_argument("--param", action="append", default=[], metavar="NAME=VALUE",
                        help="a template parameter of the built-in arm (e.g. bras_length=0.8)")


def _print_packages() -> None:
    from ..core.i18n import say
    from ..model.package_paths import describe_package_folder, packages_used

    for name, folder in packages_used().items():
        print(say(describe_package_folder(name, folder)), file=sys.stderr)


def _assignments(items: list[str]) -> list[str]:
    """``["epaule=0.5,coude=1,5"]`` -> ``["epaule=0.5", "coude=1,5"]``: a comma starts a new
    assignment only before ``NAME=``, so a French decimal comma stays in its value."""
    import re

    return [part for item in items for part in re.split(r",(?=\s*[A-Za-z_][\w.-]*\s*=)", item) if part.strip()]


def _codes(items: list[str]) -> list[str]:
    """``["BK3,BK201", "BK505"]`` -> ``["BK3", "BK201", "BK505"]`` (also for --pose items)."""
    return [code.strip() for item in items for code in item.split(",") if code.strip()]


def _use_colour() -> bool:
    return sys.stdout.isatty() and "NO_COLOR" not in os.environ and os.environ.get("TERM") != "dumb"


def _run_results(targets: list[str], lang: str, select: list[str], ignore: list[str],
                 duration: float | None, *, nodes: bool = False) -> list:
    """Each package (or, with ``nodes``, each node file) run as ``bras-kit run`` runs it, its findings."""
    if not targets:
        return []
    from ..core.i18n import say
    from ..run.findings import node_file_results, package_run_results
    from ..trust.contain import uncontained_note

    note = uncontained_note()
    if note is not None:
        print(say(note, lang), file=sys.stderr)
    results_of = node_file_results if nodes else package_run_results
    return [result for target in targets for result in
            results_of(target, lang=lang, select=select, ignore=ignore, duration=duration or 10.0)]


def run(args: argparse.Namespace) -> int:
    from ..core.errors import ParameterError
    from ..findings.data import merge_results
    from ..ros.ahead import evaluate_ahead

    # begun before the rules are imported: the build and launch evaluation runs beside them
    ahead = evaluate_ahead([f for f in args.files if not (f.endswith(".py") and os.path.isfile(f))])
    from ..findings.data import FileResult
    from ..findings.registry import select_rules
    from ..findings.report import exit_code, format_json, format_styled, format_text
    from ..trust.inert import emit
    from ..validate import (
        check_robot,
        collect_files,
        compare_generated,
        found_in,
        generated_pairs,
        validate_path,
    )
    from ..validate.package import Package, find_packages, installed_descriptions, validate_package
    from ._common import joint_values, xacro_mappings

    lang = args.lang
    select, ignore = _codes(args.select), _codes(args.ignore)
    try:
        select_rules(select, ignore)
    except ValueError as exc:
        raise ParameterError(M("--select/--ignore: no rule code starts with '{code}'", code=str(exc)),
                             hint=M("codes look like BK301; 'bras-kit explain' lists them all")) from None
    pose = joint_values(_assignments(args.pose))
    if args.duration is not None and not args.duration > 0:
        raise ParameterError(M("--duration {duration:g}: must be a positive number of seconds", duration=args.duration))
    options = dict(pose=pose or None, motion=args.motion or None, duration=args.duration, lang=lang,
                   package_paths=args.package_path, select=select, ignore=ignore, target=args.target)
    nodes = [f for f in args.files if f.endswith(".py") and os.path.isfile(f)]
    if nodes and not args.run:  # not XML: a node is checked by running it
        raise ParameterError(M("{path} is a Python file: a node is checked by running it", path=nodes[0]),
                             hint=M("add --run: bras-kit validate {path} --run", path=nodes[0]))
    if nodes:  # a lone node file, run as `bras-kit run FILE.py` runs it (not read as XML)
        args.files = [f for f in args.files if f not in nodes]
    if nodes and not args.files:
        results = _run_results(nodes, lang, select, ignore, args.duration, nodes=True)
    elif args.files:
        if args.wrist or args.inertials or args.param:
            raise ParameterError(M("--wrist, --inertials and --param apply to the built-in arm only"),
                                 hint=M("drop FILE to check the built-in arm, or edit your file"))
        mappings = xacro_mappings(args.xacro_arg)
        paths = collect_files(args.files)
        packages = find_packages(args.files)
        if not paths and not packages:
            raise ParameterError(M("no .urdf or .xacro file found in {paths}", paths=", ".join(args.files)),
                                 hint=M("give a file, or a folder holding .urdf or .xacro files"))
        read = [Package(package) for package in packages]
        for package in read:
            package.ahead = ahead
        # a file no xacro file sits beside is checked as written whatever the packages install:
        # first, while the worker evaluates the packages (their rules wait for it where they need it)
        pairs = generated_pairs(paths, [])
        alone = {path: FileResult(path, validate_path(path, mappings=mappings, roots=found_in(path, args.files),
                                                      **options))
                 for path in paths if path not in pairs}
        results = [result for package in read
                   for result in validate_package(package.root, lang=lang, select=select, ignore=ignore,
                                                  package=package, launch=True)]
        if args.run:
            results = merge_results(results, _run_results(packages, lang, select, ignore, args.duration))
        # bras.urdf beside bras.urdf.xacro: check the xacro once, unless the package installs the URDF
        # (then the launch file loads it and it is the learner's own file, checked as written)
        generated = generated_pairs(paths, [*args.files, *installed_descriptions(read)])
        results += [alone[path] if path in alone else
                    FileResult(path, compare_generated(path, generated[path], mappings=mappings,
                                                       package_paths=args.package_path, lang=lang,
                                                       select=select, ignore=ignore)
                               if path in generated else validate_path(path, mappings=mappings,
                                                                       roots=found_in(path, args.files), **options))
                    for path in paths]
        results += _run_results(nodes, lang, select, ignore, args.duration, nodes=True)
    else:
        from ..model.authoring import arm, parse_assignments

        # the arm bras-kit urdf prints with the same options (inertials: fixed to a 'world' root)
        robot = arm(wrist=args.wrist, inertials=args.inertials, params=parse_assignments(args.param),
                    world_anchor=args.inertials)
        results = [check_robot(robot, **options)]
    if args.format == "json":
        sys.stdout.write(format_json(results, strict=args.strict, lang=lang))
    else:
        if _use_colour():
            emit(sys.stdout, format_styled(results, lang), end="")
        else:
            sys.stdout.write(format_text(results, lang))
    if args.verbose:
        _print_packages()
    return exit_code(results, strict=args.strict)
