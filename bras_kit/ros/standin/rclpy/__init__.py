"""rclpy 7.1 (Jazzy), simulated by bras-kit (``bras-kit run``): what a beginner's node meets.

Only the child process that runs the node sees this package; the real thing is ``ros2 run`` on
a ROS 2 Jazzy machine. Names and behaviour follow rclpy/rclpy/__init__.py (jazzy branch).
"""

import _bras_sim

from .context import get_default_context
from .utilities import ok, try_shutdown  # noqa: F401

_EXECUTOR: list = []


def init(*, args=None, context=None, domain_id=None, signal_handler_options=None):
    """__init__.py:65-94: returns None in 7.1 (``with rclpy.init():`` came in Kilted)."""
    context = get_default_context() if context is None else context
    context.init(args, domain_id=domain_id)


def get_global_executor():
    """__init__.py:101-114: made on first use, shut down and forgotten with the default context."""
    if not _EXECUTOR:
        from .executors import SingleThreadedExecutor

        _EXECUTOR.append(SingleThreadedExecutor())

        def reset_executor():
            if _EXECUTOR:
                _EXECUTOR.pop().shutdown()

        get_default_context().on_shutdown(reset_executor)
    return _EXECUTOR[0]


def shutdown(*, context=None, uninstall_handlers=None):
    """__init__.py:117-140 -> utilities.py:70-82: after Ctrl-C the context is already shut down
    by rclpy's SIGINT handler, and this raises RCLError (context.cpp:161-164)."""
    from .utilities import shutdown as _shutdown

    _shutdown(context=context)


def create_node(node_name, *, context=None, cli_args=None, namespace=None, use_global_arguments=True,
                enable_rosout=True, start_parameter_services=True, parameter_overrides=None,
                allow_undeclared_parameters=False, automatically_declare_parameters_from_overrides=False,
                enable_logger_service=False):
    from .node import Node

    return Node(node_name, context=context, cli_args=cli_args, namespace=namespace,
                use_global_arguments=use_global_arguments, enable_rosout=enable_rosout,
                start_parameter_services=start_parameter_services, parameter_overrides=parameter_overrides,
                allow_undeclared_parameters=allow_undeclared_parameters,
                automatically_declare_parameters_from_overrides=automatically_declare_parameters_from_overrides,
                enable_logger_service=enable_logger_service)


def spin_once(node, *, executor=None, timeout_sec=None):
    executor = get_global_executor() if executor is None else executor
    try:
        executor.add_node(node)
        executor.spin_once(timeout_sec=timeout_sec)
    finally:
        executor.remove_node(node)


def spin(node, executor=None):
    """__init__.py:229-246."""
    executor = get_global_executor() if executor is None else executor
    try:
        executor.add_node(node)
        while executor.context.ok():
            executor.spin_once()
    finally:
        executor.remove_node(node)


def spin_until_future_complete(node, future, executor=None, timeout_sec=None):
    executor = get_global_executor() if executor is None else executor
    try:
        executor.add_node(node)
        executor.spin_until_future_complete(future, timeout_sec)
    finally:
        executor.remove_node(node)


def __getattr__(name):
    raise _bras_sim.not_simulated('rclpy', name)
