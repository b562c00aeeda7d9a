"""What a command asks for (``--contain auto|require|off``) turned into a :class:`Containment` or
none, and the note shown where the learner's code runs without walls."""

from __future__ import annotations

from collections.abc import Iterable

from ...core.message import M, Message
from .kernel import ContainmentError
from .probe import available
from .view import _installation
from .walls import Containment


class ContainmentUnavailable(ContainmentError):
    """Containment was required and this machine cannot give it."""


CONTAIN_MODES = ("auto", "require", "off")


def containment(mode: str, workdir: str, readable: Iterable[str] = ()) -> Containment | None:
    """The :class:`Containment` for a run in ``workdir`` reading ``readable``, by ``mode``:
    "auto" (contained where :func:`available`, else None), "require" (raises
    :class:`ContainmentUnavailable` where not), "off" (None)."""
    if mode == "off":
        return None
    if mode == "require":
        containment_required()
    if not available().ok:
        return None
    _installation()  # worked out here, once: every child forked to enter this containment has it
    return Containment(workdir, tuple(readable))


def containment_required() -> None:
    """Raise :class:`ContainmentUnavailable` (what is missing, how to get it) where :func:`available` is not ok."""
    status = available()
    if not status.ok:
        raise ContainmentUnavailable(M("code bras-kit did not write cannot be contained on this machine ({found}): "
                                       "it needs {missing}", missing=status.missing, found=status.found),
                                     hint=status.how)


def uncontained_note() -> Message | None:
    """The one line ``run`` and ``launch`` show where the learner's own code runs uncontained
    (None where it is contained)."""
    status = available()
    if status.ok:
        return None
    return M("note: your code runs without walls here (this machine lacks {missing}): it has your rights, "
             "as under ros2 run", missing=status.missing)
