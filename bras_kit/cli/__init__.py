"""The ``bras-kit`` command: thin argument parsing over the library.

Each command lives in its own module under ``bras_kit.cli`` with ``configure(parser)`` and
``run(args) -> int``. Only the module of the command being run is imported, so ``--help``
and light commands never load pyrender, matplotlib or trimesh.
"""

from __future__ import annotations

import argparse
import gc
import importlib
import logging
import os
import signal
import sys
import warnings
from collections.abc import Sequence

from .. import __version__
from ..core.errors import BrasKitError, UnknownJointError, os_reason
from ..core.i18n import (
    LANGUAGES,
    current_language,
    labelled,
    ntranslator,
    say,
    say_error,
    set_language,
    translator,
)
from ..core.message import M, Message

# name -> one-line help. The module is bras_kit.cli.<name> (``xacro`` lives in ``xacro_cmd``).
COMMANDS: dict[str, str] = {
    "demo": "make everything for the tutorial arm: package, checks, pictures, GIF, diagrams",
    "urdf": "print or write the tutorial arm's URDF (--wrist, --inertials, --param NAME=VALUE)",
    "xacro": "expand any xacro file to URDF without ROS ($(find) from --package-path)",
    "new": "scaffold the tutorial's ROS 2 package (package.xml, setup.py, launch, RViz, node)",
    "validate": "check URDF/xacro files for the tutorial's pitfalls and URDF defects",
    "explain": "print the long explanation of a validator rule (e.g. BK301)",
    "gazebo": "what Gazebo will load: links kept, merged or dropped, frames lost, why a model is refused",
    "tree": "print the TF tree: links, joint names and types",
    "fk": "forward kinematics: each link's pose (xyz, quaternion, rpy), like tf2_echo",
    "motion": "turn a motion program into a joint-state sequence (CSV/JSON), checked against limits",
    "render": "draw the arm off-screen: PNG, image sequence, GIF or MP4",
    "frames": "draw the frame tree (like view_frames): PDF, SVG, PNG or DOT",
    "plot": "plot joint angles with their limits and the path of the tool tip",
    "reach": "inverse kinematics: joint values that put the tip at X Y Z, and a motion there",
    "workspace": "draw the region the tip can reach within the joint limits",
    "simulate": "physics with MuJoCo: gravity, motors limited by effort, collisions",
    "mjcf": "write the MuJoCo model (MJCF) bras-kit builds from the URDF",
    "view": "the arm live in the browser: sliders, TF frames, motion playback, reload on save",
    "run": "run your own ROS 2 node without ROS (like ros2 run), record and check what it publishes",
    "exercises": "the tutorial as a track of exercises on your own files: watch, hints, progress",
    "build": "build ament_python packages as colcon build does: the install tree, with colcon's errors",
    "launch": "run a package's launch file as ros2 launch does: which nodes start, what they publish, findings",
    "grade": "for teachers: check, draw and score a class's submissions (process pool or Dask)",
    "doctor": "what this install can do (OpenGL, MuJoCo, viewer, browser, cache) and how to fix the rest",
}

# The groups of ``bras-kit --help``, in the order a learner meets them along the tutorial: describe
# the arm, check it, see it, package/build/launch it, move it and run a node, physics and reach,
# then teaching. A command joins a group by its name here (a name not yet in COMMANDS is skipped);
# a command in no group is listed last, under "other commands".
GROUPS: tuple[tuple[Message, tuple[str, ...]], ...] = (
    (M("start here"), ("demo", "doctor")),
    (M("describe the arm"), ("urdf", "xacro")),
    (M("check it"), ("validate", "explain")),
    (M("see it"), ("tree", "fk", "view", "render", "frames")),
    (M("package, build and launch it"), ("new", "build", "launch")),
    (M("move it and run your node"), ("motion", "run", "plot")),
    (M("physics and reach"), ("simulate", "reach", "workspace", "mjcf", "gazebo")),
    (M("teach and grade"), ("exercises", "grade")),
)
OTHER_GROUP = M("other commands")


def command_groups() -> list[tuple[Message, list[str]]]:
    """The commands of ``bras-kit --help`` by group, each command once, the unknown ones last."""
    placed: set[str] = set()
    groups = []
    for title, names in GROUPS:
        present = [name for name in names if name in COMMANDS and name not in placed]
        placed.update(present)
        if present:
            groups.append((title, present))
    rest = [name for name in COMMANDS if name not in placed]
    if rest:
        groups.append((OTHER_GROUP, rest))
    return groups


_MODULES = {"xacro": "xacro_cmd"}
_QUIET = logging.NullHandler()
_SUBPARSERS: dict[str, argparse.ArgumentParser] = {}


def _command_module(name: str):
    return importlib.import_module(f"{__name__}.{_MODULES.get(name, name)}")


def _word(text: str) -> str:
    """A help text or an argparse word in the chosen language: each is an entry of the ``cli``
    catalog, looked up as written (``python -m bras_kit.cli.catalogs update`` reads them from the parsers)."""
    return translator(current_language(), "cli")(text)


class _Formatter(argparse.RawDescriptionHelpFormatter):
    """Help in the chosen language: descriptions, epilogs, group titles and option help go
    through the ``cli`` catalog (argparse's own words through :func:`_localise_argparse`)."""

    def _format_text(self, text: str) -> str:
        return super()._format_text(_word(text))

    def start_section(self, heading: str | None) -> None:
        if heading:
            # argparse glues its colon to the heading; French typography wants a space before it
            heading = _word(heading) + (" " if current_language() == "fr" else "")
        super().start_section(heading)

    def _get_help_string(self, action: argparse.Action) -> str | None:
        from ._options import help_text

        return help_text(action, _word)


class _TopParser(argparse.ArgumentParser):
    """``bras-kit --help`` lists the commands by group (:func:`command_groups`), not in one block."""

    def format_help(self) -> str:
        formatter = self._get_formatter()
        formatter.add_usage(self.usage, self._actions, self._mutually_exclusive_groups)
        formatter.add_text(self.description)
        commands: dict[str, argparse.Action] = {}
        for group in self._action_groups:
            if any(isinstance(a, argparse._SubParsersAction) for a in group._group_actions):
                for action in group._group_actions:
                    if isinstance(action, argparse._SubParsersAction):
                        commands.update((a.dest, a) for a in action._get_subactions())
                continue
            formatter.start_section(group.title)
            formatter.add_text(group.description)
            formatter.add_arguments(group._group_actions)
            formatter.end_section()
        lang = current_language()
        for title, names in command_groups():
            formatter.start_section(say(title, lang))
            formatter.add_arguments([commands[name] for name in names if name in commands])
            formatter.end_section()
        formatter.add_text(self.epilog)
        return formatter.format_help()


def _localise_argparse() -> None:
    """argparse looks its words up through its module globals ``_`` and ``ngettext``."""
    argparse._ = _word  # type: ignore[attr-defined]
    argparse.ngettext = lambda one, many, n: ntranslator(current_language(), "cli")(one, many, n)  # type: ignore[attr-defined]


def _add_language(parser: argparse.ArgumentParser) -> None:
    if "--lang" not in parser._option_string_actions:
        parser.add_argument("--lang", choices=LANGUAGES, default=None,
                            help="language of messages and pictures (default: BRAS_KIT_LANG, "
                            "else French when the locale is French)")


def build_parser(selected: str | None) -> argparse.ArgumentParser:
    _localise_argparse()
    parser = _TopParser(
        prog="bras-kit",
        description="Describe, check, move and show a robot arm without ROS "
        "(the arm of the tutorial 'Simuler un bras robotisé avec ROS 2').",
        epilog="Run 'bras-kit COMMAND --help' for a command's options. "
        "Start with 'bras-kit demo'.",
        formatter_class=_Formatter,
    )
    parser.add_argument("--version", action="version", version=f"bras-kit {__version__}",
                        help="show the version and exit")
    _add_language(parser)
    sub = parser.add_subparsers(dest="command", metavar="COMMAND")
    for name, summary in COMMANDS.items():
        command_parser = sub.add_parser(name, help=summary, description=summary[0].upper() + summary[1:] + ".",
                                        formatter_class=_Formatter)
        _SUBPARSERS[name] = command_parser
        if name == selected:
            _command_module(name).configure(command_parser)
            command_parser.formatter_class = _Formatter
            _add_language(command_parser)
            from ._options import apply

            apply(command_parser)  # the shared options' one meaning
    return parser


def _selected_command(argv: Sequence[str]) -> str | None:
    skip = False
    for arg in argv:
        if skip:
            skip = False
            continue
        if arg == "--lang":
            skip = True
            continue
        if not arg.startswith("-"):
            return arg if arg in COMMANDS else None
    return None


def _language_in(argv: Sequence[str]) -> str | None:
    """The value of ``--lang`` wherever it stands (before or after the command name)."""
    found = None
    for i, arg in enumerate(argv):
        if arg == "--":
            break
        if arg == "--lang" and i + 1 < len(argv):
            found = argv[i + 1]
        elif arg.startswith("--lang="):
            found = arg.split("=", 1)[1]
    return found if found in LANGUAGES else None


# OpenBLAS's threads, unless the user chose their number: bras-kit's matrices are 4x4 and 6xN, which
# one thread computes as fast, and starting a thread per core costs 50-100 ms of CPU when numpy is
# imported, taken from the worker `validate PKG_DIR` runs beside it (benchmarks/validate_against_round3.py)
BLAS_THREADS = ("OPENBLAS_NUM_THREADS", "GOTO_NUM_THREADS", "OMP_NUM_THREADS")


def main(argv: Sequence[str] | None = None) -> int:
    """The command line: every byte it writes to stdout and stderr (its own words, argparse's,
    warnings, logs, a child's that it relays, those of the processes it forks) passes the
    terminal's gate (bras_kit.trust.inert.gated_streams); bras-kit's own colours pass as Styled."""
    from ..trust.inert import gated_streams

    with gated_streams():
        return _main(argv)


def _main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    if not any(os.environ.get(name) for name in BLAS_THREADS):
        os.environ["OPENBLAS_NUM_THREADS"] = "1"
    if not os.environ.get("BRAS_KIT_DEBUG"):
        warnings.showwarning = _show_warning
        # a library's log record (matplotlib's "posx and posy should be finite values") would go to
        # stderr through logging's last-resort handler: bras-kit logs nothing itself
        logging.getLogger().addHandler(_QUIET)
    try:
        lang = set_language(_language_in(argv))
    except BrasKitError as exc:  # BRAS_KIT_LANG holds an unknown language
        print(f"bras-kit: {labelled(M('error'), say_error(exc, 'en'), 'en')}", file=sys.stderr)
        return 2
    selected = _selected_command(argv)
    parser = build_parser(selected)
    args, extra = parser.parse_known_args(argv)
    keeps = getattr(args, "keeps_assignments", None)  # NAME:=VALUE after options (ros2 launch's order)
    if extra and keeps:
        setattr(args, keeps, [*getattr(args, keeps), *(e for e in extra if ":=" in e)])
        extra = [e for e in extra if ":=" not in e]
    if extra:  # the command's own usage, not the top-level one
        target = _SUBPARSERS.get(args.command or "", parser)
        target.error(_word("unrecognized arguments: %s") % " ".join(extra))
    if args.command is None:
        parser.print_help()
        return 0
    args.lang = lang
    args.lang_given = _language_in(argv) is not None  # --lang on this command line
    command = args.command
    if getattr(args, "no_cache", False):
        from ..meshes import set_disk_cache

        set_disk_cache(False)
        os.environ["BRAS_KIT_NO_CACHE"] = "1"  # worker processes (grade) inherit it
    try:
        return int(_command_module(command).run(args) or 0)
    except UnknownJointError as exc:
        from ._common import joint_name_hint

        exc.hint = joint_name_hint(exc.joint, exc.hint)
        _fail(command, say_error(exc, lang), lang)
    except BrasKitError as exc:
        _fail(command, say_error(exc, lang), lang)
        return getattr(exc, "exit_code", 2)
    except KeyboardInterrupt:
        print(say(M("interrupted"), lang), file=sys.stderr)
        return 130
    except BrokenPipeError:
        return 0
    except MemoryError:
        _fail(command, say(M("out of memory: the input is too large for this machine"), lang), lang)
    except OSError as exc:  # a file problem no command caught: still one line, never a traceback
        where = f"{exc.filename}: " if getattr(exc, "filename", None) else ""
        _fail(command, where + say(os_reason(exc), lang), lang)
    except Exception as exc:  # a bug: say so in one line; BRAS_KIT_DEBUG=1 shows the traceback
        if os.environ.get("BRAS_KIT_DEBUG"):
            raise
        print(labelled(f"bras-kit {command}", labelled(M("internal error"), f"{type(exc).__name__}: {exc}", lang), lang)
              + "\n  "
              + labelled(M("hint"), say(M("this is a bug in bras-kit; run again with BRAS_KIT_DEBUG=1 and report "
                                          "the traceback"), lang), lang),
              file=sys.stderr)
    return 2


def _show_warning(message: Warning | str, category: type[Warning], filename: str, lineno: int,
                  file: object = None, line: str | None = None) -> None:
    """Python's warnings as the command line shows them (BRAS_KIT_DEBUG=1 shows them as Python does).

    A third-party library's warning (numpy's "overflow encountered in ...", matplotlib's missing
    glyph for a tab in a joint name...) names the installation's source files and speaks to a
    programmer: it never reaches the terminal. The commands check what they print themselves
    (non-finite numbers, diverging simulations) and say it with :func:`~bras_kit.cli._common.warn`.
    A warning of bras-kit's own category (one defined in bras_kit) is shown as ours, without paths.
    """
    if not category.__module__.startswith("bras_kit"):
        return
    text = say(message.args[0]) if isinstance(message, Warning) and message.args else say(message)
    print(labelled(M("warning"), text), file=sys.stderr)


def _fail(command: str, text: str, lang: str) -> None:
    # an error may quote a learner's text: the gate in front of stderr shows its control characters
    print(labelled(f"bras-kit {command}", labelled(M("error"), text, lang), lang), file=sys.stderr)


def _terminated(signum: int, _frame: object) -> None:
    """SIGTERM (``kill``, an editor's stop button): the command leaves through the same
    ``finally`` blocks as after Ctrl-C, so its temporary folders, page and children go with it."""
    raise SystemExit(128 + signum)


def run() -> None:
    """The ``bras-kit`` command: :func:`main`, then leave at once.

    Every output is already written, closed and moved into place when :func:`main` returns, so
    the interpreter's teardown (tens of milliseconds spent unloading PyOpenGL's modules and
    freeing OpenGL contexts the process is about to lose anyway) is skipped. Library users and
    the tests call :func:`main`, which returns normally.

    The collector of reference cycles runs after 50,000 new objects instead of 700: a command
    loads thousands of long-lived module objects (PyOpenGL alone makes tens of thousands) that
    the default threshold scans again and again, about a tenth of ``bras-kit render``'s time
    (0.05 s of 0.5 s, 111 collections; one with this threshold). Cycles are still freed.
    """
    gc.set_threshold(50_000, 10, 10)
    signal.signal(signal.SIGTERM, _terminated)
    code = main()
    if "multiprocessing" in sys.modules:
        import multiprocessing

        if multiprocessing.active_children():  # worker processes (grade) are ended by the teardown
            raise SystemExit(code)
    try:
        sys.stdout.flush()
        sys.stderr.flush()
    except (BrokenPipeError, OSError):  # a reader that went away: nothing left to say
        pass
    os._exit(code)
