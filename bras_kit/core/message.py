"""Words as data: a message id (the English text) and its parameters, worded where it is shown.

Library code never builds a finished sentence for a user. It builds a :class:`Message`::

    from bras_kit.core.message import M, Mn

    raise ParameterError(M("unknown joint '{name}'", name=name),
                         hint=M("the movable joints are {names}", names=movable))
    Mn("{n} file checked", "{n} files checked", n)

and the place that shows it (the CLI, the viewer, a report, a picture) words it in the
language it resolved, with :func:`bras_kit.core.i18n.say`. ``str(message)`` is the English text.

* The id is English and uses ``str.format`` fields by name (``{name}``, ``{value:.3g}``).
* Numbers are written by :func:`number` (``0.69``, never ``0.6900000000000001``) unless the
  field gives a format spec; lists of names are quoted and cut after :data:`MAX_LISTED`;
  a parameter that is itself a :class:`Message` is worded in the same language.
* The gettext domain (``cli``, ``validate``, ``physics``, ...) follows from the module that
  builds the message (:data:`DOMAINS`), so extraction and lookup always agree.

This module is the bottom of the house: it imports nothing from bras_kit, so the error
hierarchy can hold messages without importing the catalogs.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

# module prefix -> gettext domain (longest prefix first); everything else is ``cli``. A module
# that moved between layers keeps its domain (so its catalog), hence the entries for single modules
DOMAINS: tuple[tuple[str, str], ...] = (
    ("bras_kit.findings.registry", "validate"),
    ("bras_kit.findings.report", "validate"),
    ("bras_kit.ros.evaluation", "cli"),
    ("bras_kit.findings.data", "validate"),
    ("bras_kit.trust.contain", "ros"),
    ("bras_kit.ros.formulas", "validate"),
    ("bras_kit.ros.staticpy", "validate"),
    ("bras_kit.motion.bags", "bags"),
    ("bras_kit.ros.package", "validate"),
    ("bras_kit.exercises", "exercises"),
    ("bras_kit.ros.graph", "cli"),
    ("bras_kit.scaffold", "package"),
    ("bras_kit.validate", "validate"),
    ("bras_kit.physics", "physics"),
    ("bras_kit.grade", "grade"),
    ("bras_kit.view", "view"),
    ("bras_kit.ros", "ros"),
    ("bras_kit.run", "run"),
)
DEFAULT_DOMAIN = "cli"
MAX_LISTED = 8  # names shown in a list before "... (+N)"
MAX_PARAM_CHARS = 2000  # one parameter's text is cut past this (a message stays readable)


def domain_of(module: str | None) -> str:
    """The gettext domain of messages built in ``module`` (a dotted module name)."""
    if module:
        for prefix, domain in DOMAINS:
            if module == prefix or module.startswith(prefix + "."):
                return domain
    return DEFAULT_DOMAIN


@dataclass(frozen=True)
class Message:
    """A user-facing message as data. ``plural``/``n`` make it a plural message; ``context``
    tells two identical English ids apart (the validator uses the rule code)."""

    id: str
    params: Mapping[str, Any] = field(default_factory=dict)
    domain: str = DEFAULT_DOMAIN
    context: str | None = None
    plural: str | None = None
    n: int | None = None

    def __str__(self) -> str:
        return fill(english_template(self), self.params, str)

    def with_params(self, **params: Any) -> Message:
        return Message(self.id, {**self.params, **params}, self.domain, self.context, self.plural, self.n)


def _caller_domain(depth: int = 2) -> str:
    try:
        return domain_of(sys._getframe(depth).f_globals.get("__name__"))
    except ValueError:  # no such frame
        return DEFAULT_DOMAIN


def M(id: str, /, **params: Any) -> Message:  # noqa: N802  (a marker, like gettext's _)
    """A message; its domain is the calling module's."""
    return Message(id, params, _caller_domain())


def Mn(singular: str, plural: str, n: int, /, **params: Any) -> Message:  # noqa: N802
    """A plural message; ``n`` is also a parameter (``{n}``)."""
    return Message(singular, {"n": n, **params}, _caller_domain(), None, plural, n)


def Mc(context: str, id: str, /, **params: Any) -> Message:  # noqa: N802
    """A message with a context (``msgctxt``), for ids that need different words by place."""
    return Message(id, params, _caller_domain(), context)


def english_template(message: Message) -> str:
    if message.plural is not None and message.n != 1:
        return message.plural
    return message.id


# ---------------------------------------------------------------- filling in the parameters

def number(value: float) -> str:
    """A number the way a person writes it: ``0.6``, ``-1.57``, ``0.0305``, ``1e+308``, ``0``."""
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, int):
        return str(value)
    if math.isnan(value):
        return "nan"
    if math.isinf(value):
        return "inf" if value > 0 else "-inf"
    text = f"{value:.6g}"
    return "0" if text in ("-0", "0") else text


class _Number(float):
    """A float that writes itself with :func:`number` unless the field gives a format spec."""

    def __format__(self, spec: str) -> str:
        return number(float(self)) if not spec else float.__format__(float(self), spec)

    def __str__(self) -> str:
        return number(float(self))

    __repr__ = __str__


class _Text(str):
    """A string parameter; ``{x!r}`` stays a quoted string."""


def _cut(text: str) -> str:
    if len(text) <= MAX_PARAM_CHARS:
        return text
    return text[:MAX_PARAM_CHARS] + f"... (+{len(text) - MAX_PARAM_CHARS})"


def listed(values: Any, word: Callable[[Any], str] = str, quote: bool = True) -> str:
    """Names as ``'a', 'b', ... (+N)``; numbers space-separated (``0 0 0.6``)."""
    values = list(values)
    if values and all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in values):
        shown = [number(v) for v in values[:MAX_LISTED * 4]]
        more = len(values) - len(shown)
        return " ".join(shown) + (f" ... (+{more})" if more > 0 else "")
    shown = [(f"'{word(v)}'" if quote and not isinstance(v, Message) else word(v)) for v in values[:MAX_LISTED]]
    if len(values) > MAX_LISTED:
        shown.append(f"... (+{len(values) - MAX_LISTED})")
    return ", ".join(shown)


def param_value(value: Any, word: Callable[[Any], str]) -> Any:
    """A parameter made ready for ``str.format``: numbers, lists, nested messages, None."""
    if isinstance(value, Message):
        return _Text(_cut(word(value)))
    if isinstance(value, bool):
        return str(value).lower()
    if isinstance(value, int):
        return value
    if isinstance(value, float):
        return _Number(value)
    if isinstance(value, (list, tuple, set, frozenset)):
        items = sorted(value) if isinstance(value, (set, frozenset)) else value
        return _Text(listed(items, word))
    if value is None:
        return "?"
    if isinstance(value, str):
        return _Text(_cut(value))
    return _Text(_cut(str(value)))


def fill(template: str, params: Mapping[str, Any], word: Callable[[Any], str]) -> str:
    """``template.format(**params)`` with parameters made readable; a template that names a
    parameter it was not given keeps its field as written (never a KeyError in front of a user)."""
    ready = {key: param_value(value, word) for key, value in params.items()}
    try:
        return template.format_map(_Missing(ready))
    except (ValueError, IndexError, TypeError):  # a broken translation: show its text as is
        return template


class _Missing(dict):
    def __missing__(self, key: str) -> str:
        return "{" + key + "}"
