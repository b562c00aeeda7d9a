"""Prints, logs and raises text with terminal control sequences: clear the screen, set the
window title, move the cursor back over the line (a carriage return), ring the bell."""
import rclpy
from rclpy.node import Node

TRICK = "\x1b[2J\x1b]0;pwned-title\x07\rhidden\x9b31m"


def main():
    rclpy.init()
    node = Node("echappement")
    print("print:" + TRICK)
    node.get_logger().info("log:" + TRICK)
    raise RuntimeError("raised:" + TRICK)
