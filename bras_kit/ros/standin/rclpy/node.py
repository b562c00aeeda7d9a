"""rclpy.node, simulated: the part of rclpy.node.Node that beginner nodes use.

Names, signatures, checks and error words follow rclpy/node.py; what it creates lives on the
virtual clock and every message published is recorded.
"""

import _bras_sim

from .callback_groups import MutuallyExclusiveCallbackGroup
from .clock import Clock, ROSClock
from .clock_type import ClockType
from .context import get_default_context
from .exceptions import (
    InvalidHandle,
    InvalidParameterTypeException,
    InvalidParameterValueException,
    NotInitializedException,
    NoTypeSupportImportedException,
    ParameterAlreadyDeclaredException,
    ParameterNotDeclaredException,
    ParameterUninitializedException,
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
    'create_guard_condition', 'create_action_client',
    'list_parameters', 'get_topic_names_and_types',
    'get_service_names_and_types', 'get_node_names', 'get_node_names_and_namespaces',
    'count_publishers', 'count_subscribers', 'get_publishers_info_by_topic',
    'get_subscriptions_info_by_topic', 'wait_for_node', 'add_waitable', 'remove_waitable',
    'destroy_guard_condition', 'get_fully_qualified_name',
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


def _yaml_value(text):
    """A -p value as rcl reads it (rcl_yaml_param_parser: YAML, '' an empty string)."""
    import yaml

    from bras_kit.trust import yaml_gate

    try:
        value = yaml_gate.load(text, loader=yaml.SafeLoader) if text.strip() else ''
    except yaml.YAMLError:
        return text
    return value if isinstance(value, (bool, int, float, str, list)) else text


def _check_msg_type(msg_type):
    # rclpy/type_support.py check_is_valid_msg_type
    if not hasattr(msg_type, '_type_name'):
        raise NoTypeSupportImportedException()


class Node:
    def __init__(self, node_name, *, context=None, cli_args=None, namespace=None,
                 use_global_arguments=True, enable_rosout=True, start_parameter_services=True,
                 parameter_overrides=None, allow_undeclared_parameters=False,
                 automatically_declare_parameters_from_overrides=False, enable_logger_service=False):
        object.__setattr__(self, '_destroyed', False)
        self._context = get_default_context() if context is None else context
        self._parameters = {}
        self._descriptors = {}
        self._on_set_parameters_callbacks = []
        self._pre_set_parameters_callbacks = []
        self._post_set_parameters_callbacks = []
        self._default_callback_group = MutuallyExclusiveCallbackGroup()
        self._publishers_list = []
        self._subscriptions_list = []
        self._timers_list = []
        self._services_list = []
        self._clients_list = []
        self._allow_undeclared_parameters = allow_undeclared_parameters
        # --ros-args -p NAME:=VALUE (bras-kit run -p) are global overrides, for every node
        self._parameter_overrides = {}
        for name, value in _bras_sim.STATE.parameters.items():
            try:
                self._parameter_overrides[name] = Parameter(name, value=value)
            except TypeError:  # a mixed list: rcl's YAML reading refuses it, the node never sees it
                continue
        namespace = namespace or ''
        if self._context.handle is None or not self._context.ok():
            raise NotInitializedException('cannot create node')
        validate_node_name(node_name)
        if not namespace.startswith('/'):
            namespace = '/' + namespace
        # rclpy 7.1.6 node.py:187-193 -> rcl_node_init: the node's own cli_args, then the
        # context's global arguments (rclpy.init's args) unless use_global_arguments=False
        from .context import parse_arguments

        self._local_arguments = parse_arguments(list(cli_args)) if cli_args else None
        self._global_arguments = self._context.global_arguments if use_global_arguments else None
        local, global_ = self._remap_rules()
        from bras_kit.ros.names import node_identity

        node_name, namespace = node_identity(node_name, namespace, local, global_)
        # node.py:214-215: the overrides rcl read from -p (global first, the node's own win)
        for arguments in (self._global_arguments, self._local_arguments):
            for name, text in arguments.parameters if arguments is not None else ():
                try:
                    self._parameter_overrides[name] = Parameter(name, value=_yaml_value(text))
                except TypeError:
                    continue
        self._parameter_overrides.update({p.name: p for p in parameter_overrides or []})
        self._name = node_name
        self._namespace = namespace
        self._logger = get_logger(node_name)
        self._clock = ROSClock()
        self.executor = None
        _bras_sim.STATE.nodes.append(self)
        # the name as checked, for the record: real rclpy reads it from rcl's handle, so whatever the
        # node's code sets in self._name afterwards names nothing there, and nothing here
        self._bras_name = node_name
        _bras_sim.STATE.node_names.append(node_name)
        if automatically_declare_parameters_from_overrides:
            for name, parameter in self._parameter_overrides.items():
                if name not in self._parameters:
                    self.declare_parameter(name, parameter.value)

    def __getattr__(self, name):
        if name == 'default_callback_group':
            # the property read self._default_callback_group (node.py:314-321), which a Node whose
            # Node.__init__ never ran (super().__init__ forgotten) lacks
            name = '_default_callback_group'
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
    def default_callback_group(self):
        return self._default_callback_group

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

    def _remap_rules(self):
        return ([] if self._local_arguments is None else self._local_arguments.remaps,
                [] if self._global_arguments is None else self._global_arguments.remaps)

    def resolve_topic_name(self, topic, *, only_expand=False):
        """node.py:1483-1499 -> rcl_node_resolve_name: expanded, then remapped (the node's own
        rules first, then the global ones: rcl remap.c rcl_remap_name) unless only_expand."""
        validate_topic_name(topic)
        if only_expand:
            return expand_topic_name(topic, self._name, self._namespace)
        from bras_kit.ros.names import resolve_topic_name

        return resolve_topic_name(topic, self._name, self._namespace, *self._remap_rules())

    # ------------------------------------------------------------ topics
    def create_publisher(self, msg_type, topic, qos_profile, *, callback_group=None,
                         event_callbacks=None, qos_overriding_options=None, publisher_class=Publisher):
        qos_profile = _qos(qos_profile)
        # node.py:1527: the first attribute a Node that never ran Node.__init__ lacks
        callback_group = callback_group or self.default_callback_group
        self._alive()
        final_topic = self.resolve_topic_name(topic)
        _check_msg_type(msg_type)
        publisher = Publisher(self, msg_type, final_topic, qos_profile)
        self._publishers_list.append(publisher)
        _bras_sim.STATE.publishers.append((self._bras_name, final_topic, msg_type._type_name, *_bras_sim.caller()))
        return publisher

    def create_subscription(self, msg_type, topic, callback, qos_profile, *, callback_group=None,
                            event_callbacks=None, qos_overriding_options=None, raw=False):
        qos_profile = _qos(qos_profile)
        callback_group = callback_group or self.default_callback_group  # node.py:1605
        self._alive()
        final_topic = self.resolve_topic_name(topic)
        _check_msg_type(msg_type)
        subscription = Subscription(self, msg_type, final_topic, callback, qos_profile)
        subscription.callback_group = callback_group or self._default_callback_group
        subscription.callback_group.add_entity(subscription)
        subscription._made_at = _bras_sim.caller()
        self._subscriptions_list.append(subscription)
        if self.executor is not None:
            self.executor.wake()
        _bras_sim.STATE.subscriptions.append((self._bras_name, final_topic, msg_type._type_name, *_bras_sim.caller()))
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

    # ------------------------------------------------------------ services
    def resolve_service_name(self, service, *, only_expand=False):
        return self.resolve_topic_name(service, only_expand=only_expand)  # the same rcl rules

    def create_service(self, srv_type, srv_name, callback, *, qos_profile=None, callback_group=None):
        """rclpy 7.1.6 node.py:1703-1745: the server waits for requests; nobody calls it in a
        bras-kit run, so its callback never runs and the node goes on (timers, publishers)."""
        from .service import Service, check_is_valid_srv_type, qos_services_default

        if callback_group is None:
            callback_group = self.default_callback_group
        check_is_valid_srv_type(srv_type)
        self._alive()
        name = self.resolve_service_name(srv_name)
        service = Service(srv_type, name, callback, callback_group, qos_profile or qos_services_default())
        self._services_list.append(service)
        return service

    def create_client(self, srv_type, srv_name, *, qos_profile=None, callback_group=None):
        """node.py:1661-1701."""
        from .service import Client, check_is_valid_srv_type, qos_services_default

        if callback_group is None:
            callback_group = self.default_callback_group
        check_is_valid_srv_type(srv_type)
        self._alive()
        client = Client(self, srv_type, self.resolve_service_name(srv_name),
                        qos_profile or qos_services_default(), callback_group)
        self._clients_list.append(client)
        return client

    def destroy_service(self, service):
        if service in self._services_list:
            self._services_list.remove(service)
            service.destroy()
            return True
        return False

    def destroy_client(self, client):
        if client in self._clients_list:
            self._clients_list.remove(client)
            client.destroy()
            return True
        return False

    @property
    def services(self):
        yield from self._services_list

    @property
    def clients(self):
        yield from self._clients_list

    # ------------------------------------------------------------ time
    def create_timer(self, timer_period_sec, callback, callback_group=None, clock=None, autostart=True):
        timer_period_nsec = int(float(timer_period_sec) * S_TO_NS)  # node.py:1762
        if callback_group is None:
            callback_group = self.default_callback_group  # node.py:1763-1764
        if timer_period_nsec < 0:
            raise ValueError('timer period must be non-negative')  # rcl_timer_init2
        self._alive()
        timer = Timer(callback, timer_period_nsec, self, callback_group, clock, autostart)
        callback_group.add_entity(timer)
        self._timers_list.append(timer)
        if self.executor is not None:
            self.executor.wake()
        _bras_sim.STATE.timers.append((self._bras_name, timer_period_nsec / S_TO_NS, *_bras_sim.caller()))
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
        # node.py:1791-1811: a timer of the node, whose callback wakes the sleeping thread
        timer = Timer(None, int(float(1.0 / frequency) * S_TO_NS), self, self._default_callback_group, clock)
        timer._rate = True
        self._timers_list.append(timer)
        return Rate(timer, context=self._context)

    def destroy_rate(self, rate):
        rate.destroy()
        return True

    # ------------------------------------------------------------ parameters (node.py:356-1434)
    def declare_parameter(self, name, value=None, descriptor=None, ignore_override=False):
        """node.py:356-388."""
        if value is None and descriptor is None:
            args = (name,)
        else:
            from rcl_interfaces.msg import ParameterDescriptor

            args = (name, value, ParameterDescriptor() if descriptor is None else descriptor)
        return self.declare_parameters('', [args], ignore_override)[0]

    def declare_parameters(self, namespace, parameters, ignore_override=False):
        """node.py:390-533: the type comes from the default value; an override (-p) of another
        type is refused with InvalidParameterTypeException."""
        from rcl_interfaces.msg import ParameterDescriptor

        from .validate import validate_parameter_name

        parameter_list, descriptors = [], {}
        for index, parameter_tuple in enumerate(parameters):
            if len(parameter_tuple) < 1 or len(parameter_tuple) > 3:
                raise TypeError(
                    f'Invalid parameter tuple length at index {index} in parameters list: '
                    f'{parameter_tuple}; expecting length between 1 and 3')
            value = None
            name = parameter_tuple[0]
            if not isinstance(name, str):
                raise TypeError(f'First element {name} at index {index} in parameters list is not a str.')
            if namespace:
                name = f'{namespace}.{name}'
            validate_parameter_name(name)
            second_arg = parameter_tuple[1] if 1 < len(parameter_tuple) else None
            descriptor = parameter_tuple[2] if 2 < len(parameter_tuple) else ParameterDescriptor()
            if not isinstance(descriptor, ParameterDescriptor):
                raise TypeError(f'Third element {descriptor} at index {index} in parameters list '
                                'is not a ParameterDescriptor.')
            if len(parameter_tuple) == 1:
                descriptor.dynamic_typing = True
            if isinstance(second_arg, Parameter.Type):
                if second_arg == Parameter.Type.NOT_SET:
                    raise ValueError(f'Cannot declare parameter {{{name}}} as statically typed of type NOT_SET')
                if descriptor.dynamic_typing is True:
                    raise ValueError(f'When declaring parameter {{{name}}} passing a descriptor with'
                                     '`dynamic_typing=True` is not allowed when the parameter type is provided')
                descriptor.type = second_arg.value
            else:
                value = second_arg
                if not descriptor.dynamic_typing:
                    descriptor.type = Parameter.Type.from_parameter_value(value).value
                    if descriptor.type == 0:
                        raise ValueError('Cannot declare a statically typed parameter with default value '
                                         'of type PARAMETER_NOT_SET')
            if not ignore_override and name in self._parameter_overrides:
                value = self._parameter_overrides[name].value
            parameter_list.append(Parameter(name, value=value))
            descriptors[name] = descriptor
        already = [p.name for p in parameter_list if p.name in self._parameters]
        if any(already):
            raise ParameterAlreadyDeclaredException(already)
        for param in parameter_list:  # node.py:535-588
            result = self._set_parameters_atomically_common([param], descriptors, allow_not_set_type=True)
            if not result.successful:
                if result.reason.startswith('Wrong parameter type'):
                    raise InvalidParameterTypeException(param, Parameter.Type(descriptors[param._name].type).name)
                raise InvalidParameterValueException(param.name, param.value, result.reason)
        return [self._parameters[p.name] for p in parameter_list]

    def undeclare_parameter(self, name):
        if self.has_parameter(name):
            if self._descriptors[name].read_only:
                from .exceptions import ParameterImmutableException

                raise ParameterImmutableException(name)
            del self._parameters[name]
            del self._descriptors[name]
        else:
            raise ParameterNotDeclaredException(name)

    def has_parameter(self, name):
        return name in self._parameters

    def get_parameter_types(self, names):
        return [self.get_parameter_type(name) for name in names]

    def get_parameter_type(self, name):
        if self.has_parameter(name):
            return self._parameters[name].type_
        if self._allow_undeclared_parameters:
            return Parameter.Type.NOT_SET
        raise ParameterNotDeclaredException(name)

    def get_parameters(self, names):
        if not all(isinstance(name, str) for name in names):
            raise TypeError('All names must be instances of type str')
        return [self.get_parameter(name) for name in names]

    def get_parameter(self, name):
        """node.py:665-690."""
        if self.has_parameter(name):
            parameter = self._parameters[name]
            if parameter.type_ != Parameter.Type.NOT_SET or self._descriptors[name].dynamic_typing:
                return parameter
            raise ParameterUninitializedException(name)
        if self._allow_undeclared_parameters:
            return Parameter(name, Parameter.Type.NOT_SET, None)
        raise ParameterNotDeclaredException(name)

    def get_parameter_or(self, name, alternative_value=None):
        if alternative_value is None:
            alternative_value = Parameter(name, Parameter.Type.NOT_SET)
        return self._parameters.get(name, alternative_value)

    def get_parameters_by_prefix(self, prefix):
        parameters_with_prefix = {}
        if prefix:
            prefix = prefix + '.'
        for parameter_name, param_value in self._parameters.items():
            if parameter_name.startswith(prefix):
                parameters_with_prefix[parameter_name[len(prefix):]] = param_value
        return parameters_with_prefix

    def set_parameters(self, parameter_list):
        """node.py:746-796: one result per parameter; a rejected value is a result, not an error."""
        return [self._set_parameters_atomically([param]) for param in parameter_list]

    def set_parameters_atomically(self, parameter_list):
        return self._set_parameters_atomically(parameter_list)

    def _set_parameters_atomically(self, parameter_list):
        for callback in self._pre_set_parameters_callbacks:
            parameter_list = callback(parameter_list)
        if not self._allow_undeclared_parameters:
            undeclared = [p.name for p in parameter_list if p.name not in self._parameters]
            if undeclared:
                raise ParameterNotDeclaredException(undeclared)
        return self._set_parameters_atomically_common(parameter_list)

    def _set_parameters_atomically_common(self, parameter_list, descriptors=None, allow_not_set_type=False):
        """node.py:861-959: descriptors checked, then each on-set callback (it must return a
        SetParametersResult: its ``successful`` is read, node.py:908-911), then stored."""
        from rcl_interfaces.msg import ParameterDescriptor, SetParametersResult

        result = self._apply_descriptors(parameter_list, self._descriptors if descriptors is None else descriptors,
                                         descriptors is None)
        if not result.successful:
            return result
        for callback in self._on_set_parameters_callbacks:
            result = callback(parameter_list)
            if not result.successful:
                return result
        result = SetParametersResult(successful=True)
        for param in parameter_list:
            if not allow_not_set_type and Parameter.Type.NOT_SET == param.type_:
                self._parameters.pop(param.name, None)
                self._descriptors.pop(param.name, None)
                continue
            if descriptors is not None:
                self._descriptors[param.name] = descriptors[param.name]
            elif param.name not in self._descriptors:
                descriptor = ParameterDescriptor()
                descriptor.dynamic_typing = True
                self._descriptors[param.name] = descriptor
            self._parameters[param.name] = param
        for callback in self._post_set_parameters_callbacks:
            callback(parameter_list)
        return result

    def _apply_descriptors(self, parameter_list, descriptors, check_read_only=True):
        from rcl_interfaces.msg import SetParametersResult

        for param in parameter_list:
            if param.name in descriptors:
                result = self._apply_descriptor(param, descriptors[param.name], check_read_only)
                if not result.successful:
                    return result
        return SetParametersResult(successful=True)

    def _apply_descriptor(self, parameter, descriptor, check_read_only=True):
        """node.py:1194-1250."""
        from rcl_interfaces.msg import SetParametersResult

        descriptor.name = parameter.name
        if check_read_only and descriptor.read_only:
            return SetParametersResult(successful=False,
                                       reason=f'Trying to set a read-only parameter: {parameter.name}.')
        if descriptor.dynamic_typing:
            descriptor.type = parameter.type_.value
        elif self.has_parameter(parameter.name) and parameter.type_ == Parameter.Type.NOT_SET:
            return SetParametersResult(successful=False, reason='Static parameter cannot be undeclared')
        elif parameter.type_ != Parameter.Type.NOT_SET and parameter.type_.value != descriptor.type:
            return SetParametersResult(
                successful=False,
                reason=f"Wrong parameter type, expected '{Parameter.Type(descriptor.type)}' got '{parameter.type_}'")
        if parameter.type_ == Parameter.Type.INTEGER and descriptor.integer_range:
            bounds = descriptor.integer_range[0]
            low, high = sorted((bounds.from_value, bounds.to_value))
            if not low <= parameter.value <= high or (
                    bounds.step and parameter.value not in (low, high) and (parameter.value - low) % bounds.step):
                return SetParametersResult(
                    successful=False,
                    reason=f'Parameter {parameter.name} out of range. Min: {low}, Max: {high}, value: {parameter.value}')
        if parameter.type_ == Parameter.Type.DOUBLE and descriptor.floating_point_range:
            bounds = descriptor.floating_point_range[0]
            low, high = sorted((bounds.from_value, bounds.to_value))
            if not (low - 1e-9 <= parameter.value <= high + 1e-9):
                return SetParametersResult(
                    successful=False,
                    reason=f'Parameter {parameter.name} out of range Min: {low}, Max: {high}, value: {parameter.value}')
        return SetParametersResult(successful=True)

    def add_pre_set_parameters_callback(self, callback):
        self._pre_set_parameters_callbacks.insert(0, callback)

    def add_on_set_parameters_callback(self, callback):
        """node.py:1088-1103: the last added is called first."""
        self._on_set_parameters_callbacks.insert(0, callback)

    def add_post_set_parameters_callback(self, callback):
        self._post_set_parameters_callbacks.insert(0, callback)

    def remove_pre_set_parameters_callback(self, callback):
        self._pre_set_parameters_callbacks.remove(callback)

    def remove_on_set_parameters_callback(self, callback):
        self._on_set_parameters_callbacks.remove(callback)

    def remove_post_set_parameters_callback(self, callback):
        self._post_set_parameters_callbacks.remove(callback)

    def describe_parameter(self, name):
        try:
            return self._descriptors[name]
        except KeyError:
            if self._allow_undeclared_parameters:
                from rcl_interfaces.msg import ParameterDescriptor

                return ParameterDescriptor()
            raise ParameterNotDeclaredException(name) from None

    def describe_parameters(self, names):
        return [self.describe_parameter(name) for name in names]

    def get_fully_qualified_name(self):
        return (self._namespace.rstrip('/') + '/' + self._name)

    # ------------------------------------------------------------ end
    def destroy_node(self):
        for item in (self._publishers_list + self._subscriptions_list + self._timers_list + self._services_list
                     + self._clients_list):
            item.destroy()
        self._services_list, self._clients_list = [], []
        self._publishers_list, self._subscriptions_list, self._timers_list = [], [], []
        object.__setattr__(self, '_destroyed', True)

    # rclpy 7.1's Node has no __enter__/__exit__ (node.py, jazzy): ``with Animation() as node:``
    # raises, as it does on Jazzy (they came in Kilted)


__all__ = ['Node', 'Clock', 'ClockType']
