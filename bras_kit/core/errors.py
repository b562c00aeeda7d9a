"""The error hierarchy. Every failure a user can cause is one of these; the CLI prints it and exits 2."""

from __future__ import annotations

import errno
from collections.abc import Sequence

from .message import M, Mc, Message


class BrasKitError(Exception):
    """Base class: a problem with the user's input or environment, reported without a traceback.

    ``message`` and ``hint`` are :class:`~bras_kit.core.message.Message` data (an English id and its
    parameters), worded by whoever shows the error (:func:`bras_kit.core.i18n.say_error`);
    ``str(error)`` is the English text. ``path``, ``line`` and ``element`` locate it when known.
    """

    def __init__(
        self,
        message: Message | str,
        *,
        path: str | None = None,
        line: int | None = None,
        element: str | None = None,
        hint: Message | str | None = None,
    ) -> None:
        super().__init__(str(message))
        self.message = message
        self.path = path
        self.line = line
        self.element = element
        self.hint = hint

    def __str__(self) -> str:
        where = ""
        if self.path:
            where = str(self.path)
            if self.line:
                where += f":{self.line}"
            where += ": "
        text = where + str(self.message)
        if self.element:
            text += f" (in <{self.element}>)"
        if self.hint:
            text += f"\n  hint: {self.hint}"
        return text


class XMLSafetyError(BrasKitError):
    """The XML holds a DTD, an entity declaration or an external entity: refused, never expanded.
    ``kind`` says which: ``dtd``, ``attlist``, ``entity``, ``external`` or ``undefined``."""

    kind = ""


class XMLSyntaxError(BrasKitError):
    """The file is not well-formed XML. ``detail`` is what went wrong, as data (the element left
    open and its line, where the reader stopped...), without the "not well-formed XML" words."""

    detail: Message | None = None
    fix: Message | None = None  # what to do, when the cause is known (a character pasted from elsewhere)


class ModelError(BrasKitError):
    """The robot description cannot be used as a tree (missing links, cycles, unknown names...)."""


class UnusableModelError(ModelError):
    """The model holds values a command would compute with but the reader could not use (nan, inf,
    text, a zero axis...). ``findings`` are the validator's own; the command exits 1, as
    ``bras-kit validate`` does on errors."""

    exit_code = 1

    def __init__(self, message: Message | str, findings: Sequence[object], **where: object) -> None:
        super().__init__(message, **where)  # type: ignore[arg-type]
        self.findings = findings


class XacroError(BrasKitError):
    """xacro expansion failed, or an expression was refused as unsafe."""


class ParameterError(BrasKitError):
    """A template parameter, joint value or command-line value is unknown or malformed."""


class UnknownJointError(ParameterError):
    """A name given as a joint is not a movable joint of this robot (``joint`` holds the name);
    the command line adds what the name is instead (a template parameter, the wrist...)."""

    def __init__(self, message: Message | str, joint: str, **where: object) -> None:
        super().__init__(message, **where)  # type: ignore[arg-type]
        self.joint = joint


class UnsafeExpressionError(BrasKitError):
    """An expression tried something outside the allowed arithmetic (code, imports, attributes)."""


class OutputExistsError(BrasKitError):
    """Writing would overwrite something the user made; pass --force to allow it."""


class BackendError(BrasKitError):
    """An optional backend (OpenGL, ffmpeg, ...) is missing or failed."""


class TimeInJointValueError(ParameterError):
    """A joint value (``--set``, ``--pose``) is a formula of the time ``t``: one number is wanted."""


# The operating system's reasons a user can meet, by errno: the English id is the C library's
# own text (what ``strerror`` says on Linux, so English output is unchanged) and the catalogs
# translate it; any other reason is quoted as the system wrote it.
_OS_REASONS = {
    errno.ENOENT: M("No such file or directory"),
    errno.EACCES: M("Permission denied"),
    errno.EPERM: M("Operation not permitted"),
    errno.EISDIR: M("Is a directory"),
    errno.ENOTDIR: M("Not a directory"),
    errno.EEXIST: M("File exists"),
    errno.ENOSPC: M("No space left on device"),
    errno.EDQUOT: M("Disk quota exceeded"),
    errno.EROFS: M("Read-only file system"),
    errno.ELOOP: M("Too many levels of symbolic links"),
    errno.ENAMETOOLONG: M("File name too long"),
    errno.ENOTEMPTY: M("Directory not empty"),
    errno.EBUSY: M("Device or resource busy"),
    errno.EMFILE: M("Too many open files"),
    errno.EXDEV: M("Invalid cross-device link"),
    errno.EIO: M("Input/output error"),
    errno.EINVAL: M("Invalid argument"),
    errno.ETXTBSY: M("Text file busy"),
}


def os_reason(exc: OSError) -> Message:
    """Why an :class:`OSError` happened, as a message: translated for the usual errno values,
    else the system's own words (in French after a sentence saying they are the system's)."""
    known = _OS_REASONS.get(exc.errno) if exc.errno is not None else None
    if known is not None and (exc.strerror is None or exc.strerror == known.id):
        return known
    return Mc("system", "{reason}", reason=exc.strerror or str(exc))
