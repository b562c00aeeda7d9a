import math

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState

STEP = 0.05  # seconds between messages (20 Hz)


class Waves(Node):
    def __init__(self):
        super().__init__('animation_bras')
        self.publisher = self.create_publisher(JointState, 'joint_states', 10)
        self.timer = self.create_timer(STEP, self.on_timer)
        self.t = 0.0

    def on_timer(self):
        self.t += STEP
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        msg.position = [0.8 * math.sin(self.t), 1.2 * math.sin(0.7 * self.t)]
        self.publisher.publish(msg)


def main(args=None):
    rclpy.init(args=args)
    node = Waves()
    rclpy.spin(node)
    node.destroy_node()
    rclpy.shutdown()
