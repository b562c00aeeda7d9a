"""Contributor tools for the catalogs (Babel): extract every message, merge, compile.

``python -m bras_kit.cli.catalogs update`` reads every module of bras_kit with :mod:`ast`
(:func:`extract_file`), finds each ``M(...)``, ``Mn(...)`` and
``Mc(...)`` call and each text given to a registration call listed in :data:`TEXT_CALLS`
(the validator's rules), groups them by domain (:func:`bras_kit.core.message.domain_of` of the
module), merges them into ``locale/fr/LC_MESSAGES/<domain>.po`` (translations already there
are kept, new entries are added empty, entries no longer in the code are dropped with
``--prune``), adds the command line's argparse words and help texts to ``cli``, and compiles
every ``.mo``. Nothing here runs at a user's run time.
"""

from __future__ import annotations

import ast
import sys
from collections.abc import Iterable, Iterator
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from ..core.i18n import LOCALE_DIR, catalog
from ..core.message import domain_of

PACKAGE_ROOT = Path(__file__).resolve().parents[1]
MARKERS = {"M": "message", "Mn": "plural", "Mc": "context"}
# Registration calls whose keyword arguments are user-facing texts: function name ->
# (index of the positional argument that is the msgctxt, or None; the text keywords).
# A keyword's value may be a string or a dict of strings (variants).
TEXT_CALLS: dict[str, tuple[int | None, tuple[str, ...]]] = {
    # bras_kit.findings.registry.describe("BK301", title=..., message=..., hint=..., explanation=...)
    # (message, hint and parts may hold Plural("one", "several", "n") calls: msgid_plural)
    "describe": (0, ("title", "message", "hint", "explanation", "parts")),
}


@dataclass(frozen=True)
class Extracted:
    """One message id found in the code."""

    domain: str
    id: str
    plural: str | None
    context: str | None
    path: str
    line: int

    @property
    def key(self) -> tuple[str, str | None]:
        return (self.id, self.context)


def module_name(path: Path, root: Path = PACKAGE_ROOT) -> str:
    rel = path.resolve().relative_to(root.parent).with_suffix("")
    parts = list(rel.parts)
    if parts[-1] == "__init__":
        parts.pop()
    return ".".join(parts)


def _string(node: ast.AST | None) -> str | None:
    if isinstance(node, ast.Constant) and isinstance(node.value, str):
        return node.value
    return None


def _name(func: ast.AST) -> str | None:
    if isinstance(func, ast.Name):
        return func.id
    if isinstance(func, ast.Attribute):
        return func.attr
    return None


def _plural(node: ast.AST) -> tuple[str, str] | None:
    """The two forms of a ``Plural("one", "several", "n")`` call (bras_kit.findings.registry)."""
    if isinstance(node, ast.Call) and _name(node.func) == "Plural" and len(node.args) >= 2:
        singular, plural = _string(node.args[0]), _string(node.args[1])
        if singular is not None and plural is not None:
            return singular, plural
    return None


def _texts(node: ast.AST) -> Iterator[tuple[str, str | None, int]]:
    """``(text, plural, line)``: a string, a ``Plural(...)``, or every such value of a dict literal."""
    text = _string(node)
    forms = _plural(node)
    if text is not None:
        yield text, None, node.lineno  # type: ignore[attr-defined]
    elif forms is not None:
        yield forms[0], forms[1], node.lineno  # type: ignore[attr-defined]
    elif isinstance(node, ast.Dict):
        for value in node.values:
            yield from _texts(value)


def calls_in(tree: ast.AST) -> Iterator[tuple[str | None, str, str | None, int, ast.Call]]:
    """``(context, id, plural, line, call)`` for every message-building call in ``tree``;
    ``id`` is "" when the call's id is not a plain string (the guard test reports those)."""
    for node in ast.walk(tree):
        if not isinstance(node, ast.Call):
            continue
        name = _name(node.func)
        if name == "M" and node.args:
            yield None, _string(node.args[0]) or "", None, node.lineno, node
        elif name == "Mn" and len(node.args) >= 2:
            yield None, _string(node.args[0]) or "", _string(node.args[1]), node.lineno, node
        elif name == "Mc" and len(node.args) >= 2:
            yield _string(node.args[0]), _string(node.args[1]) or "", None, node.lineno, node
        elif name in TEXT_CALLS:
            context_index, keywords = TEXT_CALLS[name]
            context = _string(node.args[context_index]) if context_index is not None and \
                len(node.args) > context_index else None
            for keyword in node.keywords:
                if keyword.arg in keywords:
                    for text, plural, line in _texts(keyword.value):
                        yield context, text, plural, line, node


def extract_file(path: Path, root: Path = PACKAGE_ROOT) -> list[Extracted]:
    tree = ast.parse(path.read_text(encoding="utf-8"), filename=str(path))
    domain = domain_of(module_name(path, root))
    return [Extracted(domain, text, plural, context, str(path), line)
            for context, text, plural, line, _call in calls_in(tree) if text]


# Jinja templates whose {% trans %} blocks go into a domain: folder (under the repository's
# bras_kit/templates/) -> domain. The package templates are the generated ROS 2 package's prose.
TEMPLATE_DOMAINS = {"package": "package"}


def templates_root() -> Path:
    from ..core.resources import templates_dir

    return Path(templates_dir())


def extract_templates() -> list[Extracted]:
    """Every ``{% trans %}`` block of the Jinja templates, read with Jinja's own Babel extractor
    (the same parser that renders them, so ids match what ``gettext`` is asked at run time)."""
    from jinja2.ext import babel_extract

    found: list[Extracted] = []
    for folder, domain in TEMPLATE_DOMAINS.items():
        for path in sorted((templates_root() / folder).rglob("*.j2")):
            options = {"extensions": "jinja2.ext.i18n", "trim_blocks": "true", "lstrip_blocks": "true",
                       "keep_trailing_newline": "true"}
            with path.open("rb") as handle:
                for line, function, message, _comments in babel_extract(handle, ("_", "gettext", "ngettext"), [],
                                                                        options):
                    singular = message[0] if isinstance(message, tuple) else message
                    plural = message[1] if isinstance(message, tuple) and function == "ngettext" else None
                    if singular:
                        found.append(Extracted(domain, singular, plural, None, str(path), line))
    return found


def extract_arm_comments() -> list[Extracted]:
    """The ``package`` ids the arm's URDF and xacro are worded with: each comment of the built-in
    xacro template (as :func:`bras_kit.model.authoring.localise_comments` asks for it) and the two
    wordings of the first comment, which names the options (``HEADER_TEXTS``)."""
    from ..core.resources import robot_template
    from ..model.authoring import _COMMENT, HEADER_TEXTS, comment_id

    template = robot_template()
    text = template.read_text(encoding="utf-8")
    found = [Extracted("package", comment_id(match.group(1)), None, None, str(template),
                       text.count("\n", 0, match.start()) + 1) for match in _COMMENT.finditer(text)]
    return found + [Extracted("package", words, None, None, str(PACKAGE_ROOT / "model" / "authoring.py"), 0)
                    for words in HEADER_TEXTS]


def extract_all(root: Path = PACKAGE_ROOT) -> list[Extracted]:
    found: list[Extracted] = []
    for path in sorted(root.rglob("*.py")):
        found.extend(extract_file(path, root))
    if root == PACKAGE_ROOT:
        found.extend(extract_templates())
        found.extend(extract_arm_comments())
    return found


def by_domain(found: Iterable[Extracted]) -> dict[str, dict[tuple[str, str | None], Extracted]]:
    out: dict[str, dict[tuple[str, str | None], Extracted]] = {}
    for item in found:
        out.setdefault(item.domain, {}).setdefault(item.key, item)
    return out


def update_catalogs(prune: bool = False) -> dict[str, list[str]]:
    """Merge the extracted ids into each domain's French ``.po``; return the untranslated ids."""
    from babel.messages.catalog import Catalog
    from babel.messages.pofile import read_po, write_po

    domains = by_domain(extract_all())
    extra_cli = _cli_words()
    untranslated: dict[str, list[str]] = {}
    for domain in sorted(set(domains) | {"cli"}):
        path = LOCALE_DIR / "fr" / "LC_MESSAGES" / f"{domain}.po"
        if path.exists():
            with path.open("rb") as handle:
                catalog = read_po(handle, locale="fr")
        else:
            catalog = Catalog(locale="fr", domain=domain, project="bras-kit")
        wanted = dict(domains.get(domain, {}))
        if domain == "cli":
            for word in extra_cli:
                wanted.setdefault((word, None), Extracted("cli", word, None, None, "", 0))
        for (msgid, context), item in wanted.items():
            key: Any = (msgid, item.plural) if item.plural else msgid
            known = catalog.get(msgid, context=context)
            if known is not None and known.pluralizable != bool(item.plural):
                catalog.delete(msgid, context=context)  # it gained or lost its plural form: asked anew
                known = None
            if known is None:
                catalog.add(key, ("", "") if item.plural else "", context=context)
        if prune:
            for message in list(catalog):
                if not message.id:
                    continue
                msgid = str(message.id[0] if isinstance(message.id, (tuple, list)) else message.id)
                if (msgid, message.context) not in wanted:
                    catalog.delete(msgid, context=message.context)
        path.parent.mkdir(parents=True, exist_ok=True)
        with path.open("wb") as handle:
            write_po(handle, catalog, width=0, omit_header=False, sort_output=False)
        untranslated[domain] = [str(m.id) for m in catalog if m.id and not _translated(m.string)]
    compile_catalogs()
    return untranslated


def _translated(string: Any) -> bool:
    if isinstance(string, tuple):
        return all(string)
    return bool(string)


def _cli_words() -> list[str]:
    """argparse's own words and every command's help texts (read from the parsers)."""
    from ._messages import ARGPARSE_WORDS, parser_words

    seen: dict[str, None] = {}
    for word in [*ARGPARSE_WORDS, *parser_words()]:
        seen.setdefault(word, None)
    return list(seen)


def compile_catalogs() -> list[Path]:
    """Compile every ``.po`` into its ``.mo`` (needs Babel: ``pip install -e .[dev]``)."""
    from babel.messages.mofile import write_mo
    from babel.messages.pofile import read_po

    written = []
    for po in sorted(LOCALE_DIR.glob("*/LC_MESSAGES/*.po")):
        with po.open("rb") as handle:
            messages = read_po(handle)
        with po.with_suffix(".mo").open("wb") as handle:
            write_mo(handle, messages, use_fuzzy=False)
        written.append(po.with_suffix(".mo"))
    catalog.cache_clear()  # the running process reads the new .mo
    return written


def _main(argv: list[str]) -> int:
    """``compile``: every .po into its .mo; ``update [--prune]``: extract, merge, compile."""
    if argv == ["compile"]:
        for path in compile_catalogs():
            print(path)
        return 0
    if argv[:1] == ["update"] and set(argv[1:]) <= {"--prune"}:
        for domain, missing in update_catalogs(prune="--prune" in argv).items():
            print(f"{domain}: {len(missing)} entries without French")
            for word in missing:
                print("  " + word.replace("\n", "\\n"))
        return 0
    print("usage: python -m bras_kit.cli.catalogs compile | update [--prune]", file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(_main(sys.argv[1:]))
