import math

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.timer = self.create_timer(0.05, self.tick)
        self.k = 0

    def tick(self):
        self.k += 1
        msg = JointState()
        if self.k % 2:  # every other message stamped: the others keep a zero stamp
            msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        msg.position = [0.8 * math.sin(0.05 * self.k), 1.2 * math.sin(0.035 * self.k)]
        if self.k % 3 == 0:
            msg.effort = [0.5]
        self.pub.publish(msg)


def main():
    rclpy.init()
    rclpy.spin(Animation())
