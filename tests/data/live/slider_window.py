"""A stand-in for the slider window (joint_state_publisher_gui) in the real rclpy: node
``joint_state_publisher`` publishing every movable joint of the URDF on /joint_states at 10 Hz
(joint_state_publisher's ``rate`` parameter defaults to 10), each at the middle of its limits
(or zero when 0 is within them, as the window starts), stamped with the time now.

    python slider_window.py URDF
"""

import signal
import sys
import xml.etree.ElementTree as ET

import rclpy
from sensor_msgs.msg import JointState

robot = ET.parse(sys.argv[1]).getroot()
names, positions = [], []
for joint in robot.iter("joint"):
    if joint.get("type") in ("revolute", "continuous", "prismatic"):
        limit = joint.find("limit")
        lower = float(limit.get("lower", 0)) if limit is not None else 0.0
        upper = float(limit.get("upper", 0)) if limit is not None else 0.0
        names.append(joint.get("name"))
        positions.append(0.0 if lower <= 0.0 <= upper else (lower + upper) / 2)

rclpy.init()
# SIGTERM (the test stopping the graph) ends the process at once, as the kernel does by
# default: rclpy's own handler now and then hangs in its shutdown (seen under load)
signal.signal(signal.SIGTERM, signal.SIG_DFL)
node = rclpy.create_node("joint_state_publisher")
publisher = node.create_publisher(JointState, "joint_states", 10)


def tick():
    msg = JointState()
    msg.header.stamp = node.get_clock().now().to_msg()
    msg.name = names
    msg.position = positions
    publisher.publish(msg)


node.create_timer(0.1, tick)
print("ready", flush=True)  # the test starts its look once every node says so
try:
    rclpy.spin(node)
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
except Exception:  # a publish racing the shutdown that Ctrl-C began
    if rclpy.ok():
        raise
