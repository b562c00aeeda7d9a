import math

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class Arm(Node):
    def __init__(self):
        super().__init__('arm')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.create_timer(0.05, self.tick)
        self.k = 0

    def tick(self):
        self.k += 1
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        if self.k == 4:
            msg.position = [0.1, 0.2, 0.3]  # one position too many
        else:
            msg.position = [0.1, math.nan if self.k == 2 else 0.2]  # tick 2: not a number
        self.pub.publish(msg)


def main():
    rclpy.init()
    rclpy.spin(Arm())
