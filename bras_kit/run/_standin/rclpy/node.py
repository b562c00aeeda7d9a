"""rclpy.node, simulated: the part of rclpy.node.Node that beginner nodes use.

Names, signatures, checks and error words follow rclpy/node.py; what it creates lives on the
virtual clock and every message published is recorded.
"""

import _bras_sim

from .clock import Clock, ROSClock
from .clock_type import ClockType
from .context import get_default_context
from .exceptions import (
    InvalidHandle,
    InvalidParameterException,
    NotInitializedException,
    ParameterAlreadyDeclaredException,
    ParameterNotDeclaredException,
)
from .logging import get_logger
from .parameter import Parameter
from .publisher import Publisher, Subscription
from .qos import QoSProfile
from .timer import Rate, Timer
from .validate import expand_topic_name, validate_node_name, validate_topic_name

S_TO_NS = 10**9

# methods of the real rclpy Node the stand-in does not simulate (rclpy/node.py)
_REAL_ONLY = {
    'create_client', 'create_service', 'create_guard_condition', 'create_action_client',
    'declare_parameters', 'undeclare_parameter', 'get_parameters_by_prefix', 'set_parameters',
    'set_parameters_atomically', 'add_on_set_parameters_callback', 'add_pre_set_parameters_callback',
    'add_post_set_parameters_callback', 'remove_on_set_parameters_callback', 'describe_parameter',
    'describe_parameters', 'set_descriptor', 'list_parameters', 'get_topic_names_and_types',
    'get_service_names_and_types', 'get_node_names', 'get_node_names_and_namespaces',
    'count_publishers', 'count_subscribers', 'get_publishers_info_by_topic',
    'get_subscriptions_info_by_topic', 'wait_for_node', 'add_waitable', 'remove_waitable',
    'destroy_client', 'destroy_service', 'destroy_guard_condition', 'get_fully_qualified_name',
    'resolve_service_name', 'get_parameter_types', 'get_parameter_type',
}


def _qos(qos_or_depth):
    if isinstance(qos_or_depth, QoSProfile):
        return qos_or_depth
    if isinstance(qos_or_depth, int):
        if qos_or_depth < 0:
            raise ValueError('history depth must be greater than or equal to zero')
        return QoSProfile(depth=qos_or_depth)
    raise TypeError(f'Expected QoSProfile or int, but received {type(qos_or_depth)!r}')


def _check_msg_type(msg_type):
    # rclpy/type_support.py check_is_valid_msg_type
    if not hasattr(msg_type, '_type_name'):
        raise NoTypeSupportImportedException()


class NoTypeSupportImportedException(Exception):
    def __init__(self):
        Exception.__init__(self, 'no type_support imported')


class Node:
    def __init__(self, node_name, *, context=None, cli_args=None, namespace=None,
                 use_global_arguments=True, enable_rosout=True, start_parameter_services=True,
                 parameter_overrides=None, allow_undeclared_parameters=False,
                 automatically_declare_parameters_from_overrides=False, enable_logger_service=False):
        object.__setattr__(self, '_destroyed', False)
        self._context = get_default_context() if context is None else context
        self._parameters = {}
        self._publishers_list = []
        self._subscriptions_list = []
        self._timers_list = []
        self._allow_undeclared_parameters = allow_undeclared_parameters
        self._parameter_overrides = {p.name: p for p in parameter_overrides or []}
        namespace = namespace or ''
        if self._context.handle is None or not self._context.ok():
            raise NotInitializedException('cannot create node')
        validate_node_name(node_name)
        if not namespace.startswith('/'):
            namespace = '/' + namespace
        self._name = node_name
        self._namespace = namespace
        self._logger = get_logger(node_name)
        self._clock = ROSClock()
        self.executor = None
        _bras_sim.STATE.nodes.append(self)

    def __getattr__(self, name):
        if name in _REAL_ONLY:
            raise _bras_sim.not_simulated('rclpy.node.Node', name)
        raise AttributeError(f"'{type(self).__name__}' object has no attribute '{name}'")

    def _alive(self):
        if self._destroyed:
            raise InvalidHandle('cannot use Destroyable because destruction was requested')

    # ------------------------------------------------------------ identity
    @property
    def context(self):
        return self._context

    @property
    def publishers(self):
        yield from self._publishers_list

    @property
    def subscriptions(self):
        yield from self._subscriptions_list

    @property
    def timers(self):
        yield from self._timers_list

    def get_name(self):
        return self._name

    def get_namespace(self):
        return self._namespace

    def get_clock(self):
        return self._clock

    def get_logger(self):
        return self._logger

    def resolve_topic_name(self, topic, *, only_expand=False):
        validate_topic_name(topic)
        return expand_topic_name(topic, self._name, self._namespace)

    # ------------------------------------------------------------ topics
    def create_publisher(self, msg_type, topic, qos_profile, *, callback_group=None,
                         event_callbacks=None, qos_overriding_options=None, publisher_class=Publisher):
        qos_profile = _qos(qos_profile)
        self._alive()
        final_topic = self.resolve_topic_name(topic)
        _check_msg_type(msg_type)
        publisher = Publisher(self, msg_type, final_topic, qos_profile)
        self._publishers_list.append(publisher)
        _bras_sim.STATE.publishers.append((self._name, final_topic, msg_type._type_name, *_bras_sim.caller()))
        return publisher

    def create_subscription(self, msg_type, topic, callback, qos_profile, *, callback_group=None,
                            event_callbacks=None, qos_overriding_options=None, raw=False):
        qos_profile = _qos(qos_profile)
        self._alive()
        final_topic = self.resolve_topic_name(topic)
        _check_msg_type(msg_type)
        subscription = Subscription(self, msg_type, final_topic, callback, qos_profile)
        self._subscriptions_list.append(subscription)
        _bras_sim.STATE.subscriptions.append((self._name, final_topic, msg_type._type_name, *_bras_sim.caller()))
        return subscription

    def destroy_publisher(self, publisher):
        if publisher in self._publishers_list:
            self._publishers_list.remove(publisher)
            publisher.destroy()
            return True
        return False

    def destroy_subscription(self, subscription):
        if subscription in self._subscriptions_list:
            self._subscriptions_list.remove(subscription)
            subscription.destroy()
            return True
        return False

    # ------------------------------------------------------------ time
    def create_timer(self, timer_period_sec, callback, callback_group=None, clock=None, autostart=True):
        self._alive()
        timer_period_nsec = int(float(timer_period_sec) * S_TO_NS)
        if timer_period_nsec < 0:
            raise ValueError('timer period must be non-negative')  # rcl_timer_init2
        timer = Timer(callback, timer_period_nsec, self)
        if not autostart:
            timer.cancel()
        self._timers_list.append(timer)
        _bras_sim.STATE.timers.append((self._name, timer_period_nsec / S_TO_NS, *_bras_sim.caller()))
        return timer

    def destroy_timer(self, timer):
        if timer in self._timers_list:
            self._timers_list.remove(timer)
            timer.destroy()
            return True
        return False

    def create_rate(self, frequency, clock=None):
        if frequency <= 0:
            raise ValueError('frequency must be > 0')
        self._alive()
        timer = Timer(None, int(S_TO_NS / frequency), self)
        return Rate(timer, context=self._context)

    def destroy_rate(self, rate):
        rate.destroy()
        return True

    # ------------------------------------------------------------ parameters
    def declare_parameter(self, name, value=None, descriptor=None, ignore_override=False):
        if not isinstance(name, str) or not name or name[0].isdigit() or not all(
                c.isalnum() or c in '_.' for c in name):
            raise InvalidParameterException(name)
        if name in self._parameters:
            raise ParameterAlreadyDeclaredException([name])
        if name in self._parameter_overrides and not ignore_override:
            value = self._parameter_overrides[name].value
        elif name in _bras_sim.STATE.parameters and not ignore_override:  # -p NAME:=VALUE
            value = _bras_sim.STATE.parameters[name]
        if isinstance(value, Parameter.Type):
            value = None
        parameter = Parameter(name, value=value)
        self._parameters[name] = parameter
        return parameter

    def has_parameter(self, name):
        return name in self._parameters

    def get_parameter(self, name):
        if name in self._parameters:
            return self._parameters[name]
        if self._allow_undeclared_parameters:
            return Parameter(name, Parameter.Type.NOT_SET, None)
        raise ParameterNotDeclaredException(name)

    def get_parameter_or(self, name, alternative_value=None):
        if alternative_value is None:
            alternative_value = Parameter(name, Parameter.Type.NOT_SET)
        return self._parameters.get(name, alternative_value)

    def get_parameters(self, names):
        if not all(isinstance(n, str) for n in names):
            raise TypeError('All names must be instances of type str')
        return [self.get_parameter(n) for n in names]

    # ------------------------------------------------------------ end
    def destroy_node(self):
        for item in self._publishers_list + self._subscriptions_list + self._timers_list:
            item.destroy()
        self._publishers_list, self._subscriptions_list, self._timers_list = [], [], []
        object.__setattr__(self, '_destroyed', True)

    def __enter__(self):
        return self

    def __exit__(self, *exc_info):
        self.destroy_node()


__all__ = ['Node', 'Clock', 'ClockType']
