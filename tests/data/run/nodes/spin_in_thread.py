import threading

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


def main():
    rclpy.init()
    node = Node('arm')
    pub = node.create_publisher(JointState, 'joint_states', 10)
    threading.Thread(target=rclpy.spin, args=(node,), daemon=True).start()  # the rate's timer is spun here
    rate = node.create_rate(10)
    while rclpy.ok():
        msg = JointState()
        msg.header.stamp = node.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        msg.position = [0.1, 0.2]
        pub.publish(msg)
        rate.sleep()
