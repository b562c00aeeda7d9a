"""rclpy.context, simulated (the checks of rclpy/context.py and rclpy/src/rclpy/context.cpp)."""

import sys

import _bras_sim


class RCLError(RuntimeError):
    """rclpy._rclpy_pybind11.RCLError: an rcl call failed (rclpy/src/rclpy/exceptions.cpp:55,
    the words are the call's, then ': ', then rcl's error string, exceptions.cpp:34-39)."""


RCLError.__module__ = 'rclpy._rclpy_pybind11'


class UnknownROSArgsError(RuntimeError):
    """rclpy._rclpy_pybind11.UnknownROSArgsError (_rclpy_pybind11.cpp:115): ``--ros-args``
    words rcl did not parse, named by their repr (utils.cpp:247-277)."""


UnknownROSArgsError.__module__ = 'rclpy._rclpy_pybind11'


class Context:
    """Like rclpy/context.py: init once, shutdown once; ``with Context()`` inits and try-shuts
    down (context.py:189-201)."""

    def __init__(self):
        self._initialized = False
        self._shutdown = False
        self._callbacks = []
        self.global_arguments = None  # bras_kit.ros.names.ROSArguments, once initialized

    @property
    def handle(self):
        return self if self._initialized else None

    def init(self, args=None, *, initialize_logging=True, domain_id=None):
        if domain_id is not None and domain_id < 0:
            raise RuntimeError(f'Domain id ({domain_id}) should not be lower than zero.')
        if self._initialized:
            raise RuntimeError('Context.init() must only be called once')  # context.py:96-97
        self.global_arguments = parse_arguments(sys.argv if args is None else args)
        self._initialized = True
        self._shutdown = False
        _bras_sim.STATE.on_sigint.append(self._on_sigint)

    def _on_sigint(self):
        # signal_handler.cpp:144 rclpy::shutdown_contexts() calls rcl_shutdown only: the Python
        # callbacks of Context.on_shutdown are not called (a Rate is not told, timer.py:136);
        # executors notice through their SIGINT guard condition (executors.py:604, 685-689)
        if self.ok():
            self._shutdown = True

    def ok(self):
        return self._initialized and not self._shutdown

    def shutdown(self):
        if not self._initialized:
            raise RuntimeError('Context must be initialized before it can be shutdown')  # context.py:127
        if self._shutdown:
            # context.cpp:161-164: rcl_shutdown() fails on a context already shut down (by
            # rclpy's SIGINT handler after Ctrl-C, or by an earlier shutdown())
            raise RCLError('failed to shutdown: rcl_shutdown already called on the given context')
        self._shutdown = True
        self._call_on_shutdown_callbacks()

    def try_shutdown(self):
        if self.ok():  # context.py:133-141
            self._shutdown = True
            self._call_on_shutdown_callbacks()

    def _call_on_shutdown_callbacks(self):
        callbacks, self._callbacks = self._callbacks, []
        for callback in callbacks:
            callback()

    def on_shutdown(self, callback):
        if not callable(callback):
            raise TypeError('callback should be a callable, got {}', type(callback))
        self._callbacks.append(callback)

    def get_domain_id(self):
        if not self._initialized:
            raise RuntimeError('Context must be initialized before it can have a domain id')
        return 0

    def __enter__(self):
        self.init()
        return self

    def __exit__(self, exc_type, exc_val, exc_tb):
        self.try_shutdown()


def parse_arguments(args):
    """What rcl keeps of ``args`` (rclpy 7.1.6 context.py:99-101 hands init's args, else sys.argv,
    to rcl_init, context.cpp:114): they become the context's global arguments, which every node
    created with use_global_arguments=True (the default) applies: remappings (rcl publisher.c and
    subscription.c resolve the topic with rcl_node_resolve_name), -p overrides, __node/__ns.
    A --ros-args word rcl does not know raises UnknownROSArgsError (context.cpp:119)."""
    from bras_kit.ros.names import InvalidROSArgs, parse_ros_arguments, unknown_ros_args_error

    try:
        # rcl_parse_arguments reads argv[0] as the program's name only when it is not a ROS word
        parsed = parse_ros_arguments([str(a) for a in args])
    except InvalidROSArgs as exc:
        raise RCLError(f'failed to initialize rcl: {exc}') from None  # context.cpp:115-117
    if parsed.unknown:
        raise UnknownROSArgsError(unknown_ros_args_error(parsed.unknown, cpp=False))
    return parsed


_DEFAULT = [None]


def get_default_context(*, shutting_down=False):
    """rclpy/utilities.py:32-44: shutting down hands out the default context and forgets it."""
    if _DEFAULT[0] is None:
        _DEFAULT[0] = Context()
    context = _DEFAULT[0]
    if shutting_down:
        _DEFAULT[0] = None
    return context
