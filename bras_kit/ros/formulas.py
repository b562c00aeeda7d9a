"""Joint formulas written in a node's Python code, turned into the text :mod:`bras_kit.model.expr` reads.

``0.8 * math.sin(self.t)`` becomes ``0.8 * sin(t)``: ``math.``/``np.`` prefixes are dropped,
constants of the module are written as numbers, and the one remaining variable (``self.t``,
``elapsed``...) is the time, when it sits inside a function of the formula (``sin``, ``cos``...).
A bare name (``[q1, q2]``), a formula with two variables, a call of another function or
anything else is not "literal": it is left out and nothing is said about it. The text is
checked later by the motion module's own safe parser; nothing here is evaluated.
"""

from __future__ import annotations

import ast
import copy
import math
from collections.abc import Mapping
from typing import Any

from ..model.expr import CONSTANTS, FUNCTIONS

_MODULES = ("math", "np", "numpy")
_TIME_NAMES = ("t", "time", "temps", "elapsed", "now")  # a ramp of these is a motion in time


def substitute(node: ast.expr, values: Mapping[str, float]) -> ast.expr:
    """A copy of ``node`` with the names in ``values`` replaced by their numbers."""

    class _Replace(ast.NodeTransformer):
        def visit_Name(self, name: ast.Name) -> ast.AST:
            if name.id in values:
                return ast.copy_location(ast.Constant(values[name.id]), name)
            return name

    return _Replace().visit(copy.deepcopy(node))


def formula(node: ast.expr, scope: Mapping[str, Any]) -> str | None:
    """The formula in ``t`` for ``node``, or None when it is not a literal formula of one variable."""
    free: set[str] = set()

    class _Rewrite(ast.NodeTransformer):
        def visit_Call(self, call: ast.Call) -> ast.AST:
            func = call.func
            if isinstance(func, ast.Attribute) and isinstance(func.value, ast.Name) \
                    and func.value.id in _MODULES and func.attr in FUNCTIONS:
                call.func = ast.copy_location(ast.Name(func.attr, ast.Load()), func)
            elif not (isinstance(func, ast.Name) and func.id in FUNCTIONS):
                raise ValueError("call")
            call.args = [self.visit(a) for a in call.args]
            if call.keywords:
                raise ValueError("keywords")
            return call

        def visit_Attribute(self, attribute: ast.Attribute) -> ast.AST:
            if isinstance(attribute.value, ast.Name) and attribute.value.id in _MODULES:
                if attribute.attr in CONSTANTS:
                    return ast.copy_location(ast.Name(attribute.attr, ast.Load()), attribute)
                raise ValueError("attribute")
            return self._variable(attribute)

        def visit_Name(self, name: ast.Name) -> ast.AST:
            if name.id in CONSTANTS:
                return name
            value = scope.get(name.id)
            if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value):
                return ast.copy_location(ast.Constant(float(value)), name)
            return self._variable(name)

        def _variable(self, node: ast.expr) -> ast.AST:
            free.add(ast.unparse(node))
            return ast.copy_location(ast.Name("t", ast.Load()), node)

    try:
        rewritten = _Rewrite().visit(copy.deepcopy(node))
        text = ast.unparse(rewritten)
    except (ValueError, RecursionError):
        return None
    if len(free) != 1:
        return None  # a constant (no time at all) or several variables: not a wave we can follow
    time_named = next(iter(free)).rsplit(".", 1)[-1] in _TIME_NAMES
    if not time_named and not any(isinstance(call, ast.Call) and any(isinstance(n, ast.Name) and n.id == "t" for n in ast.walk(call))
               for call in ast.walk(rewritten)):
        # a bare name or a sum of names (msg.position = [q1, q2], [epaule, coude]) is a value the
        # reading cannot resolve, not a wave of time: nothing is said about it
        return None
    return text
