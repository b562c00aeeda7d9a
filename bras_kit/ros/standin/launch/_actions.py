"""launch/actions/*.py (Jazzy)."""

from __future__ import annotations

import os
from typing import Any

from . import _plan
from ._core import (
    Action,
    InvalidPythonLaunchFileError,
    LaunchContext,
    LaunchDescription,
    LaunchDescriptionEntity,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)
from ._events import record_start


class DeclareLaunchArgument(Action):
    """declare_launch_argument.py"""

    def __init__(self, name: str, *, default_value: Any = None, description: str | None = None,
                 choices: list[str] | None = None, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__name = name
        self.__default_value = None if default_value is None else normalize_to_list_of_substitutions(default_value)
        self.__description = description if description is not None else 'no description given'
        self.__choices = choices
        self._conditionally_included = False
        if choices is not None and default_value is not None and isinstance(default_value, str) \
                and default_value not in choices:
            raise RuntimeError(f'Provided default_value "{default_value}" is not in provided choices "{choices}".')
        file, line = _plan.caller()
        _plan.ARGUMENTS.append({"name": name, "default": default_value if isinstance(default_value, str) else None,
                                "description": self.__description, "file": file, "line": line})

    @property
    def name(self) -> str:
        return self.__name

    @property
    def default_value(self) -> Any:
        return self.__default_value

    @property
    def description(self) -> str:
        return self.__description

    @property
    def choices(self) -> list[str] | None:
        return self.__choices

    def execute(self, context: LaunchContext) -> None:
        if self.name not in context.launch_configurations:
            if self.default_value is None:
                raise RuntimeError(f'Required launch argument "{self.name}" was not provided.')
            context.launch_configurations[self.name] = perform_substitutions(context, self.default_value)
        if self.__choices is not None:
            value = context.launch_configurations[self.name]
            if value not in self.__choices:
                raise RuntimeError(f'Argument "{self.name}" provided value "{value}" is not valid. Valid options '
                                   f'are: {self.__choices}')


class SetLaunchConfiguration(Action):
    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__name = normalize_to_list_of_substitutions(name)
        self.__value = normalize_to_list_of_substitutions(value)

    def execute(self, context: LaunchContext) -> None:
        context.launch_configurations[perform_substitutions(context, self.__name)] = \
            perform_substitutions(context, self.__value)


class UnsetLaunchConfiguration(Action):
    def __init__(self, name: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__name = normalize_to_list_of_substitutions(name)

    def execute(self, context: LaunchContext) -> None:
        context.launch_configurations.pop(perform_substitutions(context, self.__name), None)


class PushLaunchConfigurations(Action):
    def execute(self, context: LaunchContext) -> None:
        context._push_launch_configurations()


class PopLaunchConfigurations(Action):
    def execute(self, context: LaunchContext) -> None:
        context._pop_launch_configurations()


class ResetLaunchConfigurations(Action):
    def __init__(self, launch_configurations: dict | None = None, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__kept = launch_configurations

    def execute(self, context: LaunchContext) -> None:
        kept = {}
        for name, value in (self.__kept or {}).items():
            kept[perform_substitutions(context, normalize_to_list_of_substitutions(name))] = \
                perform_substitutions(context, normalize_to_list_of_substitutions(value))
        context.launch_configurations.clear()
        context.launch_configurations.update(kept)


class PushEnvironment(Action):
    def execute(self, context: LaunchContext) -> None:
        context._push_environment()


class PopEnvironment(Action):
    def execute(self, context: LaunchContext) -> None:
        context._pop_environment()


class SetEnvironmentVariable(Action):
    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__name = normalize_to_list_of_substitutions(name)
        self.__value = normalize_to_list_of_substitutions(value)

    def execute(self, context: LaunchContext) -> None:
        context.environment[perform_substitutions(context, self.__name)] = \
            perform_substitutions(context, self.__value)


class AppendEnvironmentVariable(SetEnvironmentVariable):
    pass


class UnsetEnvironmentVariable(Action):
    def __init__(self, name: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__name = normalize_to_list_of_substitutions(name)

    def execute(self, context: LaunchContext) -> None:
        context.environment.pop(perform_substitutions(context, self.__name), None)


class GroupAction(Action):
    """group_action.py: scoped (the default) pushes and pops the launch configurations, so a
    PushRosNamespace inside stays inside."""

    def __init__(self, actions: Any, *, scoped: bool = True, forwarding: bool = True,
                 launch_configurations: dict | None = None, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__actions = list(actions)
        self.__scoped = scoped
        self.__forwarding = forwarding
        self.__launch_configurations = launch_configurations or {}

    def get_sub_entities(self) -> list:
        sets = [SetLaunchConfiguration(k, v) for k, v in self.__launch_configurations.items()]
        if not self.__scoped:
            return [*sets, *self.__actions]
        reset = [] if self.__forwarding else [ResetLaunchConfigurations(self.__launch_configurations)]
        return [PushLaunchConfigurations(), PushEnvironment(), *reset, *sets, *self.__actions,
                PopEnvironment(), PopLaunchConfigurations()]

    def execute(self, context: LaunchContext) -> list:
        return self.get_sub_entities()


class TimerAction(Action):
    """timer_action.py: its actions start ``period`` seconds later (recorded on what they start)."""

    def __init__(self, *, period: Any, actions: Any, cancel_on_shutdown: Any = True, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__period = period if isinstance(period, (int, float)) else normalize_to_list_of_substitutions(period)
        self.__actions = list(actions)

    def get_sub_entities(self) -> list:
        return self.__actions

    def execute(self, context: LaunchContext) -> list:
        period = self.__period if isinstance(self.__period, (int, float)) else \
            float(perform_substitutions(context, self.__period))
        context.delay += float(period)
        outer = self

        class _EndDelay(Action):
            def execute(self, context: LaunchContext) -> None:
                context.delay -= float(period)

        del outer
        return [*self.__actions, _EndDelay()]


class OpaqueFunction(Action):
    """opaque_function.py: ``function(context, *args, **kwargs)`` returns entities or None."""

    def __init__(self, *, function: Any, args: Any = None, kwargs: Any = None, **left: Any) -> None:
        super().__init__(**left)
        if not callable(function):
            raise TypeError(f"OpaqueFunction expected a callable for 'function', got '{type(function)}'")
        self.__function = function
        self.__args = list(args or [])
        self.__kwargs = dict(kwargs or {})

    def execute(self, context: LaunchContext) -> list | None:
        return self.__function(context, *self.__args, **self.__kwargs)


class LogInfo(Action):
    def __init__(self, *, msg: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__msg = normalize_to_list_of_substitutions(msg)
        self.__where = _plan.caller()

    def execute(self, context: LaunchContext) -> None:
        _plan.record_log((context.delay, perform_substitutions(context, self.__msg), *self.__where))


class ExecuteProcess(Action):
    """execute_process.py: recorded; a process that is not a ROS node is not run."""

    def __init__(self, *, cmd: Any, name: Any = None, cwd: Any = None, env: Any = None,
                 additional_env: Any = None, shell: bool = False, output: Any = 'log', **kwargs: Any) -> None:
        condition = kwargs.pop('condition', None)
        super().__init__(condition=condition)
        self.__cmd = [normalize_to_list_of_substitutions(c) for c in cmd]
        self.__name = name
        self.__where = _plan.caller()

    @property
    def cmd(self) -> list:
        return self.__cmd

    def execute(self, context: LaunchContext) -> None:
        words = [perform_substitutions(context, c) for c in self.__cmd]
        _plan.PROCESSES.append({"cmd": words, "delay": context.delay, "file": self.__where[0],
                                "line": self.__where[1]})
        self._bras_cmd = words
        record_start(context, self)


class ExecuteLocal(ExecuteProcess):
    pass


class IncludeLaunchDescription(Action):
    """include_launch_description.py: the included description's entities are visited in the same
    scope (not scoped: wrap it in a GroupAction for that), after its launch_arguments are set."""

    def __init__(self, launch_description_source: Any, *, launch_arguments: Any = None, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        from ._sources import AnyLaunchDescriptionSource, LaunchDescriptionSource

        if isinstance(launch_description_source, LaunchDescription):
            from ._sources import LaunchDescriptionSource as Source

            launch_description_source = Source(launch_description_source)
        elif not isinstance(launch_description_source, LaunchDescriptionSource):
            launch_description_source = AnyLaunchDescriptionSource(launch_description_source)
        self.__source = launch_description_source
        # kept as given: a dict (not dict.items()) is iterated key by key in execute(), and each key is
        # unpacked into (name, value): "too many values to unpack (expected 2)" for 'gui'
        # (include_launch_description.py:150, ``for arg_name, arg_value in self.launch_arguments``)
        self.__launch_arguments = [] if launch_arguments is None else launch_arguments
        self.__where = _plan.caller()

    @property
    def launch_arguments(self) -> list:
        return self.__launch_arguments

    @property
    def launch_description_source(self) -> Any:
        return self.__source

    def execute(self, context: LaunchContext) -> list:
        """include_launch_description.py:137."""
        if self.__where[0]:
            _plan.CURRENT = self.__where
        description = self.__source.get_launch_description(context)
        location = self.__source.location if hasattr(self.__source, "location") else ""
        if location and os.path.exists(location):
            context.extend_locals({'current_launch_file_path': location,
                                   'current_launch_file_directory': os.path.dirname(location)})
            _plan.INCLUDED.append(location)
        given = [perform_substitutions(context, normalize_to_list_of_substitutions(name))
                 for name, _ in self.__launch_arguments]
        # a description that is not a LaunchDescription (None, a list) fails here as on Jazzy:
        # AttributeError: 'NoneType' object has no attribute 'get_launch_arguments_with_include_...'
        for argument, _ in description.get_launch_arguments_with_include_launch_description_actions():
            if argument._conditionally_included or argument.default_value is not None:
                continue
            if argument.name not in given and argument.name not in context.launch_configurations:
                raise RuntimeError(
                    "Included launch description missing required argument '{}' "
                    "(description: '{}'), given: [{}]".format(argument.name, argument.description, ', '.join(given)))
        sets = [SetLaunchConfiguration(name, value) for name, value in self.__launch_arguments]
        _plan.CURRENT = None
        return [*sets, description]


class RegisterEventHandler(Action):
    """register_event_handler.py: the handler is kept; its actions run only when its event happens."""

    def __init__(self, event_handler: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__event_handler = event_handler
        self.__where = _plan.caller()

    @property
    def event_handler(self) -> Any:
        return self.__event_handler

    def execute(self, context: LaunchContext) -> None:
        self.__event_handler._bras_where = self.__where
        context.register_event_handler(self.__event_handler)  # it fires when its event happens (_events.py)


class UnregisterEventHandler(Action):
    def __init__(self, event_handler: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)


class EmitEvent(Action):
    def __init__(self, *, event: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)


class Shutdown(Action):
    def __init__(self, *, reason: str = 'reason not given', **kwargs: Any) -> None:
        super().__init__(**kwargs)


class OpaqueCoroutine(Action):
    def __init__(self, *, coroutine: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)


__all__ = [name for name, value in list(globals().items())
           if isinstance(value, type) and issubclass(value, LaunchDescriptionEntity)
           and value.__module__ == __name__]
_ = InvalidPythonLaunchFileError
