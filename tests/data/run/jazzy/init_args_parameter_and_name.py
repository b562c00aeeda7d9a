import math

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class Animation(Node):
    def __init__(self):
        super().__init__('animation_bras', cli_args=['--ros-args', '-r', '~/etats:=/joint_states'])
        self.amplitude = self.declare_parameter('amplitude', 0.8).value
        # '~/etats' is under the node's name: the remapped name, given by __node below
        self.pub = self.create_publisher(JointState, '~/etats', 10)
        self.timer = self.create_timer(0.05, self.tick)
        self.t = 0.0

    def tick(self):
        self.t += 0.05
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude']
        msg.position = [self.amplitude * math.sin(self.t), 1.2 * math.sin(self.t * 0.7)]
        self.pub.publish(msg)


def main():
    rclpy.init(args=['--ros-args', '-p', 'amplitude:=0.3', '-r', '__node:=bras'])
    noeud = Animation()
    noeud.get_logger().info(f'{noeud.get_name()} {noeud.get_fully_qualified_name()}')
    rclpy.spin(noeud)
