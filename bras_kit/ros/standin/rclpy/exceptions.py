"""rclpy.exceptions, simulated: the same classes and words as rclpy/exceptions.py."""


class NotInitializedException(Exception):
    """Raised when the rclpy implementation is accessed before rclpy.init()."""

    def __init__(self, message=None):
        if message:
            Exception.__init__(self, f'rclpy.init() has not been called. msg:{message}')
        else:
            Exception.__init__(self, 'rclpy.init() has not been called.')


class NoTypeSupportImportedException(Exception):
    """Raised when a message or service type has no type support (rclpy's type_support checks)."""

    def __init__(self):
        Exception.__init__(self, 'no type_support imported')


class InvalidHandle(Exception):
    """Raised when using something that was destroyed (rclpy's _rclpy.InvalidHandle)."""


class NameValidationException(Exception):
    """Raised when a topic name, node name, or namespace are invalid."""

    def __init__(self, name_type, name, error_msg, invalid_index):
        msg = """\
Invalid {name_type}: {error_msg}:
  '{name}'
   {indent}^\
""".format(name_type=name_type, name=name, error_msg=error_msg, indent=' ' * invalid_index)
        Exception.__init__(self, msg)
        self.name, self.error_msg, self.invalid_index = name, error_msg, invalid_index


class InvalidNamespaceException(NameValidationException):
    def __init__(self, name, error_msg, invalid_index):
        NameValidationException.__init__(self, 'namespace', name, error_msg, invalid_index)


class InvalidNodeNameException(NameValidationException):
    def __init__(self, name, error_msg, invalid_index):
        NameValidationException.__init__(self, 'node name', name, error_msg, invalid_index)


class InvalidTopicNameException(NameValidationException):
    def __init__(self, name, error_msg, invalid_index):
        NameValidationException.__init__(self, 'topic name', name, error_msg, invalid_index)


class InvalidServiceNameException(NameValidationException):
    def __init__(self, name, error_msg, invalid_index):
        NameValidationException.__init__(self, 'service name', name, error_msg, invalid_index)


class ParameterException(Exception):
    def __init__(self, error_msg, parameters):
        Exception.__init__(self, f'{error_msg}: {parameters}')


class ParameterNotDeclaredException(ParameterException):
    def __init__(self, parameters):
        ParameterException.__init__(self, 'Invalid access to undeclared parameter(s)', parameters)


class ParameterAlreadyDeclaredException(ParameterException):
    def __init__(self, parameters):
        ParameterException.__init__(self, 'Parameter(s) already declared', parameters)


class InvalidParameterException(ParameterException):
    def __init__(self, parameter_name):
        ParameterException.__init__(self, 'Invalid parameter name', parameter_name)


class ParameterUninitializedException(ParameterException):
    def __init__(self, parameter_name):
        ParameterException.__init__(self, f"The parameter '{parameter_name}' is not initialized", parameter_name)


class ROSInterruptException(Exception):
    def __init__(self):
        Exception.__init__(self, 'rclpy.shutdown() has been called')


class InvalidParameterTypeException(ParameterException):
    """exceptions.py:107-119."""

    def __init__(self, desired_parameter, expected_type):
        from .parameter import Parameter

        ParameterException.__init__(
            self,
            f"Trying to set parameter '{desired_parameter._name}' to '{desired_parameter._value}'"
            f" of type '{Parameter.Type.from_parameter_value(desired_parameter._value).name}'"
            f", expecting type '{expected_type}'",
            desired_parameter.name)


class InvalidParameterValueException(ParameterException):
    """exceptions.py:122-132."""

    def __init__(self, parameter, value, reason):
        ParameterException.__init__(
            self, f'Invalid parameter value ({value}) for parameter. Reason: {reason}', parameter)


class ParameterImmutableException(ParameterException):
    def __init__(self, parameter_name):
        ParameterException.__init__(self, 'Attempted to modify read-only parameter', parameter_name)
