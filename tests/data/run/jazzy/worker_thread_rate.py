import math
import threading

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.worker = threading.Thread(target=self.loop, daemon=True)
        self.worker.start()

    def loop(self):
        rate = self.create_rate(20)
        t = 0.0
        while rclpy.ok():
            t += 0.05
            msg = JointState()
            msg.header.stamp = self.get_clock().now().to_msg()
            msg.name = ['epaule', 'coude']
            msg.position = [0.8 * math.sin(t), 1.2 * math.sin(0.7 * t)]
            self.pub.publish(msg)
            rate.sleep()


def main():
    rclpy.init()
    node = Animation()
    try:
        rclpy.spin(node)
    except KeyboardInterrupt:
        pass
