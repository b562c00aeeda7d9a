import threading

import rclpy
from rclpy.node import Node
from std_msgs.msg import Float64


class Reader(Node):
    def __init__(self):
        super().__init__('reader')
        self.pub = self.create_publisher(Float64, 'value', 10)
        self.values = [0.1, 0.2, 0.3]
        threading.Thread(target=self.loop, daemon=True).start()

    def loop(self):
        rate = self.create_rate(10)
        k = 0
        while rclpy.ok():
            self.pub.publish(Float64(data=self.values[k]))  # IndexError at the fourth tick
            k += 1
            rate.sleep()


def main():
    rclpy.init()
    node = Reader()
    threading.Timer(0.25, lambda: node.get_logger().info('timer thread')).start()
    rclpy.spin(node)
