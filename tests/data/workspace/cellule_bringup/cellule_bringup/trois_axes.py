"""Un bras à trois articulations (le poignet de l'exercice en plus) : épaule, coude, poignet."""
import math

import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState


class TroisAxes(Node):
    def __init__(self):
        super().__init__('trois_axes')
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.timer = self.create_timer(0.05, self.tick)
        self.t = 0.0

    def tick(self):
        self.t += 0.05
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = ['epaule', 'coude', 'poignet']
        msg.position = [0.3 * math.sin(self.t), 0.6 * math.sin(self.t), 0.9 * math.sin(self.t)]
        self.pub.publish(msg)


def main(args=None):
    rclpy.init(args=args)
    noeud = TroisAxes()
    rclpy.spin(noeud)
    noeud.destroy_node()
    rclpy.shutdown()
