"""One mechanism for every user-facing word: gettext catalogs, English message ids.

Library code builds :class:`~bras_kit.core.message.Message` objects (``M("...", name=...)``); the
place that shows one words it here with :func:`say` in the language it resolved. Each feature
has its own domain (``cli``, ``validate``, ``physics``, ``view``, ``grade``, ``package``, ...;
see :data:`bras_kit.core.message.DOMAINS`), whose French catalog is
``bras_kit/locale/fr/LC_MESSAGES/<domain>.po``, compiled to the ``.mo`` beside it. Contributors
refresh the catalogs with ``python -m bras_kit.cli.catalogs update`` (Babel extracts every message,
merges it into each ``.po`` and compiles); the run time reads the ``.mo`` with the standard
library's :mod:`gettext`. A test checks each ``.mo`` is current and no entry is left untranslated.

The language is ``--lang`` when given, else ``BRAS_KIT_LANG``, else the locale
(``LC_ALL``, ``LC_MESSAGES``, ``LANG``), else English.
"""

from __future__ import annotations

import gettext as _gettext
import os
from collections.abc import Callable, Mapping
from functools import cache
from pathlib import Path
from typing import Any

from .message import M, Message, english_template, fill

LANGUAGES = ("en", "fr")
DEFAULT_LANGUAGE = "en"
LOCALE_DIR = Path(__file__).resolve().parents[1] / "locale"

Translate = Callable[[str], str]


def resolve_language(value: str | None = None, environ: Mapping[str, str] | None = None) -> str:
    """``value`` if given, else ``BRAS_KIT_LANG``, else ``fr`` when the locale says French."""
    env = os.environ if environ is None else environ
    chosen = value or env.get("BRAS_KIT_LANG", "").strip().lower()
    if chosen:
        if chosen not in LANGUAGES:
            from .errors import ParameterError

            raise ParameterError(M("unknown language '{lang}'", lang=chosen), hint=M("use --lang en or --lang fr"))
        return chosen
    for var in ("LC_ALL", "LC_MESSAGES", "LANG"):
        found = env.get(var, "")
        if found:
            return "fr" if found.lower().startswith("fr") else DEFAULT_LANGUAGE
    return DEFAULT_LANGUAGE


@cache
def catalog(lang: str, domain: str) -> _gettext.NullTranslations:
    if lang == DEFAULT_LANGUAGE:
        return _gettext.NullTranslations()
    return _gettext.translation(domain, localedir=str(LOCALE_DIR), languages=[lang], fallback=True)


def translator(lang: str, domain: str = "cli") -> Translate:
    """A function turning an English message id into ``lang`` (the id itself when untranslated)."""
    return catalog(lang, domain).gettext


def ntranslator(lang: str, domain: str = "cli") -> Callable[[str, str, int], str]:
    """Plural forms: ``nt("{n} file", "{n} files", n).format(n=n)``."""
    return catalog(lang, domain).ngettext


_language: list[str] = []  # the language chosen for this process (set by the CLI), else resolved lazily


def set_language(lang: str | None) -> str:
    """Choose the language of every later message (``None``: from the environment)."""
    chosen = resolve_language(lang)
    _language[:] = [chosen]
    return chosen


def current_language() -> str:
    return _language[0] if _language else resolve_language()


def say(text: Any, lang: str | None = None) -> str:
    """``text`` worded in ``lang`` (default: the library's language, :func:`set_language`).

    A :class:`Message` is looked up in its domain's catalog (with its context and plural form)
    and filled in; a :class:`~bras_kit.core.errors.BrasKitError` becomes its full text (place,
    message, element, hint); anything else is ``str(text)``.
    """
    lang = lang or current_language()
    if isinstance(text, Message):
        return fill(_template(text, lang), text.params, lambda inner: say(inner, lang))
    from .errors import BrasKitError

    if isinstance(text, BrasKitError):
        return say_error(text, lang)
    return "" if text is None else str(text)


def _template(message: Message, lang: str) -> str:
    if lang == DEFAULT_LANGUAGE:
        return english_template(message)
    table = catalog(lang, message.domain)
    if message.plural is not None:
        n = message.n if message.n is not None else 1
        if message.context is not None:
            return table.npgettext(message.context, message.id, message.plural, n)
        return table.ngettext(message.id, message.plural, n)
    if message.context is not None:
        return table.pgettext(message.context, message.id)
    return table.gettext(message.id)


def say_error(error: Any, lang: str | None = None, *, with_hint: bool = True) -> str:
    """A :class:`~bras_kit.core.errors.BrasKitError` as the CLI prints it:
    ``path:line: message (in <element>)`` and, on the next line, ``hint: ...``."""
    from .message import M

    lang = lang or current_language()
    where = ""
    if getattr(error, "path", None):
        where = str(error.path)
        if getattr(error, "line", None):
            where += f":{error.line}"
        where += ": "
    text = where + say(error.message, lang)
    if getattr(error, "element", None):
        text += " " + say(M("(in <{element}>)", element=error.element), lang)
    if with_hint and getattr(error, "hint", None):
        text += "\n  " + labelled(M("hint"), say(error.hint, lang), lang)
    return text


def labelled(label: Message | str, text: str, lang: str | None = None) -> str:
    """``label: text`` (``warning: ...``, ``hint: ...``): the colon is a word of the catalog, so
    French puts its space before it."""
    return say(M("{label}: {text}", label=label, text=text), lang or current_language())


def domains() -> list[str]:
    return sorted(p.stem for p in (LOCALE_DIR / "fr" / "LC_MESSAGES").glob("*.po"))
