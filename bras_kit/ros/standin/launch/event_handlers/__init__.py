from .._handlers import (  # noqa: F401
    EventHandler,
    OnExecutionComplete,
    OnIncludeLaunchDescription,
    OnProcessExit,
    OnProcessIO,
    OnProcessStart,
    OnShutdown,
)
