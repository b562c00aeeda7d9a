"""rclpy.utilities, simulated (rclpy/utilities.py)."""

from .context import get_default_context


def ok(*, context=None):
    return (get_default_context() if context is None else context).ok()


def shutdown(*, context=None):
    """utilities.py:70-82: the default context is handed out and forgotten, then shut down."""
    if context is None:
        context = get_default_context(shutting_down=True)
    context.shutdown()


def try_shutdown(*, context=None):
    """utilities.py:85-104."""
    if context is None:
        context = get_default_context()
        context.try_shutdown()
        if not context.ok():
            get_default_context(shutting_down=True)
    else:
        context.try_shutdown()


def remove_ros_args(args=None):
    import sys

    args = list(sys.argv if args is None else args)
    if '--ros-args' in args:
        return args[:args.index('--ros-args')]
    return args


def get_available_rmw_implementations():
    return {'rmw_fastrtps_cpp'}
