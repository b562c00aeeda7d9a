import rclpy
from rclpy.node import Node


def main():
    # one string where rcl wants two words: '--log-level' and 'warn'
    rclpy.init(args=['--ros-args', '--log-level warn'])
    node = Node('animation_bras')
    rclpy.spin(node)
