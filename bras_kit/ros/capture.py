"""What a node prints, kept as CI logs keep it: the first and the last 64 KiB, and how much of the
middle was not kept (characters and lines), counted as it streams by, never held whole.

::

    printed = HeadTail()
    sys.stdout = printed            # in the child: the node's print() lands here
    ...
    kept = printed.kept()           # Printed(head, tail, dropped_chars, dropped_lines)

A node printing 2 GB leaves 128 KiB and two counts (issue 52, item 4); the record that carries
them to bras-kit's process checks the same bounds again (:mod:`bras_kit.ros.record_wire`), so
the count is made once, here, and never re-counted on the way.
"""

from __future__ import annotations

import io
from collections import deque
from dataclasses import dataclass

HEAD_CHARS = 64 * 1024
TAIL_CHARS = 64 * 1024
_COMPACT = 256  # tail pieces joined into one past this many (a print is two writes: text, then "\n")


@dataclass(frozen=True)
class Printed:
    """The head and the tail of what was printed, and what lay between them, not kept."""

    head: str = ""
    tail: str = ""
    dropped_chars: int = 0
    dropped_lines: int = 0  # line ends in the part not kept


class HeadTail(io.TextIOBase):
    """A text stream keeping the first ``head`` and the last ``tail`` characters written to it."""

    def __init__(self, head: int = HEAD_CHARS, tail: int = TAIL_CHARS) -> None:
        super().__init__()
        self._head_most, self._tail_most = head, tail
        self._head: list[str] = []
        self._head_len = 0
        self._tail: deque[str] = deque()
        self._tail_len = 0
        self.dropped_chars = 0
        self.dropped_lines = 0

    def writable(self) -> bool:
        return True

    def write(self, text: str) -> int:
        if not isinstance(text, str):
            raise TypeError(f"write() argument must be str, not {type(text).__name__}")
        size = len(text)
        start = 0
        room = self._head_most - self._head_len
        if room > 0:
            part = text[:room]
            self._head.append(part)
            self._head_len += len(part)
            start = len(part)
        if start >= size:
            return size
        if size - start >= self._tail_most:  # the old tail and the front of this text go
            self._drop_all_tail()
            cut = size - self._tail_most
            self._dropped(text, start, cut)
            self._tail.append(text[cut:])
            self._tail_len = self._tail_most
            return size
        self._tail.append(text[start:] if start else text)
        self._tail_len += size - start
        while self._tail_len > self._tail_most:
            first = self._tail[0]
            excess = self._tail_len - self._tail_most
            if len(first) <= excess:
                self._tail.popleft()
                self._dropped(first, 0, len(first))
                self._tail_len -= len(first)
            else:
                self._dropped(first, 0, excess)
                self._tail[0] = first[excess:]
                self._tail_len -= excess
        if len(self._tail) > _COMPACT:
            self._tail = deque(["".join(self._tail)])
        return size

    def _dropped(self, text: str, start: int, end: int) -> None:
        self.dropped_chars += end - start
        self.dropped_lines += text.count("\n", start, end)

    def _drop_all_tail(self) -> None:
        for piece in self._tail:
            self._dropped(piece, 0, len(piece))
        self._tail.clear()
        self._tail_len = 0

    def kept(self) -> Printed:
        return Printed("".join(self._head), "".join(self._tail), self.dropped_chars, self.dropped_lines)
