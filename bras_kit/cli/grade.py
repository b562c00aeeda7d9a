"""bras-kit grade: a whole class's submissions validated, drawn and scored."""

from __future__ import annotations

import argparse
import os
import sys
import time

from ..core.i18n import say
from ..core.message import M
from ._common import add_cache_argument, add_force_argument

EPILOG = """\
examples:
  bras-kit grade copies/                         one sub-folder, file or archive per learner
  bras-kit grade copies/ --lang fr -o rapport/   findings in French
  bras-kit grade copies/ --resume                only the submissions that changed
  bras-kit grade copies/ --scheduler tcp://10.0.0.5:8786   on a Dask cluster
  bras-kit grade --explain-rubric > bareme.yaml  the default rubric, to adapt
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.epilog = EPILOG
    parser.add_argument("submissions", nargs="?", metavar="SUBMISSIONS",
                        help="folder with one entry per learner: a folder, a .urdf/.xacro file or a .zip/.tar.gz")
    parser.add_argument("--rubric", metavar="YAML", help="the rubric (default: the tutorial's, out of 20)")
    parser.add_argument("--explain-rubric", action="store_true", help="print the rubric and exit")
    parser.add_argument("-o", "--output", default="grade-report", metavar="DIR",
                        help="the report folder (default: ./grade-report)")
    parser.add_argument("--jobs", type=int, default=None, metavar="N",
                        help="worker processes on this machine (default: one per core)")
    parser.add_argument("--scheduler", metavar="ADDRESS",
                        help="grade on a Dask cluster, e.g. tcp://10.0.0.5:8786 (pip install 'bras-kit[cluster]')")
    parser.add_argument("--resume", action="store_true",
                        help="reuse the report's results of submissions that have not changed")
    parser.add_argument("--gradescope", action="store_true",
                        help="also write one results.json per learner in Gradescope's shape (gradescope/)")
    parser.add_argument("--no-pictures", action="store_true", help="skip the pictures (faster)")
    add_cache_argument(parser)
    parser.add_argument("--gif", action="store_true",
                        help="each arm moving (the tutorial's motion), as pictures/LEARNER.gif")
    parser.add_argument("--run-nodes", action="store_true",
                        help="also run each package's nodes with bras-kit run's stand-in for rclpy and check what "
                        "they publish (BK640-BK659). This EXECUTES the learners' code: each node runs contained "
                        "(it writes only in its own temporary folder, reads only its package and Python, has no "
                        "network, reaches no other process: see docs/security.md) and limited in CPU time, "
                        "memory and wall-clock time; refused where this machine cannot contain it (bras-kit "
                        "doctor says why); off by default")
    parser.add_argument("--unsafe-run-nodes", action="store_true",
                        help="--run-nodes even where the nodes cannot be contained: they then run with your "
                        "rights (your files, your network); only for code you trust")
    add_force_argument(parser)


def run(args: argparse.Namespace) -> int:
    from ..core.errors import OutputExistsError, ParameterError
    from ..grade import Options, find_submissions, grade_all, load_rubric, write_reports
    from ..grade.report import REPORT_MARK, previous_results
    from ..grade.rubric import explained_rubric

    rubric = load_rubric(args.rubric)
    if args.explain_rubric:
        sys.stdout.write(explained_rubric(rubric, args.lang))
        return 0
    if args.submissions is None:
        raise ParameterError(M("no SUBMISSIONS folder given"), hint=M("bras-kit grade copies/ (one entry per learner)"))
    if args.gif and args.no_pictures:
        raise ParameterError(M("--gif and --no-pictures cannot go together"), hint=M("keep one of them"))
    if args.jobs is not None and not 1 <= args.jobs <= 256:
        raise ParameterError(M("--jobs {jobs} is out of range", jobs=args.jobs),
                             hint=M("give a number of processes from 1 to 256"))
    output = args.output
    if os.path.islink(output) or (os.path.exists(output) and not os.path.isdir(output)):
        raise OutputExistsError(M("-o {path}: exists and is not a folder", path=output),
                                hint=M("choose another report folder"))
    if os.path.isdir(output) and os.listdir(output) and not os.path.exists(os.path.join(output, REPORT_MARK)) \
            and not args.force:
        raise OutputExistsError(M("-o {path}: the folder holds files that are not a bras-kit report", path=output),
                                hint=M("choose another folder, or pass --force"))
    submissions = find_submissions(os.path.abspath(args.submissions))  # Dask workers may start elsewhere
    if not submissions:
        raise ParameterError(M("{path} is empty", path=args.submissions),
                             hint=M("put one folder, file or archive per learner in it"))
    pictures = None if args.no_pictures else os.path.abspath(os.path.join(output, "pictures"))
    if pictures:
        os.makedirs(pictures, exist_ok=True)
    run_nodes = args.run_nodes or args.unsafe_run_nodes
    if run_nodes:
        from ..grade import node_containment

        warning = node_containment(unsafe=args.unsafe_run_nodes)  # raises where refused
        if warning is not None:
            print(say(warning, args.lang), file=sys.stderr)
    previous = previous_results(output) if args.resume else None
    start = time.monotonic()
    results, finished = grade_all(submissions, rubric, Options(lang=args.lang, pictures=pictures, gif=args.gif,
                                                                   run_nodes=run_nodes,
                                                                   contain="auto" if args.unsafe_run_nodes
                                                                   else "require"),
                                  jobs=args.jobs, scheduler=args.scheduler, previous=previous)
    write_reports(output, results, rubric, args.lang, gradescope=args.gradescope, finished=finished)
    elapsed = time.monotonic() - start
    unreadable = sum(1 for r in results if r["status"] != "graded")
    mean = sum(r["score"] for r in results) / len(results) if results else 0.0
    print(say(M("graded {count} of {total} submissions in {seconds:.1f} s: mean {mean:.1f} / {max:g}, "
                "{unreadable} could not be read; report: {index}",
                count=len(results), total=len(submissions), seconds=elapsed, mean=mean, max=rubric.total,
                unreadable=unreadable, index=os.path.join(output, "index.html")), args.lang))
    if not finished:
        print(say(M("interrupted: the report holds the submissions graded so far (--resume goes on)"), args.lang),
              file=sys.stderr)
        return 130
    return 0
