import rclpy
from rclpy.duration import Duration
from rclpy.node import Node
from rclpy.qos import QoSProfile, ReliabilityPolicy
from rclpy.task import Future
from std_msgs.msg import Float64


def main():
    rclpy.init()
    node = Node('waiter')
    pub = node.create_publisher(Float64, 'elapsed', QoSProfile(depth=5, reliability=ReliabilityPolicy.BEST_EFFORT))
    start = node.get_clock().now()
    done = Future()
    ticks = []

    def tick():
        ticks.append(1)
        if len(ticks) == 3:
            done.set_result('three ticks')

    node.create_timer(0.2, tick)
    rclpy.spin_until_future_complete(node, done)
    elapsed = node.get_clock().now() - start
    pub.publish(Float64(data=elapsed.nanoseconds / 1e9))
    later = start + Duration(seconds=1.5)
    pub.publish(Float64(data=float(later.seconds_nanoseconds()[1])))
    node.get_logger().info(done.result())
    node.destroy_node()
    rclpy.shutdown()
