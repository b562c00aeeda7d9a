"""Message classes shaped like the ones rosidl_generator_py makes (``resource/_msg.py.em``).

Each field is a property whose setter checks the value the way the generated code asserts it
(``The 'position' field must be a set or sequence and each value of type 'float' ...``);
float sequences are stored as ``array.array('d')``; ``__slots__`` makes a misspelt field an
``AttributeError``; the constructor refuses unknown keyword arguments.
"""

from __future__ import annotations

import array
import importlib
import math
from collections import UserList, UserString
from collections.abc import Sequence, Set

DOUBLE_BOUND = 1.7976931348623157e+308
FLOAT_BOUND = 3.402823466e+38
INT_BOUNDS = {"int8": (-2**7, 2**7), "int16": (-2**15, 2**15), "int32": (-2**31, 2**31),
              "int64": (-2**63, 2**63), "uint8": (0, 2**8), "uint16": (0, 2**16),
              "uint32": (0, 2**32), "uint64": (0, 2**64)}


def _is_sequence(value) -> bool:
    return ((isinstance(value, Sequence) or isinstance(value, Set) or isinstance(value, UserList))
            and not isinstance(value, str) and not isinstance(value, UserString))


def _check(name: str, kind: str, value):
    """The value to store, or AssertionError with the generated code's words."""
    if kind.endswith("[]"):
        base = kind[:-2]
        if base in ("float64", "float32") and isinstance(value, array.array):
            assert value.typecode == ("d" if base == "float64" else "f"), \
                f"The '{name}' array.array() must have the type code of '{'d' if base == 'float64' else 'f'}'"
            return value
        if base in ("float64", "float32"):
            bound = DOUBLE_BOUND if base == "float64" else FLOAT_BOUND
            word = "double" if base == "float64" else "float"
            assert (_is_sequence(value) and all(isinstance(v, float) for v in value)
                    and all(not (v < -bound or v > bound) or math.isinf(v) for v in value)), \
                (f"The '{name}' field must be a set or sequence and each value of type 'float' "
                 f"and each {word} in [{-bound:f}, {bound:f}]")
            return array.array("d" if base == "float64" else "f", value)
        if base == "string":
            assert _is_sequence(value) and all(isinstance(v, str) for v in value), \
                f"The '{name}' field must be a set or sequence and each value of type 'str'"
            return value
        if base in INT_BOUNDS:
            low, high = INT_BOUNDS[base]
            assert (_is_sequence(value) and all(isinstance(v, int) for v in value)
                    and all(low <= v < high for v in value)), \
                (f"The '{name}' field must be a set or sequence and each value of type 'int' "
                 f"and each {'unsigned ' if low == 0 else ''}integer in [{low}, {high - 1}]")
            return value
        message_class = _message_class(base)
        assert _is_sequence(value) and all(isinstance(v, message_class) for v in value), \
            f"The '{name}' field must be a set or sequence and each value of type '{message_class.__name__}'"
        return value
    if kind in ("float64", "float32"):
        bound = DOUBLE_BOUND if kind == "float64" else FLOAT_BOUND
        assert isinstance(value, float), f"The '{name}' field must be of type 'float'"
        assert not (value < -bound or value > bound) or math.isinf(value), \
            f"The '{name}' field must be a {'double' if kind == 'float64' else 'float'} in [{-bound}, {bound}]"
        return value
    if kind in INT_BOUNDS:
        low, high = INT_BOUNDS[kind]
        assert isinstance(value, int), f"The '{name}' field must be of type 'int'"
        if low == 0:
            assert low <= value < high, f"The '{name}' field must be an unsigned integer in [0, {high - 1}]"
        else:
            assert low <= value < high, f"The '{name}' field must be an integer in [{low}, {high - 1}]"
        return value
    if kind == "string":
        assert isinstance(value, str), f"The '{name}' field must be of type 'str'"
        return value
    if kind == "bool":
        assert isinstance(value, bool), f"The '{name}' field must be of type 'bool'"
        return value
    message_class = _message_class(kind)
    assert isinstance(value, message_class), \
        f"The '{name}' field must be a sub message of type '{message_class.__name__}'"
    return value


def _message_class(kind: str):
    package, name = kind.split("/")
    return getattr(importlib.import_module(f"{package}.msg"), name)


def _default(kind: str):
    if kind.endswith("[]"):
        return array.array("d") if kind[:-2] in ("float64", "float32") else []
    if kind in ("float64", "float32"):
        return 0.0
    if kind in INT_BOUNDS:
        return 0
    if kind == "string":
        return ""
    if kind == "bool":
        return False
    return _message_class(kind)()


def _property(name: str, kind: str) -> property:
    def getter(self):
        return getattr(self, "_" + name)

    def setter(self, value) -> None:
        object.__setattr__(self, "_" + name, _check(name, kind, value))

    getter.__doc__ = f"Message field '{name}'."
    return property(getter, setter)


class _Metaclass(type):
    """Like the generated metaclasses: the class knows its type name."""


def message(package: str, name: str, fields: list[tuple[str, str]], constants: dict | None = None,
            defaults: dict | None = None) -> type:
    """A message class ``package/msg/name`` with ``fields`` [(field, kind)], kinds as in .msg files;
    ``defaults`` for fields whose .msg gives a default value (Quaternion's w = 1)."""
    defaults = defaults or {}
    slots = ["_" + field for field, _ in fields] + ["_check_fields"]

    def __init__(self, **kwargs) -> None:
        assert all("_" + key in self.__slots__ for key in kwargs.keys()), \
            "Invalid arguments passed to constructor: " + ", ".join(
                sorted(k for k in kwargs.keys() if "_" + k not in self.__slots__))
        object.__setattr__(self, "_check_fields", True)
        for field, kind in fields:
            if field in kwargs:
                setattr(self, field, kwargs[field])
            else:
                object.__setattr__(self, "_" + field, defaults[field] if field in defaults else _default(kind))

    def __repr__(self) -> str:
        args = ", ".join(f"{field}={getattr(self, field)!r}" for field, _ in fields)
        return f"{package}.msg.{name}({args})"

    def __eq__(self, other) -> bool:
        if not isinstance(other, self.__class__):
            return False
        return all(getattr(self, field) == getattr(other, field) for field, _ in fields)

    @classmethod  # type: ignore[misc]
    def get_fields_and_field_types(cls) -> dict:
        return {field: kind.replace("float64", "double").replace("float32", "float")
                for field, kind in fields}

    namespace: dict = {"__slots__": slots, "__init__": __init__, "__repr__": __repr__, "__eq__": __eq__,
                       "__hash__": None, "__module__": f"{package}.msg",
                       "get_fields_and_field_types": get_fields_and_field_types,
                       "_fields_and_field_types": dict(fields), "_type_name": f"{package}/msg/{name}"}
    for field, kind in fields:
        namespace[field] = _property(field, kind)
    namespace.update(constants or {})
    return _Metaclass(name, (), namespace)


def type_name(message_class) -> str | None:
    return getattr(message_class, "_type_name", None)


def to_data(value):
    """A message as plain data (dicts, lists, numbers), for the recording."""
    fields = getattr(type(value), "_fields_and_field_types", None)
    if fields is not None:
        return {field: to_data(getattr(value, field)) for field in fields}
    if isinstance(value, array.array):
        return list(value)
    if isinstance(value, (list, tuple)):
        return [to_data(v) for v in value]
    return value
