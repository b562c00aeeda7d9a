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

Template = str | Mapping[str, str]  # one text, or one per variant ("" = otherwise)


@dataclass(frozen=True)
class RuleTexts:
    """A rule's English words: ``message`` and ``hint`` are ``str.format`` templates over the
    hit's parameters, possibly one per variant; ``explanation`` is what ``bras-kit explain`` shows."""

    title: str
    message: Template
    hint: Template
    explanation: str


TEXTS: dict[str, RuleTexts] = {}


def describe(code: str, *, title: str, message: Template, hint: Template = "", explanation: str) -> None:
    """Register the English texts of rule ``code`` (extracted into ``validate.po``, msgctxt = code)."""
    if code in TEXTS:
        raise ValueError(f"rule code {code} described twice")
    TEXTS[code] = RuleTexts(title, message, hint, explanation)


def pick(template: Template, variant: str) -> str:
    """The template for ``variant`` (the ``""`` one when the variant has none)."""
    if isinstance(template, str):
        return template
    return template.get(variant) or template.get("", "")


def text_message(code: str, template: str, params: Mapping[str, object] | None = None) -> Message:
    """One of rule ``code``'s texts as a message of the ``validate`` domain (msgctxt = code)."""
    return Message(template, dict(params or {}), "validate", code)


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
