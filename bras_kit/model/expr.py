"""A small, safe evaluator for joint formulas such as ``0.8*sin(t)``.

A formula is parsed with :mod:`ast` and checked against a whitelist: numbers, the time ``t``,
the constants ``pi``, ``e`` and ``tau``, the operators ``+ - * / ** %``, parentheses, and a fixed
set of numpy functions. Anything else (names, attributes, subscripts, calls of other functions,
lambdas, comprehensions, strings, comparisons) is refused before anything runs. The accepted
tree is turned into nested numpy closures, never into Python code: nothing is ``eval``-ed.

Each compiled node returns the value and its exact time derivative together (forward-mode
differentiation), so a motion's velocities agree with its positions without finite differences.
"""

from __future__ import annotations

import ast
import builtins
import difflib
import math
import re
from collections.abc import Callable
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

if TYPE_CHECKING:
    import numpy as np
else:
    from ..core.lazy_numpy import np

from ..core.errors import ParameterError, TimeInJointValueError, UnsafeExpressionError
from ..core.message import M, Mc, Message, Mn

MAX_LENGTH = 1000  # characters of a formula
MAX_DEPTH = 100  # nesting of operations (a sum of n terms nests n deep)
MAX_EXPONENT = 100.0  # largest constant exponent of **

CONSTANTS = {"pi": math.pi, "e": math.e, "tau": math.tau}
VARIABLE = "t"

# Value and derivative arrays (or plain floats for parts that do not depend on t). Every node takes
# the times and the arithmetic it runs on: numpy for arrays (Expression.evaluate), _Floats for one
# time as a Python float (Expression.at); the same tree either way.
_Pair = tuple  # (value, derivative)
_Node = Callable[..., _Pair]


def _guarded(function: Callable[[float], float], error: Callable[[float], float]) -> Any:
    """``function`` of one float, with ``error(u)`` where Python's math raises (domain, overflow)."""

    def apply(u: float) -> float:
        try:
            return function(u)
        except (ValueError, OverflowError):
            return error(u)

    return staticmethod(apply)


def _signed_zero(out: float, u: float) -> float:
    """floor and ceil keep the sign of a zero result, as C's (and numpy's) do: ceil(-0.5) is -0.0."""
    return math.copysign(out, u) if out == 0 else out


def _pole(a: float, b: float) -> float:
    """0 (or -0) to the negative power ``b``: C's pow gives an infinity signed by odd powers of -0."""
    return math.copysign(math.inf, a) if _odd(b) else math.inf


def _odd(b: float) -> bool:
    """Whether ``b`` is an odd integer (never an infinity: Python 3.10's pow(0, -inf) comes here)."""
    return float(b).is_integer() and math.fmod(b, 2.0) != 0


class _Floats:
    """numpy's functions of one float64, as :meth:`Expression.at` runs them: the same IEEE values
    where numpy (under ``errstate(all="ignore")``) gives inf or nan and Python's math raises.
    ``**`` is C's ``pow`` (as numpy's, except that numpy 2.x takes a square root for a constant
    exponent 0.5: (-0.0)**0.5 is -0.0 there, (-inf)**0.5 NaN, where C gives 0.0 and inf).
    Checked against numpy on the whole whitelist and its edge cases (tests/model/test_expr_floats.py)."""

    sin = _guarded(math.sin, lambda u: math.nan)  # sin(inf)
    cos = _guarded(math.cos, lambda u: math.nan)
    tan = _guarded(math.tan, lambda u: math.nan)
    arcsin = _guarded(math.asin, lambda u: math.nan)  # |u| > 1
    arccos = _guarded(math.acos, lambda u: math.nan)
    arctan = staticmethod(math.atan)
    arctan2 = staticmethod(math.atan2)
    sqrt = _guarded(math.sqrt, lambda u: math.nan)  # u < 0
    exp = _guarded(math.exp, lambda u: math.inf)  # an overflow
    log = _guarded(math.log, lambda u: -math.inf if u == 0 else math.nan)
    abs = staticmethod(abs)

    @staticmethod
    def sign(u: float) -> float:
        return 0.0 if u == 0 else u if u != u else math.copysign(1.0, u)  # sign(-0.0) is 0.0, sign(nan) nan

    @staticmethod
    def floor(u: float) -> float:
        return u if not math.isfinite(u) else _signed_zero(float(math.floor(u)), u)

    @staticmethod
    def ceil(u: float) -> float:
        return u if not math.isfinite(u) else _signed_zero(float(math.ceil(u)), u)

    @staticmethod
    def where(pick: bool, a: float, b: float) -> float:
        return a if pick else b

    @staticmethod
    def divide(a: float, b: float) -> float:
        try:
            return a / b
        except ZeroDivisionError:  # numpy: 0/0 is nan, x/0 an infinity signed by both signs
            return math.nan if a == 0 or a != a else math.copysign(math.inf, a) * math.copysign(1.0, b)

    @staticmethod
    def multiply(a: float, b: float) -> float:
        return a * b

    @staticmethod
    def mod(a: float, b: float) -> float:
        try:
            return a % b  # numpy's remainder is Python's: the sign of the divisor
        except ZeroDivisionError:
            return math.nan

    @staticmethod
    def power(a: float, b: float) -> float:
        try:
            return math.pow(a, b)
        except OverflowError:
            return -math.inf if a < 0 and _odd(b) else math.inf
        except ValueError:  # a pole (0 to a negative power) or a negative base to a fraction
            return _pole(a, b) if a == 0 else math.nan


_FLOATS = _Floats()


def _unary(value: Callable[[Any], Callable], slope: Callable) -> Callable[..., _Pair]:
    """A one-argument function and its derivative rule d f(u) = slope(ops, u, f(u)) * du."""

    def apply(ops: Any, arg: _Pair) -> _Pair:
        u, du = arg
        out = value(ops)(u)
        if isinstance(du, float) and du == 0.0:  # constant argument: avoid 0 * inf
            return out, 0.0
        return out, slope(ops, u, out) * du

    return apply


def _minimum(ops: Any, *args: _Pair) -> _Pair:
    value, slope = args[0]
    for u, du in args[1:]:
        pick = u < value
        value, slope = ops.where(pick, u, value), ops.where(pick, du, slope)
    return value, slope


def _maximum(ops: Any, *args: _Pair) -> _Pair:
    value, slope = args[0]
    for u, du in args[1:]:
        pick = u > value
        value, slope = ops.where(pick, u, value), ops.where(pick, du, slope)
    return value, slope


def _clip(ops: Any, x: _Pair, low: _Pair, high: _Pair) -> _Pair:
    return _minimum(ops, _maximum(ops, x, low), high)


def _atan2(ops: Any, y: _Pair, x: _Pair) -> _Pair:
    (u, du), (v, dv) = y, x
    return ops.arctan2(u, v), ops.divide(v * du - u * dv, u * u + v * v)


def _deg(ops: Any, arg: _Pair) -> _Pair:
    u, du = arg
    return u * (math.pi / 180.0), du * (math.pi / 180.0)


def _step(function: Callable[[Any], Callable]) -> Callable[..., _Pair]:
    """floor and ceil: flat between the jumps."""
    return lambda ops, arg: (function(ops)(arg[0]), 0.0)


# name -> (smallest and largest number of arguments, rule on (value, derivative) pairs)
FUNCTIONS: dict[str, tuple[int, int, Callable[..., _Pair]]] = {
    "sin": (1, 1, _unary(lambda o: o.sin, lambda o, u, f: o.cos(u))),
    "cos": (1, 1, _unary(lambda o: o.cos, lambda o, u, f: -o.sin(u))),
    "tan": (1, 1, _unary(lambda o: o.tan, lambda o, u, f: 1.0 + f * f)),
    "asin": (1, 1, _unary(lambda o: o.arcsin, lambda o, u, f: o.divide(1.0, o.sqrt(1.0 - u * u)))),
    "acos": (1, 1, _unary(lambda o: o.arccos, lambda o, u, f: o.divide(-1.0, o.sqrt(1.0 - u * u)))),
    "atan": (1, 1, _unary(lambda o: o.arctan, lambda o, u, f: o.divide(1.0, 1.0 + u * u))),
    "atan2": (2, 2, _atan2),
    "sqrt": (1, 1, _unary(lambda o: o.sqrt, lambda o, u, f: o.divide(0.5, f))),
    "exp": (1, 1, _unary(lambda o: o.exp, lambda o, u, f: f)),
    "log": (1, 1, _unary(lambda o: o.log, lambda o, u, f: o.divide(1.0, u))),
    "abs": (1, 1, _unary(lambda o: o.abs, lambda o, u, f: o.sign(u))),
    "min": (2, 16, _minimum),
    "max": (2, 16, _maximum),
    "clip": (3, 3, _clip),
    "floor": (1, 1, _step(lambda o: o.floor)),
    "ceil": (1, 1, _step(lambda o: o.ceil)),
    "deg": (1, 1, _deg),
}

ALLOWED = M("allowed: numbers, the time t (seconds), the constants pi e tau, + - * / ** % and parentheses, "
            "and the functions {functions} (deg(x) turns x degrees into radians; clip(x, low, high))",
            functions=" ".join(FUNCTIONS))

_OPERATORS = {ast.Add: "+", ast.Sub: "-", ast.Mult: "*", ast.Div: "/", ast.Pow: "**", ast.Mod: "%"}

_REFUSED = {
    ast.Attribute: M("attribute access ('.') is not allowed"),
    ast.Subscript: M("subscripts ('[...]') are not allowed"),
    ast.Lambda: M("lambda is not allowed"),
    ast.ListComp: M("comprehensions are not allowed"),
    ast.SetComp: M("comprehensions are not allowed"),
    ast.DictComp: M("comprehensions are not allowed"),
    ast.GeneratorExp: M("comprehensions are not allowed"),
    ast.NamedExpr: M("assignment (':=') is not allowed"),
    ast.Starred: M("'*' unpacking is not allowed"),
    ast.JoinedStr: M("strings are not allowed"),
    ast.List: M("lists are not allowed"),
    ast.Tuple: M("tuples are not allowed"),
    ast.Set: M("sets are not allowed"),
    ast.Dict: M("dicts are not allowed"),
    ast.Await: M("await is not allowed"),
    ast.Yield: M("yield is not allowed"),
    ast.YieldFrom: M("yield is not allowed"),
}


@dataclass(frozen=True)
class Expression:
    """A checked formula of the time ``t``; call it with an array of times."""

    text: str
    uses_t: bool
    _node: _Node

    def evaluate(self, t: np.ndarray | float) -> tuple[np.ndarray, np.ndarray]:
        """Values and exact time derivatives at the times ``t`` (same shape as ``t``)."""
        times = np.asarray(t, dtype=float)
        with np.errstate(all="ignore"):
            value, slope = self._node(times, np)
            value = np.broadcast_to(np.asarray(value, dtype=float), times.shape).copy()
            slope = np.broadcast_to(np.asarray(slope, dtype=float), times.shape).copy()
        return value, slope

    def __call__(self, t: np.ndarray | float) -> np.ndarray:
        return self.evaluate(t)[0]

    def derivative(self, t: np.ndarray | float) -> np.ndarray:
        return self.evaluate(t)[1]

    def at(self, t: float) -> float:
        """The value at one time, a Python float, without numpy: what :meth:`evaluate` gives there
        (numpy's IEEE results, see :class:`_Floats`; a transcendental function may differ from
        numpy's in the last bit). The derivative is not given: where it is 0 * inf, numpy's depends
        on whether it got an array or one time (``sqrt(abs(sin(t)))`` at 0)."""
        return float(self._node(float(t), _FLOATS)[0])


def compile_expression(text: str, *, prefix: str = "") -> Expression:
    """Check ``text`` and compile it to an :class:`Expression`.

    Raises :class:`UnsafeExpressionError` for anything that could do more than arithmetic and
    :class:`ParameterError` for typos (syntax, unknown names, wrong argument counts). The
    message shows ``prefix + text`` with a caret under the offending character; the error's
    ``column`` attribute is that character's index in ``text``.
    """
    if not isinstance(text, str):
        raise ParameterError(M("a formula must be text, not {kind}", kind=type(text).__name__), hint=ALLOWED)
    source = text.strip()
    lead = len(text) - len(text.lstrip())
    if not source:
        raise _error(ParameterError, M("the formula is empty"), text, len(text), prefix)
    if len(source) > MAX_LENGTH:
        raise _error(UnsafeExpressionError, M("the formula is too long ({count} characters, at most {most})",
                                                        count=len(source), most=MAX_LENGTH), text, lead + MAX_LENGTH, prefix)
    if "\n" in source or "\r" in source:
        raise _error(ParameterError, M("a formula must fit on one line"), text,
                     text.index("\n") if "\n" in text else text.index("\r"), prefix)
    try:
        tree = ast.parse(source, mode="eval")
    except SyntaxError as exc:
        why: Message | str
        if not exc.offset or exc.offset > len(source):  # Python says 0 when the text stops short
            column, why = lead + len(source), M("it ends too early")
        else:  # Python's own words, quoted after the sentence that says what went wrong
            column, why = lead + exc.offset - 1, Mc("python", "{reason}", reason=exc.msg)
        raise _error(ParameterError, M("the formula is not valid: {why}", why=why), text, column, prefix) from None
    except (RecursionError, MemoryError, ValueError):
        raise _error(UnsafeExpressionError, M("the formula is nested too deeply"), text, 0, prefix) from None
    compiler = _Compiler(source, text, lead, prefix)
    node, uses_t = compiler.compile(tree.body, 0)
    return Expression(text=source, uses_t=uses_t, _node=node)


def _decimal_comma(node: ast.Tuple) -> bool:
    """``1,2*sin(t)`` parses as the tuple (1, 2*sin(t)): a French decimal comma, not a tuple."""
    first = node.elts[0] if node.elts else None
    while isinstance(first, ast.BinOp):
        first = first.right
    return isinstance(first, ast.Constant) and isinstance(first.value, int)


_DEGREES = re.compile(r"^([-+]?(?:\d+(?:[.,]\d*)?|[.,]\d+))\s*(?:deg|degrees?|°)$", re.IGNORECASE)
_COMMA_NUMBER = re.compile(r"^[-+]?\d*,\d+$")


def parse_joint_value(text: str) -> float:
    """A joint value as learners type it: ``0.5``, ``1,5`` (decimal comma), ``pi/2``,
    ``-0.5*pi``, ``90deg`` (degrees said explicitly). Radians (metres for prismatic joints)
    unless ``deg`` says otherwise; the result is finite. Formulas of ``t`` are refused."""
    raw = text.strip()
    degrees = _DEGREES.match(raw)
    if degrees:
        value = math.radians(float(degrees.group(1).replace(",", ".")))
    else:
        if _COMMA_NUMBER.match(raw):
            raw = raw.replace(",", ".")
        try:
            value = float(raw)
        except ValueError:
            expression = compile_expression(raw)
            if expression.uses_t:
                raise TimeInJointValueError(M("'{raw}' depends on the time t: a joint value is one number", raw=raw),
                                            hint=M("give a number such as 0.5, pi/2 or 90deg; formulas of t go in --motion")) from None
            value = float(expression(0.0))
    if not math.isfinite(value):
        raise ParameterError(M("'{text}' is not a finite number", text=text),
                             hint=M("give a number such as 0.5, pi/2 or 90deg"))
    return value


_SHOWN = 72  # longest excerpt of a formula shown above the caret


def _error(kind: type, message: Message, text: str, column: int, prefix: str,
           hint: Message | None = None):
    """The error ``kind`` with the formula and a caret under ``column`` (an index in ``text``)."""
    shown, at = prefix + text, len(prefix) + column
    if len(shown) > _SHOWN:  # a window around the caret, marked with ellipses
        start = max(0, min(at - _SHOWN // 2, len(shown) - _SHOWN))
        end = start + _SHOWN
        excerpt = shown[start:end]
        if start > 0:
            excerpt, at = "..." + excerpt, at - start + 3
        if end < len(shown):
            excerpt += "..."
        shown = excerpt
    exc = kind(M("{reason}\n    {formula}\n    {caret}^", reason=message, formula=shown, caret=" " * at),
               hint=hint or ALLOWED)
    exc.column = column
    exc.reason = message  # what is wrong, without the formula and its caret
    return exc


class _Compiler:
    """Walks a parsed formula, refusing what is not whitelisted and building closures."""

    def __init__(self, source: str, text: str, lead: int, prefix: str) -> None:
        self.source, self.text, self.lead, self.prefix = source, text, lead, prefix

    def column(self, node: ast.AST, byte_offset: int | None = None) -> int:
        """Character column in the user's text of a node (ast columns count UTF-8 bytes)."""
        offset = getattr(node, "col_offset", 0) if byte_offset is None else byte_offset
        return self.lead + len(self.source.encode("utf-8")[:offset].decode("utf-8", errors="ignore"))

    def fail(self, node: ast.AST, message: Message, kind: type = UnsafeExpressionError,
             hint: Message | None = None, byte_offset: int | None = None):
        return _error(kind, message, self.text, self.column(node, byte_offset), self.prefix, hint)

    def compile(self, node: ast.AST, depth: int) -> tuple[_Node, bool]:
        if depth > MAX_DEPTH:
            raise self.fail(node, M("the formula is nested too deeply (more than {most} levels)", most=MAX_DEPTH))
        if isinstance(node, ast.Constant):
            return self.constant(node)
        if isinstance(node, ast.Name):
            return self.name(node)
        if isinstance(node, ast.UnaryOp):
            return self.unary(node, depth)
        if isinstance(node, ast.BinOp):
            return self.binary(node, depth)
        if isinstance(node, ast.Call):
            return self.call(node, depth)
        if isinstance(node, (ast.Attribute, ast.Subscript)):
            # point at the '.' or '[' rather than at the start of the object
            raise self.fail(node, _REFUSED[type(node)], byte_offset=node.value.end_col_offset)
        if isinstance(node, ast.Tuple) and _decimal_comma(node):
            raise self.fail(node, M("a comma cannot be a decimal point in a formula"),
                            hint=M("write 1.2 with a dot: in a formula the comma separates the "
                                   "arguments of a function, as in atan2(y, x)"))
        if type(node) in _REFUSED:
            raise self.fail(node, _REFUSED[type(node)])
        if isinstance(node, ast.Compare):
            raise self.fail(node, M("comparisons are not allowed"), hint=M("use min, max or clip; {allowed}", allowed=ALLOWED))
        if isinstance(node, (ast.BoolOp, ast.IfExp)):
            raise self.fail(node, M("conditions (and, or, if) are not allowed"),
                            hint=M("use min, max or clip; {allowed}", allowed=ALLOWED))
        raise self.fail(node, M("'{name}' is not allowed in a formula", name=type(node).__name__))

    def constant(self, node: ast.Constant) -> tuple[_Node, bool]:
        value = node.value
        if isinstance(value, bool) or not isinstance(value, (int, float)):
            if isinstance(value, (str, bytes)):
                raise self.fail(node, M("strings are not allowed, only real numbers"))
            raise self.fail(node, M("{kind} values are not allowed, only real numbers", kind=type(value).__name__))
        try:
            number = float(value)
        except OverflowError:
            number = math.inf
        if not math.isfinite(number):
            raise self.fail(node, M("the number is too large"), kind=ParameterError)
        return (lambda t, ops: (number, 0.0)), False

    def name(self, node: ast.Name) -> tuple[_Node, bool]:
        if node.id == VARIABLE:
            return (lambda t, ops: (t, 1.0)), True
        if node.id in CONSTANTS:
            number = CONSTANTS[node.id]
            return (lambda t, ops: (number, 0.0)), False
        if node.id in FUNCTIONS:
            raise self.fail(node, M("'{name}' is a function: call it, e.g. {name}(t)", name=node.id), kind=ParameterError)
        raise self.unknown(node, node.id)

    def unknown(self, node: ast.AST, name: str):
        if name.startswith("_") or hasattr(builtins, name):
            return self.fail(node, M("'{name}' is not allowed in a formula", name=name))
        close = difflib.get_close_matches(name, [VARIABLE, *CONSTANTS, *FUNCTIONS], n=1)
        hint = M("did you mean '{close}'? {allowed}", close=close[0], allowed=ALLOWED) if close else ALLOWED
        return self.fail(node, M("unknown name '{name}'", name=name), kind=ParameterError, hint=hint)

    def unary(self, node: ast.UnaryOp, depth: int) -> tuple[_Node, bool]:
        operand, uses_t = self.compile(node.operand, depth + 1)
        if isinstance(node.op, ast.USub):
            def negate(t: np.ndarray | float, ops: Any) -> _Pair:
                u, du = operand(t, ops)
                return -u, -du
            return negate, uses_t
        if isinstance(node.op, ast.UAdd):
            return operand, uses_t
        raise self.fail(node, M("only unary '-' and '+' are allowed"))

    def binary(self, node: ast.BinOp, depth: int) -> tuple[_Node, bool]:
        if type(node.op) not in _OPERATORS:
            symbol = {ast.FloorDiv: "//", ast.MatMult: "@", ast.BitAnd: "&", ast.BitOr: "|",
                      ast.BitXor: "^", ast.LShift: "<<", ast.RShift: ">>"}.get(type(node.op), "?")
            hint = M("use floor(a / b); {allowed}", allowed=ALLOWED) if symbol == "//" else None
            raise self.fail(node, M("the operator '{symbol}' is not allowed", symbol=symbol), hint=hint,
                            byte_offset=node.left.end_col_offset)
        if isinstance(node.op, ast.Pow):
            self.check_tower(node.right)
        left, left_t = self.compile(node.left, depth + 1)
        right, right_t = self.compile(node.right, depth + 1)
        rule = _BINARY[type(node.op)]
        if isinstance(node.op, ast.Pow) and not right_t:
            self.check_exponent(node.right, right)
            rule = _power_constant

        def apply(t: np.ndarray | float, ops: Any) -> _Pair:
            return rule(ops, left(t, ops), right(t, ops))

        return apply, left_t or right_t

    def check_tower(self, exponent: ast.AST) -> None:
        for inner in ast.walk(exponent):
            if isinstance(inner, ast.BinOp) and isinstance(inner.op, ast.Pow):
                raise self.fail(exponent, M("power towers (a**b**c) are not allowed"),
                                hint=M("write the exponent without **; {allowed}", allowed=ALLOWED))

    def check_exponent(self, exponent: ast.AST, compiled: _Node) -> None:
        """A constant exponent must stay within MAX_EXPONENT (numpy would only give inf)."""
        value = float(compiled(0.0, _FLOATS)[0])
        if not abs(value) <= MAX_EXPONENT:
            raise self.fail(exponent, M("the exponent {value:g} is too large (at most {most:g})", value=value, most=MAX_EXPONENT))

    def call(self, node: ast.Call, depth: int) -> tuple[_Node, bool]:
        if not isinstance(node.func, ast.Name):
            self.compile(node.func, depth + 1)  # refuses attributes, lambdas... with their own caret
            raise self.fail(node, M("only the listed functions can be called"))
        name = node.func.id
        if name not in FUNCTIONS:
            if name in CONSTANTS or name == VARIABLE:
                raise self.fail(node.func, M("'{name}' is not a function", name=name), kind=ParameterError,
                                hint=M("write a '*' for a product, e.g. 2*pi*t; {allowed}", allowed=ALLOWED))
            raise self.unknown(node.func, name)
        if node.keywords:
            raise self.fail(node.keywords[0].value, M("keyword arguments are not allowed"))
        low, high, rule = FUNCTIONS[name]
        count = len(node.args)
        if not low <= count <= high:
            if low == high:
                takes = Mn("{name}() takes {n} argument, got {count}", "{name}() takes {n} arguments, got {count}",
                           low, name=name, count=count)
            else:
                takes = M("{name}() takes {low} to {high} arguments, got {count}", name=name, low=low, high=high,
                          count=count)
            raise self.fail(node.func, takes, kind=ParameterError)
        compiled = [self.compile(arg, depth + 1) for arg in node.args]
        parts = [c[0] for c in compiled]

        def apply(t: np.ndarray | float, ops: Any) -> _Pair:
            return rule(ops, *(part(t, ops) for part in parts))

        return apply, any(c[1] for c in compiled)


def _add(ops: Any, a: _Pair, b: _Pair) -> _Pair:
    return a[0] + b[0], a[1] + b[1]


def _sub(ops: Any, a: _Pair, b: _Pair) -> _Pair:
    return a[0] - b[0], a[1] - b[1]


def _mul(ops: Any, a: _Pair, b: _Pair) -> _Pair:
    return a[0] * b[0], a[1] * b[0] + a[0] * b[1]


def _div(ops: Any, a: _Pair, b: _Pair) -> _Pair:
    # ops.divide, not '/': constants are Python floats, and 1/0 must give inf, not an exception
    return ops.divide(a[0], b[0]), ops.divide(a[1] * b[0] - a[0] * b[1], ops.multiply(b[0], b[0]))


def _mod(ops: Any, a: _Pair, b: _Pair) -> _Pair:
    return ops.mod(a[0], b[0]), a[1] - b[1] * ops.floor(ops.divide(a[0], b[0]))


def _power(ops: Any, a: _Pair, b: _Pair) -> _Pair:
    value = ops.power(a[0], b[0])
    return value, value * (b[1] * ops.log(a[0]) + ops.divide(b[0] * a[1], a[0]))


def _power_constant(ops: Any, a: _Pair, b: _Pair) -> _Pair:
    exponent = b[0]
    if exponent == 0:
        return ops.power(a[0], 0.0), 0.0
    return ops.power(a[0], exponent), exponent * ops.power(a[0], exponent - 1.0) * a[1]


_BINARY = {ast.Add: _add, ast.Sub: _sub, ast.Mult: _mul, ast.Div: _div, ast.Mod: _mod, ast.Pow: _power}
