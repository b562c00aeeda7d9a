import rclpy
from rclpy.node import Node


def main():
    node = Node('arm')  # rclpy.init() forgotten
    rclpy.spin(node)
