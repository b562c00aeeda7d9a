import rclpy
from rclpy.action import ActionServer  # not simulated


def main():
    rclpy.init()
    print(ActionServer)
