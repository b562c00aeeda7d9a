from .._core import SubstitutionFailure, TextSubstitution  # noqa: F401
from .._substitutions import (  # noqa: F401
    AndSubstitution,
    AnonName,
    Command,
    EnvironmentVariable,
    EqualsSubstitution,
    FileContent,
    FindExecutable,
    IfElseSubstitution,
    LaunchConfiguration,
    NotSubstitution,
    OrSubstitution,
    PathJoinSubstitution,
    PythonExpression,
    ThisLaunchFile,
    ThisLaunchFileDir,
)
