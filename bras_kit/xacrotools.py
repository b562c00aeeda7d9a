"""Run the real ``xacro`` package without ROS, safely.

Three things are added around xacro:

* every file xacro parses is first read by :mod:`bras_kit.xmlio`, so a DTD or an entity is
  refused before minidom could expand it;
* every ``${...}`` and ``$(eval ...)`` expression is checked by :func:`check_expression`
  before xacro evaluates it: arithmetic, names, calls and subscripts pass; dunder names,
  introspection (``vars``, ``type``...) and huge powers do not;
* ``$(find pkg)`` is resolved from package folders given by the caller or the
  ``BRAS_KIT_PACKAGE_PATH`` environment variable (a folder holding packages, a package
  itself, or an install ``share/`` tree), then ``AMENT_PREFIX_PATH`` when ROS is there.
"""

from __future__ import annotations

import ast
import contextlib
import io
import os
import re
import threading
from collections.abc import Iterable, Mapping

from .errors import BrasKitError, XacroError
from .xmlio import check_xml_safe

PACKAGE_PATH_ENV = "BRAS_KIT_PACKAGE_PATH"

# Names that open a way from data to code (introspection, dynamic attribute access).
_FORBIDDEN_NAMES = frozenset({
    "vars", "type", "dir", "getattr", "setattr", "delattr", "globals", "locals", "eval", "exec",
    "compile", "open", "input", "help", "breakpoint", "memoryview", "object", "mro",
    "isinstance", "issubclass", "super", "classmethod", "staticmethod", "property",
    "format", "format_map", "func_globals", "gi_frame", "f_globals", "f_locals", "f_back",
    "tb_frame", "cr_frame", "load_yaml", "__import__",
})
MAX_LITERAL_EXPONENT = 64

_lock = threading.Lock()


def check_expression(expression: str) -> None:
    """Raise :class:`UnsafeExpression` unless ``expression`` is plain arithmetic-like Python.

    Used for xacro ``${}`` and ``$(eval)``; xacro's own guard only refuses names starting
    with ``__``, which string subscripts of ``vars()`` get around.
    """
    try:
        tree = ast.parse(expression.strip(), mode="eval")
    except SyntaxError as exc:
        raise XacroError(f"cannot read the expression '{expression}': {exc.msg}",
                         hint="check brackets and operators inside ${...}") from None
    for node in ast.walk(tree):
        bad = None
        if isinstance(node, ast.Name) and (node.id.startswith("_") or node.id in _FORBIDDEN_NAMES):
            bad = f"the name '{node.id}'"
        elif isinstance(node, ast.Attribute) and (node.attr.startswith("_") or node.attr in _FORBIDDEN_NAMES):
            bad = f"the attribute '.{node.attr}'"
        elif isinstance(node, ast.Constant) and isinstance(node.value, str) and "__" in node.value:
            bad = "a string with a double underscore"
        elif isinstance(node, (ast.Lambda, ast.NamedExpr, ast.Await, ast.Yield, ast.YieldFrom)):
            bad = f"a {type(node).__name__.lower()} expression"
        elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Mult) and any(
            _is_sequence(side) for side in (node.left, node.right)
        ):
            bad = "repetition of text or a list with '*'"
        elif isinstance(node, ast.BinOp) and isinstance(node.op, ast.Pow):
            exponent = node.right
            if isinstance(exponent, ast.UnaryOp) and isinstance(exponent.operand, ast.Constant):
                exponent = exponent.operand
            if isinstance(exponent, ast.Constant) and isinstance(exponent.value, (int, float)) \
                    and abs(exponent.value) > MAX_LITERAL_EXPONENT:
                bad = f"a power above {MAX_LITERAL_EXPONENT}"
            elif isinstance(exponent, ast.BinOp) and isinstance(exponent.op, ast.Pow):
                bad = "a tower of powers"
        if bad:
            raise XacroError(
                f"refused the expression '{expression.strip()}': it uses {bad}",
                hint="xacro expressions may only compute numbers and strings from properties",
            )


def _is_sequence(node: ast.AST) -> bool:
    """A literal that '*' would repeat (text, list, tuple, f-string) rather than multiply."""
    return isinstance(node, (ast.List, ast.Tuple, ast.JoinedStr, ast.ListComp)) or (
        isinstance(node, ast.Constant) and isinstance(node.value, (str, bytes))
    )


def package_roots(extra: Iterable[str] = ()) -> list[str]:
    """Folders to search for packages: the given ones, then BRAS_KIT_PACKAGE_PATH, then AMENT_PREFIX_PATH/share."""
    roots = [os.path.abspath(p) for p in extra]
    for var, suffix in ((PACKAGE_PATH_ENV, ""), ("AMENT_PREFIX_PATH", "share"), ("ROS_PACKAGE_PATH", "")):
        for entry in os.environ.get(var, "").split(os.pathsep):
            if entry:
                roots.append(os.path.join(entry, suffix) if suffix else entry)
    return roots


def find_package(name: str, roots: Iterable[str]) -> str:
    """The folder of package ``name`` under one of ``roots`` (checked for a package.xml or being a share/ entry)."""
    searched = []
    for root in roots:
        candidates = [os.path.join(root, name), os.path.join(root, "share", name)]
        if os.path.basename(os.path.normpath(root)) == name:
            candidates.insert(0, root)
        for candidate in candidates:
            searched.append(candidate)
            if os.path.isdir(candidate) and (
                os.path.isfile(os.path.join(candidate, "package.xml"))
                or os.path.basename(os.path.dirname(candidate)) == "share"
            ):
                return os.path.abspath(candidate)
    raise XacroError(
        f"$(find {name}): package '{name}' not found",
        hint=f"pass --package-path DIR (a folder holding {name}/ or an install share/ tree) "
        f"or set {PACKAGE_PATH_ENV}" + (f"; searched: {', '.join(searched)}" if searched else ""),
    )


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
        with open(path, encoding="utf-8", errors="replace") as handle:
            lines = handle.read().splitlines()
    except OSError:
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


def expand_xacro(
    path: str | os.PathLike[str],
    mappings: Mapping[str, str] | None = None,
    package_paths: Iterable[str] = (),
) -> str:
    """Expand a xacro file to URDF text with the real xacro package.

    ``mappings`` are xacro args (``name:=value`` on xacro's command line). Errors become a
    :class:`XacroError` naming the file, the best-guess line and what to do.
    """
    import xacro
    import xacro.substitution_args as subst

    path = os.fspath(path)
    if not os.path.isfile(path):
        raise BrasKitError(f"no such file: {path}", hint="check the path and spelling")
    roots = package_roots(package_paths)
    original = (xacro.parse, xacro.safe_eval, subst._eval, subst._eval_find, subst._eval_dict.get("find"))

    def safe_parse(inp, filename=None):  # type: ignore[no-untyped-def]
        if inp is None and filename is not None:
            full = os.path.normpath(os.path.join(xacro.root_dir, filename))
            try:
                with open(full, "rb") as handle:
                    data = handle.read()
            except OSError:
                return original[0](inp, filename)
            check_xml_safe(data, full)
            return original[0](data.decode("utf-8"), filename)
        if isinstance(inp, (str, bytes)):
            check_xml_safe(inp, filename)
        return original[0](inp, filename)

    def guarded_eval(expr, globals_, locals_=None):  # type: ignore[no-untyped-def]
        _checked(expr)
        return original[1](expr, globals_, locals_)

    def guarded_subst_eval(expr, context):  # type: ignore[no-untyped-def]
        _checked(expr)
        return original[2](expr, context)

    def resolve(name):  # type: ignore[no-untyped-def]
        return find_package(name, roots)

    stderr = io.StringIO()
    with _lock:
        xacro.parse, xacro.safe_eval = safe_parse, guarded_eval
        subst._eval, subst._eval_find = guarded_subst_eval, resolve
        subst._eval_dict["find"] = resolve
        try:
            with contextlib.redirect_stderr(stderr):
                doc = xacro.process_file(path, mappings=dict(mappings or {}), verbosity=0)
            return doc.toprettyxml(indent="  ")
        except Exception as exc:  # xacro raises many kinds; all become one clean error
            where = _current_file(xacro, path)
            inner = _inner_error(exc)
            if inner is not None:  # one of our guards, possibly wrapped by xacro: report it alone
                if inner.path is None:
                    inner.path = where
                    expression = getattr(inner, "expression", "")
                    inner.line = inner.line or _locate(where, inner.message, [
                        "${" + expression + "}", "$(eval " + expression, expression] if expression else [])
                raise inner from None
            message = " ".join((str(exc) or type(exc).__name__).split())
            missing = _MISSING_FILE.search(message)
            if missing:
                message = f"cannot include {missing.group(1).rstrip(':')}: no such file"
            line = getattr(exc, "lineno", None) or _locate(where, message)
            raise XacroError(f"xacro failed: {message}", path=where, line=line,
                             hint=_hint_for(message)) from None
        finally:
            xacro.parse, xacro.safe_eval = original[0], original[1]
            subst._eval, subst._eval_find = original[2], original[3]
            subst._eval_dict["find"] = original[4]
            xacro.init_stacks(None)


def _checked(expression: str) -> None:
    """:func:`check_expression`, remembering the expression on the error to find its line."""
    try:
        check_expression(expression)
    except XacroError as exc:
        exc.expression = expression.strip()  # type: ignore[attr-defined]
        raise


def _current_file(xacro_module, default: str) -> str:  # type: ignore[no-untyped-def]
    stack = [f for f in (xacro_module.filestack or []) if f]
    return os.path.normpath(stack[-1]) if stack else default


def _hint_for(message: str) -> str:
    if "Undefined substitution argument" in message or "arg" in message.lower() and "undefined" in message.lower():
        return "pass the argument as name:=value, or give it a default with <xacro:arg name=... default=...>"
    if "Undefined property" in message or "name '" in message and "is not defined" in message:
        return "define the property with <xacro:property name=... value=...> before using it"
    if "no such file" in message.lower():
        return "check the path of the included file (relative paths start from the including file)"
    if "not well-formed" in message or "mismatched tag" in message:
        return "check the XML on this line is closed and quoted properly"
    return "check the xacro syntax on this line"
