"""Which of the validator's errors stop a command: those about a value the command computes with.

A value the reader could not use (text where a number is, a decimal comma, nan, inf, a zero
axis) is kept as NaN in the model, never replaced by a default (:mod:`bras_kit.model.robot`). Before a
command computes anything, it asks :func:`blocking_findings` for the validator's own errors about
the parts of the model it uses (:data:`bras_kit.model.robot.PARTS`): ``fk`` needs the joints' origins
and axes, ``motion`` their limits, ``simulate`` everything but ``<safety_controller>``. A NaN
inertia does not stop ``fk``; a NaN axis does.
"""

from __future__ import annotations

from collections.abc import Collection, Iterable

from ..findings.data import Finding
from ..findings.registry import ERROR
from ..model.robot import PARTS, Robot

# the rules about values: unreadable, missing, not finite, or out of their domain
VALUE_RULES = ("BK122", "BK123", "BK202", "BK204", "BK206", "BK207", "BK401", "BK500", "BK501", "BK507")
# what each rule's values are for; the others say it in each finding (the parser's issue, or the
# visual or collision a size belongs to)
_RULE_PARTS = {"BK202": frozenset({"limits"}), "BK204": frozenset({"kinematics"}),
               "BK401": frozenset({"visual", "collision"}), "BK500": frozenset({"inertial"}),
               "BK501": frozenset({"inertial"}), "BK507": frozenset({"inertial"})}
_ANY = frozenset(PARTS)
EVERY_PART = frozenset(PARTS) - {"safety"}  # urdfdom checks <safety_controller>; no command uses it


def part_of(finding: Finding) -> str:
    """What the value a finding is about is for (a :data:`~bras_kit.model.robot.PARTS` entry), "" if none."""
    params = finding.params
    own = _RULE_PARTS.get(finding.code)
    return str(params.get("part") or params.get("where") or (next(iter(own)) if own and len(own) == 1 else ""))


def blocking_findings(robot: Robot, parts: Iterable[str], package_paths: Collection[str] = ()) -> list[Finding]:
    """The validator's errors (same codes, lines and hints as ``bras-kit validate``) about a value
    of one of ``parts``: a command using those parts cannot compute with this robot."""
    from . import validate

    wanted = set(parts)
    rules = [code for code in VALUE_RULES if _RULE_PARTS.get(code, _ANY) & wanted]  # no inertia maths for fk
    findings = validate(robot, select=rules, package_paths=tuple(package_paths))
    return [f for f in findings if f.severity == ERROR and part_of(f) in wanted]
