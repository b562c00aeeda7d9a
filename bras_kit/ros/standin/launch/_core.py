"""The shape of ros2/launch (Jazzy, 3.4): entities, actions, substitutions, the context.

Everything is an :class:`Action` or a :class:`Substitution`, evaluated lazily against a
:class:`LaunchContext`; a :class:`LaunchDescription` is a list of entities. The visit is
launch's ``LaunchService`` without its asyncio loop: ``visit()`` returns the entities an action
produces and they are visited in turn, depth first, in order (launch_service.py
``_process_one_event`` -> ``visit_all_entities_and_collect_futures``). Error words are the
ones launch raises, at the file and line cited.
"""

from __future__ import annotations

import os
from collections.abc import Iterable
from typing import Any

from . import _plan


class SubstitutionFailure(RuntimeError):
    """launch/substitutions/substitution_failure.py"""


class InvalidConditionExpressionError(Exception):
    """launch/conditions/invalid_condition_expression_error.py"""

    def __init__(self, expression: str, unexpanded_expression: list, valid_expressions: list) -> None:
        super().__init__(
            "invalid condition expression, expected one of [{}] but got '{}', expanded from '{}'".format(
                ', '.join(valid_expressions), expression,
                ' + '.join(s.describe() for s in unexpanded_expression)))


class InvalidPythonLaunchFileError(Exception):
    """launch/launch_description_sources/python_launch_file_utilities.py"""


class LaunchDescriptionEntity:
    def visit(self, context: LaunchContext) -> list | None:
        return None

    def describe(self) -> str:
        return f"{type(self).__name__}"

    def get_sub_entities(self) -> list:
        return []


class Substitution:
    def perform(self, context: LaunchContext) -> str:
        raise NotImplementedError

    def describe(self) -> str:
        return type(self).__name__ + "()"

    def __repr__(self) -> str:
        return self.describe()


class TextSubstitution(Substitution):
    def __init__(self, *, text: str) -> None:
        if not isinstance(text, str):
            raise TypeError(f"TextSubstitution expected Text object got '{type(text)}' instead.")
        self.text = text

    def perform(self, context: LaunchContext) -> str:
        return self.text

    def describe(self) -> str:
        return f"'{self.text}'"


def normalize_to_list_of_substitutions(subs: Any) -> list[Substitution]:
    """launch/utilities/normalize_to_list_of_substitutions_impl.py"""

    def normalize(x: Any) -> Substitution:
        if isinstance(x, Substitution):
            return x
        if isinstance(x, str):
            return TextSubstitution(text=x)
        raise TypeError(
            f"Failed to normalize given item of type '{type(x)}', when only "
            "'str' or 'launch.Substitution' were expected.")

    if isinstance(subs, str):
        return [TextSubstitution(text=subs)]
    if isinstance(subs, Substitution):
        return [subs]
    if isinstance(subs, os.PathLike):
        return [TextSubstitution(text=os.fspath(subs))]
    return [normalize(os.fspath(y) if isinstance(y, os.PathLike) else y) for y in subs]


def perform_substitutions(context: LaunchContext, subs: list[Substitution]) -> str:
    return ''.join(context.perform_substitution(sub) for sub in subs)


class _Locals:
    def __init__(self, values: dict[str, Any]) -> None:
        object.__setattr__(self, "_values", values)

    def __getattr__(self, key: str) -> Any:
        values = object.__getattribute__(self, "_values")
        if key not in values:
            raise AttributeError("context.locals does not contain attribute '{}', it contains: [{}]".format(
                key, ', '.join(values.keys())))
        return values[key]

    def __setattr__(self, key: str, value: Any) -> None:
        raise AttributeError(f"can't set attribute '{key}', locals are read-only")


class LaunchContext:
    """launch/launch_context.py: launch configurations, environment, locals, each a stack."""

    def __init__(self, *, argv: list[str] | None = None, noninteractive: bool = False) -> None:
        self.__argv = argv or []
        self.__noninteractive = noninteractive
        self.__launch_configurations_stack: list[dict[str, str]] = []
        self.__launch_configurations: dict[str, str] = {}
        self.__environment_stack: list[dict[str, str]] = []
        self.__locals_stack: list[dict[str, Any]] = [{}]
        self.is_shutdown = False
        self.delay = 0.0  # TimerAction periods on the way to the entity being visited (bras-kit's own)

    @property
    def argv(self) -> list[str]:
        return self.__argv

    @property
    def noninteractive(self) -> bool:
        return self.__noninteractive

    def _push_locals(self) -> None:
        self.__locals_stack.append(dict(self.__locals_stack[-1]))

    def _pop_locals(self) -> None:
        if len(self.__locals_stack) <= 1:
            raise RuntimeError('locals stack unexpectedly empty')
        self.__locals_stack.pop()

    def extend_locals(self, extensions: dict[str, Any]) -> None:
        self.__locals_stack[-1].update(extensions)

    def extend_globals(self, extensions: dict[str, Any]) -> None:
        for frame in self.__locals_stack:
            frame.update(extensions)

    def get_locals_as_dict(self) -> dict[str, Any]:
        return dict(self.__locals_stack[-1])

    @property
    def locals(self) -> _Locals:  # noqa: A003
        return _Locals(self.__locals_stack[-1])

    def _push_launch_configurations(self) -> None:
        self.__launch_configurations_stack.append(self.__launch_configurations.copy())

    def _pop_launch_configurations(self) -> None:
        if not self.__launch_configurations_stack:
            raise RuntimeError('launch_configurations stack unexpectedly empty')
        self.__launch_configurations = self.__launch_configurations_stack.pop()

    @property
    def launch_configurations(self) -> dict[str, str]:
        return self.__launch_configurations

    def _push_environment(self) -> None:
        self.__environment_stack.append(dict(os.environ))

    def _pop_environment(self) -> None:
        if not self.__environment_stack:
            raise RuntimeError('environment stack unexpectedly empty')
        os.environ.clear()
        os.environ.update(self.__environment_stack.pop())

    @property
    def environment(self) -> Any:
        return os.environ

    def perform_substitution(self, substitution: Substitution) -> str:
        return substitution.perform(self)

    def register_event_handler(self, event_handler: Any, append: bool = False) -> None:
        _plan.record_handler(event_handler)
        self.__dict__.setdefault("_bras_handlers", []).append(event_handler)

    def unregister_event_handler(self, event_handler: Any) -> None:
        handlers = self.__dict__.get("_bras_handlers", [])
        if event_handler in handlers:
            handlers.remove(event_handler)

    def emit_event_sync(self, event: Any) -> None:
        pass

    async def emit_event(self, event: Any) -> None:
        pass


class Condition:
    """launch/condition.py"""

    def __init__(self, *, predicate: Any = None) -> None:
        self._predicate = predicate

    def evaluate(self, context: LaunchContext) -> bool:
        return bool(self._predicate(context)) if self._predicate is not None else False

    def describe(self) -> str:
        return type(self).__name__


class Action(LaunchDescriptionEntity):
    """launch/action.py: ``visit`` executes the action only if its condition holds."""

    def __init__(self, *, condition: Condition | None = None) -> None:
        self.__condition = condition

    @property
    def condition(self) -> Condition | None:
        return self.__condition

    def visit(self, context: LaunchContext) -> list | None:
        if self.__condition is None or self.__condition.evaluate(context):
            try:
                return self.execute(context)
            finally:
                pass
        return None

    def execute(self, context: LaunchContext) -> list | None:
        return None


class LaunchDescription(LaunchDescriptionEntity):
    """launch/launch_description.py: a list of entities, visited in order."""

    def __init__(self, initial_entities: Iterable[LaunchDescriptionEntity] | None = None, *,
                 deprecated_reason: str | None = None) -> None:
        self.__entities = list(initial_entities) if initial_entities is not None else []
        self.__deprecated_reason = deprecated_reason

    def visit(self, context: LaunchContext) -> list:
        return self.__entities

    @property
    def entities(self) -> list:
        return self.__entities

    def add_entity(self, entity: LaunchDescriptionEntity) -> None:
        self.__entities.append(entity)

    def add_action(self, action: Action) -> None:
        self.add_entity(action)

    def get_launch_arguments_with_include_launch_description_actions(
            self, conditional_inclusion: bool = False) -> list:
        """launch_description.py:93 (without the nested includes' actions)."""
        return [(argument, None) for argument in self.get_launch_arguments(conditional_inclusion)]

    def get_launch_arguments(self, conditional_inclusion: bool = False) -> list:
        from .actions import DeclareLaunchArgument, IncludeLaunchDescription  # type: ignore[attr-defined]

        found = []

        def walk(entities: list) -> None:
            for entity in entities:
                if isinstance(entity, DeclareLaunchArgument):
                    found.append(entity)
                elif not isinstance(entity, IncludeLaunchDescription):
                    walk(entity.get_sub_entities())
        walk(self.__entities)
        return found


def visit_all(entity: LaunchDescriptionEntity, context: LaunchContext) -> None:
    """launch/utilities/visit_all_entities_and_collect_futures_impl.py, without futures."""
    if not isinstance(entity, LaunchDescriptionEntity):
        raise RuntimeError(
            f"Expected a LaunchDescriptionEntity, got '{type(entity).__name__}' instead")
    produced = entity.visit(context)
    for sub in produced or []:
        visit_all(sub, context)
    after = getattr(entity, "_after_visit", None)
    if after is not None:
        after(context)
