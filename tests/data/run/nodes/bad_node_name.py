import rclpy
from rclpy.node import Node


def main():
    rclpy.init()
    Node('mon-bras')  # '-' is not allowed in a node name
