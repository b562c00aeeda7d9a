"""What the validator returns: findings (worded in one language) and per-file results."""

from __future__ import annotations

from dataclasses import dataclass, field
from typing import Any

from .registry import ERROR, INFO, WARNING

SEVERITY_ORDER = {ERROR: 0, WARNING: 1, INFO: 2}
# the file could not be read at all: not well-formed, unsafe XML, xacro failure, missing file
UNREADABLE_CODES = frozenset({"BK100", "BK101", "BK102", "BK103"})


@dataclass(frozen=True)
class Finding:
    """One problem, ready to print: ``path:line: code severity <element name="..."> message``.

    ``data`` keeps the raw numbers behind the wording (expected origin, excess...) for programs
    and tests; it is not part of the JSON output.
    """

    code: str
    severity: str
    message: str
    element: str
    name: str | None
    line: int | None
    hint: str
    data: dict[str, Any] = field(default_factory=dict, compare=False, repr=False)

    def as_dict(self) -> dict[str, Any]:
        return {
            "code": self.code,
            "severity": self.severity,
            "message": self.message,
            "element": self.element,
            "name": self.name,
            "line": self.line,
            "hint": self.hint,
        }


def sort_key(finding: Finding) -> tuple[int, int, str]:
    return (finding.line or 0, SEVERITY_ORDER.get(finding.severity, 3), finding.code)


@dataclass
class FileResult:
    """The findings of one file, as shown by ``bras-kit validate``."""

    path: str
    findings: list[Finding]

    @property
    def readable(self) -> bool:
        """False when the file could not be read at all; its one finding says why."""
        return not any(f.code in UNREADABLE_CODES for f in self.findings)

    def count(self, severity: str) -> int:
        return sum(1 for f in self.findings if f.severity == severity)

    def ok(self, strict: bool = False) -> bool:
        """True when this file passes: readable, no error, and no warning when ``strict``."""
        failing = (ERROR, WARNING) if strict else (ERROR,)
        return self.readable and not any(f.severity in failing for f in self.findings)
