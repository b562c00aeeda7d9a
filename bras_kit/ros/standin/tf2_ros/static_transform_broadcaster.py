"""tf2_ros.static_transform_broadcaster, simulated (tf2_ros_py/tf2_ros/static_transform_broadcaster.py,
jazzy): one latched message holding every child frame sent; a child frame sent again keeps its
first transform (static_transform_broadcaster.py:69-72 only appends new child frames)."""

from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile
from tf2_msgs.msg import TFMessage

from .transform_broadcaster import _feed


class StaticTransformBroadcaster:
    def __init__(self, node, qos=None):
        if qos is None:
            qos = QoSProfile(depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL, history=HistoryPolicy.KEEP_LAST)
        self.pub_tf = node.create_publisher(TFMessage, '/tf_static', qos)
        self.net_message = TFMessage()
        self._child_frame_ids = set()

    def sendTransform(self, transform):
        if not isinstance(transform, list):
            transform = list(transform) if hasattr(transform, '__iter__') else [transform]
        for t_in in transform:
            if t_in.child_frame_id not in self._child_frame_ids:
                self._child_frame_ids.add(t_in.child_frame_id)
                self.net_message.transforms.append(t_in)
                _feed(t_in, True)
        self.pub_tf.publish(self.net_message)
