"""Stand-in for launch_ros (Jazzy): Node, namespaces, parameters, FindPackageShare.

A :class:`Node` does not start a process: its evaluated form (package, executable, name,
namespace, parameters, remappings, arguments) is recorded for bras-kit to start its
counterpart. The checks ``ros2 launch`` makes before starting it are made here with the same
words: the package and executable are looked up as ExecutableInPackage does
(launch_ros/substitutions/executable_in_package.py), parameters are normalised and evaluated as
launch_ros/utilities/normalize_parameters.py and evaluate_parameters.py do.
"""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from typing import Any

import yaml
from launch import _plan
from launch._actions import ExecuteProcess
from launch._core import (
    Action,
    LaunchContext,
    Substitution,
    SubstitutionFailure,
    TextSubstitution,
    normalize_to_list_of_substitutions,
    perform_substitutions,
)
from launch._events import record_start


# ------------------------------------------------------------------ substitutions
class FindPackagePrefix(Substitution):
    def __init__(self, package: Any) -> None:
        self.__package = normalize_to_list_of_substitutions(package)

    @property
    def package(self) -> list:
        return self.__package

    def describe(self) -> str:
        return 'Pkg(pkg={})'.format(' + '.join(s.describe() for s in self.package))

    def find(self, package_name: str) -> str:
        from ament_index_python.packages import get_package_prefix

        return get_package_prefix(package_name)

    def perform(self, context: LaunchContext) -> str:
        return self.find(perform_substitutions(context, self.package))


class FindPackageShare(FindPackagePrefix):
    def find(self, package_name: str) -> str:
        from ament_index_python.packages import get_package_share_directory

        return get_package_share_directory(package_name)


FindPackage = FindPackagePrefix


class ExecutableInPackage(FindPackagePrefix):
    """executable_in_package.py, its two failures word for word."""

    def __init__(self, executable: Any, package: Any) -> None:
        super().__init__(package)
        self.__executable = normalize_to_list_of_substitutions(executable)

    def perform(self, context: LaunchContext) -> str:
        executable = perform_substitutions(context, self.__executable)
        package = perform_substitutions(context, self.package)
        package_prefix = super().perform(context)
        package_libexec = os.path.join(package_prefix, 'lib', package)
        if not os.path.exists(package_libexec):
            raise SubstitutionFailure(
                f"package '{package}' found at '{package_prefix}', but libexec directory '{package_libexec}' does not exist")
        candidate = os.path.join(package_libexec, executable)
        if os.sep in executable or not os.path.isfile(candidate):
            raise SubstitutionFailure(
                f"executable '{executable}' not found on the libexec directory '{package_libexec}' ")
        return candidate


# ------------------------------------------------------------------ parameters
def perform_typed_substitution(context: LaunchContext, value: Any, data_type: Any) -> Any:
    """launch/utilities/type_utils.py:522: a scalar as it is, substitutions performed and their text
    converted (coerce_to_type: with YAML rules when no type is given, type_utils.py:255)."""
    from launch._types import SCALAR_TYPES, coerce_to_type

    if isinstance(value, SCALAR_TYPES):
        if data_type is not None and not isinstance(value, data_type):
            raise TypeError(f'value=`{value}` is a scalar and not an instance of `{data_type}`')
        return value
    if isinstance(value, Substitution):
        value = [value]
    if isinstance(value, (list, tuple)) and value and all(isinstance(v, Substitution) for v in value):
        return coerce_to_type(perform_substitutions(context, list(value)), data_type)
    if isinstance(value, (list, tuple)):
        return [perform_substitutions(context, normalize_to_list_of_substitutions(v))
                if isinstance(v, (Substitution, list)) else v for v in value]
    return value


class ParameterValue:
    def __init__(self, value: Any, *, value_type: Any = None) -> None:
        self.__value = value
        self.__value_type = value_type

    @property
    def value(self) -> Any:
        return self.__value

    @property
    def value_type(self) -> Any:
        return self.__value_type

    def evaluate(self, context: LaunchContext) -> Any:
        return perform_typed_substitution(context, self.__value, self.__value_type)


class Parameter:
    def __init__(self, name: Any, value: Any, *, value_type: Any = None) -> None:
        self.name = normalize_to_list_of_substitutions(name)
        self.parameter_value = ParameterValue(value, value_type=value_type)

    def evaluate(self, context: LaunchContext) -> tuple[str, Any]:
        return perform_substitutions(context, self.name), self.parameter_value.evaluate(context)


class ParameterFile:
    def __init__(self, param_file: Any, *, allow_substs: Any = False) -> None:
        self.param_file = param_file if isinstance(param_file, ParameterFile) else \
            normalize_to_list_of_substitutions(param_file)
        self.allow_substs = allow_substs

    def evaluate(self, context: LaunchContext) -> str:
        return perform_substitutions(context, self.param_file)


def _normalize_value(value: Any) -> Any:
    """normalize_parameters.py normalize_parameter_dict, one value."""
    if isinstance(value, ParameterValue):
        return value
    if isinstance(value, str):
        from bras_kit.trust import yaml_gate

        if len(value) > yaml_gate.MAX_CHARS:  # past bras-kit's bound: kept as text, never dumped (PyYAML's
            return (TextSubstitution(text=value),)  # emitter takes about 40 s for 60 MB); the parent reports it
        return tuple(normalize_to_list_of_substitutions(yaml.dump(value)))
    if isinstance(value, Substitution):
        return (value,)
    if isinstance(value, (float, bool, int, bytes)):
        return value
    if isinstance(value, Sequence):
        if any(isinstance(v, Substitution) for v in value):
            return tuple(normalize_to_list_of_substitutions(value))
        return list(value)
    raise TypeError(f'Unexpected type for parameter value {repr(value)}')


def _flatten(parameters: Mapping, prefix: str = '') -> list[tuple[Any, Any]]:
    if not isinstance(parameters, Mapping):
        raise TypeError('expected dict')
    out: list[tuple[Any, Any]] = []
    for name, value in parameters.items():
        names = normalize_to_list_of_substitutions(name)
        if prefix:
            names = [TextSubstitution(text=prefix + '.'), *names]
        if isinstance(value, Mapping):
            out.extend(_flatten(value, ''.join(s.text for s in names if isinstance(s, TextSubstitution))))
        else:
            out.append((names, _normalize_value(value)))
    return out


def evaluate_parameter_dict(context: LaunchContext, parameters: Mapping) -> dict[str, Any]:
    """evaluate_parameters.py evaluate_parameter_dict: a substitution's text is read as YAML."""
    output: dict[str, Any] = {}
    for names, value in _flatten(parameters):
        name = perform_substitutions(context, names)
        if isinstance(value, tuple) and value and isinstance(value[0], Substitution):
            text = perform_substitutions(context, list(value))
            if len(text) == 0:
                text = "''"
            from bras_kit.trust import yaml_gate

            if len(text) > yaml_gate.MAX_CHARS:  # a text past the bound is no YAML bras-kit reads: the parent
                output[name] = text  # says it is too large (BK632 for robot_description), having parsed nothing
                continue
            try:
                loaded = yaml_gate.load(text, loader=yaml.SafeLoader)
            except yaml.YAMLError:
                raise TypeError(
                    f'Unable to parse the value of parameter {name} as yaml. '
                    'If the parameter is meant to be a string, try wrapping it in '
                    'launch_ros.parameter_descriptions.ParameterValue'
                    '(value, value_type=str)') from None
            if type(loaded) in (bool, int, float, str, bytes):
                value = loaded
            elif isinstance(loaded, list):
                value = tuple(loaded)
            else:
                raise TypeError(
                    'Allowed value types are bytes, bool, int, float, str, Sequence[bool]'
                    f', Sequence[int], Sequence[float], Sequence[str]. Got {type(loaded)} for "{name}". '
                    'If the parameter is meant to be a string, try wrapping it in '
                    'launch_ros.parameter_descriptions.ParameterValue'
                    '(value, value_type=str)')
        elif isinstance(value, ParameterValue):
            value = value.evaluate(context)
        output[name] = value
    return output


def _parameters_file(path: str, node_name: str | None) -> dict[str, Any]:
    """A parameters file's values for this node (``/**`` or the node's name)."""
    from bras_kit.trust import yaml_gate
    from bras_kit.trust.learner_files import Unreadable, read_text

    try:
        # any file the launch file names (as launch_ros), but a regular one, of a bounded size
        data = yaml_gate.load(read_text(os.path.abspath(path), ("/",)), loader=yaml.SafeLoader) or {}
    except Unreadable as exc:
        if exc.kind == "missing":
            raise FileNotFoundError(f"[Errno 2] No such file or directory: '{path}'") from None
        raise OSError(str(exc)) from None
    out: dict[str, Any] = {}
    if isinstance(data, dict):
        for key, section in data.items():
            if key in ('/**', '**') or (node_name and str(key).strip('/').endswith(node_name)):
                if isinstance(section, dict) and isinstance(section.get('ros__parameters'), dict):
                    out.update(section['ros__parameters'])
    return out


# ------------------------------------------------------------------ namespaces
def prefix_namespace(base_ns: str | None, ns: str | None) -> str | None:
    """utilities/namespace_utils.py"""
    if base_ns is None or base_ns == '':
        return ns
    if ns is None:
        return base_ns
    if ns.startswith('/'):
        return ns
    return base_ns.rstrip('/') + '/' + ns


def make_namespace_absolute(namespace: str | None) -> str | None:
    if namespace is None:
        return None
    return namespace if namespace.startswith('/') else '/' + namespace


class PushROSNamespace(Action):
    """actions/push_ros_namespace.py"""

    def __init__(self, namespace: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__namespace = normalize_to_list_of_substitutions(namespace)

    def execute(self, context: LaunchContext) -> None:
        pushed = perform_substitutions(context, self.__namespace)
        previous = context.launch_configurations.get('ros_namespace', None)
        namespace = make_namespace_absolute(prefix_namespace(previous, pushed)) or ''
        context.launch_configurations['ros_namespace'] = namespace


PushRosNamespace = PushROSNamespace


class SetParameter(Action):
    def __init__(self, name: Any, value: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__param = Parameter(name, value)

    def execute(self, context: LaunchContext) -> None:
        name, value = self.__param.evaluate(context)
        context.launch_configurations.setdefault('global_params', [])
        context.launch_configurations['global_params'].append((name, value))


class SetUseSimTime(SetParameter):
    def __init__(self, value: Any, **kwargs: Any) -> None:
        super().__init__('use_sim_time', value, **kwargs)


class SetRemap(Action):
    def __init__(self, src: Any, dst: Any, **kwargs: Any) -> None:
        super().__init__(**kwargs)
        self.__src = normalize_to_list_of_substitutions(src)
        self.__dst = normalize_to_list_of_substitutions(dst)

    def execute(self, context: LaunchContext) -> None:
        context.launch_configurations.setdefault('ros_remaps', [])
        context.launch_configurations['ros_remaps'].append(
            (perform_substitutions(context, self.__src), perform_substitutions(context, self.__dst)))


# ------------------------------------------------------------------ Node
class Node(ExecuteProcess):
    """actions/node.py"""

    _is_node = True

    def __init__(self, *, executable: Any, package: Any = None, name: Any = None, namespace: Any = None,
                 exec_name: Any = None, parameters: Any = None, remappings: Any = None,
                 ros_arguments: Any = None, arguments: Any = None, **kwargs: Any) -> None:
        kwargs.pop('node_executable', None)
        condition = kwargs.pop('condition', None)
        super().__init__(cmd=[executable], condition=condition)
        self.__package = package
        self.__executable = executable
        self.__name = name
        self.__namespace = namespace
        if parameters is not None and not isinstance(parameters, list):
            # node.py:214 ensure_argument_type(parameters, (list), 'parameters', 'Node'): a list, nothing else
            raise TypeError(f"'Node' expected 'parameters' to be one of [{list}], but got '{parameters}' "
                            f"of type '{type(parameters)}'")
        self.__parameters = list(parameters or [])
        self.__remappings = list(remappings or [])
        self.__arguments = list(arguments or [])
        self.__ros_arguments = list(ros_arguments or [])
        self.__where = _plan.caller()
        self.__recorded: dict[str, Any] | None = None

    @property
    def node_package(self) -> Any:
        return self.__package

    @property
    def node_executable(self) -> Any:
        return self.__executable

    @property
    def node_name(self) -> str:
        if self.__recorded is None:
            raise RuntimeError("cannot access 'node_name' before executing action")
        return self.__recorded["name"] or ''

    def execute(self, context: LaunchContext) -> None:
        _plan.CURRENT = self.__where
        executable = perform_substitutions(context, normalize_to_list_of_substitutions(self.__executable))
        package = None if self.__package is None else \
            perform_substitutions(context, normalize_to_list_of_substitutions(self.__package))
        path = executable
        if package is not None:
            path = ExecutableInPackage(executable, package).perform(context)
        name = None if self.__name is None else \
            perform_substitutions(context, normalize_to_list_of_substitutions(self.__name)).lstrip('/')
        namespace = None if self.__namespace is None else \
            perform_substitutions(context, normalize_to_list_of_substitutions(self.__namespace))
        namespace = make_namespace_absolute(prefix_namespace(context.launch_configurations.get('ros_namespace'),
                                                             namespace))
        parameters: dict[str, Any] = {}
        files: list[str] = []
        for name_value in context.launch_configurations.get('global_params', []):
            if isinstance(name_value, tuple):
                parameters[name_value[0]] = name_value[1]
        for item in self.__parameters:
            if isinstance(item, Mapping):
                parameters.update(evaluate_parameter_dict(context, item))
            elif isinstance(item, Parameter):
                key, value = item.evaluate(context)
                parameters[key] = value
            else:
                file = (item.evaluate(context) if isinstance(item, ParameterFile)
                        else perform_substitutions(context, normalize_to_list_of_substitutions(item)))
                files.append(file)
                parameters.update(_parameters_file(file, name))
        remappings = list(context.launch_configurations.get('ros_remaps', []))
        for src, dst in self.__remappings:
            remappings.append((perform_substitutions(context, normalize_to_list_of_substitutions(src)),
                               perform_substitutions(context, normalize_to_list_of_substitutions(dst))))
        arguments = [perform_substitutions(context, normalize_to_list_of_substitutions(a))
                     for a in self.__arguments]
        ros_arguments = [perform_substitutions(context, normalize_to_list_of_substitutions(a))
                         for a in self.__ros_arguments]
        # the command line node.py builds (lines 201-212, 405, 474): what rcl will parse in the node
        argv = [*arguments, *(['--ros-args', *ros_arguments] if self.__ros_arguments else []), '--ros-args']
        if name is not None:
            argv += ['-r', f'__node:={name}']
        if namespace:
            argv += ['-r', f'__ns:={namespace}']
        for src, dst in remappings:
            argv += ['-r', f'{src}:={dst}']
        self.__recorded = {
            "package": package, "executable": executable, "path": path, "name": name,
            "namespace": namespace, "parameters": parameters, "parameter_files": files,
            "remappings": remappings, "arguments": arguments, "ros_arguments": ros_arguments, "argv": argv,
            "delay": context.delay, "file": self.__where[0], "line": self.__where[1],
        }
        _plan.record_node(self.__recorded)
        _plan.CURRENT = None
        self._bras_cmd = [path, *argv]
        record_start(context, self)
