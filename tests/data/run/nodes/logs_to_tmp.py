import math

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class Arm(Node):
    def __init__(self):
        super().__init__('arm')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.log = open('/tmp/angles.csv', 'w')  # a log beside the node? outside its run's folder
        self.create_timer(0.05, self.tick)
        self.t = 0.0

    def tick(self):
        self.t += 0.05
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        msg.position = [0.8 * math.sin(self.t), 1.2 * math.sin(0.7 * self.t)]
        self.log.write(f'{self.t},{msg.position[0]},{msg.position[1]}\n')
        self.pub.publish(msg)


def main():
    rclpy.init()
    rclpy.spin(Arm())
