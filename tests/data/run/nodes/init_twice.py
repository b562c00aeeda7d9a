import rclpy


def main():
    rclpy.init()
    rclpy.init()  # once is enough
