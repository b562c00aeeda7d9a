"""tf2_ros.transform_listener, simulated (tf2_ros_py/tf2_ros/transform_listener.py, jazzy):
the subscriptions to /tf and /tf_static feed the buffer (here: every Buffer reads one store)."""

from rclpy.qos import DurabilityPolicy, HistoryPolicy, QoSProfile
from tf2_msgs.msg import TFMessage


class TransformListener:
    def __init__(self, buffer, node, *, spin_thread=False, qos=None, static_qos=None):
        if qos is None:
            qos = QoSProfile(depth=100)
        if static_qos is None:
            static_qos = QoSProfile(depth=100, durability=DurabilityPolicy.TRANSIENT_LOCAL,
                                    history=HistoryPolicy.KEEP_LAST)
        self.buffer = buffer
        self.node = node
        self.tf_sub = node.create_subscription(TFMessage, '/tf', lambda msg: None, qos)
        self.tf_static_sub = node.create_subscription(TFMessage, '/tf_static', lambda msg: None, static_qos)

    def unregister(self):
        self.node.destroy_subscription(self.tf_sub)
        self.node.destroy_subscription(self.tf_static_sub)
