"""rclpy.parameter, simulated: parameters hold a value and its type."""

import enum


class Parameter:
    class Type(enum.IntEnum):
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
        def from_parameter_value(cls, value):
            if value is None:
                return cls.NOT_SET
            if isinstance(value, bool):
                return cls.BOOL
            if isinstance(value, int):
                return cls.INTEGER
            if isinstance(value, float):
                return cls.DOUBLE
            if isinstance(value, str):
                return cls.STRING
            if isinstance(value, (list, tuple)):
                if all(isinstance(v, bool) for v in value):
                    return cls.BOOL_ARRAY
                if all(isinstance(v, int) for v in value):
                    return cls.INTEGER_ARRAY
                if all(isinstance(v, float) for v in value):
                    return cls.DOUBLE_ARRAY
                if all(isinstance(v, str) for v in value):
                    return cls.STRING_ARRAY
            raise TypeError(f"The given value is not one of the allowed types '{value}'.")

    def __init__(self, name, type_=None, value=None):
        if type_ is None:
            type_ = Parameter.Type.from_parameter_value(value)
        self._name = name
        self._type_ = type_
        self._value = value

    @property
    def name(self):
        return self._name

    @property
    def value(self):
        return self._value

    @property
    def type_(self):
        return self._type_

    def get_parameter_value(self):
        return ParameterValue(self._type_, self._value)

    def __repr__(self):
        return f'Parameter(name={self._name!r}, value={self._value!r})'


class ParameterValue:
    """Like rcl_interfaces/msg/ParameterValue: one field per type."""

    def __init__(self, type_, value):
        self.type = int(type_)
        self.bool_value = value if type_ == Parameter.Type.BOOL else False
        self.integer_value = value if type_ == Parameter.Type.INTEGER else 0
        self.double_value = value if type_ == Parameter.Type.DOUBLE else 0.0
        self.string_value = value if type_ == Parameter.Type.STRING else ''
        self.bool_array_value = value if type_ == Parameter.Type.BOOL_ARRAY else []
        self.integer_array_value = value if type_ == Parameter.Type.INTEGER_ARRAY else []
        self.double_array_value = value if type_ == Parameter.Type.DOUBLE_ARRAY else []
        self.string_array_value = value if type_ == Parameter.Type.STRING_ARRAY else []
