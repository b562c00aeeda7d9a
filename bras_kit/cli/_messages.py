"""The English words of the command line, gathered for the ``cli`` gettext catalog.

``python -m bras_kit.cli._messages`` merges them into ``locale/fr/LC_MESSAGES/cli.po``
(keeping every translation already there, adding new entries empty, dropping none) and
recompiles the catalogs; a test fails while any of them has no French.

Three sources: argparse's own words, every command's help (descriptions, epilogs, group
titles, option help, read from the parsers themselves) and the strings marked ``_("...")``
in the code (found by Babel's extractor).
"""

from __future__ import annotations

import argparse
import inspect
import re
from pathlib import Path

ARGPARSE_WORDS = (
    "usage: ", "options", "positional arguments", "show this help message and exit",
    "%(prog)s: error: %(message)s\n", "the following arguments are required: %s",
    "unrecognized arguments: %s", "invalid choice: %(value)r (choose from %(choices)s)",
    "argument %(argument_name)s: %(message)s", "expected one argument",
    "expected at most one argument", "expected at least one argument",
    "invalid %(type)s value: %(value)r", "ambiguous option: %(option)s could match %(matches)s",
    "not allowed with argument %s", "one of the arguments %s is required",
    "ignored explicit argument %r", "expected %s argument", "expected %s arguments",
)


def parser_words() -> list[str]:
    """Every description, epilog, group title and help string of every command."""
    from . import COMMANDS, _command_module, build_parser

    words: list[str] = list(COMMANDS.values())
    for name in [None, *COMMANDS]:
        parser = build_parser(name)
        parsers = [parser]
        if name is not None:
            parsers.append(_subparser(parser, name))
        for p in parsers:
            words += [t for t in (p.description, p.epilog) if t]
            words += [g.title for g in p._action_groups if g.title]
            words += [a.help for a in p._actions if a.help and a.help != argparse.SUPPRESS]
        if name is not None:
            _command_module(name)  # imported so its marked strings exist
    return words


def _subparser(parser: argparse.ArgumentParser, name: str) -> argparse.ArgumentParser:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return action.choices[name]  # type: ignore[no-any-return]
    raise LookupError(name)


def marked_words(root: Path | None = None) -> list[str]:
    """Strings passed to ``_()`` in bras_kit's code (the ``cli`` domain)."""
    from babel.messages.extract import extract_from_dir

    root = root or Path(__file__).resolve().parents[1]
    words = []
    for _filename, _lineno, message, _comments, _context in extract_from_dir(
            str(root), method_map=[("**.py", "python")], keywords={"_": None}):
        if isinstance(message, str):
            words.append(message)
    return words


def all_words() -> list[str]:
    seen: dict[str, None] = {}
    for word in [*ARGPARSE_WORDS, *parser_words(), *marked_words()]:
        seen.setdefault(word, None)
    return list(seen)


def update_catalog() -> tuple[Path, list[str]]:
    """Add the missing entries to cli.po (empty); return its path and the untranslated ids."""
    from babel.messages.pofile import read_po, write_po

    from ..i18n import LOCALE_DIR, compile_catalogs

    path = LOCALE_DIR / "fr" / "LC_MESSAGES" / "cli.po"
    with path.open("rb") as handle:
        catalog = read_po(handle, locale="fr")
    for word in all_words():
        if word not in catalog:
            catalog.add(word, "")
    with path.open("wb") as handle:
        write_po(handle, catalog, width=0, omit_header=False)
    compile_catalogs()
    return path, [str(m.id) for m in catalog if m.id and not m.string]


def _check_argparse_words() -> list[str]:
    """argparse words this module lists that argparse no longer uses (a new Python changed them)."""
    source = inspect.getsource(argparse)
    return [w for w in ARGPARSE_WORDS if repr(w)[1:-1] not in source and w not in source
            and not re.search(re.escape(w.rstrip("\n")), source)]


if __name__ == "__main__":
    where, missing = update_catalog()
    print(f"{where}: {len(missing)} entries without French")
    for word in missing:
        print("  " + word.replace("\n", "\\n"))
