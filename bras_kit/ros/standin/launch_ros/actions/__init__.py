from .._core import (  # noqa: F401
    Node,
    PushROSNamespace,
    PushRosNamespace,
    SetParameter,
    SetRemap,
    SetUseSimTime,
)
