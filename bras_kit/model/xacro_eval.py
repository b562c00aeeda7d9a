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
import string
import sys
import time
from collections.abc import Callable, ItemsView, Iterator, KeysView, Mapping, Sequence, ValuesView
from dataclasses import dataclass, field
from typing import Any

from ..core.errors import XacroError
from ..core.message import M, Message

MAX_INT_BITS = 4096  # about 1,233 decimal digits
MAX_TEXT = 1_000_000  # characters of any string made by an expression
MAX_ITEMS = 100_000  # items of any list, tuple, dict, set or range
MAX_FORMAT_WIDTH = 1000  # width or precision in '%5.2f' or str.format-like padding
MAX_STEPS = 2_000_000  # nodes evaluated in one expansion
MAX_SECONDS = 10.0  # wall time of one expansion's expressions
MAX_FACTORIAL = 1000
MAX_NESTING = 100  # depth of the expression tree
MAX_CALLS = 50  # lambdas calling lambdas


class UnsafeXacroExpression(XacroError):
    """An expression uses something outside the allow-list, or grows past a bound."""


_TEXT_LIMIT = M("texts are limited to {count} characters", count=MAX_TEXT)
_ITEMS_LIMIT = M("lists are limited to {count} items", count=MAX_ITEMS)
_SIZE_LIMIT = M("results are limited to {chars} characters or {items} items", chars=MAX_TEXT, items=MAX_ITEMS)


@dataclass
class Budget:
    """Steps and time shared by every expression of one expansion."""

    steps: int = MAX_STEPS
    deadline: float = field(default_factory=lambda: time.monotonic() + MAX_SECONDS)

    def spend(self, n: int = 1) -> None:
        self.steps -= n
        if self.steps < 0:
            raise UnsafeXacroExpression(M("the expressions of this file take too many steps"),
                                        hint=M("xacro expressions are limited to {count} steps per file",
                                               count=MAX_STEPS))
        if self.steps % 4096 == 0 and time.monotonic() > self.deadline:
            raise UnsafeXacroExpression(M("the expressions of this file take more than {seconds} s",
                                          seconds=MAX_SECONDS),
                                        hint=M("simplify the expressions (no large loops or recursion)"))


class Method:
    """A method of a value, picked from the allow-list, waiting to be called."""

    __slots__ = ("owner", "name")

    def __init__(self, owner: Any, name: str) -> None:
        self.owner, self.name = owner, name

    def __repr__(self) -> str:
        return f"<built-in method {self.name} of {type(self.owner).__name__} object>"

    def __call__(self, *args: Any, **kwargs: Any) -> Any:  # map('{:.2f}'.format, values)
        return _call_method(self, list(args), kwargs)


# Python 3.12 inlined list, set and dict comprehensions into the code around them (PEP 709):
# from then on their names are looked up as the expression's own, eval's locals included, where
# up to 3.11 a comprehension was a function of its own that saw only the globals. Generator
# expressions and lambdas stay functions. The real xacro runs eval() on the user's Python, so
# bras-kit follows the Python it runs on.
INLINED_COMPREHENSIONS = sys.version_info >= (3, 12)


class FunctionScope(dict):
    """The names bound in a scope that is a function in Python (a lambda's parameters, a
    generator expression's variables, any comprehension's before 3.12): names looked up from
    inside it do not see ``$(eval)``'s locals."""


class Lambda:
    """A ``lambda`` written in an expression: its body is interpreted by the same evaluator.

    It sees the scopes around it when it was made (comprehension variables, like a Python
    closure) and its own parameters; calls nest at most :data:`MAX_CALLS` deep.
    """

    __slots__ = ("evaluator", "node", "scopes", "depth")

    def __init__(self, evaluator: Evaluator, node: ast.Lambda, scopes: list[dict[str, Any]], depth: int) -> None:
        self.evaluator, self.node, self.scopes, self.depth = evaluator, node, scopes, depth

    def __repr__(self) -> str:
        return "<function <lambda>>"

    def __call__(self, *args: Any, **kwargs: Any) -> Any:
        names = [parameter.arg for parameter in self.node.args.args]
        if kwargs or len(args) != len(names):
            raise TypeError(f"<lambda>() takes {len(names)} positional arguments but {len(args) + len(kwargs)} "
                            "were given")
        evaluator = self.evaluator
        if evaluator.calls >= MAX_CALLS:
            raise UnsafeXacroExpression(M("lambdas call each other more than {count} deep", count=MAX_CALLS),
                                        hint=M("a property probably calls itself without end"))
        saved = evaluator.scopes
        evaluator.scopes = [*self.scopes, FunctionScope(zip(names, args))]
        evaluator.calls += 1
        try:
            return evaluator.eval(self.node.body, self.depth)
        finally:
            evaluator.scopes = saved
            evaluator.calls -= 1


def _refuse(what: Message) -> UnsafeXacroExpression:
    return UnsafeXacroExpression(M("it uses {what}", what=what),
                                 hint=M("xacro expressions may only compute numbers, text and lists from properties"))


# ---------------------------------------------------------------------------- size checks

def check_value(value: Any) -> Any:
    """Raise when ``value`` is larger than the bounds; return it otherwise."""
    if isinstance(value, bool):
        return value
    if isinstance(value, int):
        if value.bit_length() > MAX_INT_BITS:
            raise UnsafeXacroExpression(M("an integer of {bits} bits is too large", bits=value.bit_length()),
                                        hint=M("integers are limited to {bits} bits", bits=MAX_INT_BITS))
    elif isinstance(value, (str, bytes)):
        if len(value) > MAX_TEXT:
            raise UnsafeXacroExpression(M("a text of {count} characters is too long", count=len(value)),
                                        hint=_TEXT_LIMIT)
    elif isinstance(value, (list, tuple, dict, set, frozenset, range)):
        if len(value) > MAX_ITEMS:
            raise UnsafeXacroExpression(M("a collection of {count} items is too large", count=len(value)),
                                        hint=_ITEMS_LIMIT)
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
            raise UnsafeXacroExpression(M("a value holding more than {count} items in all is too large",
                                          count=MAX_ITEMS),
                                        hint=M("data from YAML anchors may repeat itself many times over"))
    return value


def _length(value: Any) -> int:
    try:
        return len(value)
    except TypeError:
        return 0


def _check_repeat(seq: Any, count: Any) -> None:
    if isinstance(count, int) and not isinstance(count, bool) and isinstance(seq, (str, bytes, list, tuple)):
        if count > 0 and _length(seq) * count > (MAX_TEXT if isinstance(seq, (str, bytes)) else MAX_ITEMS):
            raise UnsafeXacroExpression(M("repeating this text or list makes it too large"), hint=_SIZE_LIMIT)


def _check_power(base: Any, exponent: Any) -> None:
    if isinstance(base, int) and isinstance(exponent, int) and exponent > 0 and abs(base) > 1:
        if (abs(base).bit_length() - 1) * exponent > MAX_INT_BITS:
            raise UnsafeXacroExpression(M("{base} ** {exponent} is too large", base=base, exponent=exponent),
                                        hint=M("integers are limited to {bits} bits; use a float (e.g. 10.0**n)",
                                               bits=MAX_INT_BITS))


def _check_shift(left: Any, right: Any) -> None:
    if isinstance(right, int) and right > MAX_INT_BITS:
        raise UnsafeXacroExpression(M("a shift by {bits} bits is too large", bits=right),
                                    hint=M("integers are limited to {bits} bits", bits=MAX_INT_BITS))


_PERCENT_SPEC = re.compile(r"%(?:\([^)]*\))?[-#0 +]*(\*|\d+)?(?:\.(\*|\d+))?[hlL]?[a-zA-Z%]")


def _check_percent_format(template: str) -> None:
    for match in _PERCENT_SPEC.finditer(template):
        for group in match.groups():
            if group == "*":
                raise _refuse(M("'*' widths in % formatting"))
            if group and int(group) > MAX_FORMAT_WIDTH:
                raise _width_refused(group)


def _width_refused(width: Any) -> UnsafeXacroExpression:
    return UnsafeXacroExpression(M("the format width {width} is too large", width=width),
                                 hint=M("widths and precisions are limited to {limit}", limit=MAX_FORMAT_WIDTH))


def _comb_refused(n: Any) -> UnsafeXacroExpression:
    return UnsafeXacroExpression(M("comb/perm of {n} is too large", n=n),
                                 hint=M("limited to n <= {limit}", limit=MAX_FACTORIAL))


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
                raise UnsafeXacroExpression(M("joining these makes a value too large"), hint=_SIZE_LIMIT)
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
        raise UnsafeXacroExpression(M("factorial({n}) is too large", n=n),
                                    hint=M("factorial is limited to n <= {limit}", limit=MAX_FACTORIAL))
    return math.factorial(n)


def _bounded_comb(n: Any, k: Any = None) -> Any:
    if isinstance(n, int) and n > MAX_FACTORIAL:
        raise _comb_refused(n)
    return math.comb(n, k) if k is not None else math.perm(n)


def _bounded_perm(n: Any, k: Any = None) -> Any:
    if isinstance(n, int) and n > MAX_FACTORIAL:
        raise _comb_refused(n)
    return math.perm(n, k)


def _bounded_pow(base: Any, exponent: Any, modulo: Any = None) -> Any:
    if modulo is None:
        _check_power(base, exponent)
        return check_value(pow(base, exponent))
    return pow(base, exponent, modulo)


def _bounded_collection(kind: Callable[..., Any]) -> Callable[..., Any]:
    def make(*args: Any, **kwargs: Any) -> Any:
        for arg in (*args, *kwargs.values()):
            if isinstance(arg, range):
                check_value(arg)
        return check_value(kind(*args, **kwargs))

    make.__name__ = getattr(kind, "__name__", "collection")
    return make


def _safe_str(*args: Any, **kwargs: Any) -> str:
    if args:
        check_nested(args[0])
    return check_value(str(*args, **kwargs))


def _safe_repr(value: Any) -> str:
    check_nested(value)
    return check_value(repr(value))


def _check_digits(args: tuple[Any, ...]) -> None:
    if args and isinstance(args[0], str) and len(args[0]) > 5000:
        raise UnsafeXacroExpression(M("a number written with too many digits"),
                                    hint=M("numbers are limited to {count} digits", count=5000))


def _safe_int(*args: Any, **kwargs: Any) -> int:
    _check_digits(args)
    return check_value(int(*args, **kwargs))


def _safe_complex(*args: Any, **kwargs: Any) -> complex:
    _check_digits(args)
    return complex(*args, **kwargs)


def _safe_hash(value: Any) -> int:
    check_nested(value)
    return hash(value)


def _safe_type(*args: Any, **kwargs: Any) -> Any:
    if len(args) != 1 or kwargs:
        raise _refuse(M("type() with more than one argument (it makes a new class)"))
    return type(args[0])


def _safe_sum(values: Any, /, start: Any = 0) -> Any:
    total = start
    for count, value in enumerate(values):
        if count > MAX_ITEMS:
            raise UnsafeXacroExpression(M("sum over too many items"), hint=_ITEMS_LIMIT)
        total = _BINOPS[ast.Add](total, value)
    return total


# Builtins xacro exposes (directly and in its `python` namespace) that are pure and bounded here.
BUILTINS: dict[str, Callable[..., Any]] = {
    "list": _bounded_collection(list), "dict": _bounded_collection(dict), "len": len, "str": _safe_str,
    "float": float, "int": _safe_int, "bool": bool, "min": min, "max": max, "round": round,
    "abs": abs, "all": all, "any": any, "divmod": divmod, "ord": ord, "chr": chr, "repr": _safe_repr,
    "reversed": reversed, "set": _bounded_collection(set),
    "frozenset": _bounded_collection(frozenset), "sum": _safe_sum, "tuple": _bounded_collection(tuple),
    "zip": zip, "enumerate": enumerate, "sorted": _bounded_collection(sorted), "range": _bounded_range,
    "pow": _bounded_pow, "map": map, "filter": filter, "complex": _safe_complex, "hash": _safe_hash,
    "isinstance": isinstance, "issubclass": issubclass, "slice": slice, "type": _safe_type,
}
# ``map``, ``filter``, ``zip``, ``enumerate`` and ``reversed`` are Python's own lazy iterators,
# as in xacro (a ``map`` read twice is empty the second time): what they iterate is already
# bounded, and the functions given to them are swapped for their safe versions first
# (:data:`CALLS_ITS_ARGUMENTS`).
CALLS_ITS_ARGUMENTS = frozenset(id(BUILTINS[name]) for name in ("map", "filter", "sorted", "min", "max"))
_ITERABLE_TYPES = (str, list, tuple, dict, set, frozenset, range, Iterator, KeysView, ValuesView, ItemsView)

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
    "format",
})
_LIST_METHODS = frozenset({"index", "count"})
_DICT_METHODS = frozenset({"keys", "values", "items", "get"})
_WIDTH_METHODS = frozenset({"zfill", "ljust", "rjust", "center"})
_FORMAT_WIDTHS = re.compile(r"\d+")
_formatter = string.Formatter()


def check_format(template: str, args: Sequence[Any], kwargs: Mapping[str, Any]) -> None:
    """Refuse a ``str.format`` template that reaches a dunder (``{0.__class__}``) or pads past the bounds.

    xacro lets ``'{0.__class__}'.format(x)`` through (its guard only reads the expression's names):
    that is the door to Python's internals, so it is closed here, as is a nested width
    (``{:{w}}``) and any width or precision past :data:`MAX_FORMAT_WIDTH`.
    """
    for value in (*args, *kwargs.values()):
        check_nested(value)
    try:
        fields = list(_formatter.parse(template))
    except ValueError:
        return  # str.format raises the same error, with Python's words, as in xacro
    for _, name, spec, _ in fields:
        if name is None:
            continue
        if "_" in name and re.search(r"(^|[.\[])_", name):
            raise _refuse(M("the field '{{{name}}}' in a format string", name=name))
        if spec and "{" in spec:
            raise _refuse(M("a nested field in the format '{spec}'", spec=spec))
        for width in _FORMAT_WIDTHS.findall(spec or ""):
            if int(width) > MAX_FORMAT_WIDTH:
                raise _width_refused(width)


def _call_method(method: Method, args: list[Any], kwargs: dict[str, Any]) -> Any:
    owner, name = method.owner, method.name
    if isinstance(owner, str):
        if name in _WIDTH_METHODS and args and isinstance(args[0], int) and args[0] > MAX_TEXT:
            raise UnsafeXacroExpression(M("'{name}' to a width of {width} is too large", name=name, width=args[0]),
                                        hint=_TEXT_LIMIT)
        if name == "replace" and len(args) >= 2 and isinstance(args[1], str):
            grows = owner.count(args[0]) * max(len(args[1]) - len(args[0]), 0) if args[0] else len(owner) * len(args[1])
            if len(owner) + grows > MAX_TEXT:
                raise UnsafeXacroExpression(M("this replace makes a text too long"), hint=_TEXT_LIMIT)
        if name == "join" and args:
            items = list(args[0]) if not isinstance(args[0], (list, tuple)) else args[0]
            check_value(items)
            if sum(_length(item) for item in items) + len(owner) * len(items) > MAX_TEXT:
                raise UnsafeXacroExpression(M("this join makes a text too long"), hint=_TEXT_LIMIT)
            args = [items, *args[1:]]
        if name == "format":
            check_format(owner, args, kwargs)
    return check_value(getattr(owner, name)(*args, **kwargs))  # dict views stay views, as in xacro


def method_of(value: Any, name: str, key_lookup: Callable[[Any, str], Any] | None = None) -> Any:
    """``value.name`` when the allow-list has it."""
    if name.startswith("__"):
        raise _refuse(M("the attribute '.{name}'", name=name))
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
    if isinstance(value, complex) and name in ("real", "imag"):
        return getattr(value, name)
    if key_lookup is not None:
        return key_lookup(value, name)
    raise _refuse(M("the attribute '.{name}' of a {kind}", name=name, kind=type(value).__name__))


# ---------------------------------------------------------------------------- the evaluator

Namespace = Mapping[str, Any]


class Evaluator:
    """Interpret one expression's syntax tree with names from ``lookup``.

    ``lookup(name)`` returns a value or raises ``KeyError``; ``attribute(value, name)`` is
    asked for ``value.name`` when ``value`` is not a str/list/dict/number (namespaces, YAML
    dictionaries); ``callables`` maps the identity of every function a value may hold to
    the safe function to call instead. ``inner_lookup``, when given, is what names inside a
    function scope see instead of ``lookup`` (``$(eval ...)`` runs with its arguments as
    Python *locals*, which a lambda, a generator expression and, before Python 3.12, any
    comprehension do not see: :data:`INLINED_COMPREHENSIONS`).
    """

    def __init__(self, lookup: Callable[[str], Any], attribute: Callable[[Any, str], Any] | None,
                 callables: Mapping[int, Callable[..., Any]], budget: Budget,
                 inner_lookup: Callable[[str], Any] | None = None) -> None:
        self.lookup, self.attribute, self.callables, self.budget = lookup, attribute, callables, budget
        self.inner_lookup = inner_lookup
        self.scopes: list[dict[str, Any]] = []
        self.calls = 0

    def run(self, expression: str) -> Any:
        try:
            tree = ast.parse(expression.strip(), mode="eval")
        except SyntaxError:
            raise  # xacro reports a SyntaxError itself, with its own words
        except (ValueError, MemoryError, RecursionError):
            raise UnsafeXacroExpression(M("cannot read the expression"), hint=M("check brackets and quotes")) from None
        return check_nested(self.eval(tree.body, 0))  # xacro turns the result into text

    def eval(self, node: ast.AST, depth: int) -> Any:
        self.budget.spend()
        if depth > MAX_NESTING:
            raise UnsafeXacroExpression(M("the expression is nested too deeply"),
                                        hint=M("limited to {count} levels", count=MAX_NESTING))
        handler = getattr(self, "_" + type(node).__name__, None)
        if handler is None:
            raise _refuse(M("a {kind} expression", kind=type(node).__name__))
        return handler(node, depth + 1)

    # literals and names
    def _Constant(self, node: ast.Constant, depth: int) -> Any:
        if not isinstance(node.value, (int, float, complex, str, bool, type(None))):
            raise _refuse(M("a {kind} literal", kind=type(node.value).__name__))
        return check_value(node.value)

    def _Name(self, node: ast.Name, depth: int) -> Any:
        if node.id.startswith("__"):
            raise _refuse(M("the name '{name}'", name=node.id))
        for scope in reversed(self.scopes):
            if node.id in scope:
                return scope[node.id]
        in_function = any(isinstance(scope, FunctionScope) for scope in self.scopes)
        lookup = self.inner_lookup if in_function and self.inner_lookup is not None else self.lookup
        try:
            return lookup(node.id)
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
        return check_value(out)

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
            raise _refuse(M("the operator {kind}", kind=type(node.op).__name__))
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
            raise _refuse(M("indexing a {kind}", kind=type(value).__name__))
        if isinstance(index, (slice, int, bool)) or isinstance(value, dict):
            return check_value(value[index])
        raise TypeError(f"{type(value).__name__} indices must be integers or slices, not {type(index).__name__}")

    def _Slice(self, node: ast.Slice, depth: int) -> Any:
        parts = [None if part is None else self.eval(part, depth) for part in (node.lower, node.upper, node.step)]
        return slice(*parts)

    def _Attribute(self, node: ast.Attribute, depth: int) -> Any:
        if node.attr.startswith("__"):  # xacro refuses these names too; one underscore is a YAML key
            raise _refuse(M("the attribute '.{name}'", name=node.attr))
        value = self.eval(node.value, depth)
        return method_of(value, node.attr, self.attribute)

    def _Call(self, node: ast.Call, depth: int) -> Any:
        function = self.eval(node.func, depth)
        args = self._elements(node.args, depth)
        kwargs: dict[str, Any] = {}
        for keyword in node.keywords:
            if keyword.arg is None:
                extra = self.eval(keyword.value, depth)
                if not isinstance(extra, Mapping):
                    raise TypeError(f"argument after ** must be a mapping, not {type(extra).__name__}")
                kwargs.update(extra)
            else:
                kwargs[keyword.arg] = self.eval(keyword.value, depth)
        if isinstance(function, (Method, Lambda)):
            return check_value(function(*args, **kwargs))
        safe = self.callables.get(id(function))
        if safe is None:
            raise _refuse(M("the function '{name}', which is not allowed", name=_name_of(function)))
        if id(safe) in CALLS_ITS_ARGUMENTS:  # map(f, ...), sorted(key=f): f is called by Python itself
            args = [self._function_argument(a) for a in args]
            kwargs = {k: self._function_argument(v) for k, v in kwargs.items()}
        return check_value(safe(*args, **kwargs))

    def _function_argument(self, value: Any) -> Any:
        if not callable(value) or isinstance(value, (Method, Lambda)):
            return value
        safe = self.callables.get(id(value))
        if safe is None:
            raise _refuse(M("the function '{name}', which is not allowed, as an argument", name=_name_of(value)))
        return safe

    def _Lambda(self, node: ast.Lambda, depth: int) -> Any:
        arguments = node.args
        if arguments.vararg or arguments.kwarg or arguments.kwonlyargs or arguments.defaults \
                or arguments.posonlyargs:
            raise _refuse(M("a lambda with default, keyword-only, * or ** parameters"))
        return Lambda(self, node, list(self.scopes), depth)

    # f-strings
    def _JoinedStr(self, node: ast.JoinedStr, depth: int) -> Any:
        parts: list[str] = []
        for value in node.values:
            parts.append(self.eval(value, depth))
            if sum(map(len, parts)) > MAX_TEXT:
                raise UnsafeXacroExpression(M("a text of {count} characters is too long", count=sum(map(len, parts))),
                                            hint=_TEXT_LIMIT)
        return "".join(parts)

    def _FormattedValue(self, node: ast.FormattedValue, depth: int) -> Any:
        value = check_nested(self.eval(node.value, depth))
        if node.conversion == ord("s"):
            value = _safe_str(value)
        elif node.conversion in (ord("r"), ord("a")):
            value = (repr if node.conversion == ord("r") else ascii)(value)
        spec = self.eval(node.format_spec, depth) if node.format_spec is not None else ""
        for width in _FORMAT_WIDTHS.findall(spec):
            if int(width) > MAX_FORMAT_WIDTH:
                raise _width_refused(width)
        return check_value(format(value, spec))

    # comprehensions
    def _ListComp(self, node: ast.ListComp, depth: int) -> Any:
        return check_value(self._generate(node, depth))

    def _GeneratorExp(self, node: ast.GeneratorExp, depth: int) -> Any:
        return iter(check_value(self._generate(node, depth)))  # read once, like Python's generator

    def _SetComp(self, node: ast.SetComp, depth: int) -> Any:
        return check_value(set(self._generate(node, depth)))

    def _DictComp(self, node: ast.DictComp, depth: int) -> Any:
        pairs = self._generate(node, depth, pair=True)
        return check_value(dict(pairs))

    def _generate(self, node: Any, depth: int, pair: bool = False) -> list[Any]:
        results: list[Any] = []
        first = self._iterable(node.generators[0], depth)  # Python evaluates it in the enclosing scope
        inlined = INLINED_COMPREHENSIONS and not isinstance(node, ast.GeneratorExp)
        scope: dict[str, Any] = {} if inlined else FunctionScope()
        self.scopes.append(scope)
        try:
            self._loop(node, node.generators, 0, scope, results, depth, pair, first)
        finally:
            self.scopes.pop()
        return results

    def _iterable(self, generator: ast.comprehension, depth: int) -> Any:
        if generator.is_async:
            raise _refuse(M("async comprehensions"))
        iterable = self.eval(generator.iter, depth)
        if not isinstance(iterable, _ITERABLE_TYPES):
            raise _refuse(M("iterating over a {kind}", kind=type(iterable).__name__))
        return iterable

    def _loop(self, node: Any, generators: list[ast.comprehension], index: int, scope: dict[str, Any],
              results: list[Any], depth: int, pair: bool, iterable: Any = None) -> None:
        if index == len(generators):
            results.append((self.eval(node.key, depth), self.eval(node.value, depth)) if pair
                           else self.eval(node.elt, depth))
            if len(results) > MAX_ITEMS:
                raise UnsafeXacroExpression(M("a comprehension makes too many items"), hint=_ITEMS_LIMIT)
            return
        generator = generators[index]
        if iterable is None:
            iterable = self._iterable(generator, depth)
        for count, item in enumerate(iterable):
            if count > MAX_ITEMS:
                raise UnsafeXacroExpression(M("a comprehension loops too many times"), hint=_ITEMS_LIMIT)
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
            raise _refuse(M("this loop target"))


def _name_of(function: Any) -> str:
    name = getattr(function, "__name__", None)
    return name if isinstance(name, str) else type(function).__name__


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
            raise _refuse(M("a {kind} expression", kind=type(node).__name__))
        if isinstance(node, ast.Attribute) and node.attr.startswith("__"):
            raise _refuse(M("the attribute '.{name}'", name=node.attr))
        if isinstance(node, ast.Name):
            names = True
            if node.id.startswith("__"):
                raise _refuse(M("the name '{name}'", name=node.id))
        if isinstance(node, ast.Call):
            called = node.func.attr if isinstance(node.func, ast.Attribute) else getattr(node.func, "id", None)
            if called is not None and called not in _ALLOWED_CALL_NAMES:
                raise _refuse(M("the function '{name}', which is not allowed", name=called))
    if not names:
        Evaluator(lambda name: (_ for _ in ()).throw(KeyError(name)), None, {}, Budget()).run(expression)
