"""rclpy.parameter, simulated (rclpy/parameter.py, jazzy): a name, a type, a value."""

import array
from enum import Enum


class Parameter:
    class Type(Enum):
        NOT_SET = 0
        BOOL = 1
        INTEGER = 2
        DOUBLE = 3
        STRING = 4
        BYTE_ARRAY = 5
        BOOL_ARRAY = 6
        INTEGER_ARRAY = 7
        DOUBLE_ARRAY = 8
        STRING_ARRAY = 9

        @classmethod
        def from_parameter_value(cls, parameter_value):
            if parameter_value is None:
                return Parameter.Type.NOT_SET
            if isinstance(parameter_value, bool):
                return Parameter.Type.BOOL
            if isinstance(parameter_value, int):
                return Parameter.Type.INTEGER
            if isinstance(parameter_value, float):
                return Parameter.Type.DOUBLE
            if isinstance(parameter_value, str):
                return Parameter.Type.STRING
            if isinstance(parameter_value, (list, tuple, array.array)):
                for kind, python in ((Parameter.Type.BYTE_ARRAY, bytes), (Parameter.Type.BOOL_ARRAY, bool),
                                     (Parameter.Type.INTEGER_ARRAY, int), (Parameter.Type.DOUBLE_ARRAY, float),
                                     (Parameter.Type.STRING_ARRAY, str)):
                    if all(isinstance(v, python) for v in parameter_value):
                        return kind
                raise TypeError('The given value is not a list of one of the allowed types'
                                f" '{parameter_value}'.")
            raise TypeError(f"The given value is not one of the allowed types '{parameter_value}'.")

        def check(self, parameter_value):
            if self is Parameter.Type.NOT_SET:
                return parameter_value is None
            try:
                found = Parameter.Type.from_parameter_value(parameter_value)
            except TypeError:
                return False
            # an empty list suits every array type (parameter.py:117-130)
            if isinstance(parameter_value, (list, tuple, array.array)) and not len(parameter_value):
                return self.name.endswith('_ARRAY')
            return found is self

    @classmethod
    def from_parameter_msg(cls, param_msg):
        type_ = Parameter.Type(param_msg.value.type)
        value = None if type_ is Parameter.Type.NOT_SET else getattr(param_msg.value, _FIELDS[type_])
        if isinstance(value, array.array):
            value = value.tolist()
        return cls(param_msg.name, type_, value)

    def __init__(self, name, type_=None, value=None):
        if type_ is None:
            type_ = Parameter.Type.from_parameter_value(value)
        if not isinstance(type_, Parameter.Type):
            raise TypeError(f"type must be an instance of '{repr(Parameter.Type)}'")
        if not type_.check(value):
            raise ValueError(f"Type '{type_}' and value '{value}' do not agree")
        self._type_ = type_
        self._name = name
        self._value = value

    @property
    def name(self):
        return self._name

    @property
    def type_(self):
        return self._type_

    @property
    def value(self):
        return self._value

    def get_parameter_value(self):
        from rcl_interfaces.msg import ParameterValue

        message = ParameterValue(type=self._type_.value)
        if self._type_ is not Parameter.Type.NOT_SET:
            setattr(message, _FIELDS[self._type_], self._value)
        return message

    def to_parameter_msg(self):
        from rcl_interfaces.msg import Parameter as ParameterMsg

        return ParameterMsg(name=self._name, value=self.get_parameter_value())

    def __repr__(self):
        return f'<Parameter {self._name}={self._value!r} ({self._type_.name})>'


_FIELDS = {Parameter.Type.BOOL: 'bool_value', Parameter.Type.INTEGER: 'integer_value',
           Parameter.Type.DOUBLE: 'double_value', Parameter.Type.STRING: 'string_value',
           Parameter.Type.BYTE_ARRAY: 'byte_array_value', Parameter.Type.BOOL_ARRAY: 'bool_array_value',
           Parameter.Type.INTEGER_ARRAY: 'integer_array_value', Parameter.Type.DOUBLE_ARRAY: 'double_array_value',
           Parameter.Type.STRING_ARRAY: 'string_array_value'}


def parameter_value_to_python(parameter_value):
    type_ = Parameter.Type(parameter_value.type)
    return None if type_ is Parameter.Type.NOT_SET else getattr(parameter_value, _FIELDS[type_])
