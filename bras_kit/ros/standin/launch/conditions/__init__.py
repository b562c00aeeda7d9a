from .._conditions import (  # noqa: F401
    IfCondition,
    LaunchConfigurationEquals,
    LaunchConfigurationNotEquals,
    UnlessCondition,
    evaluate_condition_expression,
)
from .._core import InvalidConditionExpressionError  # noqa: F401
