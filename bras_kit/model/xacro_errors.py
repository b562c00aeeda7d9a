"""An xacro failure turned into one :class:`~bras_kit.core.errors.XacroError`: the file and the
best-guess line it is about, the expression at fault, and a hint of what to do."""

from __future__ import annotations

import os
import re
from collections.abc import Iterable
from typing import Any

from ..core.errors import BrasKitError, XacroError
from ..core.message import M, Message
from .xacro_files import _read_limited


def _locate(path: str, message: str, extra: Iterable[str] = ()) -> int | None:
    """Best guess at the line of ``path`` an xacro error is about, from the names it quotes."""
    tokens = list(extra) + re.findall(r"['\"]([^'\"]{1,80})['\"]", message)
    tokens += re.findall(r"\$\{[^}]*\}|\$\([^)]*\)", message)
    tokens += [f"$(arg {name})" for name in re.findall(r"Undefined substitution argument (\S+)", message)]
    tokens += re.findall(r"[\w./-]+\.(?:xacro|urdf|yaml)\b", message)
    paths = [os.path.normpath(t) for t in tokens if "/" in t or t.startswith(".")]
    # an included file is quoted with its full path; the including file holds a relative one
    tokens += paths + [p.split(os.sep, k)[-1] for p in paths for k in range(1, p.count(os.sep) + 1)]
    try:
        lines = _read_limited(path).decode("utf-8", errors="replace").splitlines()
    except (OSError, BrasKitError):
        return None
    for token in tokens:
        for number, text in enumerate(lines, 1):
            if token and token in text:
                return number
    return None


def _inner_error(exc: BaseException) -> BrasKitError | None:
    """The BrasKitError (from our guards) that xacro wrapped in its own exception, if any."""
    seen: set[int] = set()
    current: BaseException | None = exc
    while current is not None and id(current) not in seen:
        seen.add(id(current))
        if isinstance(current, BrasKitError):
            return current
        inner = getattr(current, "exc", None)
        current = inner if isinstance(inner, BaseException) else (current.__cause__ or current.__context__)
    return None


_MISSING_FILE = re.compile(r"No such file or directory: (\S+)")
_EVALUATING = re.compile(r"when evaluating expression '(.*)'\s*$", re.S)
_ESCAPES = (("&", "&amp;"), ("<", "&lt;"), (">", "&gt;"), ('"', "&quot;"), ("'", "&apos;"))


def _chain(xacro: Any, exc: BaseException) -> tuple[BaseException, list[str]]:
    """The root cause of a chain of xacro exceptions and the expressions it went through, innermost first."""
    expressions: list[str] = []
    current: BaseException = exc
    seen: set[int] = set()
    while id(current) not in seen:
        seen.add(id(current))
        suffix = getattr(current, "suffix", None)
        if isinstance(suffix, str):
            found = _EVALUATING.search(suffix.strip())
            if found:
                expressions.append(found.group(1))
        inner = getattr(current, "exc", None)
        if not isinstance(inner, BaseException):
            break
        current = inner
    return current, expressions[::-1]


def _escaped(text: str) -> list[str]:
    forms = [text]
    for plain, escape in _ESCAPES:
        forms += [form.replace(plain, escape) for form in forms if plain in form]
    return forms


def find_expression(expression: str, files: Iterable[str]) -> tuple[str, int] | None:
    """The first file and line (in ``files`` order) where ``${expression}`` or ``$(eval expression)`` is written."""
    expression = expression.strip()
    tokens = [wrap.format(form) for form in _escaped(expression) for wrap in ("${{{}}}", "$(eval {})")]
    for path in dict.fromkeys(files):
        try:
            text = _read_limited(path).decode("utf-8", errors="replace")
        except (OSError, BrasKitError):
            continue
        for token in tokens:
            at = text.find(token)
            if at >= 0:
                return path, text.count("\n", 0, at) + 1
    return None


def _clean_error(xacro: Any, path: str, exc: BaseException, files: Iterable[str] = ()) -> BrasKitError:
    where = _current_file(xacro, path)
    files = [where, *files, path]
    inner = _inner_error(exc)
    if inner is not None:  # one of our walls, possibly wrapped by xacro: report it alone
        expression = getattr(inner, "expression", "")
        if inner.path is None:
            found = find_expression(expression, files) if expression else None
            inner.path, inner.line = found or (where, inner.line or _locate(where, str(inner.message)))
        return inner
    root, expressions = _chain(xacro, exc)
    if isinstance(root, RecursionError):
        return XacroError(M("the file nests too deeply (macros, properties or elements)"), path=where,
                          hint=M("a macro or property probably refers to itself"))
    if isinstance(root, MemoryError):
        return XacroError(M("the expansion ran out of memory"), path=where, hint=M("simplify the file"))
    close = getattr(root, "close", None)  # safe_eval's guess at a misspelt name
    if expressions:  # root cause first, where its expression is written; then what used it
        cause = _one_line(str(root) or type(root).__name__)
        if not isinstance(root, xacro.XacroException) and type(root).__name__ not in cause:
            cause = f"{type(root).__name__}: {cause}"
        found = find_expression(expressions[0], files)
        message = M("{cause} in the expression '{expression}'", cause=cause, expression=expressions[0])
        if len(expressions) > 1:
            message = M("{message} (used by {expressions})", message=message, expressions=expressions[1:])
        at, line = found or (where, None)
        hint = _hint_for(cause)
        if close:
            hint = M("did you mean '{close}'? Otherwise, {hint}", close=close, hint=hint)
        error = XacroError(message, path=at, line=line, hint=hint)
        error.close = close  # type: ignore[attr-defined]  # validate's BK102 names it too
        return error
    text = _one_line(str(exc) or type(exc).__name__)
    missing = _MISSING_FILE.search(text)
    if missing:
        return XacroError(M("cannot include {path}: no such file", path=missing.group(1).rstrip(":")), path=where,
                          line=_locate(where, text), hint=_hint_for("no such file"))
    line = getattr(exc, "lineno", None) or _locate(where, text)
    return XacroError(M("xacro failed: {error}", error=text), path=where, line=line, hint=_hint_for(text))


def _one_line(text: str) -> str:
    text = " ".join(text.split())
    return text if len(text) <= 500 else text[:500] + "..."


def _current_file(xacro_module, default: str) -> str:
    stack = [f for f in (xacro_module.filestack or []) if f]
    return os.path.normpath(stack[-1]) if stack else default


_NOT_DEFINED = re.compile(r"name '([^']*)' is not defined")


def _names_in(table: Any) -> list[str]:
    """Every name an expression can read in ``table``: its properties, its parents' (macro
    parameters over the file's properties), then xacro's globals (math, the namespaces)."""
    names: list[str] = []
    seen: set[int] = set()
    while isinstance(table, dict) and id(table) not in seen:
        seen.add(id(table))
        names += [n for n in dict.keys(table) if isinstance(n, str) and not n.startswith("_")]
        table = getattr(table, "parent", None)
    return names


def _closest(name: str, names: Iterable[str]) -> str | None:
    import difflib

    close = difflib.get_close_matches(name, list(dict.fromkeys(names)), n=1, cutoff=0.6) if name else []
    return close[0] if close else None


def _hint_for(message: str) -> Message:
    if "Undefined substitution argument" in message or "arg" in message.lower() and "undefined" in message.lower():
        return M("pass the argument as name:=value, or give it a default with <xacro:arg name=... default=...>")
    if "Undefined property" in message or "name '" in message and "is not defined" in message:
        return M("define the property with <xacro:property name=... value=...> before using it")
    if "no such file" in message.lower():
        return M("check the path of the included file (relative paths start from the including file)")
    if "not well-formed" in message or "mismatched tag" in message:
        return M("check the XML on this line is closed and quoted properly")
    return M("check the xacro syntax on this line")
