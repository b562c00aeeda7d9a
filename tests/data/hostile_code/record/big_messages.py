"""Publishes a message of 2,000 joints every millisecond of simulated time, and one too large
for a line of the record (400,000 joints)."""
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState

JOINTS = 2000


def main():
    rclpy.init()
    node = Node("bras_node")
    pub = node.create_publisher(JointState, "joint_states", 10)
    names = [f"joint_{k}" for k in range(JOINTS)]
    pub.publish(JointState(name=["j"] * 400_000, position=[0.0] * 400_000))
    count = [0]

    def tick():
        count[0] += 1
        pub.publish(JointState(name=names, position=[0.001 * count[0]] * JOINTS))

    node.create_timer(0.001, tick)
    rclpy.spin(node)
