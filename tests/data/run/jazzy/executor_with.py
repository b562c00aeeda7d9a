import rclpy
from rclpy.executors import SingleThreadedExecutor
from rclpy.node import Node
from std_msgs.msg import String


def main():
    rclpy.init()
    node = Node('talker')
    pub = node.create_publisher(String, 'chatter', 10)
    node.create_timer(0.5, lambda: pub.publish(String(data='hi')))
    with SingleThreadedExecutor() as executor:  # executors have __enter__ in 7.1
        executor.add_node(node)
        try:
            executor.spin()
        except KeyboardInterrupt:
            pass
    rclpy.try_shutdown()
