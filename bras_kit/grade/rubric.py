"""A rubric: points per item, each item one check of the findings or of the model."""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..core.errors import ParameterError, os_reason
from ..core.message import M, Message
from ..core.wording import quoted

DEFAULT_RUBRIC = Path(__file__).with_name("tutorial.yaml")
MAX_RUBRIC_BYTES = 1 << 20
CHECKS = ("loads", "no_findings", "joints", "joint", "inertials")
SEVERITIES = {"info": 0, "warning": 1, "error": 2}
_KEYS = {"id", "title", "points", "check", "codes", "severity", "joints", "joint", "parent", "at_tip",
         "tolerance", "needs_package"}


@dataclass(frozen=True)
class Item:
    id: str
    title: str
    points: float
    check: str
    codes: tuple[str, ...] = ()
    severity: str = "error"
    joints: tuple[str, ...] = ()
    joint: str = ""
    parent: str = ""
    at_tip: bool = False
    tolerance: float = 0.005
    needs_package: bool = False


@dataclass(frozen=True)
class Rubric:
    name: str
    items: tuple[Item, ...]
    text: str = field(repr=False, compare=False, default="")

    @property
    def total(self) -> float:
        return sum(item.points for item in self.items)

    @property
    def digest(self) -> str:
        return hashlib.sha256(self.text.encode()).hexdigest()[:16]


def load_rubric(path: str | None = None) -> Rubric:
    """The rubric in ``path`` (YAML), or the tutorial's; a malformed one is a ParameterError."""
    import yaml

    from ..trust import yaml_gate

    where = Path(path) if path else DEFAULT_RUBRIC
    try:
        if not where.is_file() or where.stat().st_size > MAX_RUBRIC_BYTES:
            raise ParameterError(M("the rubric must be a YAML file of at most {most} kB", most=MAX_RUBRIC_BYTES >> 10),
                                 path=str(where), hint=M("bras-kit grade --explain-rubric prints the default one"))
        text = where.read_text(encoding="utf-8")
        data = yaml_gate.load(text, loader=yaml.SafeLoader)
    except (OSError, UnicodeDecodeError) as exc:
        reason = os_reason(exc) if isinstance(exc, OSError) else quoted(str(exc))
        raise ParameterError(M("cannot read the rubric: {reason}", reason=reason), path=str(where),
                             hint=M("give a YAML file; bras-kit grade --explain-rubric prints the default one")) from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        raise ParameterError(M("the rubric is not valid YAML: {problem}",
                               problem=quoted(str(getattr(exc, "problem", exc)))), path=str(where),
                             line=mark.line + 1 if mark else None) from None
    if not isinstance(data, dict) or not isinstance(data.get("items"), list) or not data["items"]:
        raise ParameterError(M("the rubric has no 'items' list"), path=str(where),
                             hint=M("see bras-kit grade --explain-rubric for the shape"))
    items = [_item(raw, k, str(where)) for k, raw in enumerate(data["items"], 1)]
    ids = [item.id for item in items]
    if len(set(ids)) != len(ids):
        raise ParameterError(M("two rubric items have the same id"), path=str(where),
                             hint=M("give each item its own id"))
    return Rubric(str(data.get("name") or where.stem), tuple(items), text)


def _item(raw: Any, number: int, where: str) -> Item:
    if not isinstance(raw, dict):
        raise ParameterError(M("rubric item {number} is not a mapping", number=number), path=where)
    unknown = sorted(set(raw) - _KEYS)
    if unknown:
        raise ParameterError(M("rubric item {number}: unknown key '{key}'", number=number, key=unknown[0]),
                             path=where, hint=M("keys: {keys}", keys=", ".join(sorted(_KEYS))))
    check = raw.get("check")
    if check not in CHECKS:
        raise ParameterError(M("rubric item {number}: unknown check {check}", number=number, check=repr(check)),
                             path=where, hint=M("checks: {checks}", checks=", ".join(CHECKS)))
    points = raw.get("points")
    if isinstance(points, bool) or not isinstance(points, (int, float)) or not math.isfinite(points) or points < 0:
        raise ParameterError(M("rubric item {number}: points must be a number of 0 or more", number=number), path=where)
    severity = str(raw.get("severity", "error"))
    if severity not in SEVERITIES:
        raise ParameterError(M("rubric item {number}: unknown severity '{severity}'", number=number,
                               severity=severity), path=where, hint=M("error, warning or info"))
    codes = raw.get("codes") or ()
    joints = raw.get("joints") or ()
    if isinstance(codes, str):
        codes = [codes]
    if isinstance(joints, str):
        joints = [joints]
    item = Item(id=str(raw.get("id") or f"item{number}"), title=str(raw.get("title") or raw.get("id") or check),
                points=float(points), check=check, codes=tuple(str(c).upper() for c in codes), severity=severity,
                joints=tuple(str(j) for j in joints), joint=str(raw.get("joint") or ""),
                parent=str(raw.get("parent") or ""), at_tip=bool(raw.get("at_tip", False)),
                tolerance=float(raw.get("tolerance", 0.005)), needs_package=bool(raw.get("needs_package", False)))
    if check == "joint" and not item.joint:
        raise ParameterError(M("rubric item {number}: the joint check needs 'joint'", number=number), path=where)
    if check == "joints" and not item.joints:
        raise ParameterError(M("rubric item {number}: the joints check needs 'joints'", number=number), path=where)
    return item


# The words of the default rubric (tutorial.yaml), so the catalog holds them: its name, its items'
# titles and the comment that explains the checks. A teacher's own rubric is shown as written.
DEFAULT_WORDS: dict[str, Message] = {m.id: m for m in (
    M("bras-kit tutorial: the arm, the wrist exercise and the inertials exercise"),
    M("The robot description loads"),
    M("No validator error"),
    M("None of the tutorial's pitfalls (BK3xx)"),
    M("The tutorial's joints epaule and coude"),
    M("Exercise 1: a joint poignet at the tip of avant_bras"),
    M("Exercise 2: every moving link has a mass and an inertia"),
    M("The ROS 2 package has none of the package pitfalls (BK6xx)"),
)}
_EXPLANATION = M(
    "The default rubric of bras-kit grade: the tutorial's arm and its two exercises, out of 20.\n"
    "Copy it, change the points or the checks, and pass it with --rubric.\n"
    "\n"
    "Each item is worth its points when its check passes, nothing otherwise. Checks:\n"
    "  loads          the robot description can be read (well-formed URDF, xacro that expands)\n"
    "  no_findings    no validator finding of at least `severity` (error, warning or info)\n"
    "                 among `codes` (code prefixes; all codes when left out)\n"
    "  joints         every joint of `joints` exists and moves\n"
    "  joint          the joint `joint` exists, its parent is `parent`, and with `at_tip` its\n"
    "                 origin is at the end of the parent's shape (within `tolerance`, metres)\n"
    "  inertials      every link that moves has a mass above 0 and a positive inertia\n"
    "`needs_package: true` gives no points when the submission holds no ROS 2 package.")


def rubric_words(text: str) -> Message | str:
    """A rubric's name or an item's title, worded where shown when it is one of the default rubric's."""
    return DEFAULT_WORDS.get(text, text)


def explained_rubric(rubric: Rubric, lang: str | None = None) -> str:
    """The rubric's YAML as ``--explain-rubric`` prints it: the default rubric with its comment, name
    and titles in ``lang``; any other rubric as written."""
    from ..core.i18n import say

    if rubric.text != DEFAULT_RUBRIC.read_text(encoding="utf-8"):
        return rubric.text
    lines = rubric.text.splitlines(keepends=True)
    body = [line for line in lines if not line.startswith("#")]
    comment = "".join(("# " + line).rstrip() + "\n" for line in say(_EXPLANATION, lang).split("\n"))
    out = []
    for line in body:
        key, sep, value = line.partition(": ")
        words = DEFAULT_WORDS.get(value.strip().strip('"')) if sep and key.strip() in ("name", "- title", "title") \
            else None
        if words is not None:
            line = f'{key}: "{say(words, lang)}"\n'
        out.append(line)
    return comment + "".join(out)
