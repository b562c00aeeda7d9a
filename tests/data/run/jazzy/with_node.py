import rclpy
from rclpy.node import Node


class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras')


def main():
    rclpy.init()
    with Animation() as node:  # rclpy 7.1's Node has no __enter__
        rclpy.spin(node)
