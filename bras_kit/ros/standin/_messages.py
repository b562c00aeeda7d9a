"""Message packages made at import time from Jazzy's own definitions, with Jazzy's Python setters.

The definitions are rosbags' Jazzy type store (``rosbags.typesys.Stores.ROS2_JAZZY``: the
.msg files of common_interfaces, rcl_interfaces, geometry2's tf2_msgs...). Each class behaves
like the one rosidl_generator_py (Jazzy, 0.22) writes from ``resource/_msg.py.em``:

- a setter checks nothing unless ``ROS_PYTHON_CHECK_FIELDS=1`` (``_idl.py.em:10``,
  ``_msg.py.em:297-300, 440``); numeric sequences are stored as ``array.array(code, value)``
  (``_msg.py.em:604``), so ``[0, 0]``, a tuple or a numpy array are all taken;
  fixed-size numeric arrays are numpy arrays (``_msg.py.em:602``);
- with the check on, the asserts and their words are the template's (``_msg.py.em:440-600``);
- unknown constructor keywords are refused only when checking (``_msg.py.em:301-304``);
- what the setter let through is checked when the message is published, by the C conversion
  (``_msg_support.c.em``): a float field holding an ``int`` fails ``assert(PyFloat_Check(field))``
  (line 485) and the process aborts. :func:`convert_check` says which field would.
"""

from __future__ import annotations

import array
import importlib.abc
import importlib.machinery
import math
import os
import re
import types
from collections import UserList, UserString
from collections.abc import Sequence, Set
from typing import Any

# rosidl_generator_py/generate_py_impl.py:42 SPECIAL_NESTED_BASIC_TYPES
TYPE_CODES = {"float32": "f", "float64": "d", "int8": "b", "uint8": "B", "int16": "h", "uint16": "H",
              "int32": "i", "uint32": "I", "int64": "q", "uint64": "Q"}
DTYPES = {"float32": "float32", "float64": "float64", "int8": "int8", "uint8": "uint8", "int16": "int16",
          "uint16": "uint16", "int32": "int32", "uint32": "uint32", "int64": "int64", "uint64": "uint64"}
FLOATS = ("float32", "float64")
FLOAT_BOUND = {"float32": 3.402823466e+38, "float64": 1.7976931348623157e+308}
IDL_NAMES = {"float64": "double", "float32": "float", "bool": "boolean", "byte": "octet", "char": "uint8"}
# .msg default values rosbags' field definitions do not carry (geometry_msgs/msg/Quaternion.msg: "float64 w 1")
DEFAULTS = {("geometry_msgs/msg/Quaternion", "w"): 1.0}

# _idl.py.em:10: read once, when the generated module is imported
CHECK_FIELDS = os.environ.get("ROS_PYTHON_CHECK_FIELDS", "") == "1"

_STORE: dict | None = None


def definitions() -> dict:
    """``{"sensor_msgs/msg/JointState": (constants, fields)}`` of Jazzy."""
    global _STORE
    if _STORE is None:
        from rosbags.typesys import Stores, get_typestore

        _STORE = dict(get_typestore(Stores.ROS2_JAZZY).fielddefs)
    return _STORE


# Services, which rosbags' store does not hold: the .srv files of Jazzy's common_interfaces
# (std_srvs/srv/*.srv, 5.3.6), request and response, read with rosbags' .msg parser
SERVICES = {
    "std_srvs/srv/Empty": ("", ""),
    "std_srvs/srv/SetBool": ("bool data", "bool success\nstring message"),
    "std_srvs/srv/Trigger": ("", "bool success\nstring message"),
}


def service_definitions() -> dict:
    """``{"std_srvs/srv/SetBool_Request": (constants, fields), ...}`` of Jazzy."""
    from rosbags.typesys import get_types_from_msg

    out = {}
    for service, (request, response) in SERVICES.items():
        package, _, name = service.split("/")
        for part, text in (("Request", request), ("Response", response)):
            parsed = get_types_from_msg(text, f"{package}/msg/{name}_{part}")
            out[f"{service}_{part}"] = next(iter(parsed.values()))
    return out


def packages() -> set[str]:
    return {name.split("/")[0] for name in definitions()} | {name.split("/")[0] for name in SERVICES}


def _service_class(service: str, request: type, response: type) -> type:
    """What rosidl_generator_py writes for a .srv (``_srv.py.em``): a class holding Request and
    Response; the node's create_service/create_client take it."""
    package, _, name = service.split("/")
    return type(name, (), {"Request": request, "Response": response, "_type_name": service,
                           "_TYPE_SUPPORT": service, "__module__": f"{package}.srv._{_snake(name)}",
                           "__doc__": f"Service class '{name}'."})


def _snake(name: str) -> str:
    return re.sub(r"(?<=[a-z0-9])(?=[A-Z])|(?<=[A-Z])(?=[A-Z][a-z])", "_", name).lower()


def message_class(type_name: str) -> type:
    package, _, name = type_name.split("/")
    return getattr(importlib_module(f"{package}.msg"), name)


def importlib_module(name: str) -> types.ModuleType:
    import importlib

    return importlib.import_module(name)


# ---------------------------------------------------------------- field kinds


class Kind:
    """One field's type: ``base`` ("float64", "string", "std_msgs/msg/Header"), ``nested``
    ("" for a scalar, "sequence" or "array") and ``size`` (array size or sequence/string bound)."""

    __slots__ = ("base", "nested", "size", "string_bound", "_class")

    def __init__(self, definition: tuple) -> None:
        node, detail = definition
        self.nested, self.size, self.string_bound = "", 0, 0
        self._class: type | None = None
        if node.name in ("SEQUENCE", "ARRAY"):
            self.nested = "sequence" if node.name == "SEQUENCE" else "array"
            (node, detail), self.size = detail
        if node.name == "NAME":
            self.base = detail
        else:
            self.base, self.string_bound = detail

    @property
    def is_message(self) -> bool:
        return "/" in self.base

    def idl(self) -> str:
        """The type as ``get_fields_and_field_types()`` names it (``_msg.py.em:215-250``)."""
        if self.is_message:
            package, _, name = self.base.split("/")
            base = f"{package}/{name}"
        else:
            base = IDL_NAMES.get(self.base, self.base)
            if self.string_bound:
                base += f"<{self.string_bound}>"
        if self.nested == "sequence":
            return f"sequence<{base}, {self.size}>" if self.size else f"sequence<{base}>"
        if self.nested == "array":
            return f"{base}[{self.size}]"
        return base

    def python_type(self) -> type:
        if self.base in FLOATS:
            return float
        if self.base == "bool":
            return bool
        if self.base in ("string", "wstring"):
            return str
        if self.base == "byte":
            return bytes
        if self.is_message:
            if self._class is None:
                self._class = message_class(self.base)
            return self._class
        return int

    def default(self) -> object:
        if self.nested == "array":
            if self.base in TYPE_CODES:
                import numpy

                return numpy.zeros(self.size, dtype=DTYPES[self.base])
            return [self._scalar_default() for _ in range(self.size)]
        if self.nested == "sequence":
            return array.array(TYPE_CODES[self.base]) if self.base in TYPE_CODES else []
        return self._scalar_default()

    def _scalar_default(self) -> object:
        if self.base == "byte":
            return bytes([0])
        return self.python_type()()

    def store(self, value: Any) -> object:
        """What the setter keeps (``_msg.py.em:600-606``)."""
        if self.base in TYPE_CODES and self.nested == "array":
            import numpy

            return numpy.array(value, dtype=DTYPES[self.base])
        if self.base in TYPE_CODES and self.nested == "sequence":
            return array.array(TYPE_CODES[self.base], value)
        return value


def _is_sequence(value: object) -> bool:
    return ((isinstance(value, (Sequence, Set, UserList))) and not isinstance(value, (str, UserString)))


def _assert_field(name: str, kind: Kind, value: Any) -> bool:
    """The setter's asserts under ROS_PYTHON_CHECK_FIELDS=1 (``_msg.py.em:440-598``); True when the
    value was an array of the right code or dtype, which the setter keeps as it is."""
    if kind.nested and kind.base in TYPE_CODES:
        if kind.nested == "array" and type(value).__name__ == "ndarray":
            assert str(value.dtype) == DTYPES[kind.base], \
                f"The '{name}' numpy.ndarray() must have the dtype of 'numpy.{DTYPES[kind.base]}'"
            assert value.size == kind.size, f"The '{name}' numpy.ndarray() must have a size of {kind.size}"
            return True
        if kind.nested == "sequence" and isinstance(value, array.array):
            assert value.typecode == TYPE_CODES[kind.base], \
                f"The '{name}' array.array() must have the type code of '{TYPE_CODES[kind.base]}'"
            if kind.size:
                assert len(value) <= kind.size, f"The '{name}' array.array() must have a size <= {kind.size}"
            return True
    python = kind.python_type()
    if kind.nested:
        suffixes = ["a set or sequence"]
        ok = _is_sequence(value)
        items: list[Any] = list(value) if ok else []
        if kind.string_bound:
            ok = ok and all(len(v) <= kind.string_bound for v in items)
            suffixes.append(f"and each string value not longer than {kind.string_bound}")
        if kind.nested == "array":
            ok = ok and len(items) == kind.size
            suffixes.insert(1, f"with length {kind.size}")
        elif kind.size:
            ok = ok and len(items) <= kind.size
            suffixes.insert(1, f"with length <= {kind.size}")
        ok = ok and all(isinstance(v, python) for v in items)
        suffixes.append(f"and each value of type '{python.__name__}'")
        if kind.base in TYPE_CODES and kind.base not in FLOATS:
            bits = int(kind.base.lstrip("uint"))
            low, high = (0, 2**bits) if kind.base.startswith("u") else (-(2**(bits - 1)), 2**(bits - 1))
            ok = ok and all(low <= v < high for v in items)
            suffixes.append(f"and each {'unsigned ' if low == 0 else ''}integer in [{low}, {high - 1}]")
        elif kind.base in FLOATS:
            bound = FLOAT_BOUND[kind.base]
            ok = ok and all(not (v < -bound or v > bound) or math.isinf(v) for v in items)
            suffixes.append(f"and each {'float' if kind.base == 'float32' else 'double'} in [{-bound:f}, {bound:f}]")
        assert ok, f"The '{name}' field must be {' '.join(suffixes)}"
        return False
    if kind.is_message:
        assert isinstance(value, python), f"The '{name}' field must be a sub message of type '{python.__name__}'"
        return False
    if kind.string_bound:
        assert isinstance(value, (str, UserString)) and len(value) <= kind.string_bound, \
            f"The '{name}' field must be string value not longer than {kind.string_bound}"
        return False
    if kind.base == "byte":
        assert isinstance(value, bytes) and len(value) == 1, \
            f"The '{name}' field must be of type 'bytes' or 'ByteString' with length 1"
        return False
    assert isinstance(value, python), f"The '{name}' field must be of type '{python.__name__}'"
    number: Any = value
    if kind.base in FLOATS:
        bound = FLOAT_BOUND[kind.base]
        assert not (number < -bound or number > bound) or math.isinf(number), \
            f"The '{name}' field must be a {'float' if kind.base == 'float32' else 'double'} in [{-bound}, {bound}]"
    elif kind.base in TYPE_CODES:
        bits = int(kind.base.lstrip("uint"))
        if kind.base.startswith("u"):
            assert 0 <= number < 2**bits, f"The '{name}' field must be an unsigned integer in [0, {2**bits - 1}]"
        else:
            assert -(2**(bits - 1)) <= number < 2**(bits - 1), \
                f"The '{name}' field must be an integer in [{-(2**(bits - 1))}, {2**(bits - 1) - 1}]"
    return False


def _property(name: str, kind: Kind) -> property:
    slot = "_" + name

    def getter(self):
        return getattr(self, slot)

    def setter(self, value) -> None:
        if self._check_fields and _assert_field(name, kind, value):
            object.__setattr__(self, slot, value)
            return
        object.__setattr__(self, slot, kind.store(value))

    getter.__doc__ = f"Message field '{name}'."
    return property(getter, setter)


def _make_class(type_name: str, constants: list, fields: list) -> type:
    package, _, name = type_name.split("/")
    # std_msgs/msg/Empty: rosidl adds one uint8 member that the Python class leaves out (_msg.py.em:207)
    kinds = {field: Kind(definition) for field, definition in fields
             if not (len(fields) == 1 and field == "structure_needs_at_least_one_member")}

    def __init__(self, **kwargs) -> None:
        object.__setattr__(self, "_check_fields", kwargs["check_fields"] if "check_fields" in kwargs
                           else CHECK_FIELDS)
        if self._check_fields:
            assert all("_" + key in self.__slots__ for key in kwargs.keys()), \
                "Invalid arguments passed to constructor: %s" % ", ".join(  # noqa: UP031 - _msg.py.em:303
                    sorted(k for k in kwargs.keys() if "_" + k not in self.__slots__))
        for field, kind in kinds.items():
            if field in kwargs:
                setattr(self, field, kwargs[field])
            elif (type_name, field) in DEFAULTS:
                setattr(self, field, DEFAULTS[(type_name, field)])
            else:
                object.__setattr__(self, "_" + field, kind.default())

    def __repr__(self) -> str:
        args = []
        for field, kind in kinds.items():
            text = repr(getattr(self, field))
            if kind.nested == "sequence" and kind.base in TYPE_CODES:
                text = "[]" if not len(getattr(self, field)) else text[len("array('X', "):-1]
            args.append(f"{field}={text}")
        return f"{package}.msg.{name}({', '.join(args)})"

    def __eq__(self, other) -> bool:
        if not isinstance(other, self.__class__):
            return False
        for field, kind in kinds.items():
            mine, theirs = getattr(self, field), getattr(other, field)
            if kind.nested == "array" and kind.base in TYPE_CODES:
                if not all(mine == theirs):
                    return False
            elif mine != theirs:
                return False
        return True

    def get_fields_and_field_types(cls) -> dict:
        return dict(cls._fields_and_field_types)

    namespace: dict = {
        "__slots__": ["_" + field for field in kinds] + ["_check_fields"],
        "__init__": __init__, "__repr__": __repr__, "__eq__": __eq__, "__hash__": None,
        "__module__": f"{package}.msg._{_snake(name)}", "__qualname__": name,
        "__doc__": f"Message class '{name}'.",
        "get_fields_and_field_types": classmethod(get_fields_and_field_types),
        "_fields_and_field_types": {field: kind.idl() for field, kind in kinds.items()},
        "_kinds": kinds, "_type_name": type_name, "_TYPE_SUPPORT": type_name,
    }
    for field, kind in kinds.items():
        namespace[field] = _property(field, kind)
    for constant, _kind, value in constants:
        namespace[constant] = value
    return type(name, (), namespace)


# ---------------------------------------------------------------- what publishing checks


def convert_check(message: object, path: str = "") -> tuple[str, str, str] | None:
    """The field the C conversion (``_msg_support.c.em``, run by ``publish``) would abort on, the
    assertion that fails and the type the field held; None when the message converts."""
    kinds = getattr(type(message), "_kinds", {})
    for field, kind in kinds.items():
        value = getattr(message, field)
        where = f"{path}{field}"
        if kind.nested:
            if kind.base in TYPE_CODES and isinstance(value, array.array):
                continue  # the buffer path (_msg_support.c.em:257)
            if kind.nested == "array" and type(value).__name__ == "ndarray":
                continue
            # PySequence_Fast (_msg_support.c.em:400-420) takes any iterable: a str is a
            # sequence of one-letter strings, which is what goes out
            items = list(value) if _iterable(value) else None
            if items is None:
                return where, "PySequence_Check(field)", _held(value)
            for k, item in enumerate(items):
                found = _convert_scalar(kind, item, f"{where}[{k}]")
                if found:
                    return found
            continue
        found = _convert_scalar(kind, value, where)
        if found:
            return found
    return None


def _iterable(value: object) -> bool:
    try:
        iter(value)  # type: ignore[call-overload]
    except TypeError:
        return False
    return True


def split_strings(message: object, path: str = "") -> list[tuple[str, str]]:
    """The string-sequence fields (``name`` of a JointState) given one string: ``(field, value)``.
    Jazzy's setter keeps it (no check, ``_msg.py.em:440``) and the C conversion iterates it
    (PySequence_Fast): 'epaule, coude' goes out as 13 one-letter names."""
    found = []
    for field, kind in getattr(type(message), "_kinds", {}).items():
        value = getattr(message, field)
        if kind.nested and kind.base in ("string", "wstring") and isinstance(value, str):
            found.append((f"{path}{field}", value))
        elif kind.is_message and not kind.nested:
            found.extend(split_strings(value, f"{path}{field}."))
    return found


def _held(value: object) -> str:
    kind = type(value)
    return kind.__name__ if kind.__module__ == "builtins" else f"{kind.__module__}.{kind.__qualname__}"


def _convert_scalar(kind: Kind, value: object, where: str) -> tuple[str, str, str] | None:
    if kind.is_message:
        expected = kind.python_type()
        if type(value) is not expected:  # _msg_support.c.em:195: the class's full name is compared
            return where, f'strncmp("{kind.base.replace("/", ".")}", full_classname_dest, ...) == 0', _held(value)
        return convert_check(value, where + ".")
    checks = [(FLOATS, float, "PyFloat_Check(field)"),  # line 485
              (("bool",), bool, "PyBool_Check(field)"),  # line 482
              (("string", "wstring"), str, "PyUnicode_Check(field)"),  # line 436
              (("byte",), bytes, "PyBytes_Check(field)")]
    for bases, python, assertion in checks:
        if kind.base in bases:
            return None if isinstance(value, python) else (where, assertion, _held(value))
    return None if isinstance(value, int) else (where, "PyLong_Check(field)", _held(value))  # lines 496-513


def to_data(value: object) -> object:
    """A message as plain data (dicts, lists, numbers), for the recording: what was sent (a
    sequence field holding a str or another iterable goes out as its items)."""
    kinds = getattr(type(value), "_kinds", None)
    if kinds is not None:
        out = {}
        for field, kind in kinds.items():
            item = getattr(value, field)
            if kind.nested and isinstance(item, (str, set, frozenset, range)):
                item = list(item)
            out[field] = to_data(item)
        return out
    if isinstance(value, array.array):
        return value.tolist()
    if type(value).__name__ == "ndarray":
        return value.tolist()  # type: ignore[attr-defined]
    if isinstance(value, (list, tuple)):
        return [to_data(v) for v in value]
    return value


def type_name(message_type: object) -> str | None:
    return getattr(message_type, "_type_name", None)


# ---------------------------------------------------------------- the import hook


class _Loader(importlib.abc.Loader):
    def create_module(self, spec):
        return None

    def exec_module(self, module: types.ModuleType) -> None:
        name = module.__name__
        package, _, interface = name.partition(".")
        module.__path__ = []
        if interface == "msg":
            prefix = f"{package}/msg/"
            for type_name_, (constants, fields) in sorted(definitions().items()):
                if type_name_.startswith(prefix):
                    cls = _make_class(type_name_, constants, fields)
                    setattr(module, cls.__name__, cls)
                    cls.__module__ = f"{name}._{_snake(cls.__name__)}"
        if interface == "srv":
            parts = service_definitions()
            for service in sorted(SERVICES):
                if service.startswith(f"{package}/srv/"):
                    made = [_make_class(f"{service}_{part}", *parts[f"{service}_{part}"])
                            for part in ("Request", "Response")]
                    cls = _service_class(service, *made)
                    for made_class in (*made, cls):
                        made_class.__module__ = f"{name}._{_snake(cls.__name__)}"
                        setattr(module, made_class.__name__, made_class)
        # where Jazzy's apt packages put it: `from std_msgs.msg import JointState` fails with
        # Python's "cannot import name 'JointState' from 'std_msgs.msg' (.../__init__.py)", and
        # `from sensor_msgs import JointState` (.msg forgotten) from 'sensor_msgs' (an empty __init__.py)
        module.__file__ = "/".join(filter(None, (JAZZY_SITE, package, interface, "__init__.py")))
        module.__getattr__ = _missing(name, complete=True)  # type: ignore[method-assign]


JAZZY_SITE = "/opt/ros/jazzy/lib/python3.12/site-packages"


def _missing(module: str, complete: bool = False):
    """A name a message module lacks: Jazzy's definitions of the package are all there, so it
    does not exist on Jazzy either (AttributeError, which ``from ... import`` makes the
    ImportError Python raises on Jazzy); elsewhere, something bras-kit does not simulate."""
    def __getattr__(attribute: str):
        import _bras_sim

        if complete and not attribute.startswith("_"):
            raise AttributeError(f"module '{module}' has no attribute '{attribute}'")
        raise _bras_sim.not_simulated(module, attribute)

    return __getattr__


def near_names(type_name: str) -> list[str]:
    """Jazzy's interface types whose name is close to ``type_name`` ("Jointstate" -> ["sensor_msgs.msg.JointState"])."""
    import difflib

    every = {t.rsplit("/", 1)[-1]: t for t in (*definitions(), *SERVICES)}
    close = difflib.get_close_matches(type_name, list(every), n=3, cutoff=0.8)
    return [every[name].replace("/", ".") for name in close]


def near_packages(package: str, others: Set[str] = frozenset()) -> list[str]:
    """Jazzy's interface packages whose name is close to ``package`` ("sensors_msgs" -> ["sensor_msgs"]):
    those bras-kit holds the definitions of, and ``others``."""
    import difflib

    return difflib.get_close_matches(package, sorted(packages() | set(others)), n=3, cutoff=0.8)


def homes_of(type_name: str) -> list[str]:
    """The interface modules of Jazzy that define ``type_name`` ("JointState" -> ["sensor_msgs.msg"])."""
    found = {f"{t.split('/')[0]}.msg" for t in definitions() if t.rsplit("/", 1)[-1] == type_name}
    found |= {f"{t.split('/')[0]}.srv" for t in SERVICES if t.rsplit("/", 1)[-1] == type_name}
    return sorted(found)


def find_spec(fullname: str) -> importlib.machinery.ModuleSpec | None:
    """The spec of ``pkg`` or ``pkg.msg`` when ``pkg`` is a message package of Jazzy's store."""
    package, _, rest = fullname.partition(".")
    if rest not in ("", "msg", "srv") or package not in packages():
        return None
    if rest and not any(t.startswith(f"{package}/{rest}/") for t in (*definitions(), *SERVICES)):
        return None  # std_srvs has no msg module on Jazzy
    return importlib.machinery.ModuleSpec(fullname, _Loader(), is_package=True)
