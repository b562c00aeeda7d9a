"""bras_kit.trust.inert: a learner's text made inert for a terminal and for a spreadsheet.

Oracles: the Unicode character database (Python's unicodedata: general category Cc, the
bidirectional classes of the embedding, override and isolate controls) over every code point,
and OWASP's list of the first characters a spreadsheet evaluates."""

from __future__ import annotations

import unicodedata

import pytest

from bras_kit.trust.inert import TerminalWriter, for_spreadsheet, for_terminal

BIDI_CONTROLS = {"LRE", "RLE", "LRO", "RLO", "PDF", "LRI", "RLI", "FSI", "PDI", "LRM", "RLM", "ALM"}


def _obeyed(text: str) -> list[str]:
    """Characters of ``text`` a terminal would act on, or that reorder what it shows."""
    return [c for c in text if (unicodedata.category(c) == "Cc" and c not in "\n\t")
            or unicodedata.bidirectional(c) in BIDI_CONTROLS]


def test_no_code_point_comes_out_as_a_control_a_terminal_obeys():
    everything = "".join(chr(c) for c in range(0x110000) if not 0xD800 <= c <= 0xDFFF)
    assert _obeyed(everything)  # the oracle finds them in the input
    assert _obeyed(for_terminal(everything)) == []


@pytest.mark.parametrize(("text", "shown"), [
    ("\x1b[2J", "\\x1b[2J"),
    ("\x1b]0;title\x07", "\\x1b]0;title\\x07"),
    ("over\rwritten", "over\\x0dwritten"),
    ("\x9b31m", "\\u009b31m"),  # \u: also a JSON escape
    ("access\u202eled", "access\\u202eled"),
    ("two\nlines\tand a tab, é, 机械臂", "two\nlines\tand a tab, é, 机械臂"),
])
def test_controls_are_written_as_escapes_and_text_is_kept(text, shown):
    assert for_terminal(text) == shown


def test_the_writer_passes_everything_through_the_filter():
    import io

    sink = io.StringIO()
    writer = TerminalWriter(sink)
    print("a\x1b[2Jb", file=writer)  # type: ignore[arg-type]
    assert sink.getvalue() == "a\\x1b[2Jb\n" and writer.getvalue() == sink.getvalue()


@pytest.mark.parametrize("first", ["=", "+", "-", "@", "\t", "\r"])  # OWASP, CSV Injection
def test_a_cell_starting_like_a_formula_becomes_text(first):
    assert for_spreadsheet(first + "HYPERLINK(1)").startswith("'" + first)


@pytest.mark.parametrize("cell", ["alice", "1.5", "", "a-b", "x=1", "bob smith"])
def test_other_cells_are_left_as_they_are(cell):
    assert for_spreadsheet(cell) == cell


@pytest.mark.parametrize(("cell", "shown"), [
    (" =after a space", " '=after a space"),  # a spreadsheet splitting on spaces
    ("bob;=cmd|' /C calc'!A0", "bob;'=cmd|'' /C calc'!A0"),  # a French spreadsheet splitting on ;
    ("'quoted", "''quoted"),  # one more quote: from_spreadsheet gives the exact text back
])
def test_every_part_a_spreadsheet_may_split_off_is_text(cell, shown):
    assert for_spreadsheet(cell) == shown
