"""A reader of the description in the real rclpy, standing for RViz's RobotModel display: node
``rviz2`` reading /robot_description reliable and transient_local, as a reader started after
robot_state_publisher must to get its latched message (``--volatile``: volatile instead).

    python rviz_reader.py [--volatile]
"""

import signal
import sys

import rclpy
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy
from std_msgs.msg import String

durability = DurabilityPolicy.VOLATILE if "--volatile" in sys.argv else DurabilityPolicy.TRANSIENT_LOCAL
rclpy.init()
# SIGTERM (the test stopping the graph) ends the process at once, as the kernel does by
# default: rclpy's own handler now and then hangs in its shutdown (seen under load)
signal.signal(signal.SIGTERM, signal.SIG_DFL)
node = rclpy.create_node("rviz2")
node.create_subscription(String, "robot_description", lambda msg: None, QoSProfile(
    depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=durability))
print("ready", flush=True)  # the test starts its look once every node says so
try:
    rclpy.spin(node)
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
except Exception:  # a publish racing the shutdown that Ctrl-C began
    if rclpy.ok():
        raise
