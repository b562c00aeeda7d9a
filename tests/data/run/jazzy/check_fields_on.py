import os

os.environ['ROS_PYTHON_CHECK_FIELDS'] = '1'  # the Humble-style checks, on demand

import rclpy  # noqa: E402
from rclpy.node import Node  # noqa: E402
from sensor_msgs.msg import JointState  # noqa: E402


def main():
    rclpy.init()
    node = Node('arm')
    pub = node.create_publisher(JointState, 'joint_states', 10)
    msg = JointState()
    msg.position = [0, 1]
    pub.publish(msg)
