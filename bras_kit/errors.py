"""The error hierarchy. Every failure a user can cause is one of these; the CLI prints it and exits 2."""

from __future__ import annotations


class BrasKitError(Exception):
    """Base class: a problem with the user's input or environment, reported without a traceback.

    ``path`` and ``line`` locate it when known; ``hint`` says what to do.
    """

    def __init__(
        self,
        message: str,
        *,
        path: str | None = None,
        line: int | None = None,
        element: str | None = None,
        hint: str | None = None,
    ) -> None:
        super().__init__(message)
        self.message = message
        self.path = path
        self.line = line
        self.element = element
        self.hint = hint

    def __str__(self) -> str:
        from .i18n import _, translate_message

        where = ""
        if self.path:
            where = str(self.path)
            if self.line:
                where += f":{self.line}"
            where += ": "
        text = where + translate_message(self.message)
        if self.element:
            text += " " + _("(in <{}>)").format(self.element)
        if self.hint:
            text += f"\n  {_('hint')}: {translate_message(self.hint)}"
        return text


class XMLSafetyError(BrasKitError):
    """The XML holds a DTD, an entity declaration or an external entity: refused, never expanded."""


class XMLSyntaxError(BrasKitError):
    """The file is not well-formed XML."""


class ModelError(BrasKitError):
    """The robot description cannot be used as a tree (missing links, cycles, unknown names...)."""


class XacroError(BrasKitError):
    """xacro expansion failed, or an expression was refused as unsafe."""


class ParameterError(BrasKitError):
    """A template parameter, joint value or command-line value is unknown or malformed."""


class UnknownJointError(ParameterError):
    """A name given as a joint is not a movable joint of this robot (``joint`` holds the name);
    the command line adds what the name is instead (a template parameter, the wrist...)."""

    def __init__(self, message: str, joint: str, **where: object) -> None:
        super().__init__(message, **where)  # type: ignore[arg-type]
        self.joint = joint


class UnsafeExpressionError(BrasKitError):
    """An expression tried something outside the allowed arithmetic (code, imports, attributes)."""


class OutputExistsError(BrasKitError):
    """Writing would overwrite something the user made; pass --force to allow it."""


class BackendError(BrasKitError):
    """An optional backend (OpenGL, ffmpeg, ...) is missing or failed."""
