"""tf2_ros.transform_broadcaster, simulated (tf2_ros_py/tf2_ros/transform_broadcaster.py, jazzy)."""

from rclpy.qos import QoSProfile
from tf2_msgs.msg import TFMessage

from ._core import NS, STORE


class TransformBroadcaster:
    def __init__(self, node, qos=None):
        if qos is None:
            qos = QoSProfile(depth=100)  # transform_broadcaster.py:52-53
        self.pub_tf = node.create_publisher(TFMessage, '/tf', qos)

    def sendTransform(self, transform):
        if not isinstance(transform, list):
            transform = list(transform) if hasattr(transform, '__iter__') else [transform]
        self.pub_tf.publish(TFMessage(transforms=transform))
        for t in transform:
            _feed(t, False)


def _feed(t, static):
    x = t.transform
    STORE.set(t.header.frame_id, t.child_frame_id, t.header.stamp.sec * NS + t.header.stamp.nanosec,
              ((x.translation.x, x.translation.y, x.translation.z),
               (x.rotation.x, x.rotation.y, x.rotation.z, x.rotation.w)), static)
