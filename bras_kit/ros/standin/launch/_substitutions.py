"""launch/substitutions/*.py (Jazzy)."""

from __future__ import annotations

import math
import os
import shlex
from typing import Any

from ._core import (
    LaunchContext,
    Substitution,
    SubstitutionFailure,
    TextSubstitution,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)


class LaunchConfiguration(Substitution):
    """launch_configuration.py: the value of a launch argument, or its default, or a failure."""

    def __init__(self, variable_name: Any, *, default: Any = None) -> None:
        self.__variable_name = normalize_to_list_of_substitutions(variable_name)
        if default is None:
            self.__default = None
        elif isinstance(default, (list, tuple)) and not default:
            self.__default = [TextSubstitution(text='')]
        else:
            self.__default = normalize_to_list_of_substitutions(  # type: ignore[assignment]
                default if not isinstance(default, (list, tuple)) else list(default))

    @property
    def variable_name(self) -> list[Substitution]:
        return self.__variable_name

    def describe(self) -> str:
        return 'LaunchConfig({})'.format(' + '.join(s.describe() for s in self.variable_name))

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.variable_name)
        if name not in context.launch_configurations:
            if self.__default is None:
                raise SubstitutionFailure(f"launch configuration '{name}' does not exist")
            return perform_substitutions(context, self.__default)  # type: ignore[arg-type]
        return context.launch_configurations[name]


class PathJoinSubstitution(Substitution):
    """path_join_substitution.py: each component (itself a list of substitutions) joined by os.path.join."""

    def __init__(self, substitutions: Any) -> None:
        self.__substitutions = [normalize_to_list_of_substitutions(item) for item in substitutions]

    @property
    def substitutions(self) -> list:
        return self.__substitutions

    def describe(self) -> str:
        return "PathJoin('{}')".format(' + '.join(
            s.describe() for component in self.__substitutions for s in component))

    def perform(self, context: LaunchContext) -> str:
        return os.path.join(*[perform_substitutions(context, c) for c in self.__substitutions])

    def __truediv__(self, additional_path: Any) -> PathJoinSubstitution:
        return PathJoinSubstitution([*self.__substitutions, normalize_to_list_of_substitutions(additional_path)])


class EnvironmentVariable(Substitution):
    def __init__(self, name: Any, *, default_value: Any = None) -> None:
        self.name = normalize_to_list_of_substitutions(name)
        self.default_value = None if default_value is None else normalize_to_list_of_substitutions(default_value)

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.name)
        value = context.environment.get(name)
        if value is None:
            if self.default_value is None:
                raise SubstitutionFailure(f"environment variable '{name}' does not exist")
            return perform_substitutions(context, self.default_value)
        return value


class FindExecutable(Substitution):
    """find_executable.py: only the programs of the simulated ROS install are found."""

    KNOWN = ("xacro", "python3", "python")

    def __init__(self, *, name: Any) -> None:
        self.name = normalize_to_list_of_substitutions(name)

    def perform(self, context: LaunchContext) -> str:
        name = perform_substitutions(context, self.name)
        if name not in self.KNOWN:
            raise SubstitutionFailure(f"executable '{name}' not found on the PATH")
        return name


class Command(Substitution):
    """command.py: ``xacro FILE [NAME:=VALUE ...]`` runs bras-kit's xacro; any other program
    is not part of the simulated ROS install."""

    def __init__(self, command: Any, *, on_stderr: Any = 'fail') -> None:
        self.__command = normalize_to_list_of_substitutions(command)
        self.__on_stderr = normalize_to_list_of_substitutions(on_stderr)

    @property
    def command(self) -> list[Substitution]:
        return self.__command

    def describe(self) -> str:
        return 'Command({})'.format(' + '.join(sub.describe() for sub in self.command))

    def perform(self, context: LaunchContext) -> str:
        from xacro import _run_command

        command_str = perform_substitutions(context, self.command)
        words = shlex.split(command_str)
        if not words:
            raise SubstitutionFailure('file not found: [Errno 2] No such file or directory: \'\'')
        code, out, err = _run_command(words)
        if code != 0:
            message = f'executed command failed. Command: {command_str}'
            if err:
                message += f'\nCaptured stderr output: {err}'
            raise SubstitutionFailure(message)
        return out


class PythonExpression(Substitution):
    """python_expression.py: the learner's own expression, evaluated (in the sandbox child)."""

    def __init__(self, expression: Any, python_modules: Any = ('math',)) -> None:
        self.expression = normalize_to_list_of_substitutions(expression)
        self.python_modules = list(python_modules)

    def perform(self, context: LaunchContext) -> str:
        namespace: dict[str, Any] = {'math': math}
        for module in self.python_modules:
            name = module if isinstance(module, str) else perform_substitutions(context, [module])
            namespace[name] = __import__(name)
        return str(eval(perform_substitutions(context, self.expression), namespace))  # noqa: S307


class ThisLaunchFileDir(Substitution):
    def perform(self, context: LaunchContext) -> str:
        try:
            return context.locals.current_launch_file_directory
        except AttributeError:
            raise SubstitutionFailure('ThisLaunchFileDir used outside of a launch file (in a script)') from None


class ThisLaunchFile(Substitution):
    def perform(self, context: LaunchContext) -> str:
        try:
            return context.locals.current_launch_file_path
        except AttributeError:
            raise SubstitutionFailure('ThisLaunchFile used outside of a launch file (in a script)') from None


class IfElseSubstitution(Substitution):
    def __init__(self, condition: Any, if_value: Any = '', else_value: Any = '') -> None:
        self.condition = normalize_to_list_of_substitutions(condition)
        self.if_value = normalize_to_list_of_substitutions(if_value)
        self.else_value = normalize_to_list_of_substitutions(else_value)

    def perform(self, context: LaunchContext) -> str:
        from ._conditions import evaluate_condition_expression

        chosen = self.if_value if evaluate_condition_expression(context, self.condition) else self.else_value
        return perform_substitutions(context, chosen)


class NotSubstitution(Substitution):
    def __init__(self, value: Any) -> None:
        self.value = normalize_to_list_of_substitutions(value)

    def perform(self, context: LaunchContext) -> str:
        from ._conditions import evaluate_condition_expression

        return str(not evaluate_condition_expression(context, self.value)).lower()


class AndSubstitution(Substitution):
    def __init__(self, left: Any, right: Any) -> None:
        self.left, self.right = (normalize_to_list_of_substitutions(x) for x in (left, right))

    def perform(self, context: LaunchContext) -> str:
        from ._conditions import evaluate_condition_expression

        return str(evaluate_condition_expression(context, self.left)
                   and evaluate_condition_expression(context, self.right)).lower()


class OrSubstitution(AndSubstitution):
    def perform(self, context: LaunchContext) -> str:
        from ._conditions import evaluate_condition_expression

        return str(evaluate_condition_expression(context, self.left)
                   or evaluate_condition_expression(context, self.right)).lower()


class EqualsSubstitution(Substitution):
    def __init__(self, left: Any, right: Any) -> None:
        self.left, self.right = (normalize_to_list_of_substitutions(x) for x in (left, right))

    def perform(self, context: LaunchContext) -> str:
        return str(perform_substitutions(context, self.left) == perform_substitutions(context, self.right)).lower()


class FileContent(Substitution):
    def __init__(self, path: Any) -> None:
        self.path = normalize_to_list_of_substitutions(path)

    def perform(self, context: LaunchContext) -> str:
        path = perform_substitutions(context, self.path)
        try:
            with open(path) as handle:
                return handle.read()
        except FileNotFoundError:
            raise SubstitutionFailure(f'File not found: {path}') from None


class AnonName(Substitution):
    def __init__(self, name: Any) -> None:
        self.name = normalize_to_list_of_substitutions(name)

    def perform(self, context: LaunchContext) -> str:
        return perform_substitutions(context, self.name) + '_0'
