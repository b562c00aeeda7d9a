import rclpy
from rclpy.node import Node
from std_msgs.msg import Float64


def main():
    rclpy.init()
    node = Node('poller')
    pub = node.create_publisher(Float64, 'angle', 10)
    ticks = []
    node.create_timer(0.1, lambda: ticks.append(pub.publish(Float64(data=0.1 * len(ticks)))))
    while rclpy.ok():
        rclpy.spin_once(node, timeout_sec=0.0)  # polls: returns at once when nothing is due
