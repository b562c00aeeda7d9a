"""The English words of the command line that are not ``M()`` messages, for the ``cli`` catalog.

Two sources: argparse's own words and every command's help (descriptions, epilogs, group
titles, option help, read from the parsers themselves). ``python -m bras_kit.cli.catalogs update``
merges them into ``locale/fr/LC_MESSAGES/cli.po`` with the messages of the code; the command
line looks each up as written (:func:`bras_kit.cli._word`).
"""

from __future__ import annotations

import argparse

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
    from ._options import JOINED

    words: list[str] = [*COMMANDS.values(), JOINED]
    for name in [None, *COMMANDS]:
        parser = build_parser(name)
        parsers = [parser]
        if name is not None:
            parsers.append(_subparser(parser, name))
        for p in parsers:
            words += [t for t in (p.description, p.epilog) if t]
            words += [g.title for g in p._action_groups if g.title]
            words += [a.help for a in p._actions if a.help and a.help != argparse.SUPPRESS]
            words += [a.detail for a in p._actions if getattr(a, "detail", None)]  # type: ignore[attr-defined]
        if name is not None:
            _command_module(name)  # imported so its marked strings exist
    return words


def _subparser(parser: argparse.ArgumentParser, name: str) -> argparse.ArgumentParser:
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return action.choices[name]
    raise LookupError(name)
