"""The rule registry: every check has a stable code, a name, a severity and one small function.

A rule function reads its family's context (for the URDF rules a
:class:`bras_kit.validate.context.Context`: the robot model, its issues and a few indexes built once) and yields :class:`Hit` objects: where the defect is and
the numbers that describe it, never words. Each rule's English texts (title, message, hint,
explanation) are registered with :func:`describe` (modules ``texts``); the French is in the
gettext catalog ``locale/fr/LC_MESSAGES/validate.po`` with the rule code as ``msgctxt``. A finding
is worded where it is shown (:mod:`bras_kit.findings.data`).

Codes by family: BK1xx structure, BK2xx joints, BK3xx the tutorial's pitfalls, BK4xx geometry,
BK5xx inertia, BK6xx the whole ROS 2 package,
BK7xx what Gazebo will make of the robot, BK8xx the live ROS 2 graph (``doctor --ros``). Codes never change meaning; a retired code is not reused.
"""

from __future__ import annotations

from collections.abc import Callable, Iterable, Iterator, Mapping
from dataclasses import dataclass, field
from typing import Any

from ..core.message import M, Message

ERROR, WARNING, INFO = "error", "warning", "info"
SEVERITIES = (ERROR, WARNING, INFO)

FAMILIES = {
    "BK1": "structure",
    "BK2": "joints",
    "BK3": "pitfalls",
    "BK4": "geometry",
    "BK5": "inertia",
    "BK6": "package",
    "BK7": "gazebo",
    "BK8": "live",
}
FAMILY_TITLES: dict[str, Message] = {
    "structure": M("structure (is this a robot, and one tree?)"),
    "joints": M("joints (types, axes, limits)"),
    "pitfalls": M("the tutorial's pitfalls"),
    "geometry": M("geometry (shapes, meshes, colours)"),
    "inertia": M("inertia (mass and inertia for simulation)"),
    "package": M("the ROS 2 package (setup.py, launch file, RViz configuration, nodes)"),
    "gazebo": M("Gazebo (what libsdformat's URDF reader keeps, merges, drops or refuses)"),
    "live": M("the live ROS 2 graph (what keeps RViz empty or the arm still)"),
}
SEVERITY_WORDS: dict[str, Message] = {ERROR: M("error"), WARNING: M("warning"), INFO: M("info")}

@dataclass(frozen=True)
class Plural:
    """A text whose words follow a count: ``Plural("{count} message", "{count} messages", "count")``.

    ``n`` names the hit parameter that counts (an int, or a list whose length counts). It is
    worded with ``npgettext(code, singular, plural, n)``, so each language applies its own rule
    (French: 0 and 1 take the singular, read from the ``Plural-Forms`` of ``validate.po``).

    Why this shape: gettext gives one count per entry, so the count goes beside the two English
    forms, in the same ``describe(...)`` call as the rest of the rule's words, where a reader (and
    the extractor, :mod:`bras_kit.cli.catalogs`) sees the whole sentence at once. A sentence with
    several counts (``{names} names but {positions} positions``) names its counted phrases as
    fields and declares each in ``describe(parts=...)``, one ``Plural`` each; the sentence itself
    can be a ``Plural`` too, for the count its verb agrees with.
    """

    singular: str
    plural: str
    n: str


Text = str | Plural
Template = Text | Mapping[str, Text]  # one text, or one per variant ("" = otherwise)


@dataclass(frozen=True)
class RuleTexts:
    """A rule's English words: ``message`` and ``hint`` are ``str.format`` templates over the
    hit's parameters, possibly one per variant; ``parts`` are counted phrases those templates
    name as fields; ``explanation`` is what ``bras-kit explain`` shows."""

    title: str
    message: Template
    hint: Template
    explanation: str
    parts: Mapping[str, Plural] = field(default_factory=dict)


TEXTS: dict[str, RuleTexts] = {}


def describe(code: str, *, title: str, message: Template, hint: Template = "", explanation: str,
             parts: Mapping[str, Plural] | None = None) -> None:
    """Register the English texts of rule ``code`` (extracted into ``validate.po``, msgctxt = code)."""
    if code in TEXTS:
        raise ValueError(f"rule code {code} described twice")
    TEXTS[code] = RuleTexts(title, message, hint, explanation, dict(parts or {}))


def pick(template: Template, variant: str) -> Text:
    """The template for ``variant`` (the ``""`` one when the variant has none)."""
    if isinstance(template, (str, Plural)):
        return template
    return template.get(variant) or template.get("", "")


def count_of(value: object) -> int:
    """The number a plural form follows: an int as it is, a list or tuple by its length."""
    if isinstance(value, (list, tuple, set, frozenset, dict)):
        return len(value)
    if isinstance(value, bool):
        return int(value)
    if isinstance(value, int):
        return value
    if isinstance(value, float) and value.is_integer():
        return int(value)
    raise TypeError(f"a plural form counts an int or a list, not {value!r}")


def _worded(code: str, text: Text, params: Mapping[str, object]) -> Message:
    if isinstance(text, Plural):
        n = count_of(params[text.n]) if text.n in params else 2  # a missing count: the "other" form
        return Message(text.singular, params, "validate", code, text.plural, n)
    return Message(text, params, "validate", code)


def text_message(code: str, template: Text, params: Mapping[str, object] | None = None) -> Message:
    """One of rule ``code``'s texts as a message of the ``validate`` domain (msgctxt = code); the
    rule's counted ``parts`` become parameters, each worded with its own count."""
    given = dict(params or {})
    texts = TEXTS.get(code)
    parts = {name: _worded(code, part, given) for name, part in (texts.parts.items() if texts else ())
             if part.n in given}
    return _worded(code, template, {**given, **parts})


@dataclass(frozen=True)
class Hit:
    """One defect found by a rule: the named element that holds it, its line, and the facts.

    ``element``/``name`` identify the link, joint, material or robot (``<joint name="coude">``);
    ``line`` is the most precise source line known (the ``<origin>`` or ``<limit>`` line when
    that is where the fix goes). ``params`` fill the message templates; ``variant`` picks one
    wording when a rule has several (``"gap"`` / ``"overlap"``...).
    """

    element: str
    name: str | None
    line: int | None
    params: Mapping[str, object] = field(default_factory=dict)
    variant: str = ""


# a family's context: the URDF rules read bras_kit.validate.context.Context, the package rules
# their package context; the registry needs neither
Check = Callable[[Any], Iterable[Hit]]


@dataclass(frozen=True)
class Rule:
    """A registered check. ``check`` is None for loader rules, which the file loader reports
    itself (the file could not be read at all, or is a xacro macro library)."""

    code: str
    name: str
    severity: str
    check: Check | None

    @property
    def family(self) -> str:
        return FAMILIES[self.code[:3]]

    @property
    def reported_by_loader(self) -> bool:
        return self.check is None

    @property
    def texts(self) -> RuleTexts:
        return TEXTS[self.code]

    @property
    def title(self) -> Message:
        return text_message(self.code, self.texts.title)

    @property
    def explanation(self) -> Message:
        return text_message(self.code, self.texts.explanation)


RULES: dict[str, Rule] = {}


def _register(code: str, name: str, severity: str, check: Check | None) -> None:
    if code in RULES:
        raise ValueError(f"rule code {code} registered twice")
    if code[:3] not in FAMILIES or len(code) != 5 or not code[2:].isdigit():
        raise ValueError(f"bad rule code {code!r}")
    if severity not in SEVERITIES:
        raise ValueError(f"bad severity {severity!r} for {code}")
    RULES[code] = Rule(code, name, severity, check)


def rule(code: str, name: str, severity: str) -> Callable[[Check], Check]:
    """Decorator registering ``check`` under ``code``."""

    def decorate(check: Check) -> Check:
        _register(code, name, severity, check)
        return check

    return decorate


def loader_rule(code: str, name: str, severity: str = ERROR) -> None:
    """Register a rule that the file loader reports rather than a check over the model."""
    _register(code, name, severity, None)


def hit(element: str, name: str | None, line: int | None, variant: str = "", **params: object) -> Hit:
    return Hit(element, name, line, params, variant)


def sorted_rules() -> list[Rule]:
    return [RULES[code] for code in sorted(RULES)]


def select_rules(select: Iterable[str] = (), ignore: Iterable[str] = ()) -> list[Rule]:
    """Rules chosen by code prefixes, like ruff: ``BK3`` is every pitfall, ``BK301`` one rule.

    An empty ``select`` means every rule. Unknown prefixes raise ``ValueError`` (the CLI turns
    that into a usage error).
    """
    chosen = [p.strip().upper() for p in select if p.strip()]
    dropped = [p.strip().upper() for p in ignore if p.strip()]
    for prefix in chosen + dropped:
        if not any(code.startswith(prefix) for code in RULES):
            raise ValueError(prefix)
    return [
        r for r in sorted_rules()
        if (not chosen or any(r.code.startswith(p) for p in chosen))
        and not any(r.code.startswith(p) for p in dropped)
    ]


def run_rules(rules: Iterable[Rule], context: Any) -> Iterator[tuple[Rule, Hit]]:
    for r in rules:
        if r.check is not None:
            for found in r.check(context):
                yield r, found
