"""launch_xml and launch_yaml (Jazzy: launch 3.4.3, launch_ros 0.26.6) for the tags beginners write.

The file becomes the same actions and substitutions as a Python launch file: each tag goes to its
action's ``parse`` (launch/frontend/expose.py ``instantiate_action``), which reads the entity's
attributes with ``get_attr`` — in launch_xml's and launch_yaml's words when one is missing
(launch_xml/entity.py:93, launch_yaml/entity.py:118) — and then refuses any attribute or nested
tag it did not read (``assert_entity_completely_parsed``, expose.py:108). Command lines
(``args``, ``ros_args``, ``cmd``) are read for substitutions *before* they are split into words
(execute_process.py ``_parse_cmdline``, line 243). Substitutions ``$(var)``,
``$(find-pkg-share)``, ``$(find-pkg-prefix)``, ``$(command)``, ``$(env)``, ``$(eval)``,
``$(dirname)``, ``$(anon)`` nest as in launch/frontend/grammar.lark."""

from __future__ import annotations

import os
import shlex
import xml.etree.ElementTree as ElementTree
from typing import Any

from . import _plan
from ._core import LaunchDescription, Substitution, SubstitutionFailure, TextSubstitution


class InvalidLaunchFileError(Exception):
    """launch/invalid_launch_file_error.py: what every loader of a launch file said, in one message."""

    def __init__(self, extension: str = '', *, likely_errors: list[BaseException] | None = None) -> None:
        super().__init__()
        self._extension = extension
        self._likely_errors = likely_errors
        if self._extension == '' or not self._likely_errors:
            self._error_message = 'The launch file may have a syntax error, or its format is unknown'
        else:
            self._error_message = 'Caught {} when trying to load file of format [{}]:'.format(
                'multiple exceptions' if len(self._likely_errors) > 1 else 'exception', self._extension)
            for error in self._likely_errors:
                self._error_message += f'\n - {type(error).__name__}: {error}'
            self.__cause__ = self._likely_errors[0]

    def __str__(self) -> str:
        return self._error_message


class InvalidFrontendLaunchFileError(InvalidLaunchFileError):
    """launch/frontend/parser.py:54"""


class _DirName(Substitution):
    def __init__(self, path: str) -> None:
        self.path = path

    def perform(self, context: Any) -> str:
        return os.path.dirname(self.path)


def parse_substitution(text: str, launch_file: str) -> list[Substitution]:
    """``a $(var b) c`` -> [Text('a '), LaunchConfiguration('b'), Text(' c')]."""
    out: list[Substitution] = []
    i = 0
    plain = ""
    while i < len(text):
        if text.startswith("$(", i):
            if plain:
                out.append(TextSubstitution(text=plain))
                plain = ""
            depth, j, quote = 1, i + 2, ""
            while j < len(text) and depth:
                c = text[j]
                if quote:
                    quote = "" if c == quote else quote
                elif c in "'\"":
                    quote = c
                elif text.startswith("$(", j):
                    depth += 1
                    j += 1
                elif c == ")":
                    depth -= 1
                j += 1
            if depth:
                raise InvalidFrontendLaunchFileError(f"unterminated substitution in '{text}'")
            out.append(_substitution(text[i + 2:j - 1], launch_file))
            i = j
        else:
            plain += text[i]
            i += 1
    if plain or not out:
        out.append(TextSubstitution(text=plain))
    return out


def _arguments(body: str) -> list[str]:
    words, word, quote, depth = [], "", "", 0
    for c in body:
        if quote:
            if c == quote and depth == 0:
                quote = ""
                continue
            word += c
        elif c in "'\"" and depth == 0:
            quote = c
        elif c == " " and depth == 0:
            if word:
                words.append(word)
            word = ""
        else:
            depth += (c == "(") - (c == ")")
            word += c
    if word:
        words.append(word)
    return words


def _substitution(body: str, launch_file: str) -> Substitution:
    from launch_ros.substitutions import FindPackagePrefix, FindPackageShare

    from ._substitutions import (
        AnonName,
        Command,
        EnvironmentVariable,
        LaunchConfiguration,
        PythonExpression,
    )

    name, _, rest = body.strip().partition(" ")
    args = [parse_substitution(a, launch_file) for a in _arguments(rest)]
    if name == "var" and len(args) == 1:
        return LaunchConfiguration(args[0])
    if name == "find-pkg-share" and len(args) == 1:
        return FindPackageShare(args[0])
    if name == "find-pkg-prefix" and len(args) == 1:
        return FindPackagePrefix(args[0])
    if name == "command" and args:
        return Command(args[0])
    if name == "env" and args:
        return EnvironmentVariable(args[0], default_value=args[1] if len(args) > 1 else None)
    if name == "eval" and len(args) == 1:
        return PythonExpression(args[0])
    if name == "anon" and len(args) == 1:
        return AnonName(args[0])
    if name == "dirname" and not args:
        return _DirName(launch_file)
    raise SubstitutionFailure(f"Unknown substitution: {name}")



def parse_if_substitutions(value: Any, launch_file: str) -> Any:
    """launch/frontend/parse_substitution.py:119: text without substitutions stays a str, other
    scalars stay as they are, text with substitutions becomes a list of substitutions."""
    kinds = set()

    def one(item: Any) -> Any:
        if isinstance(item, str):
            output = parse_substitution(item, launch_file)
            if len(output) == 1 and isinstance(output[0], TextSubstitution):
                kinds.add(str)
                return output[0].text
            return output
        kinds.add(type(item))
        return item

    output = [one(x) for x in value] if isinstance(value, list) else one(value)
    if len(kinds) > 1:
        raise ValueError('The result is a non-uniform list')
    return output


def parse_cmdline(cmd: str, launch_file: str) -> list[list[Substitution]]:
    """execute_process.py:243 ``_parse_cmdline``: substitutions first, then the text around them
    split with shlex; a substitution glued to text stays in the same argument."""
    result: list[list[Substitution]] = []
    arg: list[Substitution] = []

    def close() -> None:
        nonlocal arg
        result.append(arg)
        arg = []

    for sub in parse_substitution(cmd, launch_file):
        if not isinstance(sub, TextSubstitution):
            arg.append(sub)
            continue
        tokens = shlex.split(sub.text)
        if not tokens:
            close()  # only spaces: two substitutions are two arguments
            continue
        if sub.text[0].isspace() and arg:
            close()
        arg.append(TextSubstitution(text=tokens[0]))
        if len(tokens) > 1:
            close()
            arg.append(TextSubstitution(text=tokens[-1]))
        if len(tokens) > 2:
            result.extend([TextSubstitution(text=x)] for x in tokens[1:-1])
        if sub.text[-1].isspace():
            close()
    if arg:
        result.append(arg)
    return result


# ---------------------------------------------------------------- entities from XML or YAML

_BOOL = {"true": True, "false": False, "1": True, "0": False}


class _XmlEntity:
    """launch_xml/entity.py: a tag, read attribute by attribute."""

    def __init__(self, element: ElementTree.Element) -> None:
        self._element = element
        self._read_attributes: set[str] = set()
        self._read_children: set[str] = set()
        self.line = int(getattr(element, "line", 0))

    @property
    def type_name(self) -> str:
        return self._element.tag

    @property
    def children(self) -> list[_XmlEntity]:
        self._read_children = {item.tag for item in self._element}
        return [_XmlEntity(item) for item in self._element]

    def assert_entity_completely_parsed(self) -> None:
        unparsed_tags = {item.tag for item in self._element} - self._read_children
        if unparsed_tags:
            raise ValueError(f'Unexpected nested tag(s) found in `{self._element.tag}`: {unparsed_tags}')
        unparsed = set(self._element.attrib) - self._read_attributes
        if unparsed:
            raise ValueError(f'Unexpected attribute(s) found in `{self._element.tag}`: {unparsed}')

    def get_attr(self, name: str, *, data_type: Any = str, optional: bool = False) -> Any:
        missing = AttributeError(f"Attribute '{name}' of type '{data_type}' not found in Entity '{self.type_name}'")
        if data_type is list:  # List[Entity]: the nested tags of that name
            found = [x for x in self._element if x.tag == name]
            if not found:
                if optional:
                    return None
                raise missing
            self._read_children.add(name)
            return [_XmlEntity(x) for x in found]
        if name not in self._element.attrib:
            if optional:
                return None
            raise missing
        self._read_attributes.add(name)
        value = self._element.attrib[name]
        if data_type is bool:
            if value.lower() not in _BOOL:
                raise TypeError(f"Attribute '{name}' of Entity '{self.type_name}' expected to be of type "
                                f"'{data_type}'.'{value}' can not be converted to one of those types")
            return _BOOL[value.lower()]
        if data_type in (None, int, float):  # launch_xml's get_typed_value(value, data_type, can_be_str=True)
            from ._types import coerce_to_type

            return coerce_to_type(value, data_type, can_be_str=True)
        return value


class _YamlEntity:
    """launch_yaml/entity.py: a mapping (or a list of children), read key by key."""

    def __init__(self, element: Any, type_name: str, line: int = 0) -> None:
        self._element = element
        self._type_name = type_name
        self._read_keys: set[str] = set()
        self._children_called = False
        self.line = line or int(getattr(element, "line", 0))

    @property
    def type_name(self) -> str:
        return self._type_name

    @property
    def children(self) -> list[_YamlEntity]:
        self._children_called = True
        if not isinstance(self._element, (dict, list)):
            raise TypeError(f'Expected a dict or list, got {type(self._element)}:\n---\n{self._element}\n---')
        if isinstance(self._element, dict):
            if 'children' not in self._element:
                raise ValueError(f'Expected entity `{self._type_name}` to have children entities.'
                                 'That can be a list of subentities or a dictionary with a `children` '
                                 'list element')
            self._read_keys.add('children')
            children = self._element['children']
        else:
            children = self._element
        entities = []
        for child in children:
            if not isinstance(child, dict) or len(child) != 1:
                raise RuntimeError('Subentities must be a dictionary with only one key, which is the entity type')
            type_name = list(child.keys())[0]
            entities.append(_YamlEntity(child[type_name], type_name, int(getattr(child, "line", 0))))
        return entities

    def assert_entity_completely_parsed(self) -> None:
        if isinstance(self._element, list):
            if not self._children_called:
                raise ValueError(f'Unexpected nested entity(ies) found in `{self._type_name}`: {self._element}')
            return
        unparsed = set(self._element.keys()) - self._read_keys
        if unparsed:
            raise ValueError(f'Unexpected key(s) found in `{self._type_name}`: {unparsed}')

    def get_attr(self, name: str, *, data_type: Any = str, optional: bool = False) -> Any:
        if not isinstance(self._element, dict) or name not in self._element:
            if not optional:
                raise AttributeError(f"Can not find attribute '{name}' in Entity '{self.type_name}'")
            return None
        self._read_keys.add(name)
        data = self._element[name]
        if data_type is list:
            if isinstance(data, list) and data and isinstance(data[0], dict):
                return [_YamlEntity(child, name) for child in data]
            raise TypeError(f"Attribute '{name}' of Entity '{self.type_name}' expected to be a list of dictionaries.")
        from ._types import is_instance_of_valid_type

        if data_type is None:
            ok = is_instance_of_valid_type(data, can_be_str=True)
        else:
            ok = isinstance(data, (data_type, str)) and not (data_type is not bool and isinstance(data, bool)
                                                             and data_type is not str)
        if not ok:
            raise TypeError(f"Attribute '{name}' of Entity '{self.type_name}' expected to be of type "
                            f"'{data_type}', got '{type(data)}'")
        return data


class _LineDict(dict):
    line = 0


class _LineLoader(__import__("yaml").SafeLoader):  # type: ignore[misc]
    """yaml's safe loader, each mapping keeping the line it starts on (for the learner's place)."""

    def construct_mapping(self, node: Any, deep: bool = False) -> Any:
        mapping = _LineDict(super().construct_mapping(node, deep=True))
        mapping.line = node.start_mark.line + 1
        return mapping


_LineLoader.add_constructor(
    "tag:yaml.org,2002:map", lambda loader, node: loader.construct_mapping(node))


def _xml_root(path: str) -> _XmlEntity:
    """The XML as ElementTree elements, each keeping its line (expat's, for the learner's place)."""
    from xml.parsers import expat

    class Lined(ElementTree.Element):  # a subclass has room for the line
        line = 0

    builder = ElementTree.TreeBuilder(element_factory=Lined)
    parser = expat.ParserCreate()

    def start(tag: str, attrs: dict) -> None:
        element = builder.start(tag, attrs)
        element.line = parser.CurrentLineNumber  # type: ignore[attr-defined]

    parser.StartElementHandler = start
    parser.EndElementHandler = builder.end
    parser.CharacterDataHandler = builder.data
    with open(path, "rb") as handle:
        try:
            parser.Parse(handle.read(), True)
        except expat.ExpatError as exc:  # launch_xml reads with ElementTree: its ParseError
            raise ElementTree.ParseError(str(exc)) from None
    return _XmlEntity(builder.close())


def _yaml_root(path: str) -> _YamlEntity:
    from bras_kit.trust import yaml_gate

    with open(path, encoding="utf-8") as handle:
        text = handle.read(yaml_gate.MAX_CHARS + 1)
    data = yaml_gate.load(text, loader=_LineLoader)  # a SafeLoader that keeps line numbers, bounded
    if not isinstance(data, dict) or len(data) != 1:  # launch_yaml/parser.py: one root, 'launch'
        raise RuntimeError('Expected only one root')
    type_name = list(data.keys())[0]
    return _YamlEntity(data[type_name], type_name)


# ---------------------------------------------------------------- one parse per tag, as each action's parse()


def _base(entity: Any, file: str) -> dict[str, Any]:
    """launch/action.py:54 Action.parse: if/unless."""
    from ._conditions import IfCondition, UnlessCondition

    if_cond = entity.get_attr('if', optional=True)
    unless_cond = entity.get_attr('unless', optional=True)
    if if_cond is not None and unless_cond is not None:
        raise RuntimeError("if and unless conditions can't be used simultaneously")
    if if_cond is not None:
        return {"condition": IfCondition(parse_substitution(if_cond, file))}
    if unless_cond is not None:
        return {"condition": UnlessCondition(parse_substitution(unless_cond, file))}
    return {}


def _subs(entity: Any, key: str, file: str, *, optional: bool = False) -> Any:
    value = entity.get_attr(key, optional=optional)
    return None if value is None else parse_substitution(str(value), file)


def _process_options(entity: Any, file: str, kwargs: dict[str, Any], *, with_name: bool = True) -> None:
    """execute_process.py:309 ExecuteProcess.parse: the options bras-kit records or lets pass."""
    for key in ("cwd", "launch-prefix", "output", "respawn"):
        entity.get_attr(key, optional=True)
    if with_name:
        name = entity.get_attr('name', optional=True)
        if name is not None:
            kwargs['name'] = parse_substitution(name, file)
    on_exit = entity.get_attr('on_exit', optional=True)
    if on_exit is not None and on_exit != 'shutdown':
        raise ValueError(f'Attribute on_exit of Entity node expected to be shutdown but got `{on_exit}`'
                         'Other on_exit actions not yet supported')
    for key in ("respawn_max_retries", "respawn_delay", "sigkill_timeout", "sigterm_timeout"):
        entity.get_attr(key, optional=True)
    for key in ("shell", "emulate_tty"):
        entity.get_attr(key, data_type=bool, optional=True)
    env = entity.get_attr('env', data_type=list, optional=True)
    for item in env or []:
        item.get_attr('name')
        item.get_attr('value')
        item.assert_entity_completely_parsed()


def _parameters(params: list, file: str) -> list[Any]:
    """launch_ros/actions/node.py:240 parse_nested_parameters."""
    from launch_ros.parameter_descriptions import ParameterFile, ParameterValue

    types = {"str": str, "int": int, "float": float, "bool": bool}

    def nested(items: list) -> dict:
        out: dict = {}
        for param in items:
            name = tuple(parse_substitution(param.get_attr('name'), file))
            type_identifier = param.get_attr('type', optional=True)
            data_type = None
            if type_identifier is not None:
                if type_identifier not in types:
                    raise ValueError(f"Unrecognized type identifier '{type_identifier}'")  # get_data_type_from_identifier
                data_type = types[type_identifier]
            value = param.get_attr('value', data_type=data_type, optional=True)
            inner = param.get_attr('param', data_type=list, optional=True)
            param.assert_entity_completely_parsed()
            if value is not None and inner:
                raise RuntimeError('nested parameters and value attributes are mutually exclusive')
            if data_type is not None and inner:
                raise RuntimeError('nested parameters and type attributes are mutually exclusive')
            if value is not None:
                out[name] = ParameterValue(parse_if_substitutions(value, file), value_type=data_type)
            elif inner:
                out[name] = nested(inner)
            else:
                raise RuntimeError('either a value attribute or nested params are needed')
        return out

    normalized: list[Any] = []
    for param in params:
        from_attr = param.get_attr('from', optional=True)
        allow_substs = param.get_attr('allow_substs', data_type=bool, optional=True)
        name = param.get_attr('name', optional=True)
        if from_attr is not None and name is not None:
            raise RuntimeError('name and from attributes are mutually exclusive')
        if from_attr is not None:
            param.assert_entity_completely_parsed()
            normalized.append(ParameterFile(parse_substitution(from_attr, file), allow_substs=bool(allow_substs)))
        elif name is not None:
            if allow_substs is not None:
                raise RuntimeError("'allow_substs' can only be used together with 'from' attribute")
            normalized.append(nested([param]))
        else:
            raise ValueError('param Entity should have name or from attribute')
    return normalized


def _node(entity: Any, file: str) -> Any:
    """launch_ros/actions/node.py:305 Node.parse."""
    from launch_ros.actions import Node

    kwargs = _base(entity, file)
    _process_options(entity, file, kwargs)
    args = entity.get_attr('args', optional=True)
    if args is not None:
        kwargs['arguments'] = parse_cmdline(args, file)
    ros_args = entity.get_attr('ros_args', optional=True)
    if ros_args is not None:
        kwargs['ros_arguments'] = parse_cmdline(ros_args, file)
    entity.get_attr('node-name', optional=True)
    name = entity.get_attr('name', optional=True)
    if name is not None:
        kwargs['name'] = parse_substitution(name, file)
    entity.get_attr('exec_name', optional=True)
    package = entity.get_attr('pkg', optional=True)
    if package is not None:
        kwargs['package'] = parse_substitution(package, file)
    kwargs['executable'] = parse_substitution(entity.get_attr('exec'), file)
    namespace = entity.get_attr('namespace', optional=True)
    if namespace is not None:
        kwargs['namespace'] = parse_substitution(namespace, file)
    remappings = entity.get_attr('remap', data_type=list, optional=True)
    if remappings is not None:
        kwargs['remappings'] = [(parse_substitution(r.get_attr('from'), file), parse_substitution(r.get_attr('to'), file))
                                for r in remappings]
        for remap in remappings:
            remap.assert_entity_completely_parsed()
    parameters = entity.get_attr('param', data_type=list, optional=True)
    if parameters is not None:
        kwargs['parameters'] = _parameters(parameters, file)
    return Node(**kwargs)


def _executable(entity: Any, file: str) -> Any:
    """execute_process.py:309 ExecuteProcess.parse (the <executable> tag)."""
    from ._actions import ExecuteProcess

    kwargs = _base(entity, file)
    kwargs['cmd'] = parse_cmdline(entity.get_attr('cmd'), file)
    _process_options(entity, file, kwargs)
    kwargs.pop('name', None)
    return ExecuteProcess(**kwargs)


def _include(entity: Any, file: str) -> Any:
    """include_launch_description.py:85 IncludeLaunchDescription.parse."""
    from ._actions import IncludeLaunchDescription
    from ._sources import AnyLaunchDescriptionSource

    kwargs = _base(entity, file)
    path = parse_substitution(entity.get_attr('file'), file)
    args = entity.get_attr('arg', data_type=list, optional=True)
    if args is not None:
        kwargs['launch_arguments'] = [(parse_substitution(e.get_attr('name'), file),
                                       parse_substitution(e.get_attr('value'), file)) for e in args]
        for e in args:
            e.assert_entity_completely_parsed()
    return IncludeLaunchDescription(AnyLaunchDescriptionSource(path), **kwargs)


def _group(entity: Any, file: str) -> Any:
    """group_action.py:90 GroupAction.parse."""
    from ._actions import GroupAction

    kwargs = _base(entity, file)
    scoped = entity.get_attr('scoped', data_type=bool, optional=True)
    forwarding = entity.get_attr('forwarding', data_type=bool, optional=True)
    keeps = entity.get_attr('keep', data_type=list, optional=True)
    if scoped is not None:
        kwargs['scoped'] = scoped
    if forwarding is not None:
        kwargs['forwarding'] = forwarding
    if keeps is not None:
        kwargs['launch_configurations'] = {tuple(parse_substitution(e.get_attr('name'), file)):
                                           parse_substitution(e.get_attr('value'), file) for e in keeps}
        for e in keeps:
            e.assert_entity_completely_parsed()
    return GroupAction([_parse_action(e, file) for e in entity.children if e.type_name != 'keep'], **kwargs)


def _timer(entity: Any, file: str) -> Any:
    from ._actions import TimerAction

    kwargs = _base(entity, file)
    period = parse_if_substitutions(entity.get_attr('period'), file)
    if isinstance(period, str):
        period = float(period)
    actions = [_parse_action(child, file) for child in entity.children]
    entity.get_attr('cancel_on_shutdown', optional=True)
    return TimerAction(period=period, actions=actions, **kwargs)


def _arg(entity: Any, file: str) -> Any:
    from ._actions import DeclareLaunchArgument

    kwargs = _base(entity, file)
    name = entity.get_attr('name')
    default = entity.get_attr('default', optional=True)
    description = entity.get_attr('description', optional=True)
    choices = entity.get_attr('choice', data_type=list, optional=True)
    return DeclareLaunchArgument(str(name), default_value=None if default is None else parse_substitution(default, file),
                                 description=description,
                                 choices=None if choices is None else [c.get_attr('value') for c in choices], **kwargs)


def _simple(factory_name: str, *keys: str) -> Any:
    """Actions built from substitution attributes only (let, log, set_env, set_parameter, ...)."""

    def parse(entity: Any, file: str) -> Any:
        from launch_ros import actions as ros_actions

        from . import _actions

        factory = getattr(_actions, factory_name, None) or getattr(ros_actions, factory_name)
        kwargs = _base(entity, file)
        values = [parse_substitution(entity.get_attr(k), file) for k in keys]
        if factory_name == "LogInfo":
            return factory(msg=values[0], **kwargs)
        return factory(*values, **kwargs)

    return parse


_TAGS = {  # launch/frontend/expose.py: the names each action is exposed under
    "node": _node, "executable": _executable, "include": _include, "group": _group, "timer": _timer,
    "arg": _arg, "let": _simple("SetLaunchConfiguration", "name", "value"), "log": _simple("LogInfo", "message"),
    "set_env": _simple("SetEnvironmentVariable", "name", "value"),
    "append_env": _simple("AppendEnvironmentVariable", "name", "value"),
    "unset_env": _simple("UnsetEnvironmentVariable", "name"),
    "push-ros-namespace": _simple("PushROSNamespace", "namespace"),
    "push_ros_namespace": _simple("PushROSNamespace", "namespace"),
    "set_parameter": _simple("SetParameter", "name", "value"), "set_remap": _simple("SetRemap", "from", "to"),
}


def _parse_action(entity: Any, file: str) -> Any:
    """expose.py:37 instantiate_action, then the wrapper's assert_entity_completely_parsed (line 108)."""
    _plan.CURRENT = (file, entity.line)
    parse = _TAGS.get(entity.type_name)
    if parse is None:
        raise RuntimeError(f'Unrecognized entity of the type: {entity.type_name}')
    action = parse(entity, file)
    entity.assert_entity_completely_parsed()
    return action


def get_launch_description_from_frontend_launch_file(path: str) -> LaunchDescription:
    """frontend/parser.py:226 Parser.load — the reader the extension names (``.xml``,
    ``.yaml``/``.yml``), then the other, each failure to *read* kept (lines 246-260) — then
    parse_description (line 128), whose errors stop the launch as they are."""
    loaders = [_xml_root, _yaml_root]
    if path.endswith((".yaml", ".yml")):
        loaders.reverse()
    errors: list[BaseException] = []
    root: Any = None
    for loader in loaders:
        try:
            root = loader(path)
            break
        except Exception as exc:  # noqa: BLE001 - kept, as parser.py keeps it
            errors.append(exc)
    else:
        extension = os.path.splitext(path)[1][1:] if path.endswith((".xml", ".yaml", ".yml")) else ''
        raise InvalidFrontendLaunchFileError(extension, likely_errors=errors)
    if root.type_name != 'launch':
        raise RuntimeError("Expected 'launch' as root tag")
    root.get_attr('deprecated', optional=True)
    description = LaunchDescription([_parse_action(child, path) for child in root.children])
    _plan.CURRENT = None
    return description
