"""The safe formula evaluator: exact values, exact derivatives, and everything unsafe refused."""

from __future__ import annotations

import builtins
import math

import numpy as np
import pytest

from bras_kit.core.errors import BrasKitError, ParameterError, UnsafeExpressionError
from bras_kit.model.expr import MAX_LENGTH, compile_expression

GRID = np.arange(0, 201) * 0.05  # the tutorial's 20 Hz over 10 s


def value(formula: str, t: float | np.ndarray = 0.0) -> np.ndarray:
    return compile_expression(formula)(t)


def caret_column(exc: BrasKitError) -> int:
    """Index, in the shown text, of the caret of an error message."""
    lines = str(exc.message).splitlines()
    return lines[2].index("^") - 4


# ---------------------------------------------------------------- values


def test_tutorial_shoulder_formula_equals_numpy_to_the_last_bit():
    got = value("0.8*sin(t)", GRID)
    assert np.max(np.abs(got - 0.8 * np.sin(GRID))) <= 1e-15


def test_tutorial_elbow_formula_equals_numpy_to_the_last_bit():
    got = value("1.2*sin(0.7*t)", GRID)
    assert np.max(np.abs(got - 1.2 * np.sin(0.7 * GRID))) <= 1e-15


def test_result_has_the_shape_of_t_even_for_constants():
    assert value("0.5", np.zeros(3)).tolist() == [0.5, 0.5, 0.5]
    assert value("pi", np.zeros((2, 2))).shape == (2, 2)


@pytest.mark.parametrize("formula, expected", [
    ("2 + 3 * 4 ** 2 / 8 - 1", 7.0),  # ** before * and /, before + and -
    ("(2 + 3) * 4", 20.0),
    ("2 * 3 ** 2", 18.0),
    ("-2 ** 2", -4.0),  # unary minus binds looser than **, as in Python
    ("(-2) ** 2", 4.0),
    ("2 ** -1", 0.5),
    ("-(3 - 5)", 2.0),
    ("--3", 3.0),
    ("+3 - -3", 6.0),
    ("7 % 3", 1.0),
    ("-7 % 3", 2.0),  # Python's modulo: the sign of the divisor
    ("8 / 4 / 2", 1.0),  # left to right
    ("2 ** 3 * 2", 16.0),
])
def test_operator_precedence_follows_python(formula, expected):
    assert value(formula) == expected


@pytest.mark.parametrize("formula, expected", [
    ("clip(t, -1, 0.5)", [-1.0, 0.0, 0.5]),
    ("min(t, 1, 0.5)", [-2.0, 0.0, 0.5]),
    ("max(t, -1)", [-1.0, 0.0, 2.0]),
    ("abs(t)", [2.0, 0.0, 2.0]),
    ("floor(t / 3)", [-1.0, 0.0, 0.0]),
    ("ceil(t / 3)", [-0.0, 0.0, 1.0]),
    ("-t", [2.0, -0.0, -2.0]),
    ("t % 1.5", [1.0, 0.0, 0.5]),
])
def test_piecewise_functions(formula, expected):
    assert value(formula, np.array([-2.0, 0.0, 2.0])).tolist() == expected


@pytest.mark.parametrize("formula, expected", [
    ("atan2(1, 1)", math.pi / 4),
    ("deg(180)", math.pi),
    ("deg(90) * 2", math.pi),
    ("sqrt(16)", 4.0),
    ("log(e)", 1.0),
    ("exp(0)", 1.0),
    ("asin(1)", math.pi / 2),
    ("acos(1)", 0.0),
    ("atan(1)", math.pi / 4),
    ("tau", 2 * math.pi),
    ("cos(pi)", -1.0),
])
def test_functions_and_constants(formula, expected):
    assert value(formula) == pytest.approx(expected, abs=1e-15)


def test_tan_of_a_quarter_turn_is_one():
    assert value("tan(pi/4)") == pytest.approx(1.0, abs=2e-16)


# ---------------------------------------------------------------- derivatives


def test_derivative_of_the_shoulder_formula_is_exact():
    slope = compile_expression("0.8*sin(t)").derivative(GRID)
    assert np.max(np.abs(slope - 0.8 * np.cos(GRID))) <= 1e-15


# Times chosen away from the kinks of clip (+-0.5), abs (1.3), max (1) and % (1.5).
SMOOTH_TIMES = np.linspace(0.11, 2.93, 50)


@pytest.mark.parametrize("formula", [
    "t**3", "exp(-t)*cos(2*t)", "atan2(sin(t), cos(t) + 2)", "sqrt(1 + t*t)", "log(2 + t)",
    "t**t", "asin(0.5*sin(t))", "acos(0.3*cos(t))", "tan(0.3*t)", "atan(t - 1)", "clip(2*t, -1, 1)",
    "abs(t - 1.3)", "max(t, 2 - t)", "min(t, 2 - t, 1)", "1/(1 + t)", "t % 1.5", "deg(30)*t",
    "2**t", "floor(t) + t", "-t**2 / 3",
])
def test_derivative_agrees_with_central_differences(formula):
    expression = compile_expression(formula)
    h = 1e-6
    numeric = (expression(SMOOTH_TIMES + h) - expression(SMOOTH_TIMES - h)) / (2 * h)
    assert np.allclose(expression.derivative(SMOOTH_TIMES), numeric, rtol=1e-6, atol=1e-6)


def test_constant_formula_has_zero_derivative_even_where_the_slope_is_infinite():
    assert compile_expression("sqrt(0) + 1").derivative(np.zeros(2)).tolist() == [0.0, 0.0]


# ---------------------------------------------------------------- refused: unsafe


@pytest.mark.parametrize("formula, column", [
    ("__import__('os')", 0),
    ("__import__('os').system('true')", 16),
    ("().__class__", 2),
    ("t.real", 1),
    ("t.__class__.__subclasses__()", 11),
    ("t[0]", 1),
    ("lambda: 1", 0),
    ("[x for x in t]", 0),
    ("sin(x for x in t)", 3),
    ("{x: 1 for x in t}", 0),
    ("10**10**10", 4),
    ("9**999999", 3),
    ("2**(1000*t**2)", 4),
    ("open('motion.csv')", 0),
    ("eval('1')", 0),
    ("exec", 0),
    ("getattr(t, 'real')", 0),
    ("'t' * 10", 0),
    ("(x := 1)", 1),
    ("1 if t else 2", 0),
    ("t > 1", 0),
    ("t and 1", 0),
    ("sin(t, x=1)", 9),
    ("2 // t", 1),
    ("~t", 0),
    ("1j * t", 0),
    ("True * t", 0),
    ("[t, t]", 0),
    ("(t, t)", 0),
])
def test_unsafe_formula_is_refused_with_a_caret(formula, column):
    with pytest.raises(UnsafeExpressionError) as caught:
        compile_expression(formula)
    assert caught.value.column == column
    assert caret_column(caught.value) == column
    assert "allowed:" in str(caught.value.hint)


def test_import_message_shows_the_formula_and_a_caret_under_it():
    with pytest.raises(UnsafeExpressionError) as caught:
        compile_expression("t.real")
    lines = str(caught.value.message).splitlines()
    assert lines == ["attribute access ('.') is not allowed", "    t.real", "     ^"]


def test_caret_counts_characters_not_utf8_bytes():
    with pytest.raises(UnsafeExpressionError) as caught:
        compile_expression("t + π.real")  # π takes two bytes
    assert caught.value.column == 5


def test_caret_is_shifted_by_the_shown_prefix():
    with pytest.raises(UnsafeExpressionError) as caught:
        compile_expression("t.real", prefix="coude=")
    assert str(caught.value.message).splitlines()[1:] == ["    coude=t.real", "           ^"]
    assert caught.value.column == 1


def test_formula_never_reaches_python_builtins(monkeypatch):
    calls = []
    monkeypatch.setattr(builtins, "boom", lambda *a: calls.append(a) or 1.0, raising=False)
    with pytest.raises(UnsafeExpressionError):
        compile_expression("boom(t)")(np.zeros(2))
    assert calls == []


def test_too_long_formula_is_refused():
    formula = "sin(t)+" * 200 + "t"
    assert len(formula) > MAX_LENGTH
    with pytest.raises(UnsafeExpressionError, match="too long"):
        compile_expression(formula)


def test_deep_nesting_is_refused_without_recursion_error():
    with pytest.raises(UnsafeExpressionError, match="nested too deeply"):
        compile_expression("-" * 500 + "t")


def test_too_many_parentheses_are_refused():
    with pytest.raises(BrasKitError):
        compile_expression("(" * 300 + "t" + ")" * 300)


def test_huge_literal_is_refused():
    with pytest.raises(ParameterError, match="too large"):
        compile_expression("1" + "0" * 400)


# ---------------------------------------------------------------- refused: typos


@pytest.mark.parametrize("formula, column, words", [
    ("sinn(t)", 0, "unknown name 'sinn'"),
    ("sin(t", 3, "never closed"),
    ("2 +* t", 3, "not valid"),
    ("x * t", 0, "unknown name 'x'"),
    ("sin", 0, "is a function"),
    ("sin(1, 2)", 0, "takes 1 argument"),
    ("clip(t, 1)", 0, "takes 3 arguments"),
    ("t(2)", 0, "not a function"),
    ("  ", 2, "empty"),
    ("0.8*sin(t) +", 12, "ends too early"),
    ("sin(t))", 6, "unmatched"),
])
def test_typo_is_a_parameter_error_with_a_caret(formula, column, words):
    with pytest.raises(ParameterError) as caught:
        compile_expression(formula)
    assert not isinstance(caught.value, UnsafeExpressionError)
    assert words in str(caught.value.message)
    assert caught.value.column == column
    assert caret_column(caught.value) == column


def test_misspelt_function_suggests_the_right_one():
    with pytest.raises(ParameterError) as caught:
        compile_expression("cso(t)")
    assert str(caught.value.hint).startswith("did you mean 'cos'?")


def test_leading_spaces_keep_the_caret_under_the_character():
    with pytest.raises(UnsafeExpressionError) as caught:
        compile_expression("   t.real")
    assert caught.value.column == 4
