"""Every message the code builds is in its domain's French catalog, with the same fields.

The ids are collected from the code's syntax tree (``M``, ``Mn``, ``Mc`` calls and the texts
given to registration calls), not from a list kept by hand, so a new message cannot be
forgotten: it fails here until ``python -m bras_kit.cli.catalogs update`` has added it and a French
translation is written.
"""

from __future__ import annotations

import ast
import re
from collections import Counter
from pathlib import Path

import pytest

from bras_kit.cli import catalogs as i18n_tools
from bras_kit.core.i18n import LOCALE_DIR, say
from bras_kit.core.message import M, Message, Mn, domain_of, number

babel_pofile = pytest.importorskip("babel.messages.pofile")

FIELD = re.compile(r"\{([A-Za-z_][A-Za-z0-9_]*)(?:[!:][^{}]*)?\}")


def _fields(text: str) -> Counter:
    return Counter(FIELD.findall(text))


def _catalog(domain: str):
    path = LOCALE_DIR / "fr" / "LC_MESSAGES" / f"{domain}.po"
    if not path.exists():
        return None
    with path.open("rb") as handle:
        return babel_pofile.read_po(handle)


def test_every_message_in_the_code_is_translated_with_the_same_fields():
    catalogs: dict = {}
    problems = []
    found = i18n_tools.extract_all()
    assert found, "the extractor found no message at all"
    for item in found:
        if item.domain not in catalogs:  # each catalog read once
            catalogs[item.domain] = _catalog(item.domain)
        catalog = catalogs[item.domain]
        where = f"{Path(item.path).relative_to(i18n_tools.PACKAGE_ROOT.parent)}:{item.line}"
        if catalog is None:
            problems.append(f"{where}: no catalog for domain {item.domain!r}")
            continue
        entry = catalog.get(item.id, context=item.context)
        if entry is None:
            problems.append(f"{where}: not in {item.domain}.po: {item.id!r}")
            continue
        strings = entry.string if isinstance(entry.string, tuple) else (entry.string,)
        if not all(strings):
            problems.append(f"{where}: no French for {item.id!r}")
            continue
        english = [item.id] + ([item.plural] if item.plural else [])
        wanted = set().union(*(_fields(e) for e in english))
        for french in strings:
            if set(_fields(french)) - wanted:
                problems.append(f"{where}: French names fields the English lacks: {item.id!r} -> {french!r}")
        if _fields(item.id) != _fields(strings[0]):
            problems.append(f"{where}: fields differ: {item.id!r} -> {strings[0]!r}")
    assert not problems, "\n".join(problems)


def test_message_ids_are_plain_strings_never_built_at_run_time():
    """``M(f"...")`` or ``M(a + b)`` could never be in a catalog."""
    bad = []
    for path in sorted(i18n_tools.PACKAGE_ROOT.rglob("*.py")):
        tree = ast.parse(path.read_text(encoding="utf-8"))
        for _context, text, _plural, line, call in i18n_tools.calls_in(tree):
            if not text and i18n_tools._name(call.func) in i18n_tools.MARKERS:
                bad.append(f"{path.name}:{line}")
    assert not bad, "message ids that are not string literals: " + ", ".join(bad)


def test_the_domain_follows_the_module_that_builds_the_message():
    assert domain_of("bras_kit.validate.pitfalls") == "validate"
    assert domain_of("bras_kit.validate.package.rules") == "validate"
    assert domain_of("bras_kit.physics.run") == "physics"
    assert domain_of("bras_kit.cli.render") == "cli"
    assert domain_of("bras_kit.validatex") == "cli"
    assert M("x").domain == "cli"  # built in a test module: the default domain


def test_numbers_are_written_as_people_write_them():
    assert number(0.6900000000000001) == "0.69"
    assert number(-0.0) == "0"
    assert number(1e308) == "1e+308"
    assert number(float("nan")) == "nan"
    assert str(M("{v} rad", v=0.1 + 0.59)) == "0.69 rad"
    assert str(M("{v:.2f} rad", v=1 / 3)) == "0.33 rad"


def test_lists_are_quoted_and_cut():
    names = [f"j{i}" for i in range(20)]
    text = str(M("joints {names}", names=names))
    assert text.startswith("joints 'j0', 'j1'") and text.endswith("... (+12)")
    assert str(M("xyz {v}", v=(0.0, 0.0, 0.6))) == "xyz 0 0 0.6"


def test_plural_and_nested_messages_are_worded_in_the_shown_language():
    one, many = Mn("{n} file checked", "{n} files checked", 1), Mn("{n} file checked", "{n} files checked", 3)
    assert (str(one), str(many)) == ("1 file checked", "3 files checked")
    nested = M("{inner}", inner=M("hint"))
    assert say(nested, "en") == "hint"
    assert say(nested, "fr") == say(M("hint"), "fr") != "hint"


def test_a_missing_field_never_raises():
    assert str(Message("value {value} of {name}", {"value": 1})) == "value 1 of {name}"


def test_an_error_holds_data_and_is_worded_where_shown():
    from bras_kit.core.errors import ParameterError

    error = ParameterError(M("unknown joint '{name}'", name="Coude"), path="bras.urdf", line=3, element="joint",
                           hint=M("hint"))
    assert str(error) == "bras.urdf:3: unknown joint 'Coude' (in <joint>)\n  hint: hint"
    french = say(error, "fr")
    assert french.startswith("bras.urdf:3: ") and "(dans <joint>)" in french
    assert str(error) == "bras.urdf:3: unknown joint 'Coude' (in <joint>)\n  hint: hint"  # unchanged after


def test_errors_do_not_import_the_catalogs():
    source = (i18n_tools.PACKAGE_ROOT / "core" / "errors.py").read_text()
    assert "i18n" not in {n.module for n in ast.walk(ast.parse(source))
                          if isinstance(n, ast.ImportFrom) and n.module}


def _error_classes() -> set[str]:
    """The names of every BrasKitError subclass defined in bras_kit (read from the code)."""
    import bras_kit.core.errors as errors

    names = {n for n, v in vars(errors).items() if isinstance(v, type) and issubclass(v, errors.BrasKitError)}
    for path in sorted(i18n_tools.PACKAGE_ROOT.rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.ClassDef) and any(isinstance(b, ast.Name) and b.id in names for b in node.bases):
                names.add(node.name)
    return names


def test_every_error_and_warning_carries_a_message_never_a_finished_sentence():
    """An error, a hint or a warning built from a string literal, an f-string or a concatenation
    could only ever be English: each must be an ``M(...)`` (or a value holding one)."""
    errors = _error_classes()
    assert {"BrasKitError", "ParameterError", "XMLSyntaxError"} <= errors
    bad = []
    for path in sorted(i18n_tools.PACKAGE_ROOT.rglob("*.py")):
        if "standin" in path.parts and "ros" in path.parts:  # the rclpy stand-in raises rclpy's own (English) errors
            continue
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if not isinstance(node, ast.Call):
                continue
            name = i18n_tools._name(node.func)
            if name not in errors and name != "warn":
                continue
            texts = list(node.args[:1]) + [k.value for k in node.keywords if k.arg in ("message", "hint")]
            for value in texts:
                if isinstance(value, (ast.JoinedStr, ast.BinOp)) or (
                        isinstance(value, ast.Constant) and isinstance(value.value, str)):
                    bad.append(f"{path.relative_to(i18n_tools.PACKAGE_ROOT.parent)}:{node.lineno} {name}")
    assert not bad, "finished sentences where a Message belongs:\n" + "\n".join(bad)


def test_a_prune_of_the_catalogs_drops_no_french_a_user_can_be_shown(tmp_path, monkeypatch):
    """``catalogs update --prune`` keeps every id bras-kit asks for at run time, including those
    that are not M(...) calls (the arm template's comments, the URDF's first line): the French the
    committed catalogs hold comes out of a prune unchanged, and nothing stale is left in them."""
    import shutil

    from babel.messages.pofile import read_po

    from bras_kit.core import i18n

    copy = tmp_path / "locale"
    shutil.copytree(LOCALE_DIR, copy)
    monkeypatch.setattr(i18n_tools, "LOCALE_DIR", copy)
    try:
        i18n_tools.update_catalogs(prune=True)
    finally:
        i18n.catalog.cache_clear()

    def entries(folder: Path) -> dict[str, set[tuple[str, str]]]:
        out = {}
        for po in sorted(folder.glob("fr/LC_MESSAGES/*.po")):
            with po.open("rb") as handle:
                out[po.stem] = {(str(m.id), str(m.string)) for m in read_po(handle) if m.id}
        return out

    before, after = entries(LOCALE_DIR), entries(copy)
    assert {d: sorted(before[d] - after.get(d, set()))[:5] for d in before if before[d] - after.get(d, set())} == {}
    assert {d: sorted(after[d] - before.get(d, set()))[:5] for d in after if after[d] - before.get(d, set())} == {}
