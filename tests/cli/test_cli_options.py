"""An option string two commands share has one meaning (issue 52, item 6).

The walk reads every sub-command's parser as ``bras-kit`` builds it (sub-parsers of a command
included) and groups the actions by option string. The oracle of "one meaning" is the table of
meanings the parsers are built from (bras_kit/cli/_options.py): an option of two commands that
is not in it fails, and so does one whose help does not begin with its meaning. No list of
today's options is written here.
"""

from __future__ import annotations

import argparse
import collections
import subprocess
import sys

import pytest

from bras_kit import cli
from bras_kit.cli import _options


def _actions(parser: argparse.ArgumentParser, where: str):  # type: ignore[no-untyped-def]
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for name, sub in action.choices.items():
                yield from _actions(sub, f"{where} {name}")
        elif action.option_strings and not isinstance(action, argparse._HelpAction):
            yield where, action


def _by_option() -> dict[str, list[tuple[str, argparse.Action]]]:
    found: dict[str, list[tuple[str, argparse.Action]]] = collections.defaultdict(list)
    for name in cli.COMMANDS:
        cli.build_parser(name)
        for where, action in _actions(cli._SUBPARSERS[name], name):
            if action.help == argparse.SUPPRESS:  # a deprecated spelling that warns when used
                continue
            for option in action.option_strings:
                found[option].append((where, action))
    return found


SHARED = {option: uses for option, uses in _by_option().items() if len({w for w, _ in uses}) > 1}


def test_the_walk_sees_the_options_every_command_shares():
    assert len(cli.COMMANDS) > 20
    assert {"--lang", "--force", "--output", "--no-browser"} <= set(SHARED)


@pytest.mark.parametrize("option", sorted(SHARED))
def test_an_option_of_several_commands_has_one_meaning(option):
    meaning = _options.meaning_of(option)
    assert meaning is not None, (f"{option} is taken by {sorted({w for w, _ in SHARED[option]})}: write its one "
                                 "meaning in bras_kit/cli/_options.py MEANINGS")
    for where, action in SHARED[option]:
        assert action.help == meaning, f"bras-kit {where} {option}: {action.help!r} is not {meaning!r}"
        shown = _options.help_text(action, lambda text: text)
        assert shown is not None and shown.startswith(meaning)


def test_a_new_command_taking_a_shared_option_gets_its_meaning():
    parser = argparse.ArgumentParser()
    parser.add_argument("--no-browser", action="store_true", help="run a batch without a page")
    parser.add_argument("--only-here", action="store_true", help="mine")
    _options.apply(parser)
    no_browser, only_here = parser._actions[1], parser._actions[2]
    assert no_browser.help == "serve the page and print its address, without opening a browser"
    assert _options.help_text(no_browser, str) == no_browser.help + ": run a batch without a page"
    assert only_here.help == "mine"


def test_a_meaning_and_its_detail_read_in_french(run_cli):
    code, out, _ = run_cli("plot", "--help", "--lang", "fr")
    assert code == 0
    text = " ".join(out.split())
    assert "où écrire : une image" in text


def _help(command: str) -> str:
    done = subprocess.run([sys.executable, "-m", "bras_kit", command, "--help", "--lang", "en"],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return " ".join(done.stdout.split())


def test_no_browser_says_the_same_in_view_and_launch():
    for command in ("view", "launch"):
        assert "--no-browser serve the page and print its address, without opening a browser" in _help(command)
    assert "--no-page no page: print what started" in _help("launch")


class _Page:
    url = "http://127.0.0.1:8080/"


@pytest.mark.parametrize(("argv", "opened"), [((), True), (("--no-browser",), False)])
def test_launch_opens_a_browser_unless_no_browser(monkeypatch, capsys, argv, opened):
    """``launch --no-browser`` serves the page (its address printed) and opens no browser, as view does;
    the batch without a page is ``--no-page``."""
    import webbrowser

    from bras_kit.cli import launch

    args = cli.build_parser("launch").parse_args(["launch", "bras_description", *argv])
    assert args.no_page is False
    monkeypatch.setenv("DISPLAY", ":0")
    monkeypatch.setattr(webbrowser, "open", lambda url: calls.append(url))
    calls: list[str] = []
    args.lang = "en"
    launch._announce(args, _Page(), "bras_description")
    assert "bras-kit launch: http://127.0.0.1:8080/ (Ctrl-C to stop)" in capsys.readouterr().out
    assert calls == ([_Page.url] if opened else [])


def test_no_page_is_launchs_batch():
    args = cli.build_parser("launch").parse_args(["launch", "bras_description", "--no-page"])
    assert args.no_page is True and args.no_browser is False
