import math
import time

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


def main():
    rclpy.init()
    node = Node('arm')
    pub = node.create_publisher(JointState, 'joint_states', 10)
    t = 0.0
    while rclpy.ok():
        msg = JointState()
        msg.header.stamp = node.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        msg.position = [0.5 * math.sin(t), 0.0]
        pub.publish(msg)
        time.sleep(0.05)
        t += 0.05
