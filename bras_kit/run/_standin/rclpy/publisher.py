"""rclpy.publisher, simulated: every publish is recorded with the simulated time."""

import _bras_msgs
import _bras_sim

from .exceptions import InvalidHandle


class Publisher:
    def __init__(self, node, msg_type, topic, qos_profile):
        self._node = node
        self.msg_type = msg_type
        self.topic = topic
        self.qos_profile = qos_profile
        self._destroyed = False

    @property
    def topic_name(self):
        return self.topic

    def publish(self, msg):
        if self._destroyed or self._node._destroyed:
            raise InvalidHandle('cannot use Destroyable because destruction was requested')
        if not isinstance(msg, self.msg_type):
            # rclpy/publisher.py Publisher.publish
            raise TypeError(f'Expected {self.msg_type}, got {type(msg)}')
        fields = _bras_msgs.to_data(msg)
        _bras_sim.record(self._node.get_name(), self.topic, _bras_msgs.type_name(self.msg_type) or '?', fields)
        from .executors import deliver

        deliver(self.topic, self.msg_type, msg)

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
