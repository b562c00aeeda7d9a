"""The French command line: complete catalogs, current .mo files, and commands that speak French.

The catalogs are read with Babel (the contributor tool that compiles them); the commands run
in subprocesses with ``--lang fr`` (or a French locale) and their whole output is searched for
English words a French learner should never see.
"""

from __future__ import annotations

import functools
import os
import re
import subprocess
import sys
from collections import Counter
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

from bras_kit.core.i18n import LOCALE_DIR

babel_pofile = pytest.importorskip("babel.messages.pofile")
babel_mofile = pytest.importorskip("babel.messages.mofile")

PO_FILES = sorted(LOCALE_DIR.glob("*/LC_MESSAGES/*.po"))

# str.format fields ({name}, {duration:g}, {}) and %-style fields (%(prog)s, %s, %r): the code fills
# them in, so a translation must keep every one (brace fields by name, unnamed holes by count).
BRACE_FIELD = re.compile(r"\{[^{}\s\"']*\}")
PERCENT_FIELD = re.compile(r"%(?:\([A-Za-z_]+\))?[-#0+]?\d*(?:\.\d+)?[sdrifgxXc%]")


def _messages(po: Path) -> list:
    with po.open("rb") as handle:
        catalog = babel_pofile.read_po(handle)
    return [m for m in catalog if m.id]


def _fields(text: str) -> tuple[Counter, Counter]:
    return Counter(BRACE_FIELD.findall(text)), Counter(PERCENT_FIELD.findall(text))


def test_field_patterns_see_what_the_code_fills_in():
    braces, percents = _fields("%(prog)s: error: %(message)s {name} took {duration:g} s, {} and %r but not 50 % and")
    assert braces == Counter({"{name}": 1, "{duration:g}": 1, "{}": 1})
    assert percents == Counter({"%(prog)s": 1, "%(message)s": 1, "%r": 1})
    assert _fields('write {"time": 0.5, "positions": {"epaule": 0.3}}') == (Counter(), Counter())


def test_there_is_a_french_cli_catalog():
    assert LOCALE_DIR / "fr" / "LC_MESSAGES" / "cli.po" in PO_FILES


@functools.cache
def _template_prose() -> frozenset[str]:
    """The ids of the package templates' {% trans %} blocks (paragraphs of generated files)."""
    from bras_kit.cli.catalogs import extract_templates

    return frozenset(item.id for item in extract_templates())


@pytest.mark.parametrize("po", PO_FILES, ids=lambda p: f"{p.parent.parent.name}/{p.stem}")
def test_every_entry_is_translated_and_keeps_its_fields(po):
    problems = []
    messages = _messages(po)
    assert len(messages) > 10
    for message in messages:
        english, french = (message.id, message.string) if isinstance(message.id, str) else \
            (message.id[0], message.string[0])
        if not french:
            problems.append(f"no translation: {english!r}")
            continue
        if _fields(english) != _fields(french):
            problems.append(f"fields differ: {english!r} -> {french!r}")
        reflowed = english in _template_prose()  # a generated file's paragraph: French wraps its own lines
        if message.context and message.context.startswith("BK"):
            # a validator rule's explanation: prose wrapped at about 95 columns in each language;
            # its paragraphs, not its lines, must match
            if english.count("\n\n") != french.count("\n\n"):
                problems.append(f"paragraphs differ: {english!r} -> {french!r}")
        elif not reflowed and (english.count("\n") != french.count("\n")
                               or english.endswith("\n") != french.endswith("\n")):
            problems.append(f"newlines differ: {english!r} -> {french!r}")
        if "\u00a0" in french or "\u202f" in french:
            problems.append(f"non-breaking space: {french!r}")
    assert not problems, "\n".join(problems)


def _po_entries(po: Path) -> dict[object, object]:
    """What a .po says, keyed as the standard library's gettext keys a compiled catalog: an id
    (``context\x04id`` with a context) -> its translation; ``(id, n)`` -> each plural form.
    Untranslated and fuzzy entries are left out, as a compiled catalog leaves them out."""
    with po.open("rb") as handle:
        catalog = babel_pofile.read_po(handle)
    entries: dict[object, object] = {}
    for message in catalog:
        if not message.id or message.fuzzy:
            continue
        ids = message.id if isinstance(message.id, (tuple, list)) else (message.id,)
        strings = message.string if isinstance(message.string, (tuple, list)) else (message.string,)
        if not all(strings):
            continue
        key = f"{message.context}\x04{ids[0]}" if message.context else ids[0]
        if len(ids) > 1:
            for n, text in enumerate(strings):
                entries[(key, n)] = text
        else:
            entries[key] = strings[0]
    return entries


@pytest.mark.parametrize("po", PO_FILES, ids=lambda p: f"{p.parent.parent.name}/{p.stem}")
def test_every_mo_file_is_compiled_from_its_po(po):
    """The .mo the run time reads holds exactly the .po's translations (ids, contexts, plural
    forms), read back by the standard library's gettext: not compared byte for byte with what
    today's Babel would write, whose header and layout change between its releases."""
    import gettext

    mo = po.with_suffix(".mo")
    assert mo.exists(), f"{mo} is missing: run python -m bras_kit.cli.catalogs compile"
    with mo.open("rb") as handle:
        compiled = dict(gettext.GNUTranslations(handle)._catalog)  # type: ignore[attr-defined]
    compiled.pop("", None)  # the header
    expected = _po_entries(po)
    missing = sorted(str(k) for k in expected.keys() - compiled.keys())
    stale = sorted(str(k) for k in compiled.keys() - expected.keys())
    changed = sorted(str(k) for k in expected.keys() & compiled.keys() if expected[k] != compiled[k])
    assert not (missing or stale or changed), (
        f"{mo} is older than {po.name}: run python -m bras_kit.cli.catalogs compile\n"
        f"missing: {missing[:5]}\nno longer in the .po: {stale[:5]}\ntranslated otherwise: {changed[:5]}")


# ------------------------------------------------------------------ the commands, in French

# English words that must not reach a French learner (whole words, any case). "options:" is left out:
# the French word is the same ("options" -> "options"), so argparse's heading is the same too.
ENGLISH = re.compile(r"\b(error|hint|warning|wrote|usage|positional arguments|unknown|joint)\b", re.IGNORECASE)


def _case(argv: list[str], code: int, env: dict[str, str] | None = None) -> tuple[list[str], int, dict[str, str]]:
    return argv, code, env or {}


def _cases(tmp: Path) -> dict[str, tuple[list[str], int, dict[str, str]]]:
    from bras_kit.cli import COMMANDS

    cases = {f"help-{name}": _case(["--lang", "fr", name, "--help"], 0) for name in COMMANDS}
    cases.update({
        "help": _case(["--lang", "fr", "--help"], 0),
        "render-ok": _case(["--lang", "fr", "render", "--set", "epaule=0.5", "-o", str(tmp / "pose.png")], 0),
        "render-exists": _case(["--lang", "fr", "render", "-o", str(tmp / "wp.csv")], 2),
        "render-bad-view": _case(["--lang", "fr", "render", "--view", "bogus"], 2),
        "render-bad-size": _case(["--lang", "fr", "render", "--size", "10", "-o", str(tmp / "s.png")], 2),
        "bad-option": _case(["--lang", "fr", "tree", "--bogus"], 2),
        "bad-option-locale": _case(["tree", "--bogus"], 2, {"LANG": "fr_FR.UTF-8"}),
        "unknown-joint": _case(["--lang", "fr", "fk", "--set", "genou=1"], 2),
        "wrist-without-flag": _case(["--lang", "fr", "tree", "--set", "poignet=1"], 2),
        "wrong-value": _case(["--lang", "fr", "validate", "--set", "coude=abc"], 2),
        "wrong-formula": _case(["--lang", "fr", "motion", "--motion", "coude=foo(t)"], 2),
        "unknown-parameter": _case(["--lang", "fr", "urdf", "--param", "bras_lenght=1"], 2),
        "missing-file": _case(["--lang", "fr", "tree", str(tmp / "absent.urdf")], 2),
        "missing-folder": _case(["--lang", "fr", "plot", "-o", str(tmp / "absent" / "p.png")], 2),
        "motion-ok": _case(["--lang", "fr", "motion", "--duration", "2"], 0),
        "motion-past-limits": _case(["--lang", "fr", "motion", "--motion", "coude=2.5*sin(t)", "--duration", "3"], 0),
        "motion-waypoints-too-fast": _case(["--lang", "fr", "motion", "--motion", str(tmp / "wp.csv")], 0),
        "tree-ok": _case(["--lang", "fr", "tree", "--set", "coude=pi/2"], 0),
        "reach-ok": _case(["--lang", "fr", "reach", "0.3", "0", "0.6"], 0),
        "frames-past-limit": _case(["--lang", "fr", "frames", "-o", str(tmp / "f.svg"), "--set", "coude=3"], 0),
    })
    return cases


def _run(argv: list[str], extra_env: dict[str, str]) -> tuple[int, str]:
    env = {k: v for k, v in os.environ.items()
           if k not in ("BRAS_KIT_LANG", "LC_ALL", "LC_MESSAGES", "LANG", "LANGUAGE")}
    env.update({"PYOPENGL_PLATFORM": env.get("PYOPENGL_PLATFORM", "egl"), "MPLBACKEND": "Agg"}, **extra_env)
    done = subprocess.run([sys.executable, "-m", "bras_kit", *argv], capture_output=True, text=True,
                          env=env, timeout=120)
    return done.returncode, done.stdout + done.stderr


@pytest.fixture(scope="module")
def french_runs(tmp_path_factory):
    tmp = tmp_path_factory.mktemp("fr")
    (tmp / "wp.csv").write_text("time,epaule,coude\n0,0,0\n0.5,1,1.5\n", encoding="utf-8")
    cases = _cases(tmp)
    with ThreadPoolExecutor(max_workers=4) as pool:
        futures = {name: pool.submit(_run, argv, env) for name, (argv, _code, env) in cases.items()}
        results = {name: future.result() for name, future in futures.items()}
    return tmp, cases, results


@functools.cache
def _typed_names() -> tuple[str, ...]:
    """Option metavars (JOINT=VALUE, FILE), command names and the validator's rule names: words a
    user types, the same in every language."""
    from bras_kit import cli
    from bras_kit.findings.registry import RULES

    names: set[str] = set(cli.COMMANDS)
    for command in cli.COMMANDS:
        cli.build_parser(command)
        for action in cli._SUBPARSERS[command]._actions:
            metavar = action.metavar
            names.update(metavar if isinstance(metavar, tuple) else [metavar or action.dest.upper()])
            if action.choices and not action.option_strings:  # a positional's words: bras-kit exercises hint
                names.update(str(choice) for choice in action.choices)
    names.update(rule.name for rule in RULES.values())
    return tuple(sorted((n for n in names if n), key=len, reverse=True))


def _not_english(text: str) -> str:
    """The text left to check once option names (--joint) and typed names are taken out."""
    text = re.sub(r"(?<=\w)-\n\s+(?=\w)", "-", text)  # argparse wraps help lines at hyphens
    text = re.sub(r"(?<![\w-])--?[A-Za-z][\w-]*", " ", text)
    for name in _typed_names():
        text = re.sub(r"(?<![\w-])" + re.escape(name) + r"(?![\w-])", " ", text)
    return text


def _names():
    return sorted(_cases(Path("/nonexistent")))


@pytest.mark.parametrize("name", _names())
def test_the_command_speaks_french(french_runs, name):
    tmp, cases, results = french_runs
    _argv, expected, _env = cases[name]
    code, output = results[name]
    assert code == expected, output
    assert "Traceback" not in output
    leftover = ENGLISH.findall(_not_english(output.replace(str(tmp), "TMP")))
    assert not leftover, f"English words {sorted(set(leftover))} in:\n{output}"
    if expected == 2:
        assert "erreur" in output  # a failure says so in French
    if name.startswith("help"):
        assert "utilisation : bras-kit" in output


def test_the_good_render_wrote_a_png(french_runs):
    tmp, _cases, results = french_runs
    assert (tmp / "pose.png").read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "pose.png écrit" in results["render-ok"][1]


def test_the_metavar_filter_keeps_english_prose():
    # the filter must not hide what it looks for: English words outside names still show
    assert ENGLISH.findall(_not_english("unknown joint 'genou' --joint JOINT=VALUE BK301 joint-not-at-segment-end"))
    assert ENGLISH.findall(_not_english("--set JOINT=VALUE")) == []
