"""Where a launch says what it does, as ``ros2 launch`` does on a terminal: its lines on
standard output, ROS's own errors on standard error, bras-kit's warnings labelled."""

from __future__ import annotations

import sys
from typing import IO, Any

from ..core.message import M, Message


class Reporter:
    """Words a launch's lines in ``lang`` and writes them; ``out`` and ``err`` default to the
    process's streams as they are when a line is written (the CLI's are gated)."""

    def __init__(self, lang: str | None = None, out: IO[str] | None = None, err: IO[str] | None = None) -> None:
        self.lang = lang
        self._out, self._err = out, err

    @property
    def out(self) -> IO[str]:
        return self._out if self._out is not None else sys.stdout

    @property
    def err(self) -> IO[str]:
        return self._err if self._err is not None else sys.stderr

    def say(self, message: Message | str) -> str:
        from ..core.i18n import say

        return say(message, self.lang) if isinstance(message, Message) else message

    def line(self, text: Message | str) -> None:
        """A line of the launch's own output (what started, what a node published)."""
        print(self.say(text), file=self.out)

    def error(self, text: Message | str) -> None:
        """A line of ROS's errors, or a node's failure."""
        print(self.say(text), file=self.err, flush=True)

    def warn(self, message: Any) -> None:
        """``warning: ...``, worded in the launch's language."""
        from ..core.i18n import labelled, say

        print(labelled(M("warning"), say(message, self.lang), self.lang), file=self.err)

    def findings(self, results: list[Any]) -> None:
        """The findings of a build, as ``bras-kit validate`` words them."""
        from ..findings.report import format_text

        self.out.write(format_text(results, self.lang))
        self.flush()

    def flush(self) -> None:
        self.out.flush()
        self.err.flush()
