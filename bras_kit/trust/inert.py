"""Text a learner wrote, made inert for the program that shows it (docs/security.md).

A terminal obeys the control characters in what it prints (``ESC [ 2 J`` clears the screen,
``ESC ] 0 ;`` sets the window title, a carriage return writes over a line), and a spreadsheet
evaluates a cell that starts like a formula. A node's exception text, a log line, a folder
name handed in to ``grade``: each is the learner's, so each is shown as text. Each boundary
has one gate, which every byte crossing it takes:

- **the terminal**: :func:`gated_streams` (entered once by the command line, ``bras_kit.cli.main``)
  puts a :class:`TerminalWriter` in front of ``sys.stdout`` and ``sys.stderr``; whatever is
  printed, logged, warned or said by argparse then passes :func:`for_terminal`, which writes
  every character a terminal acts on, or that reorders or hides text, as a visible escape
  (``\\x1b``, ``\\u202e``). bras-kit's own colours and screen clearing pass by another channel:
  a :class:`Styled` value (spans of text, each with one of the styles of :data:`_STYLES`), written
  by :func:`emit`; its text is escaped like any other, only the styles' own sequences are raw.
  A string never becomes a style: ``str`` of a :class:`Styled` is its plain text.
- **a spreadsheet**: :func:`csv_text` writes every CSV bras-kit writes, from typed cells: a
  number stays a number; a text cell goes through :func:`for_spreadsheet`, which puts a single
  quote before each part of it a spreadsheet could read as a formula, at its start and after
  every character a spreadsheet may split cells or rows on (OWASP's advice against CSV
  injection, owasp.org/www-community/attacks/CSV_Injection; French spreadsheets split on ``;``).
"""

from __future__ import annotations

import contextlib
import re
import sys
from collections.abc import Iterable, Iterator, Sequence
from typing import Any, TextIO

# What a terminal must not receive raw: every control (Unicode categories Cc, Cf, Cs, Zl, Zp)
# but the line feed and the tab, generated from Unicode 15.0 (tests/trust/test_walls_inert.py checks
# it against the running Python's unicodedata, code point by code point):
# - C0 and C1 (ESC starts CSI, OSC, DCS, APC, PM and SOS; 0x9b, 0x9d... are their 8-bit forms), DEL;
# - the bidirectional marks, embeddings, overrides and isolates ("Trojan Source", CVE-2021-42574),
#   the Arabic letter mark;
# - the other invisible format characters (soft hyphen, zero-width space, word joiner, BOM, tags,
#   interlinear annotations...), which hide text or make two names look the same; kept: the
#   zero-width non-joiner and joiner (U+200C, U+200D), which Persian, the Indic scripts and emoji
#   need to be written at all, and which move nothing;
# - the line and paragraph separators (U+2028, U+2029), which some terminals take as line breaks;
# - lone surrogates: bytes a decoder could not read (surrogateescape), which would go out as
#   the raw bytes they stand for (0x9b, an 8-bit CSI).
_CONTROLS = re.compile(
    "[\x00-\x08\x0b-\x1f\x7f-\x9f\xad\u0600-\u0605\u061c\u06dd\u070f\u0890\u0891\u08e2\u180e\u200b"
    "\u200e\u200f\u2028-\u202e\u2060-\u2064\u2066-\u206f\ud800-\udfff\ufeff\ufff9-\ufffb"
    "\U000110bd\U000110cd\U00013430-\U0001343f\U0001bca0-\U0001bca3\U0001d173-\U0001d17a"
    "\U000e0001\U000e0020-\U000e007f]")


def _escape(match: re.Match[str]) -> str:
    code = ord(match.group())
    if code < 0x7f:
        return f"\\x{code:02x}"
    if code < 0x10000:  # \u007f, \u009b...: also a valid JSON escape, so a JSON report stays JSON
        return f"\\u{code:04x}"
    code -= 0x10000  # as a JSON surrogate pair
    return f"\\u{0xd800 + (code >> 10):04x}\\u{0xdc00 + (code & 0x3ff):04x}"


def for_terminal(text: str) -> str:
    """``text`` with each control character written as a visible escape (``\\x1b``, ``\\r``
    as ``\\x0d``, U+202E as ``\\u202e``...); line feeds and tabs kept."""
    return _CONTROLS.sub(_escape, text)


# bras-kit's own styles: the only sequences that reach a terminal raw
_STYLES = {"bold": ("\x1b[1m", "\x1b[0m"), "dim": ("\x1b[2m", "\x1b[0m"), "red": ("\x1b[31m", "\x1b[0m"),
           "green": ("\x1b[32m", "\x1b[0m"), "yellow": ("\x1b[33m", "\x1b[0m"), "cyan": ("\x1b[36m", "\x1b[0m"),
           "clear": ("\x1b[H\x1b[2J\x1b[3J", ""), "line start": ("\r", "")}

_CONTROL_STYLES = ("clear", "line start")


class Styled:
    """Text bras-kit styles itself: spans of text, each plain or in one of :data:`_STYLES`.

    Made by :func:`styled` and ``+`` only; written by :func:`emit`. ``str()`` of it (an
    f-string, ``print``) is its plain text: a style never travels inside a string.
    """

    __slots__ = ("_spans",)

    def __init__(self, spans: Iterable[tuple[str, str | None]] = ()) -> None:
        self._spans = tuple(spans)

    def __add__(self, other: str | Styled) -> Styled:
        return Styled(self._spans + _spans(other))

    def __radd__(self, other: str) -> Styled:
        return Styled(_spans(other) + self._spans)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Styled) and other._spans == self._spans

    def __hash__(self) -> int:
        return hash(self._spans)

    def __str__(self) -> str:
        return "".join(text for text, _ in self._spans)

    def __repr__(self) -> str:
        return f"Styled({self._spans!r})"

    def __len__(self) -> int:
        return len(str(self))

    def rstrip(self) -> Styled:
        spans = list(self._spans)
        while spans and spans[-1][1] not in _CONTROL_STYLES and not spans[-1][0].rstrip():
            spans.pop()
        if spans and spans[-1][1] not in _CONTROL_STYLES:
            spans[-1] = (spans[-1][0].rstrip(), spans[-1][1])
        return Styled(spans)

    def render(self) -> str:
        """The text for a terminal: each span's text inert, its style's sequences around it."""
        out = []
        for text, style in self._spans:
            start, end = _STYLES[style] if style is not None else ("", "")
            out.append(start + for_terminal(text) + end)
        return "".join(out)


Shown = str | Styled


def _spans(part: Shown) -> tuple[tuple[str, str | None], ...]:
    if isinstance(part, Styled):
        return part._spans
    if isinstance(part, str):
        return ((part, None),) if part else ()
    raise TypeError(f"a terminal takes str or Styled, not {type(part).__name__}")


def styled(text: str, style: str) -> Styled:
    """``text`` in one of bras-kit's styles (bold, dim, red, green, yellow, cyan; with empty
    text, ``clear``: the screen cleared, ``line start``: back to the start of the line)."""
    if style not in _STYLES:
        raise ValueError(f"no style {style!r}")
    return Styled(((text, style),))


CLEAR_SCREEN = styled("", "clear")
LINE_START = styled("", "line start")  # a progress bar drawn again over itself


def join(separator: str, parts: Iterable[Shown]) -> Shown:
    """``separator.join(parts)`` for parts that may be :class:`Styled` (then so is the result)."""
    parts = list(parts)
    if all(isinstance(part, str) for part in parts):
        return separator.join(parts)  # type: ignore[arg-type]
    out = Styled()
    for i, part in enumerate(parts):
        out = out + (separator if i else "") + part
    return out


class TerminalWriter:
    """A text stream in front of a terminal's: what it is given goes through :func:`for_terminal`
    (the CLI's stdout and stderr, a node's ``print`` and logs shown live); :meth:`write_styled`
    takes bras-kit's own styles; everything else is the wrapped stream's."""

    def __init__(self, stream: TextIO) -> None:
        self._stream = stream

    @property
    def raw(self) -> TextIO:
        return self._stream

    def write(self, text: str) -> int:
        self._stream.write(for_terminal(text))
        return len(text)

    def write_styled(self, text: Styled) -> None:
        self._stream.write(text.render())

    def writelines(self, lines: Any) -> None:
        for line in lines:
            self.write(line)

    def __getattr__(self, name: str) -> Any:
        return getattr(self._stream, name)


def emit(stream: Any, *parts: Shown, end: str = "\n") -> None:
    """Write ``parts`` and ``end`` to ``stream`` for a terminal: text inert, styles as styles.

    The one way a :class:`Styled` reaches a stream; on a stream with no gate in front (a
    library caller's, a test's StringIO) the text is made inert here."""
    rendered = "".join(part.render() if isinstance(part, Styled) else for_terminal(part)
                       for part in (*parts, end))
    (stream.raw if isinstance(stream, TerminalWriter) else stream).write(rendered)


def write_document(stream: Any, text: str) -> None:
    """A document a command prints instead of a file (``-o -``, the URDF ``xacro`` expands):
    to a pipe or a file as it is, byte for byte; to a terminal through the gate."""
    raw = stream.raw if isinstance(stream, TerminalWriter) else stream
    isatty = getattr(raw, "isatty", None)
    (stream if isatty is not None and isatty() else raw).write(text)


@contextlib.contextmanager
def gated_streams() -> Iterator[None]:
    """While inside, ``sys.stdout`` and ``sys.stderr`` are :class:`TerminalWriter` s (once: a
    stream already gated is kept); they are given back as they were on the way out."""
    saved = sys.stdout, sys.stderr
    if not isinstance(sys.stdout, TerminalWriter) and sys.stdout is not None:
        sys.stdout = TerminalWriter(sys.stdout)
    if not isinstance(sys.stderr, TerminalWriter) and sys.stderr is not None:
        sys.stderr = TerminalWriter(sys.stderr)
    try:
        yield
    finally:
        sys.stdout, sys.stderr = saved


# --- cells for a spreadsheet -------------------------------------------------------------------

# OWASP's first characters of a formula (=, +, -, @, tab, carriage return), ASVS 1.2.10's NUL,
# the line feed, and their full-width and small forms (an East Asian spreadsheet or input method
# takes ＝ as =); spaces a spreadsheet may trim (no-break, ideographic) are skipped before the
# first character is judged.
_FORMULA_STARTS = "=+\\-@\t\r\n\x00\uff1d\uff0b\uff0d\uff20\ufe66\ufe62\ufe63\ufe6b"
# where a spreadsheet may start a new cell or row: the separators it may be told to split on
# (comma, semicolon, tab, space, colon, pipe), the line breaks of a file read without its quotes,
# and the quote itself (a quoted cell's text starts after it)
_SEPARATORS = ",;\t |:\r\n\"\v\f"
_TRIMMED = "\u00a0\u2007\u202f\u3000"
# a quote goes in at each start (the cell's, and after each separator) followed by a formula's
# first character, or by a quote (so that the text read back is exact: from_spreadsheet)
_STARTS = re.compile(f"(^|[{re.escape(_SEPARATORS)}])(?=[{_TRIMMED}]*[{_FORMULA_STARTS}]|')")
_QUOTED_STARTS = re.compile(f"(^|[{re.escape(_SEPARATORS)}])'")


def for_spreadsheet(cell: str) -> str:
    """``cell`` as a spreadsheet shows it as text, however it splits it into cells: a single
    quote before every part of it (its start, and after each separator) a spreadsheet would
    read as a formula; a part already starting with a quote gets one more, so that
    :func:`from_spreadsheet` gives the exact text back."""
    return _STARTS.sub(r"\1'", cell)


def from_spreadsheet(cell: str) -> str:
    """The text :func:`for_spreadsheet` was given (bras-kit reading back its own CSV)."""
    return _QUOTED_STARTS.sub(r"\1", cell)


Cell = str | float | int


def _cell(value: Cell, number_format: str) -> str:
    if isinstance(value, bool):
        raise TypeError("a CSV cell is text or a number, not a bool")
    if isinstance(value, str):
        return for_spreadsheet(value)
    if isinstance(value, float):
        # repr: the shortest text that reads back as the same float (-0.5, 1e-07, nan)
        return format(value, number_format) if number_format else repr(value)
    if isinstance(value, int):
        return str(value)
    raise TypeError(f"a CSV cell is text or a number, not {type(value).__name__}")


def csv_text(rows: Iterable[Sequence[Cell]], delimiter: str = ",", number_format: str = "") -> str:
    """The CSV bras-kit writes: every row's text cells through :func:`for_spreadsheet`, its
    numbers as numbers (``number_format``: a format spec for the floats, ``g`` for grades;
    by default the shortest exact text); Python's csv module quotes what needs it."""
    import csv
    import io

    # csv quotes a cell holding a character of its line terminator: told "\r\n", it quotes a lone
    # carriage return too (which a reader takes for the end of a row); the file's rows end in "\n"
    buffer = io.StringIO()
    writer = csv.writer(buffer, delimiter=delimiter, lineterminator="\r\n")
    out = []
    for row in rows:
        writer.writerow([_cell(value, number_format) for value in row])
        out.append(buffer.getvalue()[:-2] + "\n")
        buffer.seek(0)
        buffer.truncate()
    return "".join(out)


# --- names that become files -------------------------------------------------------------------

# a name kept as it is: lower-case ASCII letters, digits, '_', '.', '-', not starting with '.' or
# '-' (so the same file on every file system, case-insensitive or normalising ones included)...
_PLAIN = re.compile(r"[a-z0-9_][a-z0-9_.-]{0,63}")
# ...unless it could be another name's stem: a slug, a dash and a digest
_DIGEST_LENGTH = 16
_STEM_FORM = re.compile(rf".*-[0-9a-f]{{{_DIGEST_LENGTH}}}")
# names Windows keeps for devices, whatever their extension (a report copied to a USB key)
# Windows' reserved device names, with any extension (learn.microsoft.com, "Naming Files, Paths, and Namespaces"):
# COM and LPT take 0-9 and the superscripts 1-3
_DEVICES = {"con", "prn", "aux", "nul", *(f"{port}{n}" for port in ("com", "lpt") for n in "0123456789\u00b9\u00b2\u00b3")}
_SLUG_BYTES = 96


def file_stem(name: str) -> str:
    """The file name (without extension) of a user-given name (a learner's, in a graded class):
    two different names never share one, on any file system, and a name always gets the same.

    A plain lower-case ASCII name is kept as it is ("alice"); any other is a readable slug,
    a dash and 16 hex digits of the SHA-256 of the exact name ("bob smith" ->
    "bob_smith-7e50351d7a4c5116"). A plain name never has that form, so never equals another's stem;
    two stems differing only in case differ in their digests too."""
    if _PLAIN.fullmatch(name) and not _STEM_FORM.fullmatch(name) and name.split(".")[0] not in _DEVICES:
        return name
    import hashlib
    import unicodedata

    slug = "".join(c if c.isalnum() or c in "-_." else "_" for c in unicodedata.normalize("NFC", name))
    slug = re.sub(r"_+", "_", slug).strip("._-")
    slug = slug.encode("utf-8", "ignore")[:_SLUG_BYTES].decode("utf-8", "ignore") or "learner"
    if slug.split(".")[0].lower() in _DEVICES:  # Windows reserves CON, CON.txt, con.bob alike
        slug = f"_{slug}"
    digest = hashlib.sha256(name.encode("utf-8", "surrogatepass")).hexdigest()[:_DIGEST_LENGTH]
    return f"{slug}-{digest}"
