import rclpy
from rclpy.node import Node


def main():
    rclpy.init()
    node = Node('arm')
    count = 0
    while rclpy.ok():  # never sleeps, never spins: the clock stands still
        count += 1
    node.destroy_node()
