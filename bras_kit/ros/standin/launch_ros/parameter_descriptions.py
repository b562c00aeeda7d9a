from ._core import Parameter, ParameterFile, ParameterValue  # noqa: F401
