"""A stand-in for robot_state_publisher 3.3.3 (Jazzy), in the real rclpy, following
src/robot_state_publisher.cpp (github.com/ros/robot_state_publisher, tag 3.3.3) line for line
where the graph can see it:

* node ``robot_state_publisher`` (line 77), parameters ``robot_description`` (line 80; the file
  given as first argument when it is empty, lines 81-101), ``publish_frequency`` 20.0 (118-121),
  ``frame_prefix`` "" (124), ``ignore_timestamp`` false (127);
* /robot_description: ``rclcpp::QoS(1).transient_local()``, reliable (lines 132-135), published
  once in setupURDF (lines 213-217);
* /joint_states read with ``SensorDataQoS`` (best effort, volatile, depth 5) and QoS overriding
  options with the default policies (lines 139-147), which declare the
  ``qos_overrides./joint_states.subscription.*`` parameters;
* /parameter_events read (lines 156-158, on_parameter_event);
* callbackJointState (lines 300-363): the size check, the clock gone backwards, the least recently
  published joint, the publish interval, mimic joints, then one transform per moving joint. It
  logs what rsp logs (its WARN and ERROR lines) and, when tf2_msgs imports, publishes /tf and
  /tf_static (tf2_ros's broadcasters' QoS: depth 100, /tf_static transient_local). tf2_msgs has no
  wheel on PyPI: there, the transforms are counted, not sent.

    python state_publisher.py URDF [--volatile] [--text TEXT] [--use-sim-time] [--name NAME] [--silent]
                                   [--namespace NS] [--publish-frequency HZ]

``--volatile`` publishes it volatile (a hand-written publisher that forgot the durability);
``--text`` publishes TEXT instead of the file's contents (a path given as the description, "");
``--silent`` makes the publisher and never publishes (a hand-written node that forgot to).
"""

import argparse
import signal
import xml.etree.ElementTree as ET

import rclpy
from rcl_interfaces.msg import ParameterEvent
from rclpy.duration import Duration
from rclpy.parameter import Parameter
from rclpy.qos import DurabilityPolicy, QoSProfile, ReliabilityPolicy, qos_profile_sensor_data
from rclpy.qos_overriding_options import QoSOverridingOptions
from rclpy.time import Time
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
parser.add_argument("--publish-frequency", type=float, default=20.0)
parser.add_argument("--replace-after", type=float, default=None,
                    help="SECONDS after a second reader (the doctor) joined, set robot_description to --replace-with "
                         "(ros2 param set: onParameterEvent's setupURDF publishes it, lines 420-432)")
parser.add_argument("--replace-with", default=None)
args = parser.parse_args()
with open(args.urdf, encoding="utf-8") as file:
    description = file.read() if args.text is None else args.text

try:
    from tf2_msgs.msg import TFMessage
except ImportError:  # no wheel on PyPI: the transforms are counted only
    TFMessage = None

MOVING = ("revolute", "continuous", "prismatic")  # kdl_parser: the joint types with an axis


def segments(text):
    """(moving joints by name -> (parent, child), fixed ones, mimic by name), as setupURDF and
    addChildren make them (lines 180-245); a floating joint is skipped (229-236)."""
    moving, fixed, mimic = {}, {}, {}
    try:
        root = ET.fromstring(text)
    except ET.ParseError:
        return moving, fixed, mimic
    for joint in root.iter("joint"):
        name, kind = joint.get("name"), joint.get("type")
        parent, child = joint.find("parent"), joint.find("child")
        if name is None or parent is None or child is None:
            continue
        pair = (parent.get("link"), child.get("link"))
        if kind in MOVING:
            moving[name] = pair
        elif kind != "floating":
            fixed[name] = pair
        copy = joint.find("mimic")
        if copy is not None:
            mimic[name] = (copy.get("joint"), float(copy.get("multiplier", 1.0)), float(copy.get("offset", 0.0)))
    return moving, fixed, dict(sorted(mimic.items()))  # a std::map: by name


rclpy.init()
# SIGTERM (the test stopping the graph) ends the process at once, as the kernel does by
# default: rclpy's own handler now and then hangs in its shutdown (seen under load)
signal.signal(signal.SIGTERM, signal.SIG_DFL)
node = rclpy.create_node(args.name, namespace=args.namespace or None, parameter_overrides=[
    Parameter("use_sim_time", Parameter.Type.BOOL, args.use_sim_time)])
node.declare_parameter("robot_description", description)
publish_frequency = node.declare_parameter("publish_frequency", args.publish_frequency).value
if publish_frequency < 0.0 or publish_frequency > 1000.0:
    raise RuntimeError("publish_frequency must be between 0 and 1000")
node.declare_parameter("frame_prefix", "")
node.declare_parameter("ignore_timestamp", False)
durability = DurabilityPolicy.VOLATILE if args.volatile else DurabilityPolicy.TRANSIENT_LOCAL
tf_pub = static_pub = None
if TFMessage is not None:  # tf2_ros's TransformBroadcaster and StaticTransformBroadcaster (lines 129-130)
    tf_pub = node.create_publisher(TFMessage, "/tf", QoSProfile(depth=100))
    static_pub = node.create_publisher(TFMessage, "/tf_static", QoSProfile(
        depth=1, durability=DurabilityPolicy.TRANSIENT_LOCAL))
publisher = node.create_publisher(String, "robot_description", QoSProfile(
    depth=1, reliability=ReliabilityPolicy.RELIABLE, durability=durability))
moving, fixed, mimic = segments(description)
last_publish_time = {}
last_callback_time = [Time(clock_type=node.get_clock().clock_type)]
published = [0]


def transforms(pairs, stamp):
    from geometry_msgs.msg import TransformStamped

    prefix = node.get_parameter("frame_prefix").value
    out = []
    for parent, child in pairs:
        t = TransformStamped()
        t.header.stamp = stamp
        t.header.frame_id, t.child_frame_id = prefix + parent, prefix + child
        t.transform.rotation.w = 1.0  # the pose itself is KDL's: the graph test reads frames and stamps
        out.append(t)
    return out


def callback_joint_state(state):
    """callbackJointState, lines 300-363."""
    if len(state.name) != len(state.position):
        if not state.position:
            node.get_logger().warn("Robot state publisher ignored a JointState message about joint(s) "
                                   f"\"{state.name[0]}\"(,...) whose position member was empty.")
        else:
            node.get_logger().error("Robot state publisher ignored an invalid JointState message")
        return
    now = node.get_clock().now()
    if last_callback_time[0].nanoseconds > now.nanoseconds:
        node.get_logger().warn("Moved backwards in time, re-publishing joint transforms!")
        last_publish_time.clear()
    last_callback_time[0] = now
    last_published = now.nanoseconds
    for name in state.name:
        t = last_publish_time.setdefault(name, 0)  # std::map::operator[] inserts a zero time
        last_published = min(t, last_published)
    current = Time.from_msg(state.header.stamp).nanoseconds
    interval = Duration(nanoseconds=int(1000.0 / publish_frequency) * 1_000_000).nanoseconds
    if node.get_parameter("ignore_timestamp").value or current >= last_published + interval:
        positions = {}
        for name, position in zip(state.name, state.position):
            positions.setdefault(name, position)
        for name, (leader, multiplier, offset) in mimic.items():
            if leader in positions:
                positions.setdefault(name, positions[leader] * multiplier + offset)
        pairs = [moving[name] for name in sorted(positions) if name in moving]
        if tf_pub is not None:
            tf_pub.publish(TFMessage(transforms=transforms(pairs, state.header.stamp)))
        published[0] += 1
        for name in state.name:
            last_publish_time[name] = current


node.create_subscription(JointState, "joint_states", callback_joint_state, qos_profile_sensor_data,
                         qos_overriding_options=QoSOverridingOptions.with_default_policies())
node.create_subscription(ParameterEvent, "/parameter_events", lambda event: None, QoSProfile(depth=1000))
if static_pub is not None:  # publishFixedTransforms (lines 279-298), stamped now
    static_pub.publish(TFMessage(transforms=transforms(fixed.values(), node.get_clock().now().to_msg())))
if not args.silent:
    publisher.publish(String(data=description))
    node.get_logger().info("Robot initialized")
if args.volatile and not args.silent:  # a volatile description is only seen by whoever listens at that instant: say it again
    node.create_timer(0.5, lambda: publisher.publish(String(data=description)))
if args.replace_after is not None:
    with open(args.replace_with, encoding="utf-8") as file:
        replacement = file.read()
    matched = []

    def replace():
        if not matched and publisher.get_subscription_count() >= 2:  # the RViz stand-in and the doctor
            matched.append(node.get_clock().now())
        if matched and (node.get_clock().now() - matched[0]).nanoseconds > args.replace_after * 1e9:
            node.set_parameters([Parameter("robot_description", Parameter.Type.STRING, replacement)])
            globals()["moving"], globals()["fixed"], globals()["mimic"] = segments(replacement)
            publisher.publish(String(data=replacement))
            node.get_logger().info("Robot initialized")
            timer.cancel()

    timer = node.create_timer(0.1, replace)
print("ready", flush=True)  # the test starts its look once every node says so
try:
    rclpy.spin(node)
except (KeyboardInterrupt, rclpy.executors.ExternalShutdownException):
    pass
except Exception:  # a publish racing the shutdown that Ctrl-C began
    if rclpy.ok():
        raise
