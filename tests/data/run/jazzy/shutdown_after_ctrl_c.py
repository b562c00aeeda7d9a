import rclpy
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('talker')
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
    node.destroy_node()
    rclpy.shutdown()  # line 13: the SIGINT handler already shut the context down
