"""rclpy.utilities, simulated."""

from . import ok, shutdown, try_shutdown  # noqa: F401
from .context import get_default_context  # noqa: F401


def remove_ros_args(args=None):
    args = list(args or [])
    if '--ros-args' in args:
        return args[:args.index('--ros-args')]
    return args
