"""rclpy, simulated by bras-kit (``bras-kit run``): enough of it for a beginner's node.

Only the child process that runs the node sees this package. The real thing is ``ros2 run``
on a ROS 2 machine.
"""

import _bras_sim

from .context import get_default_context
from .executors import SingleThreadedExecutor

_EXECUTOR: list = []


def init(*, args=None, context=None, domain_id=None, signal_handler_options=None):
    (context or get_default_context()).init(args, domain_id=domain_id)


def get_global_executor():
    if not _EXECUTOR:
        _EXECUTOR.append(SingleThreadedExecutor())
    return _EXECUTOR[0]


def shutdown(*, context=None, uninstall_handlers=None):
    context = context or get_default_context()
    context.shutdown()
    if _EXECUTOR:
        _EXECUTOR.pop().shutdown()


def try_shutdown(*, context=None, uninstall_handlers=None):
    (context or get_default_context()).try_shutdown()
    if _EXECUTOR:
        _EXECUTOR.pop().shutdown()


def ok(*, context=None):
    return (context or get_default_context()).ok()


def create_node(node_name, *, context=None, cli_args=None, namespace=None, use_global_arguments=True,
                enable_rosout=True, start_parameter_services=True, parameter_overrides=None,
                allow_undeclared_parameters=False, automatically_declare_parameters_from_overrides=False,
                enable_logger_service=False):
    from .node import Node

    return Node(node_name, context=context, cli_args=cli_args, namespace=namespace,
                allow_undeclared_parameters=allow_undeclared_parameters, parameter_overrides=parameter_overrides)


def spin_once(node, *, executor=None, timeout_sec=None):
    executor = get_global_executor() if executor is None else executor
    try:
        executor.add_node(node)
        executor.spin_once(timeout_sec=timeout_sec)
    finally:
        executor.remove_node(node)


def spin(node, executor=None):
    executor = get_global_executor() if executor is None else executor
    try:
        executor.add_node(node)
        while executor.context.ok():
            executor.spin_once()
    finally:
        executor.remove_node(node)


def spin_until_future_complete(node, future, executor=None, timeout_sec=None):
    executor = get_global_executor() if executor is None else executor
    node_added = False
    try:
        node_added = executor.add_node(node)
        executor.spin_until_future_complete(future, timeout_sec)
    finally:
        if node_added:
            executor.remove_node(node)


def __getattr__(name):
    raise _bras_sim.not_simulated('rclpy', name)
