"""Text a learner wrote, made inert for the program that shows it (docs/security.md).

A terminal obeys the control characters in what it prints (``ESC [ 2 J`` clears the screen,
``ESC ] 0 ;`` sets the window title, a carriage return writes over a line), and a spreadsheet
evaluates a cell that starts like a formula. A node's exception text, a log line, a folder
name handed in to ``grade``: each is the learner's, so each is shown as text:

- :func:`for_terminal` writes every control character as a visible escape (``\\x1b``), the
  way ``repr`` would, keeping only the line feed and the tab; the Unicode controls that reorder
  text on screen ("Trojan Source", CVE-2021-42574) too;
- :func:`for_spreadsheet` prefixes a cell whose first character a spreadsheet reads as a
  formula (``=``, ``+``, ``-``, ``@``, tab, carriage return) with a single quote, OWASP's
  advice against CSV injection (owasp.org/www-community/attacks/CSV_Injection).
"""

from __future__ import annotations

import re
from typing import Any, TextIO

# C0 but line feed and tab, DEL, C1; the bidirectional embeddings, overrides and isolates
_CONTROLS = re.compile("[\x00-\x08\x0b-\x1f\x7f-\x9f\u061c\u200e\u200f\u202a-\u202e\u2066-\u2069]")
_FORMULA_STARTS = ("=", "+", "-", "@", "\t", "\r")


def _escape(match: re.Match[str]) -> str:
    code = ord(match.group())
    return f"\\x{code:02x}" if code < 0x100 else f"\\u{code:04x}"


def for_terminal(text: str) -> str:
    """``text`` with each control character written as a visible escape (``\\x1b``, ``\\r``
    as ``\\x0d``...); line feeds and tabs kept."""
    return _CONTROLS.sub(_escape, text)


def for_spreadsheet(cell: str) -> str:
    """``cell`` as a spreadsheet shows it as text: a single quote before a formula's first character."""
    return "'" + cell if cell.startswith(_FORMULA_STARTS) else cell


class TerminalWriter:
    """A text stream that writes what it is given through :func:`for_terminal` (the node's
    ``print`` and logs when they are shown live); everything else is the wrapped stream's."""

    def __init__(self, stream: TextIO) -> None:
        self._stream = stream

    def write(self, text: str) -> int:
        self._stream.write(for_terminal(text))
        return len(text)

    def writelines(self, lines: Any) -> None:
        for line in lines:
            self.write(line)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)
