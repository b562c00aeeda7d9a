"""``bras-kit exercises``: the tutorial as a track of exercises on the learner's own files."""

from __future__ import annotations

import argparse
import os
import shutil
import sys

from ..core.errors import BrasKitError
from ..core.message import M
from ..trust.inert import emit, join

ACTIONS = ("watch", "init", "check", "list", "hint", "reset")

_EPILOG = """\
A track of small exercises that follow the tutorial, each a file with a mistake or a gap, laid out
in a folder of your own. Watch mode shows the current exercise, checks it again each time you save,
gives the next hint on request (key h) and moves on when it passes. Each check judges what your file
does (where the tip of the arm is, what the validator finds, what your node publishes), never its
text: any correct solution passes. Progress is kept in progress.json beside the exercises.

examples:
  bras-kit exercises init exos        lay the track out in exos/
  cd exos && bras-kit exercises       watch mode: edit the files, save, read
  bras-kit exercises check            check the current exercise once (exit code 0 when it passes)
  bras-kit exercises list             every exercise and where you are
  bras-kit exercises hint             the next hint of the current exercise
  bras-kit exercises reset 3          lay exercise 3's starting files out again (asks first)
"""


def configure(parser: argparse.ArgumentParser) -> None:
    parser.formatter_class = argparse.RawDescriptionHelpFormatter
    parser.epilog = _EPILOG
    parser.add_argument("action", nargs="?", default="watch", choices=ACTIONS, metavar="ACTION",
                        help="watch (default), init, check, list, hint or reset")
    parser.add_argument("target", nargs="?", metavar="DIR|N",
                        help="init: the folder to lay the track out in (default: bras-kit-exercises); "
                        "check, hint: an exercise number (default: the current one); reset: the exercise number")
    parser.add_argument("-C", "--dir", metavar="DIR", default=None,
                        help="the track's folder (default: the current folder or the first parent holding "
                        "progress.json)")
    parser.add_argument("--track", dest="exercise_set", metavar="DIR", default="builtin",
                        help="init: a teacher's exercise set (a folder with track.yaml) instead of the built-in track")
    parser.add_argument("--force", action="store_true",
                        help="reset: your files are replaced without asking")


def run(args: argparse.Namespace) -> int:
    from ..core.i18n import current_language

    lang = args.lang or current_language()
    action = args.action
    if action == "init":
        return _init(args, lang)
    lang = _track_language(args, lang)
    if action == "watch":
        if args.target is not None:
            raise BrasKitError(M("watch mode takes no argument"), hint=M("use -C DIR to name the track's folder"))
        from ..exercises.watch import watch

        return watch(_folder(args), lang)
    if action == "list":
        return _list(args, lang)
    if action == "check":
        return _check(args, lang)
    if action == "hint":
        return _hint(args, lang)
    return _reset(args, lang)


def _track_language(args: argparse.Namespace, lang: str) -> str:
    """The language the track was laid out in, unless --lang names another on this command line:
    a track made with --lang fr answers in French when started with the command init printed."""
    from ..core.i18n import set_language
    from ..exercises.progress import find_track_folder, read_progress

    if getattr(args, "lang_given", None):
        return lang
    folder = _folder(args) or find_track_folder(os.getcwd())
    try:
        kept = read_progress(folder).lang if folder is not None else ""
    except BrasKitError:
        return lang  # said by the action itself, which opens the track
    return set_language(kept) if kept else lang


def _folder(args: argparse.Namespace):
    from pathlib import Path

    return Path(args.dir) if args.dir else None


def _width() -> int:
    return shutil.get_terminal_size((80, 24)).columns if sys.stdout.isatty() else 80


def _style():
    from ..exercises.screen import Style, wants_colour

    return Style(wants_colour(sys.stdout))


def _init(args: argparse.Namespace, lang: str) -> int:
    from ..core.i18n import say
    from ..exercises import init_track

    folder = args.target or args.dir or "bras-kit-exercises"
    track = init_track(folder, args.exercise_set, lang)
    print(say(M("laid out {n} exercises in {path}", n=len(track.exercises), path=folder), lang))
    print(say(M("next: cd {path} && bras-kit exercises", path=folder), lang))
    return 0


def _pick(track, progress, target):
    from ..exercises import current_exercise

    return track.exercise(target) if target is not None else current_exercise(track, progress)


def _list(args: argparse.Namespace, lang: str) -> int:
    from ..exercises import open_track
    from ..exercises.screen import list_lines

    if args.target is not None:
        raise BrasKitError(M("list takes no argument"))
    track, progress = open_track(_folder(args))
    emit(sys.stdout, join("\n", list_lines(track, progress, lang, _width(), _style())))
    return 0


def _check(args: argparse.Namespace, lang: str) -> int:
    from ..exercises import check_exercise, open_track
    from ..exercises.screen import done_lines, exercise_lines

    track, progress = open_track(_folder(args))
    exercise = _pick(track, progress, args.target)
    if exercise is None:
        emit(sys.stdout, join("\n", done_lines(track, lang, _width(), _style())))
        return 0
    outcome = check_exercise(track, progress, exercise, lang)
    emit(sys.stdout, join("\n", exercise_lines(track, progress, exercise, outcome, lang, _width(), _style())))
    if outcome.state == "passed":
        from ..core.i18n import say
        from ..exercises import current_exercise

        following = current_exercise(track, progress)
        if following is not None:
            print(say(M("next: exercise {number}, {title}", number=following.number,
                        title=following.title_in(lang)), lang))
        return 0
    return 1


def _hint(args: argparse.Namespace, lang: str) -> int:
    from ..exercises import open_track, reveal_hint
    from ..exercises.screen import hint_lines

    track, progress = open_track(_folder(args))
    exercise = _pick(track, progress, args.target)
    if exercise is None:
        raise BrasKitError(M("every exercise passed: there is no hint left to give"))
    seen = reveal_hint(progress, exercise)
    emit(sys.stdout, join("\n", hint_lines(exercise, range(1, seen + 1), lang, _width(), _style())))
    return 0


def _reset(args: argparse.Namespace, lang: str) -> int:
    from ..core.i18n import say
    from ..exercises import exercise_files, open_track, reset_exercise, start_files

    if args.target is None:
        raise BrasKitError(M("reset needs the exercise's number"), hint=M("for example: bras-kit exercises reset 3"))
    track, progress = open_track(_folder(args))
    exercise = track.exercise(args.target)
    mine = [str(p) for p in exercise_files(progress.folder, exercise) if p.exists()]
    others = [name for name in start_files(exercise)
              if os.path.exists(os.path.join(progress.folder, exercise.id, name))]
    if (mine or others) and not args.force and not _confirmed(exercise, mine or others, lang):
        print(say(M("nothing was changed"), lang), file=sys.stderr)
        return 1
    reset_exercise(progress, exercise)
    print(say(M("exercise {number} is back to its starting files: {files}", number=exercise.number,
                files=list(exercise.files)), lang))
    return 0


def _confirmed(exercise, files, lang: str) -> bool:
    from ..core.i18n import say

    if not sys.stdin.isatty():
        raise BrasKitError(M("reset replaces your files {files}: it asks first, and there is no terminal to ask in",
                             files=files),
                           hint=M("run it in a terminal to confirm, or copy your files elsewhere first"))
    question = say(M("replace your files {files} with the starting ones? [y/N] ", files=files), lang)
    try:
        answer = input(question).strip().lower()
    except EOFError:
        return False
    return answer in {say(M("y"), lang).lower(), say(M("yes"), lang).lower(), "y", "yes"}
