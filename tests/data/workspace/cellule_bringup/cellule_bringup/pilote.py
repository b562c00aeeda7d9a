"""Publie sur /joint_states les articulations du bras que décrit l'autre paquet, bras_description."""
import math
import os
import xml.etree.ElementTree as ET

import rclpy
from ament_index_python.packages import get_package_share_directory
from rclpy.node import Node
from sensor_msgs.msg import JointState


def articulations():
    urdf = os.path.join(get_package_share_directory('bras_description'), 'urdf', 'bras.urdf')
    return [j.get('name') for j in ET.parse(urdf).getroot().iter('joint') if j.get('type') != 'fixed']


class Pilote(Node):
    def __init__(self):
        super().__init__('pilote')
        self.noms = articulations()
        self.pub = self.create_publisher(JointState, 'joint_states', 10)
        self.timer = self.create_timer(0.05, self.tick)
        self.t = 0.0

    def tick(self):
        self.t += 0.05
        msg = JointState()
        msg.header.stamp = self.get_clock().now().to_msg()
        msg.name = self.noms
        msg.position = [0.5 * math.sin(self.t)] * len(self.noms)
        self.pub.publish(msg)


def main(args=None):
    rclpy.init(args=args)
    noeud = Pilote()
    rclpy.spin(noeud)
    noeud.destroy_node()
    rclpy.shutdown()
