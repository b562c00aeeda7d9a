"""One 2,000-joint message, then 200,000 references to its line of the record and to a dict
(the attack that made run -o and grade reach 3.6 GB when the record crossed as objects)."""
import _bras_sim
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState

JOINTS = 2000


def main():
    rclpy.init()
    node = Node("bras_node")
    pub = node.create_publisher(JointState, "joint_states", 10)
    msg = JointState(name=[f"joint_{k}" for k in range(JOINTS)], position=[0.001 * k for k in range(JOINTS)],
                     velocity=[0.0] * JOINTS, effort=[0.0] * JOINTS)
    msg.header.stamp = node.get_clock().now().to_msg()
    pub.publish(msg)
    messages = _bras_sim.STATE.messages
    messages.extend([messages[-1]] * 200_000)
    rclpy.shutdown()
