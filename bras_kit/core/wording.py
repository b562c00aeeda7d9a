"""Small shapes of words shared by the features: messages joined into one.

A list of messages is worded item by item where it is shown; the separators stay as written
(``", "`` or ``"; "``) and "or" between names is a word of the catalog.
"""

from __future__ import annotations

from collections.abc import Sequence

from .message import M, Mc, Message


def joined(items: Sequence[Message | str], separator: str = ", ") -> Message | str:
    """``a, b, c`` (or ``a; b; c`` with ``separator="; "``) of messages or plain names."""
    if not items:
        return ""
    said: Message | str = items[0]
    for item in items[1:]:
        said = M("{left}; {right}", left=said, right=item) if separator == "; " else \
            M("{left}, {right}", left=said, right=item)
    return said


def either(names: Sequence[Message | str]) -> Message | str:
    """``a or b or c``, the "or" worded where it is shown."""
    if not names:
        return ""
    said: Message | str = names[0]
    for name in names[1:]:
        said = M("{left} or {right}", left=said, right=name)
    return said


def quoted(text: str) -> Message:
    """Words from below (a library's or the system's English message) kept as they are: in
    English as written, in French in quotation marks after the sentence that uses them."""
    return Mc("quoted", "{text}", text=text)
