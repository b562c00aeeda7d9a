import time

import rclpy
from rclpy.callback_groups import ReentrantCallbackGroup
from rclpy.executors import MultiThreadedExecutor
from rclpy.node import Node
from sensor_msgs.msg import JointState
from std_msgs.msg import String


class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras')
        group = ReentrantCallbackGroup()
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.slow = self.create_publisher(String, 'slow', 10)
        self.create_timer(0.05, self.tick, callback_group=group)
        self.create_timer(0.5, self.think, callback_group=group)

    def tick(self):
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        msg.position = [0.1, 0.2]
        self.pub.publish(msg)

    def think(self):
        time.sleep(0.3)  # a long computation: the other timer keeps its 20 Hz meanwhile
        self.slow.publish(String(data='done'))


def main():
    rclpy.init()
    executor = MultiThreadedExecutor(num_threads=4)
    executor.add_node(Animation())
    try:
        executor.spin()
    except KeyboardInterrupt:
        pass
