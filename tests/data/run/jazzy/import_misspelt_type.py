import math

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointSate


class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras')
        self.pub = self.create_publisher(JointSate, 'joint_states', 10)
        self.timer = self.create_timer(0.05, self.tick)
        self.t = 0.0

    def tick(self):
        self.t += 0.05
        msg = JointSate()
        msg.name = ['epaule', 'coude']
        msg.position = [0.8 * math.sin(self.t), 1.2 * math.sin(self.t * 0.7)]
        self.pub.publish(msg)


def main():
    rclpy.init()
    rclpy.spin(Animation())
