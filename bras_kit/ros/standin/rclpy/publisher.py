"""rclpy.publisher, simulated: every publish is recorded with the simulated time."""

import sys

import _bras_sim
import _messages

from .exceptions import InvalidHandle


class Publisher:
    def __init__(self, node, msg_type, topic, qos_profile):
        self._node = node
        self._node_name = node._bras_name  # as checked when the node was made: recorded with each message
        self.msg_type = msg_type
        self.topic = topic
        self._topic = topic  # the resolved name as checked by create_publisher
        self.qos_profile = qos_profile
        self._destroyed = False

    @property
    def topic_name(self):
        return self.topic

    def publish(self, msg):
        if self._destroyed or self._node._destroyed:
            raise InvalidHandle('cannot use Destroyable because destruction was requested')
        if not isinstance(msg, self.msg_type):
            # rclpy/src/rclpy/publisher.cpp Publisher::publish (via the type support's
            # convert_from_py): the message must be of the publisher's type
            raise TypeError(f'Expected {self.msg_type}, got {type(msg)}')
        broken = _messages.convert_check(msg)
        if broken is not None:
            # the setters let anything in (no ROS_PYTHON_CHECK_FIELDS): the C conversion's assert
            # stops the process (_msg_support.c.em:436-516), with no Python exception to catch
            field, assertion, held = broken
            aborted = _bras_sim.Aborted(f"{_messages.type_name(self.msg_type)} field '{field}': "
                                        f"Assertion `{assertion}' failed")
            aborted.field, aborted.held = field, held
            raise aborted
        for field, value in _messages.split_strings(msg):
            path, line = _bras_sim.caller()
            _bras_sim.STATE.split_strings.append((self._node_name, self._topic, field, value, path, line))
        fields = _messages.to_data(msg)
        _bras_sim.record(self._node_name, self._topic, _messages.type_name(self.msg_type) or '?', fields)
        from .executors import deliver

        deliver(self.topic, self.msg_type, msg)
        tf = sys.modules.get('tf2_ros._core')
        if tf is not None and self.topic == '/joint_states' and hasattr(msg, 'position'):
            tf.joint_states_published(msg)  # robot_state_publisher's /tf, for the node's Buffer

    def get_subscription_count(self):
        from .executors import subscriptions_on

        return len(subscriptions_on(self.topic))

    def destroy(self):
        self._destroyed = True


class Subscription:
    def __init__(self, node, msg_type, topic, callback, qos_profile):
        self._node = node
        self.msg_type = msg_type
        self.topic = topic
        self.callback = callback
        self.qos_profile = qos_profile
        self.queue = []
        self._destroyed = False

    @property
    def topic_name(self):
        return self.topic

    def destroy(self):
        self._destroyed = True
