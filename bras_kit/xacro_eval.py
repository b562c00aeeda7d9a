"""An allow-list evaluator for xacro's ``${...}`` and ``$(eval ...)`` expressions.

xacro hands every expression to Python's ``eval``, guarded only against names that start
with ``__``; subscripts and string joining walk around that (``python['vars']``,
``'_'+'_class_'+'_'``). This module never calls ``eval``: it parses the expression with
:mod:`ast` and interprets the tree itself, node by node. What it accepts is what robot
descriptions use: numbers, strings, arithmetic, comparisons, boolean logic, conditional
expressions, list/tuple/dict/set literals, indexing and slicing, simple comprehensions, the
``math`` functions and constants, a list of builtins and of string/list/dict methods, and
xacro's own helpers (``xacro.arg``, ``xacro.load_yaml`` of files the caller allows...).

Everything is bounded: the number of steps and the wall time of a whole expansion, the size
of every value made (bits of an integer, characters of a string, items of a list), format
widths, and the arguments of functions that grow fast (``factorial``, ``comb``, ``pow``).
A refusal is an :class:`UnsafeXacroExpression` naming the expression and what was refused.

Values are real Python values and every operator is Python's own (from :mod:`operator`), so
an accepted expression gives exactly what xacro's ``eval`` gives.
"""

from __future__ import annotations

import ast
import math
import operator
import re
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from .errors import XacroError

MAX_INT_BITS = 4096  # about 1,233 decimal digits
MAX_TEXT = 1_000_000  # characters of any string made by an expression
MAX_ITEMS = 100_000  # items of any list, tuple, dict, set or range
MAX_FORMAT_WIDTH = 1000  # width or precision in '%5.2f' or str.format-like padding
MAX_STEPS = 2_000_000  # nodes evaluated in one expansion
MAX_SECONDS = 10.0  # wall time of one expansion's expressions
MAX_FACTORIAL = 1000
MAX_NESTING = 100  # depth of the expression tree


class UnsafeXacroExpression(XacroError):
    """An expression uses something outside the allow-list, or grows past a bound."""


@dataclass
class Budget:
    """Steps and time shared by every expression of one expansion."""

    steps: int = MAX_STEPS
    deadline: float = field(default_factory=lambda: time.monotonic() + MAX_SECONDS)

    def spend(self, n: int = 1) -> None:
        self.steps -= n
        if self.steps < 0:
            raise UnsafeXacroExpression("the expressions of this file take too many steps",
                                        hint=f"xacro expressions are limited to {MAX_STEPS:,} steps per file")
        if self.steps % 4096 == 0 and time.monotonic() > self.deadline:
            raise UnsafeXacroExpression(f"the expressions of this file take more than {MAX_SECONDS:g} s",
                                        hint="simplify the expressions (no large loops or recursion)")


class Method:
    """A method of a value, picked from the allow-list, waiting to be called."""

    __slots__ = ("owner", "name")

    def __init__(self, owner: Any, name: str) -> None:
        self.owner, self.name = owner, name

    def __repr__(self) -> str:
        return f"<method {self.name} of {type(self.owner).__name__}>"


def _refuse(what: str) -> UnsafeXacroExpression:
    return UnsafeXacroExpression(f"it uses {what}",
                                 hint="xacro expressions may only compute numbers, text and lists from properties")


# ---------------------------------------------------------------------------- size checks

def check_value(value: Any) -> Any:
    """Raise when ``value`` is larger than the bounds; return it otherwise."""
    if isinstance(value, bool):
        return value
    if isinstance(value, int):
        if value.bit_length() > MAX_INT_BITS:
            raise UnsafeXacroExpression(f"an integer of {value.bit_length():,} bits is too large",
                                        hint=f"integers are limited to {MAX_INT_BITS} bits")
    elif isinstance(value, (str, bytes)):
        if len(value) > MAX_TEXT:
            raise UnsafeXacroExpression(f"a text of {len(value):,} characters is too long",
                                        hint=f"texts are limited to {MAX_TEXT:,} characters")
    elif isinstance(value, (list, tuple, dict, set, frozenset, range)):
        if len(value) > MAX_ITEMS:
            raise UnsafeXacroExpression(f"a collection of {len(value):,} items is too large",
                                        hint=f"lists are limited to {MAX_ITEMS:,} items")
    return value


def check_nested(value: Any) -> Any:
    """Raise when ``value`` holds more than MAX_ITEMS items in all (shared parts counted each time).

    A YAML file with anchors can build a list whose text is exponentially long although it
    takes little memory; turning it into text is what would fill the machine.
    """
    seen = 0
    stack = [value]
    while stack:
        item = stack.pop()
        if isinstance(item, (list, tuple, set, frozenset)):
            seen += len(item)
            stack.extend(list.__iter__(item) if isinstance(item, list) else item)
        elif isinstance(item, dict):
            seen += 2 * len(item)
            stack.extend(dict.keys(item))
            stack.extend(dict.values(item))
        if seen > MAX_ITEMS:
            raise UnsafeXacroExpression(f"a value holding more than {MAX_ITEMS:,} items in all is too large",
                                        hint="data from YAML anchors may repeat itself many times over")
    return value


def _length(value: Any) -> int:
    try:
        return len(value)
    except TypeError:
        return 0


def _check_repeat(seq: Any, count: Any) -> None:
    if isinstance(count, int) and not isinstance(count, bool) and isinstance(seq, (str, bytes, list, tuple)):
        if count > 0 and _length(seq) * count > (MAX_TEXT if isinstance(seq, (str, bytes)) else MAX_ITEMS):
            raise UnsafeXacroExpression("repeating this text or list makes it too large",
                                        hint=f"results are limited to {MAX_TEXT:,} characters or {MAX_ITEMS:,} items")


def _int_bits(value: Any) -> int:
    return abs(value).bit_length() if isinstance(value, int) else 0


def _check_power(base: Any, exponent: Any) -> None:
    if isinstance(base, int) and isinstance(exponent, int) and exponent > 0 and abs(base) > 1:
        if (abs(base).bit_length() - 1) * exponent > MAX_INT_BITS:
            raise UnsafeXacroExpression(f"{base} ** {exponent} is too large",
                                        hint=f"integers are limited to {MAX_INT_BITS} bits; use a float (e.g. 10.0**n)")


def _check_shift(left: Any, right: Any) -> None:
    if isinstance(right, int) and right > MAX_INT_BITS:
        raise UnsafeXacroExpression(f"a shift by {right} bits is too large", hint=f"integers are limited to {MAX_INT_BITS} bits")


_PERCENT_SPEC = re.compile(r"%(?:\([^)]*\))?[-#0 +]*(\*|\d+)?(?:\.(\*|\d+))?[hlL]?[a-zA-Z%]")


def _check_percent_format(template: str) -> None:
    for match in _PERCENT_SPEC.finditer(template):
        for group in match.groups():
            if group == "*":
                raise _refuse("'*' widths in % formatting")
            if group and int(group) > MAX_FORMAT_WIDTH:
                raise UnsafeXacroExpression(f"the format width {group} is too large",
                                            hint=f"widths and precisions are limited to {MAX_FORMAT_WIDTH}")


def _binop(op: Callable[[Any, Any], Any]) -> Callable[[Any, Any], Any]:
    def apply(left: Any, right: Any) -> Any:
        if op is operator.mul:
            _check_repeat(left, right)
            _check_repeat(right, left)
        elif op is operator.pow:
            _check_power(left, right)
        elif op is operator.lshift:
            _check_shift(left, right)
        elif op is operator.mod and isinstance(left, str):
            _check_percent_format(left)
            check_nested(right)
        elif op is operator.add and isinstance(left, (str, list, tuple)) and isinstance(right, type(left)):
            if _length(left) + _length(right) > (MAX_TEXT if isinstance(left, str) else MAX_ITEMS):
                raise UnsafeXacroExpression("joining these makes a value too large",
                                            hint=f"results are limited to {MAX_TEXT:,} characters or {MAX_ITEMS:,} items")
        return check_value(op(left, right))

    return apply


_BINOPS: dict[type, Callable[[Any, Any], Any]] = {
    ast.Add: _binop(operator.add), ast.Sub: _binop(operator.sub), ast.Mult: _binop(operator.mul),
    ast.Div: _binop(operator.truediv), ast.FloorDiv: _binop(operator.floordiv), ast.Mod: _binop(operator.mod),
    ast.Pow: _binop(operator.pow), ast.LShift: _binop(operator.lshift), ast.RShift: _binop(operator.rshift),
    ast.BitAnd: _binop(operator.and_), ast.BitOr: _binop(operator.or_), ast.BitXor: _binop(operator.xor),
}
_UNARY: dict[type, Callable[[Any], Any]] = {
    ast.UAdd: operator.pos, ast.USub: operator.neg, ast.Not: operator.not_, ast.Invert: operator.invert,
}
_COMPARE: dict[type, Callable[[Any, Any], Any]] = {
    ast.Eq: operator.eq, ast.NotEq: operator.ne, ast.Lt: operator.lt, ast.LtE: operator.le,
    ast.Gt: operator.gt, ast.GtE: operator.ge, ast.Is: operator.is_, ast.IsNot: operator.is_not,
    ast.In: lambda a, b: a in b, ast.NotIn: lambda a, b: a not in b,
}


# ---------------------------------------------------------------------------- allowed functions

def _bounded_range(*args: Any) -> range:
    result = range(*args)
    return check_value(result)


def _bounded_factorial(n: Any) -> Any:
    if isinstance(n, int) and n > MAX_FACTORIAL:
        raise UnsafeXacroExpression(f"factorial({n}) is too large", hint=f"factorial is limited to n <= {MAX_FACTORIAL}")
    return math.factorial(n)


def _bounded_comb(n: Any, k: Any = None) -> Any:
    if isinstance(n, int) and n > MAX_FACTORIAL:
        raise UnsafeXacroExpression(f"comb/perm of {n} is too large", hint=f"limited to n <= {MAX_FACTORIAL}")
    return math.comb(n, k) if k is not None else math.perm(n)


def _bounded_perm(n: Any, k: Any = None) -> Any:
    if isinstance(n, int) and n > MAX_FACTORIAL:
        raise UnsafeXacroExpression(f"comb/perm of {n} is too large", hint=f"limited to n <= {MAX_FACTORIAL}")
    return math.perm(n, k)


def _bounded_pow(base: Any, exponent: Any, modulo: Any = None) -> Any:
    if modulo is None:
        _check_power(base, exponent)
        return check_value(pow(base, exponent))
    return pow(base, exponent, modulo)


def _bounded_collection(kind: Callable[..., Any]) -> Callable[..., Any]:
    def make(*args: Any) -> Any:
        for arg in args:
            if isinstance(arg, range):
                check_value(arg)
        return check_value(kind(*args))

    make.__name__ = getattr(kind, "__name__", "collection")
    return make


def _safe_str(*args: Any) -> str:
    if args:
        check_nested(args[0])
    return check_value(str(*args))


def _safe_repr(value: Any) -> str:
    check_nested(value)
    return check_value(repr(value))


def _safe_int(*args: Any) -> int:
    if args and isinstance(args[0], str) and len(args[0]) > 5000:
        raise UnsafeXacroExpression("a number written with too many digits", hint="numbers are limited to 5,000 digits")
    return check_value(int(*args))


def _safe_sum(values: Any, start: Any = 0) -> Any:
    total = start
    for count, value in enumerate(values):
        if count > MAX_ITEMS:
            raise UnsafeXacroExpression("sum over too many items", hint=f"limited to {MAX_ITEMS:,} items")
        total = _BINOPS[ast.Add](total, value)
    return total


# Builtins xacro exposes (directly and in its `python` namespace) that are pure and bounded here.
BUILTINS: dict[str, Callable[..., Any]] = {
    "list": _bounded_collection(list), "dict": _bounded_collection(dict), "len": len, "str": _safe_str,
    "float": float, "int": _safe_int, "bool": bool, "min": min, "max": max, "round": round,
    "abs": abs, "all": all, "any": any, "divmod": divmod, "ord": ord, "chr": chr, "repr": _safe_repr,
    "reversed": _bounded_collection(lambda *a: list(reversed(*a))), "set": _bounded_collection(set),
    "frozenset": _bounded_collection(frozenset), "sum": _safe_sum, "tuple": _bounded_collection(tuple),
    "zip": _bounded_collection(lambda *a: list(zip(*a))), "enumerate": _bounded_collection(lambda *a: list(enumerate(*a))),
    "sorted": _bounded_collection(sorted), "range": _bounded_range, "pow": _bounded_pow,
    "map": _bounded_collection(lambda f, *a: list(map(f, *a))), "filter": _bounded_collection(lambda f, a: list(filter(f, a))),
}
# ``map`` and ``filter`` return lazy iterators in Python; they are made lists here only when
# the function given to them is itself allowed (see Evaluator._call).

_MATH_OVERRIDES: dict[str, Callable[..., Any]] = {
    "factorial": _bounded_factorial, "comb": _bounded_comb, "perm": _bounded_perm, "pow": math.pow,
    "prod": lambda values, *, start=1: check_value(math.prod(values, start=start)),
}
MATH: dict[str, Any] = {
    name: _MATH_OVERRIDES.get(name, value) for name, value in vars(math).items() if not name.startswith("_")
}

_STR_METHODS = frozenset({
    "lower", "upper", "strip", "lstrip", "rstrip", "split", "rsplit", "splitlines", "startswith", "endswith",
    "find", "rfind", "index", "rindex", "count", "isdigit", "isalpha", "isalnum", "isspace", "islower",
    "isupper", "isnumeric", "isdecimal", "capitalize", "title", "swapcase", "casefold", "partition",
    "rpartition", "join", "replace", "zfill", "ljust", "rjust", "center", "removeprefix", "removesuffix",
})
_LIST_METHODS = frozenset({"index", "count"})
_DICT_METHODS = frozenset({"keys", "values", "items", "get"})
_WIDTH_METHODS = frozenset({"zfill", "ljust", "rjust", "center"})


def _call_method(method: Method, args: list[Any], kwargs: dict[str, Any]) -> Any:
    owner, name = method.owner, method.name
    if isinstance(owner, str):
        if name in _WIDTH_METHODS and args and isinstance(args[0], int) and args[0] > MAX_TEXT:
            raise UnsafeXacroExpression(f"'{name}' to a width of {args[0]:,} is too large",
                                        hint=f"texts are limited to {MAX_TEXT:,} characters")
        if name == "replace" and len(args) >= 2 and isinstance(args[1], str):
            grows = owner.count(args[0]) * max(len(args[1]) - len(args[0]), 0) if args[0] else len(owner) * len(args[1])
            if len(owner) + grows > MAX_TEXT:
                raise UnsafeXacroExpression("this replace makes a text too long",
                                            hint=f"texts are limited to {MAX_TEXT:,} characters")
        if name == "join" and args:
            items = list(args[0]) if not isinstance(args[0], (list, tuple)) else args[0]
            check_value(items)
            if sum(_length(item) for item in items) + len(owner) * len(items) > MAX_TEXT:
                raise UnsafeXacroExpression("this join makes a text too long",
                                            hint=f"texts are limited to {MAX_TEXT:,} characters")
            args = [items, *args[1:]]
    result = getattr(owner, name)(*args, **kwargs)
    if isinstance(result, (list, tuple)) or not hasattr(result, "__iter__") or isinstance(result, (str, dict)):
        return check_value(result)
    return check_value(list(result))  # dict views: real lists are what templates iterate


def method_of(value: Any, name: str, key_lookup: Callable[[Any, str], Any] | None = None) -> Any:
    """``value.name`` when the allow-list has it."""
    if isinstance(value, str) and name in _STR_METHODS:
        return Method(value, name)
    if isinstance(value, (list, tuple)) and name in _LIST_METHODS:
        return Method(value, name)
    if isinstance(value, dict) and name in _DICT_METHODS:
        return Method(value, name)
    if isinstance(value, float) and name in ("is_integer", "real", "imag"):
        return Method(value, name) if name == "is_integer" else getattr(value, name)
    if isinstance(value, int) and name in ("real", "imag", "numerator", "denominator"):
        return getattr(value, name)
    if key_lookup is not None:
        return key_lookup(value, name)
    raise _refuse(f"the attribute '.{name}' of a {type(value).__name__}")


# ---------------------------------------------------------------------------- the evaluator

Namespace = Mapping[str, Any]


class Evaluator:
    """Interpret one expression's syntax tree with names from ``lookup``.

    ``lookup(name)`` returns a value or raises ``KeyError``; ``attribute(value, name)`` is
    asked for ``value.name`` when ``value`` is not a str/list/dict/number (namespaces, YAML
    dictionaries); ``callables`` maps the identity of every function a value may hold to
    the safe function to call instead.
    """

    def __init__(self, lookup: Callable[[str], Any], attribute: Callable[[Any, str], Any] | None,
                 callables: Mapping[int, Callable[..., Any]], budget: Budget) -> None:
        self.lookup, self.attribute, self.callables, self.budget = lookup, attribute, callables, budget
        self.scopes: list[dict[str, Any]] = []

    def run(self, expression: str) -> Any:
        try:
            tree = ast.parse(expression.strip(), mode="eval")
        except SyntaxError:
            raise  # xacro reports a SyntaxError itself, with its own words
        except (ValueError, MemoryError, RecursionError):
            raise UnsafeXacroExpression("cannot read the expression", hint="check brackets and quotes") from None
        return check_nested(self.eval(tree.body, 0))  # xacro turns the result into text

    def eval(self, node: ast.AST, depth: int) -> Any:
        self.budget.spend()
        if depth > MAX_NESTING:
            raise UnsafeXacroExpression("the expression is nested too deeply", hint=f"limited to {MAX_NESTING} levels")
        handler = getattr(self, "_" + type(node).__name__, None)
        if handler is None:
            raise _refuse(f"a {type(node).__name__} expression")
        return handler(node, depth + 1)

    # literals and names
    def _Constant(self, node: ast.Constant, depth: int) -> Any:
        if not isinstance(node.value, (int, float, str, bool, type(None))):
            raise _refuse(f"a {type(node.value).__name__} literal")
        return check_value(node.value)

    def _Name(self, node: ast.Name, depth: int) -> Any:
        if node.id.startswith("__"):
            raise _refuse(f"the name '{node.id}'")
        for scope in reversed(self.scopes):
            if node.id in scope:
                return scope[node.id]
        try:
            return self.lookup(node.id)
        except KeyError:
            raise NameError(f"name '{node.id}' is not defined") from None

    def _List(self, node: ast.List, depth: int) -> Any:
        return check_value(self._elements(node.elts, depth))

    def _Tuple(self, node: ast.Tuple, depth: int) -> Any:
        return check_value(tuple(self._elements(node.elts, depth)))

    def _Set(self, node: ast.Set, depth: int) -> Any:
        return check_value(set(self._elements(node.elts, depth)))

    def _elements(self, nodes: list[ast.expr], depth: int) -> list[Any]:
        out: list[Any] = []
        for element in nodes:
            if isinstance(element, ast.Starred):
                out.extend(check_value(list(self.eval(element.value, depth))))
            else:
                out.append(self.eval(element, depth))
        return out

    def _Dict(self, node: ast.Dict, depth: int) -> Any:
        out: dict[Any, Any] = {}
        for key, value in zip(node.keys, node.values):
            if key is None:
                out.update(self.eval(value, depth))
            else:
                out[self.eval(key, depth)] = self.eval(value, depth)
        return check_value(out)

    # operators
    def _BinOp(self, node: ast.BinOp, depth: int) -> Any:
        op = _BINOPS.get(type(node.op))
        if op is None:
            raise _refuse(f"the operator {type(node.op).__name__}")
        return op(self.eval(node.left, depth), self.eval(node.right, depth))

    def _UnaryOp(self, node: ast.UnaryOp, depth: int) -> Any:
        return _UNARY[type(node.op)](self.eval(node.operand, depth))

    def _BoolOp(self, node: ast.BoolOp, depth: int) -> Any:
        value: Any = None
        for operand in node.values:
            value = self.eval(operand, depth)
            if isinstance(node.op, ast.And) and not value:
                return value
            if isinstance(node.op, ast.Or) and value:
                return value
        return value

    def _Compare(self, node: ast.Compare, depth: int) -> Any:
        left = self.eval(node.left, depth)
        for op, right_node in zip(node.ops, node.comparators):
            right = self.eval(right_node, depth)
            if not _COMPARE[type(op)](left, right):
                return False
            left = right
        return True

    def _IfExp(self, node: ast.IfExp, depth: int) -> Any:
        return self.eval(node.body if self.eval(node.test, depth) else node.orelse, depth)

    # access
    def _Subscript(self, node: ast.Subscript, depth: int) -> Any:
        value = self.eval(node.value, depth)
        index = self.eval(node.slice, depth)
        if not isinstance(value, (str, list, tuple, dict, range)):
            if self.attribute is not None and isinstance(index, str):
                return self.attribute(value, index)
            raise _refuse(f"indexing a {type(value).__name__}")
        if isinstance(index, (slice, int, bool)) or isinstance(value, dict):
            return check_value(value[index])
        raise TypeError(f"{type(value).__name__} indices must be integers or slices, not {type(index).__name__}")

    def _Slice(self, node: ast.Slice, depth: int) -> Any:
        parts = [None if part is None else self.eval(part, depth) for part in (node.lower, node.upper, node.step)]
        return slice(*parts)

    def _Attribute(self, node: ast.Attribute, depth: int) -> Any:
        if node.attr.startswith("_"):
            raise _refuse(f"the attribute '.{node.attr}'")
        value = self.eval(node.value, depth)
        return method_of(value, node.attr, self.attribute)

    def _Call(self, node: ast.Call, depth: int) -> Any:
        function = self.eval(node.func, depth)
        args = self._elements(node.args, depth)
        kwargs: dict[str, Any] = {}
        for keyword in node.keywords:
            if keyword.arg is None:
                kwargs.update(self.eval(keyword.value, depth))
            else:
                kwargs[keyword.arg] = self.eval(keyword.value, depth)
        if isinstance(function, Method):
            return _call_method(function, args, kwargs)
        safe = self.callables.get(id(function))
        if safe is None:
            name = getattr(function, "__name__", type(function).__name__)
            raise _refuse(f"the function '{name}', which is not allowed")
        for arg in args:  # map(f, ...) and filter(f, ...) may only be given allowed functions
            if callable(arg) and not isinstance(arg, Method) and id(arg) not in self.callables:
                raise _refuse("a function that is not allowed, as an argument")
        args = [self.callables.get(id(a), a) if callable(a) else a for a in args]
        return check_value(safe(*args, **kwargs))

    # comprehensions
    def _ListComp(self, node: ast.ListComp, depth: int) -> Any:
        return check_value(list(self._generate(node, depth)))

    def _GeneratorExp(self, node: ast.GeneratorExp, depth: int) -> Any:
        return check_value(list(self._generate(node, depth)))

    def _SetComp(self, node: ast.SetComp, depth: int) -> Any:
        return check_value(set(self._generate(node, depth)))

    def _DictComp(self, node: ast.DictComp, depth: int) -> Any:
        pairs = self._generate(node, depth, pair=True)
        return check_value(dict(pairs))

    def _generate(self, node: Any, depth: int, pair: bool = False) -> list[Any]:
        results: list[Any] = []
        scope: dict[str, Any] = {}
        self.scopes.append(scope)
        try:
            self._loop(node, node.generators, 0, scope, results, depth, pair)
        finally:
            self.scopes.pop()
        return results

    def _loop(self, node: Any, generators: list[ast.comprehension], index: int, scope: dict[str, Any],
              results: list[Any], depth: int, pair: bool) -> None:
        if index == len(generators):
            results.append((self.eval(node.key, depth), self.eval(node.value, depth)) if pair
                           else self.eval(node.elt, depth))
            if len(results) > MAX_ITEMS:
                raise UnsafeXacroExpression("a comprehension makes too many items", hint=f"limited to {MAX_ITEMS:,}")
            return
        generator = generators[index]
        if generator.is_async:
            raise _refuse("async comprehensions")
        iterable = self.eval(generator.iter, depth)
        if not isinstance(iterable, (str, list, tuple, dict, set, frozenset, range)):
            raise _refuse(f"iterating over a {type(iterable).__name__}")
        for count, item in enumerate(iterable):
            if count > MAX_ITEMS:
                raise UnsafeXacroExpression("a comprehension loops too many times", hint=f"limited to {MAX_ITEMS:,}")
            self.budget.spend()
            self._bind(generator.target, item, scope)
            if all(self.eval(test, depth) for test in generator.ifs):
                self._loop(node, generators, index + 1, scope, results, depth, pair)

    def _bind(self, target: ast.AST, value: Any, scope: dict[str, Any]) -> None:
        if isinstance(target, ast.Name):
            scope[target.id] = value
        elif isinstance(target, (ast.Tuple, ast.List)):
            items = list(value)
            if len(items) != len(target.elts):
                raise ValueError(f"cannot unpack {len(items)} values into {len(target.elts)} names")
            for sub, item in zip(target.elts, items):
                self._bind(sub, item, scope)
        else:
            raise _refuse("this loop target")


# ---------------------------------------------------------------------------- vetting alone

_ALLOWED_CALL_NAMES = frozenset(BUILTINS) | frozenset(k for k, v in MATH.items() if callable(v)) | _STR_METHODS \
    | _LIST_METHODS | _DICT_METHODS | {"is_integer", "arg", "tokenize", "dotify", "abs_filename", "load_yaml",
                                       "message", "warning", "error", "print_location", "fatal", "find", "env",
                                       "optenv", "dirname"}


def vet(expression: str) -> None:
    """Check an expression without its properties: refuse what the evaluator would always refuse.

    Raises ``SyntaxError`` for text that is not an expression and
    :class:`UnsafeXacroExpression` otherwise. An expression made of literals only is evaluated
    (under the same bounds), so ``10**10**10`` is caught here too.
    """
    tree = ast.parse(expression.strip(), mode="eval")
    names = False
    for node in ast.walk(tree):
        if isinstance(node, ast.expr) and not hasattr(Evaluator, "_" + type(node).__name__):
            raise _refuse(f"a {type(node).__name__} expression")
        if isinstance(node, ast.Attribute) and node.attr.startswith("_"):
            raise _refuse(f"the attribute '.{node.attr}'")
        if isinstance(node, ast.Name):
            names = True
            if node.id.startswith("_"):
                raise _refuse(f"the name '{node.id}'")
        if isinstance(node, ast.Call):
            called = node.func.attr if isinstance(node.func, ast.Attribute) else getattr(node.func, "id", None)
            if called is not None and called not in _ALLOWED_CALL_NAMES:
                raise _refuse(f"the function '{called}', which is not allowed")
    if not names:
        Evaluator(lambda name: (_ for _ in ()).throw(KeyError(name)), None, {}, Budget()).run(expression)
