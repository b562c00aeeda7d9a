"""launch/utilities/type_utils.py (Jazzy 3.4.3): how a value's text becomes a typed value.

A parameter value without a type (XML ``<param value="..."/>`` without ``type=``, YAML without
``type:``, ``ParameterValue(x)`` without ``value_type``) is read with YAML rules once its
substitutions are performed (``coerce_to_type(value, None)``, line 255): a URDF whose text YAML
cannot read stops the launch with "Failed to convert '...' using yaml rules: yaml.safe_load()
failed" (line 244).
"""

from __future__ import annotations

from typing import Any

import yaml

SCALAR_TYPES = (int, float, bool, str)  # type_utils.py ScalarTypesTuple


def is_instance_of_valid_type(value: Any, *, can_be_str: bool = False) -> bool:
    """type_utils.py:165"""
    if isinstance(value, list):
        if not value:
            return True
        member_type = next((type(x) for x in value if type(x) is not str), str)
        if member_type not in SCALAR_TYPES:
            return False
        valid_types = (member_type, str) if can_be_str else member_type
        return all(isinstance(x, valid_types) for x in value)
    return isinstance(value, SCALAR_TYPES)


def _list_of(data_type: Any) -> Any:
    """List[int] -> int (type_utils.py extract_type), else None."""
    args = getattr(data_type, "__args__", None)
    return args[0] if getattr(data_type, "__origin__", None) is list and args else None


def coerce_to_type(value: str, data_type: Any = None, *, can_be_str: bool = False) -> Any:
    """type_utils.py:211, word for word in its failures."""

    def convert_as_yaml(text: str, error_msg: str) -> Any:
        if not text:
            return text
        from bras_kit.trust import yaml_gate

        try:
            output = yaml_gate.load(text, loader=yaml.SafeLoader)
        except Exception as err:  # noqa: BLE001 - type_utils.py:241 catches every error of the reader
            if can_be_str:
                return text
            raise ValueError(f'{error_msg}: yaml.safe_load() failed\n{err}') from None
        if not is_instance_of_valid_type(output, can_be_str=can_be_str):
            raise ValueError(f'{error_msg}: output type is not allowed, got {type(output)}')
        return output

    if not isinstance(value, str):
        raise TypeError(f"Expected 'value' to be of type '{str}', got '{type(value)}'")  # ensure_argument_type
    if data_type is None:
        return convert_as_yaml(value, f"Failed to convert '{value}' using yaml rules")
    member = _list_of(data_type)
    type_obj = member if member is not None else data_type
    valid_types = (str, type_obj) if can_be_str else type_obj
    if member is not None:
        output = convert_as_yaml(value, f"Cannot convert value '{value}' to a list of '{valid_types}'")
        if not isinstance(output, list):
            raise ValueError(f"Cannot convert value '{value}' to a list of '{valid_types}'")
        if not all(isinstance(x, valid_types) for x in output):
            raise ValueError(f"Cannot convert value '{value}' to a list of '{valid_types}', got {output}")
        return output
    if type_obj is str:
        return value
    if type_obj in (int, float):
        try:
            return type_obj(value)
        except ValueError:
            if can_be_str:
                return value
            raise
    if type_obj is bool:
        value = {"1": "true", "0": "false"}.get(value, value)
    else:
        raise ValueError('data_type is invalid. Expected one of: int, float, str, bool, List[int], List[float], '
                         f'List[str], List[bool]. Got {data_type}')
    output = convert_as_yaml(value, f"Failed to convert '{value}' to '{type_obj}'")
    if isinstance(output, valid_types):
        return output
    raise ValueError(f"Cannot convert value '{value}' to '{type_obj}'")
