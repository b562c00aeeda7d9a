"""launch/conditions/*.py (Jazzy)."""

from __future__ import annotations

from typing import Any

from ._core import (
    Condition,
    InvalidConditionExpressionError,
    LaunchContext,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)

VALID_TRUE_EXPRESSIONS = ['true', '1']
VALID_FALSE_EXPRESSIONS = ['false', '0']


def evaluate_condition_expression(context: LaunchContext, expression: list) -> bool:
    """evaluate_condition_expression_impl.py: 'true'/'1' or 'false'/'0', stripped and lowered."""
    expanded = perform_substitutions(context, expression).strip().lower()
    if expanded in VALID_TRUE_EXPRESSIONS:
        return True
    if expanded in VALID_FALSE_EXPRESSIONS:
        return False
    raise InvalidConditionExpressionError(expanded, expression, VALID_TRUE_EXPRESSIONS + VALID_FALSE_EXPRESSIONS)


class IfCondition(Condition):
    def __init__(self, predicate_expression: Any) -> None:
        self.__predicate_expression = normalize_to_list_of_substitutions(predicate_expression)
        super().__init__(predicate=self._predicate_func)

    def _predicate_func(self, context: LaunchContext) -> bool:
        return evaluate_condition_expression(context, self.__predicate_expression)

    def describe(self) -> str:
        return self.__repr__()


class UnlessCondition(IfCondition):
    def _predicate_func(self, context: LaunchContext) -> bool:
        return not super()._predicate_func(context)


class LaunchConfigurationEquals(Condition):
    def __init__(self, launch_configuration_name: str, expected_value: Any) -> None:
        self.__name = launch_configuration_name
        self.__expected = None if expected_value is None else normalize_to_list_of_substitutions(expected_value)
        super().__init__(predicate=self._predicate_func)

    def _predicate_func(self, context: LaunchContext) -> bool:
        expanded = None if self.__expected is None else perform_substitutions(context, self.__expected)
        return context.launch_configurations.get(self.__name) == expanded


class LaunchConfigurationNotEquals(LaunchConfigurationEquals):
    def _predicate_func(self, context: LaunchContext) -> bool:
        return not super()._predicate_func(context)
