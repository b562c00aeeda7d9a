import numpy as np
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
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        # a list of integers, a tuple, a numpy array: all three work on Jazzy
        msg.position = [[0, 0], (0.1, 0.2), np.array([0.3, 0.4])][self.k % 3]
        self.pub.publish(msg)


def main():
    rclpy.init()
    rclpy.spin(Animation())
