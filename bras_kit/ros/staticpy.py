"""Read Python files of a ROS 2 package without running them: a tiny static evaluator over :mod:`ast`.

``setup.py``, launch files and nodes are parsed, never imported or executed. The evaluator
knows the handful of things these files compute: strings and their concatenation, f-strings,
lists, tuples, dicts, ``os.path.join``, ``glob`` (matched against the package folder itself),
``sorted``/``list``, comprehensions over known values, ``get_package_share_directory`` /
``FindPackageShare`` (a symbolic :class:`Share`), and calls of small helper functions defined
in the same file (bound arguments, assignments, ``return``). Anything else is :data:`UNKNOWN`,
and rules that meet an unknown value stay silent rather than guess.
"""

from __future__ import annotations

import ast
import glob as globmod
import os
import posixpath
from collections.abc import Iterator, Mapping
from dataclasses import dataclass
from typing import Any


class _Unknown:
    def __repr__(self) -> str:
        return "UNKNOWN"


UNKNOWN: Any = _Unknown()
MAX_CALL_DEPTH = 4  # helper functions calling helper functions
MAX_ITEMS = 10_000  # values a comprehension may produce
MAX_LENGTH = 100_000  # characters of a string, or items of a list, built by '+'


@dataclass(frozen=True)
class Share:
    """``get_package_share_directory(package)``: the package's installed share/ folder."""

    package: str


@dataclass(frozen=True)
class ShareFile:
    """A path below a package's share/ folder, e.g. ``ShareFile('bras_description', 'urdf/bras.urdf')``."""

    package: str
    relative: str


def parse_python(path: str, root: str | None = None) -> tuple[ast.Module | None, str | None, int | None]:
    """The module's tree, or (None, reason, line) when it cannot be read or parsed. The file is read
    through the one reader (:mod:`bras_kit.trust.learner_files`): inside ``root`` (default: its folder),
    a regular file, never a device, a pipe or a link out."""
    from ..trust.learner_files import Unreadable, read_bytes

    try:
        source = read_bytes(path, (root or os.path.dirname(os.path.abspath(path)),))
    except Unreadable as exc:
        return None, str(exc).rpartition(": ")[2], None
    except OSError as exc:
        return None, exc.strerror or str(exc), None
    try:
        return ast.parse(source, filename=path), None, None
    except SyntaxError as exc:
        return None, exc.msg, exc.lineno
    except ValueError as exc:  # null bytes
        return None, str(exc), None
    except (RecursionError, MemoryError):
        return None, "too deeply nested to read", None


def known(value: Any) -> bool:
    """True when ``value`` (and everything inside it) was computed."""
    if value is UNKNOWN:
        return False
    if isinstance(value, (list, tuple)):
        return all(known(v) for v in value)
    if isinstance(value, dict):
        return all(known(k) and known(v) for k, v in value.items())
    return True


_SHARE_FUNCTIONS = {"get_package_share_directory", "get_package_share_path", "FindPackageShare"}


class Evaluator:
    """Evaluates expressions of one module against its own simple assignments.

    ``root`` is the folder ``glob`` patterns are matched in (the package folder: colcon runs
    ``setup.py`` from there). ``names`` holds module-level constants; ``functions`` the
    module's ``def`` statements, callable when their body is simple enough.
    """

    def __init__(self, tree: ast.Module, root: str, names: Mapping[str, Any] | None = None) -> None:
        self.root = root
        self.names: dict[str, Any] = dict(names or {})
        self.functions = {node.name: node for node in tree.body if isinstance(node, ast.FunctionDef)}
        for node in tree.body:
            self.assign(node, self.names)
        self.unstable = changed_names(tree)
        for name in self.unstable:
            self.names[name] = UNKNOWN

    # ------------------------------------------------------------ statements

    def assign(self, node: ast.stmt, scope: dict[str, Any], depth: int = 0) -> None:
        if isinstance(node, ast.Assign) and len(node.targets) == 1:
            self._bind(node.targets[0], self.value(node.value, scope, depth), scope)
        elif isinstance(node, ast.AnnAssign) and node.value is not None:
            self._bind(node.target, self.value(node.value, scope, depth), scope)

    def _bind(self, target: ast.expr, value: Any, scope: dict[str, Any]) -> None:
        if isinstance(target, ast.Name):
            scope[target.id] = value
        elif isinstance(target, (ast.Tuple, ast.List)):
            items = list(value) if isinstance(value, (list, tuple)) and len(value) == len(target.elts) else None
            for k, element in enumerate(target.elts):
                self._bind(element, items[k] if items is not None else UNKNOWN, scope)

    def scope_of(self, function: ast.FunctionDef) -> dict[str, Any]:
        """The names a function's statements bind, in order (loops and branches included once)."""
        scope = dict(self.names)
        for node in ast.walk(function):
            if isinstance(node, (ast.Assign, ast.AnnAssign)):
                self.assign(node, scope)
            elif isinstance(node, ast.With):
                for item in node.items:
                    if isinstance(item.optional_vars, ast.Name):
                        scope[item.optional_vars.id] = UNKNOWN
        for name in self.unstable:
            scope[name] = UNKNOWN
        return scope

    # ------------------------------------------------------------ expressions

    def value(self, node: ast.expr | None, scope: Mapping[str, Any] | None = None, depth: int = 0) -> Any:
        scope = self.names if scope is None else scope
        try:
            return self._value(node, scope, depth)
        except (TypeError, ValueError, KeyError, IndexError, RecursionError, OverflowError):
            return UNKNOWN

    def _value(self, node: ast.expr | None, scope: Mapping[str, Any], depth: int) -> Any:
        if node is None:
            return UNKNOWN
        if isinstance(node, ast.Constant):
            return node.value
        if isinstance(node, ast.Name):
            return scope.get(node.id, UNKNOWN)
        if isinstance(node, (ast.List, ast.Tuple)):
            items: list[Any] = []
            for element in node.elts:
                if isinstance(element, ast.Starred):
                    inner = self._value(element.value, scope, depth)
                    if not isinstance(inner, (list, tuple)):
                        return UNKNOWN
                    items.extend(inner)
                else:
                    items.append(self._value(element, scope, depth))
            return items if isinstance(node, ast.List) else tuple(items)
        if isinstance(node, ast.Dict):
            if any(k is None for k in node.keys):
                return UNKNOWN
            keys = [self._value(k, scope, depth) for k in node.keys]
            if not all(isinstance(k, (str, int, float, bool)) for k in keys):
                return UNKNOWN
            return dict(zip(keys, (self._value(v, scope, depth) for v in node.values)))
        if isinstance(node, ast.BinOp) and isinstance(node.op, ast.Add):
            left, right = self._value(node.left, scope, depth), self._value(node.right, scope, depth)
            if isinstance(left, str) and isinstance(right, str):
                return left + right if len(left) + len(right) <= MAX_LENGTH else UNKNOWN
            if isinstance(left, list) and isinstance(right, list):
                return left + right if len(left) + len(right) <= MAX_LENGTH else UNKNOWN
            return UNKNOWN
        if isinstance(node, ast.JoinedStr):
            parts = []
            for piece in node.values:
                if isinstance(piece, ast.Constant):
                    parts.append(str(piece.value))
                elif isinstance(piece, ast.FormattedValue) and piece.format_spec is None and piece.conversion == -1:
                    inner = self._value(piece.value, scope, depth)
                    if not isinstance(inner, (str, int)):
                        return UNKNOWN
                    parts.append(str(inner))
                else:
                    return UNKNOWN
            return "".join(parts)
        if isinstance(node, (ast.ListComp, ast.GeneratorExp)):
            return self._comprehension(node, scope, depth)
        if isinstance(node, ast.Call):
            return self._call(node, scope, depth)
        return UNKNOWN

    def _comprehension(self, node: ast.ListComp | ast.GeneratorExp, scope: Mapping[str, Any], depth: int) -> Any:
        results: list[Any] = []

        def walk(level: int, local: dict[str, Any]) -> bool:
            if level == len(node.generators):
                results.append(self._value(node.elt, local, depth))
                return len(results) <= MAX_ITEMS
            generator = node.generators[level]
            if generator.ifs or generator.is_async:
                return False
            iterable = self._value(generator.iter, local, depth)
            if not isinstance(iterable, (list, tuple)):
                return False
            for item in iterable:
                inner = dict(local)
                self._bind(generator.target, item, inner)
                if not walk(level + 1, inner):
                    return False
            return True

        return results if walk(0, dict(scope)) else UNKNOWN

    def _call(self, node: ast.Call, scope: Mapping[str, Any], depth: int) -> Any:
        name = call_name(node.func)
        args: list[Any] = []
        for argument in node.args:
            if isinstance(argument, ast.Starred):
                inner = self._value(argument.value, scope, depth)
                if not isinstance(inner, (list, tuple)):
                    return UNKNOWN
                args.extend(inner)
            else:
                args.append(self._value(argument, scope, depth))
        if name in ("os.path.join", "path.join", "join", "PathJoinSubstitution"):
            if name == "PathJoinSubstitution":
                args = list(args[0]) if len(args) == 1 and isinstance(args[0], (list, tuple)) else [UNKNOWN]
            return join_paths(args)
        if name.rsplit(".", 1)[-1] in _SHARE_FUNCTIONS:
            package = args[0] if args else UNKNOWN
            return Share(package) if isinstance(package, str) else UNKNOWN
        if name in ("glob", "glob.glob"):
            return self._glob(args[0]) if len(args) == 1 and isinstance(args[0], str) else UNKNOWN
        if name in ("sorted", "list", "tuple") and len(args) == 1:
            if isinstance(args[0], dict):
                items = list(args[0])
            elif isinstance(args[0], (list, tuple)):
                items = list(args[0])
            else:
                return UNKNOWN
            if name == "sorted":
                return sorted(items) if all(isinstance(i, str) for i in items) else UNKNOWN
            return items if name == "list" else tuple(items)
        if name == "str" and len(args) == 1 and isinstance(args[0], (str, ShareFile)):
            return args[0]
        if isinstance(node.func, ast.Attribute) and node.func.attr in ("keys", "values", "items") and not args:
            owner = self._value(node.func.value, scope, depth)
            if isinstance(owner, dict):
                return list(getattr(owner, node.func.attr)())
            return UNKNOWN
        if name in self.functions and depth < MAX_CALL_DEPTH:
            return self._call_helper(self.functions[name], args, node, scope, depth + 1)
        return UNKNOWN

    def _call_helper(self, function: ast.FunctionDef, args: list[Any], node: ast.Call,
                     scope: Mapping[str, Any], depth: int) -> Any:
        """A helper defined in the file: bind its parameters, follow assignments to its return."""
        parameters = function.args
        if parameters.kwonlyargs or parameters.kwarg or node.keywords:
            return UNKNOWN
        names = [a.arg for a in parameters.posonlyargs + parameters.args]
        local: dict[str, Any] = dict(self.names)
        if len(args) < len(names) - len(parameters.defaults) or (len(args) > len(names) and not parameters.vararg):
            return UNKNOWN
        defaults = [self._value(d, scope, depth) for d in parameters.defaults]
        for k, parameter in enumerate(names):
            if k < len(args):
                local[parameter] = args[k]
            else:
                local[parameter] = defaults[k - (len(names) - len(defaults))]
        if parameters.vararg:
            local[parameters.vararg.arg] = tuple(args[len(names):])
        for statement in function.body:
            if isinstance(statement, ast.Return):
                return self._value(statement.value, local, depth)
            if isinstance(statement, (ast.Assign, ast.AnnAssign)):
                self.assign(statement, local, depth)
            elif isinstance(statement, ast.If) and _only_raises(statement):
                continue  # a guard ("no file found: stop the build"); the normal path goes on
            elif isinstance(statement, ast.Expr) and isinstance(statement.value, ast.Constant):
                continue  # docstring
            else:
                return UNKNOWN
        return UNKNOWN

    def _glob(self, pattern: str) -> Any:
        if os.path.isabs(pattern) or ".." in pattern.replace("\\", "/").split("/"):
            return UNKNOWN
        root = os.path.abspath(self.root)
        found = globmod.glob(os.path.join(globmod.escape(root), pattern))
        return [os.path.relpath(path, root).replace(os.sep, "/") for path in found]


_MUTATORS = frozenset({"append", "extend", "insert", "update", "remove", "pop", "clear", "setdefault", "sort"})


def changed_names(tree: ast.Module) -> set[str]:
    """Names whose value the evaluator cannot follow: changed in place (``x.append``, ``x +=``,
    ``x[k] =``), or assigned inside a loop, branch or ``try`` at module level."""
    out: set[str] = set()
    for node in ast.walk(tree):
        if isinstance(node, ast.AugAssign) and isinstance(node.target, ast.Name):
            out.add(node.target.id)
        elif isinstance(node, (ast.Assign, ast.AugAssign)):
            targets = node.targets if isinstance(node, ast.Assign) else [node.target]
            out.update(t.value.id for t in targets if isinstance(t, ast.Subscript) and isinstance(t.value, ast.Name))
        elif isinstance(node, ast.Call) and isinstance(node.func, ast.Attribute) \
                and node.func.attr in _MUTATORS and isinstance(node.func.value, ast.Name):
            out.add(node.func.value.id)
    for statement in tree.body:
        if isinstance(statement, (ast.For, ast.While, ast.If, ast.Try, ast.With)):
            for node in ast.walk(statement):
                if isinstance(node, (ast.Assign, ast.AnnAssign, ast.AugAssign)):
                    targets = node.targets if isinstance(node, ast.Assign) else [node.target]
                    out.update(n.id for t in targets for n in ast.walk(t) if isinstance(n, ast.Name))
                elif isinstance(node, (ast.For, ast.comprehension)):
                    out.update(n.id for n in ast.walk(node.target) if isinstance(n, ast.Name))
    return out


def _only_raises(statement: ast.If) -> bool:
    return not statement.orelse and all(isinstance(s, ast.Raise) for s in statement.body)


def join_paths(parts: list[Any]) -> Any:
    """``os.path.join`` over strings (``PathJoinSubstitution`` performs it too), or a :class:`ShareFile`
    when the first part is a :class:`Share`: a path compared as the system opens it, never as text
    (``join(join(share), 'urdf')``, 'urdf/', './urdf', 'launch/../urdf' and a doubled slash all name
    share/PKG/urdf). As ``os.path.join`` does, an absolute part drops the parts before it."""
    if not parts:
        return UNKNOWN
    absolute = [k for k, p in enumerate(parts) if isinstance(p, str) and p.startswith("/")]
    parts = parts[absolute[-1]:] if absolute else parts
    head, rest = parts[0], parts[1:]
    if isinstance(head, (Share, ShareFile)) and all(isinstance(p, str) for p in rest):
        return share_file(head.package, posixpath.join(head.relative if isinstance(head, ShareFile) else "", *rest))
    if all(isinstance(p, str) for p in parts):
        return os.path.join(*parts).replace(os.sep, "/")
    return UNKNOWN


def share_file(package: str, relative: str) -> Any:
    """``relative`` (below share/PACKAGE) normalised as the system resolves it; UNKNOWN when its '..'
    leave the share folder (where they land depends on how the workspace was installed)."""
    normal = posixpath.normpath(relative) if relative else "."
    if normal == ".." or normal.startswith("../"):
        return UNKNOWN
    return ShareFile(package, "" if normal == "." else normal)


def call_name(func: ast.expr) -> str:
    """``os.path.join`` for ``os.path.join(...)``, ``Node`` for ``Node(...)``, '' otherwise."""
    parts: list[str] = []
    while isinstance(func, ast.Attribute):
        parts.append(func.attr)
        func = func.value
    if isinstance(func, ast.Name):
        parts.append(func.id)
        return ".".join(reversed(parts))
    return ""


def calls(tree: ast.AST) -> Iterator[ast.Call]:
    """Every call in the tree, in source order."""
    found = [node for node in ast.walk(tree) if isinstance(node, ast.Call)]
    yield from sorted(found, key=lambda n: (n.lineno, n.col_offset))


def keyword(node: ast.Call, name: str) -> ast.expr | None:
    for item in node.keywords:
        if item.arg == name:
            return item.value
    return None
