"""bras-kit explain: what a validator rule checks, why it matters and how to fix it."""

from __future__ import annotations

import argparse
import sys


def configure(parser: argparse.ArgumentParser) -> None:
    parser.add_argument("code", nargs="?", metavar="CODE",
                        help="a rule code (BK301) or name (joint-not-at-segment-end); omit to list every rule")


def run(args: argparse.Namespace) -> int:
    from ..validate.catalogue import explain_text, find_rule, rule_list_text

    lang = args.lang
    if args.code is None:
        sys.stdout.write(rule_list_text(lang))
        return 0
    text = explain_text(find_rule(args.code), lang)
    sys.stdout.write(text if text.endswith("\n") else text + "\n")
    return 0
