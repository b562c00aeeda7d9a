import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


def main():
    rclpy.init()
    node = Node('arm')
    node.create_publisher(JointState, 'joint states', 10)  # a space: not a legal topic name
