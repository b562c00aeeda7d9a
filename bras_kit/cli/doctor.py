"""bras-kit doctor: what this install can do (OpenGL, MuJoCo, the browser viewer...) and how to fix the rest;
with --ros, what keeps RViz empty or the arm still on the live ROS 2 graph."""

from __future__ import annotations

import argparse

EPILOG = """\
examples:
  bras-kit doctor                         what this install can do; in a colcon workspace (its root or below),
                                          what is stale, unsourced or shadowed there; this machine's ROS 2 settings
  bras-kit doctor --ros                   join the running ROS 2 graph for 3 s: why RViz stays empty or the arm still
  bras-kit doctor --ros --format json     the same, for programs
  bras-kit doctor --ros --save look.json  keep what was seen; 'bras-kit doctor --ros --from look.json' reports it again

exit codes: 0 nothing to fix, 1 something to fix (see 'fix'); with --ros: 0 nothing keeps RViz from showing the
arm moving, 1 something does, 3 could not look (no rclpy: source ROS 2 or install 'bras-kit[ros]')
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.epilog = EPILOG
    parser.add_argument("--clear-cache", action="store_true",
                        help="remove the decoded meshes kept in the cache folder, then run the checks")
    parser.add_argument("--ros", action="store_true",
                        help="join it (ROS_DOMAIN_ID, discovery range and RMW from the environment) and say what keeps RViz empty or the arm still")
    parser.add_argument("--duration", type=float, default=None, metavar="S",
                        help="with --ros: the graph is watched for (default 3)")
    parser.add_argument("--format", choices=("text", "json"), default="text",
                        help="with --ros: text for people (default) or JSON for programs")
    parser.add_argument("--save", metavar="FILE",
                        help="with --ros: also write what was seen to FILE (JSON), to look at again with --from "
                             "or to send to a teacher")
    parser.add_argument("--from", dest="from_file", metavar="FILE",
                        help="with --ros: a look saved with --save, reported instead of joining the graph")
    from ._common import add_force_argument

    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    if args.ros:
        from ._doctor_ros import run_ros

        return run_ros(args)
    from ..core.i18n import labelled, say
    from ..core.message import M, Mn
    from ..doctor.install import CHECKS, healthy, run_checks

    if args.duration is not None or args.save or args.from_file or args.format != "text":
        from ..core.errors import ParameterError

        raise ParameterError(M("--duration, --format, --save and --from go with --ros"),
                             hint=M("add --ros to look at the live ROS 2 graph"))

    lang = args.lang
    if getattr(args, "clear_cache", False):
        from ..meshes import clear_cache

        removed = clear_cache()
        print(say(Mn("removed {n} decoded mesh ({size:.1f} MB) from {path}",
                     "removed {n} decoded meshes ({size:.1f} MB) from {path}", removed.entries,
                     size=removed.bytes / 1e6, path=removed.folder), lang), flush=True)
    status_words = {"ok": say(M("ok"), lang), "note": say(M("note"), lang), "fail": say(M("fail"), lang)}
    width = max(len(word) for word in status_words.values())
    results = []
    for check in CHECKS:  # one at a time: each line shows as soon as its check is done
        (result,) = run_checks([check])
        results.append(result)
        print(f"{status_words[result.status]:<{width}}  " + labelled(result.name, say(result.found, lang), lang),
              flush=True)
        if result.fix is not None:
            label = M("fix") if result.status == "fail" else M("hint")
            print(f"{'':<{width}}  " + labelled(label, say(result.fix, lang), lang), flush=True)
    from ._surroundings import print_surroundings

    results += print_surroundings(lang, width=width, graphics=True)
    failed = sum(result.status == "fail" for result in results)
    if healthy(results):
        print(say(M("everything bras-kit needs works here"), lang))
        return 0
    print(say(Mn("{n} problem to fix: see 'fix' above", "{n} problems to fix: see 'fix' above", failed), lang))
    return 1
