"""A stand-in for robot_state_publisher 3.3 (Jazzy), in the real rclpy: it publishes the URDF on
/robot_description reliable, transient_local, depth 1 (src/robot_state_publisher.cpp:133-135) and
reads /joint_states with SensorDataQoS (:144-147). No TF: tf2_msgs has no wheel on PyPI yet.

    python state_publisher.py URDF [--volatile] [--text TEXT] [--use-sim-time] [--name NAME] [--silent]

``--volatile`` publishes it volatile (a hand-written publisher that forgot the durability);
``--text`` publishes TEXT instead of the file's contents (a path given as the description, "");
``--silent`` makes the publisher and never publishes (a hand-written node that forgot to).
"""

import argparse
import signal

import rclpy
from rclpy.parameter import Parameter
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy, qos_profile_sensor_data
from sensor_msgs.msg import JointState
from std_msgs.msg import String

parser = argparse.ArgumentParser()
parser.add_argument("urdf")
parser.add_argument("--volatile", action="store_true")
parser.add_argument("--text")
parser.add_argument("--use-sim-time", action="store_true")
parser.add_argument("--name", default="robot_state_publisher")
parser.add_argument("--silent", action="store_true")
parser.add_argument("--namespace", default="", help="the node's namespace (the launch's namespace='/arm')")
args = parser.parse_args()
with open(args.urdf, encoding="utf-8") as file:
    description = file.read() if args.text is None else args.text

rclpy.init()
# SIGTERM (the test stopping the graph) ends the process at once, as the kernel does by
# default: rclpy's own handler now and then hangs in its shutdown (seen under load)
signal.signal(signal.SIGTERM, signal.SIG_DFL)
node = rclpy.create_node(args.name, namespace=args.namespace or None, parameter_overrides=[
    Parameter("use_sim_time", Parameter.Type.BOOL, args.use_sim_time)])
node.declare_parameter("robot_description", description)
durability = DurabilityPolicy.VOLATILE if args.volatile else DurabilityPolicy.TRANSIENT_LOCAL
publisher = node.create_publisher(String, "robot_description", QoSProfile(
    depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=durability))
node.create_subscription(JointState, "joint_states", lambda msg: None, qos_profile_sensor_data)
if not args.silent:
    publisher.publish(String(data=description))
if args.volatile and not args.silent:  # a volatile description is only seen by whoever listens at that instant: say it again
    node.create_timer(0.5, lambda: publisher.publish(String(data=description)))
print("ready", flush=True)  # the test starts its look once every node says so
try:
    rclpy.spin(node)
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
except Exception:  # a publish racing the shutdown that Ctrl-C began
    if rclpy.ok():
        raise
