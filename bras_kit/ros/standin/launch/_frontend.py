"""launch_xml and launch_yaml (Jazzy) for the tags beginners write: the file becomes the same
actions and substitutions as a Python launch file (launch/frontend/parser.py maps each tag to the
action's ``parse``). Substitutions ``$(var)``, ``$(find-pkg-share)``, ``$(find-pkg-prefix)``,
``$(command)``, ``$(env)``, ``$(eval)``, ``$(dirname)``, ``$(anon)`` nest as in
launch/frontend/grammar.lark."""

from __future__ import annotations

import os
import xml.etree.ElementTree as ElementTree
from typing import Any

from ._core import LaunchDescription, Substitution, SubstitutionFailure, TextSubstitution


class InvalidFrontendLaunchFileError(Exception):
    pass


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


# ---------------------------------------------------------------- entities from XML or YAML


class _Entity:
    """launch/frontend/entity.py: a tag, its attributes and children."""

    def __init__(self, tag: str, attributes: dict[str, Any], children: list[_Entity], line: int = 0) -> None:
        self.tag, self.attributes, self.children, self.line = tag, attributes, children, line


def _xml_entities(path: str) -> _Entity:
    def convert(element: ElementTree.Element) -> _Entity:
        return _Entity(element.tag, dict(element.attrib), [convert(c) for c in element])

    root = ElementTree.parse(path).getroot()
    if root.tag != "launch":
        raise InvalidFrontendLaunchFileError(f"expected a <launch> root, got <{root.tag}>")
    return convert(root)


def _yaml_entities(path: str) -> _Entity:
    import yaml

    with open(path, encoding="utf-8") as handle:
        data = yaml.safe_load(handle)
    if not isinstance(data, dict) or "launch" not in data:
        raise InvalidFrontendLaunchFileError("expected a 'launch' key at the top")

    def convert(tag: str, value: Any) -> _Entity:
        if isinstance(value, list):  # a list of one-key dicts: children
            return _Entity(tag, {}, [convert(*next(iter(item.items()))) for item in value if isinstance(item, dict)])
        attributes, children = {}, []
        for key, item in (value or {}).items():
            if key in ("param", "remap", "arg") and isinstance(item, list):
                children += [_Entity(key, dict(x), []) for x in item if isinstance(x, dict)]
            elif key == "children" and isinstance(item, list):
                children += [convert(*next(iter(x.items()))) for x in item if isinstance(x, dict)]
            else:
                attributes[key] = item
        return _Entity(tag, attributes, children)

    return convert("launch", data["launch"])


def _subs(entity: _Entity, key: str, launch_file: str, default: Any = None) -> Any:
    value = entity.attributes.get(key)
    if value is None:
        return default
    return parse_substitution(str(value), launch_file)


def _condition(entity: _Entity, launch_file: str) -> Any:
    from ._conditions import IfCondition, UnlessCondition

    if "if" in entity.attributes:
        return IfCondition(_subs(entity, "if", launch_file))
    if "unless" in entity.attributes:
        return UnlessCondition(_subs(entity, "unless", launch_file))
    return None


def _action(entity: _Entity, launch_file: str) -> Any:  # noqa: C901 - one branch per tag, as parser.py's table
    from launch_ros.actions import Node, PushROSNamespace, SetParameter, SetRemap
    from launch_ros.parameter_descriptions import ParameterFile, ParameterValue

    from . import _actions as actions
    from ._sources import AnyLaunchDescriptionSource

    tag = entity.tag.replace("-", "_")
    condition = _condition(entity, launch_file)
    if tag == "arg":
        return actions.DeclareLaunchArgument(
            str(entity.attributes["name"]), default_value=_subs(entity, "default", launch_file),
            description=entity.attributes.get("description"), condition=condition)
    if tag == "let":
        return actions.SetLaunchConfiguration(str(entity.attributes["name"]), _subs(entity, "value", launch_file),
                                              condition=condition)
    if tag == "node":
        parameters: list[Any] = []
        remappings = []
        for child in entity.children:
            if child.tag == "param" and "from" in child.attributes:
                parameters.append(ParameterFile(_subs(child, "from", launch_file)))
            elif child.tag == "param":
                value_type = {"str": str, "int": int, "float": float, "bool": bool}.get(
                    str(child.attributes.get("type", "")))
                value = _subs(child, "value", launch_file, [TextSubstitution(text="")])
                parameters.append({str(child.attributes["name"]): ParameterValue(value, value_type=value_type)})
            elif child.tag == "remap":
                remappings.append((_subs(child, "from", launch_file), _subs(child, "to", launch_file)))
        args = entity.attributes.get("args")
        return Node(package=_subs(entity, "pkg", launch_file), executable=_subs(entity, "exec", launch_file),
                    name=_subs(entity, "name", launch_file), namespace=_subs(entity, "namespace", launch_file),
                    parameters=parameters, remappings=remappings,
                    arguments=[parse_substitution(a, launch_file) for a in str(args).split()] if args else None,
                    condition=condition)
    if tag == "include":
        launch_arguments = [(str(c.attributes["name"]), _subs(c, "value", launch_file))
                            for c in entity.children if c.tag == "arg"]
        return actions.IncludeLaunchDescription(AnyLaunchDescriptionSource(_subs(entity, "file", launch_file)),
                                                launch_arguments=launch_arguments, condition=condition)
    if tag == "group":
        scoped = str(entity.attributes.get("scoped", "true")).lower() != "false"
        return actions.GroupAction([_action(c, launch_file) for c in entity.children], scoped=scoped,
                                   condition=condition)
    if tag == "push_ros_namespace":
        return PushROSNamespace(_subs(entity, "namespace", launch_file), condition=condition)
    if tag == "set_parameter":
        return SetParameter(str(entity.attributes["name"]), _subs(entity, "value", launch_file), condition=condition)
    if tag == "set_remap":
        return SetRemap(_subs(entity, "from", launch_file), _subs(entity, "to", launch_file), condition=condition)
    if tag == "timer":
        return actions.TimerAction(period=float(entity.attributes.get("period", 0)),
                                   actions=[_action(c, launch_file) for c in entity.children], condition=condition)
    if tag == "log":
        return actions.LogInfo(msg=_subs(entity, "message", launch_file), condition=condition)
    if tag in ("executable", "exec"):
        return actions.ExecuteProcess(cmd=[parse_substitution(w, launch_file)
                                           for w in str(entity.attributes.get("cmd", "")).split()],
                                      condition=condition)
    if tag == "set_env":
        return actions.SetEnvironmentVariable(_subs(entity, "name", launch_file), _subs(entity, "value", launch_file),
                                              condition=condition)
    raise InvalidFrontendLaunchFileError(f"Unrecognized entity of the type: {entity.tag}")


def get_launch_description_from_frontend_launch_file(path: str) -> LaunchDescription:
    if path.endswith((".yaml", ".yml")):
        root = _yaml_entities(path)
    elif path.endswith(".xml"):
        root = _xml_entities(path)
    else:
        raise InvalidFrontendLaunchFileError(
            f"The launch file may have a syntax error, or its format is unknown: {path}")
    return LaunchDescription([_action(child, path) for child in root.children])
