import rclpy
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('arm')
    node.destroy_node()
    rclpy.spin(node)
