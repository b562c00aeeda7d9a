"""A rubric: points per item, each item one check of the findings or of the model."""

from __future__ import annotations

import hashlib
import math
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

from ..errors import ParameterError

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

    where = Path(path) if path else DEFAULT_RUBRIC
    try:
        if not where.is_file() or where.stat().st_size > MAX_RUBRIC_BYTES:
            raise ParameterError(f"the rubric must be a YAML file of at most {MAX_RUBRIC_BYTES >> 10} kB",
                                 path=str(where), hint="bras-kit grade --explain-rubric prints the default one")
        text = where.read_text(encoding="utf-8")
        data = yaml.safe_load(text)
    except (OSError, UnicodeDecodeError) as exc:
        raise ParameterError(f"cannot read the rubric: {getattr(exc, 'strerror', None) or exc}", path=str(where),
                             hint="give a YAML file; bras-kit grade --explain-rubric prints the default one") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        raise ParameterError(f"the rubric is not valid YAML: {getattr(exc, 'problem', exc)}", path=str(where),
                             line=mark.line + 1 if mark else None) from None
    if not isinstance(data, dict) or not isinstance(data.get("items"), list) or not data["items"]:
        raise ParameterError("the rubric has no 'items' list", path=str(where),
                             hint="see bras-kit grade --explain-rubric for the shape")
    items = [_item(raw, k, str(where)) for k, raw in enumerate(data["items"], 1)]
    ids = [item.id for item in items]
    if len(set(ids)) != len(ids):
        raise ParameterError("two rubric items have the same id", path=str(where), hint="give each item its own id")
    return Rubric(str(data.get("name") or where.stem), tuple(items), text)


def _item(raw: Any, number: int, where: str) -> Item:
    if not isinstance(raw, dict):
        raise ParameterError(f"rubric item {number} is not a mapping", path=where)
    unknown = sorted(set(raw) - _KEYS)
    if unknown:
        raise ParameterError(f"rubric item {number}: unknown key '{unknown[0]}'", path=where,
                             hint="keys: " + ", ".join(sorted(_KEYS)))
    check = raw.get("check")
    if check not in CHECKS:
        raise ParameterError(f"rubric item {number}: unknown check {check!r}", path=where,
                             hint="checks: " + ", ".join(CHECKS))
    points = raw.get("points")
    if isinstance(points, bool) or not isinstance(points, (int, float)) or not math.isfinite(points) or points < 0:
        raise ParameterError(f"rubric item {number}: points must be a number of 0 or more", path=where)
    severity = str(raw.get("severity", "error"))
    if severity not in SEVERITIES:
        raise ParameterError(f"rubric item {number}: unknown severity '{severity}'", path=where,
                             hint="error, warning or info")
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
        raise ParameterError(f"rubric item {number}: the joint check needs 'joint'", path=where)
    if check == "joints" and not item.joints:
        raise ParameterError(f"rubric item {number}: the joints check needs 'joints'", path=where)
    return item
