"""Renames itself after rclpy checked its name, once through Node's attribute, once through the
stand-in's own: a title sequence and a bidi override, meant for the teacher's terminal."""
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState

PLANTED = "\x1b]0;pwned\x07evil\u202e"


def main():
    rclpy.init()
    node = Node("bras_node")
    pub = node.create_publisher(JointState, "joint_states", 10)
    msg = JointState(name=["epaule"], position=[0.1])
    pub.publish(msg)                        # sent before the rename: stays as sent
    node._name = PLANTED                    # what get_name() returns from now on
    node.create_publisher(JointState, "joint_states", 10)
    pub.publish(msg)                        # recorded under the name rclpy checked
    node._bras_name = PLANTED               # the stand-in's own copy of the name
    pub._node_name = PLANTED
    pub._topic = "/joint_states\x1b[2J"
    node.create_publisher(JointState, "joint_states", 10)
    pub.publish(msg)                        # refused by bras-kit's process: not a ROS 2 name
    rclpy.shutdown()
