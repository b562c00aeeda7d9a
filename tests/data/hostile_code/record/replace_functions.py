"""Replaces the stand-in's functions: the recorder, and the writer of the record itself, which
then sends a forged summary (a planted node and topic, a source path out of the package, a huge
count of messages claimed dropped)."""
import json

import _bras_sim
import rclpy
from rclpy.node import Node
from sensor_msgs.msg import JointState

from bras_kit.ros import record_wire

PLANTED = "\x1b]0;pwned\x07"


def forged(summary, messages, logs):
    summary = dict(summary, nodes=[PLANTED, "bras_node"], source="../../../etc/passwd",
                   publishers=[[PLANTED, "/joint_states", "sensor_msgs/msg/JointState", "/etc/passwd", 1]],
                   ended="owned", rate_sleeps="many", output="x" * 500_000)
    lines = [json.dumps(["m", 0, "bras_node", "/joint_states", "sensor_msgs/msg/JointState",
                         {"name": ["epaule"], "position": [0.5]}]).encode() + b"\n"]
    return json.dumps(summary).encode() + b"\n" + b"".join(lines) + b"[" * 100_000 + b"\n"


def main():
    rclpy.init()
    node = Node("bras_node")
    pub = node.create_publisher(JointState, "joint_states", 10)
    _bras_sim.record = lambda *args: _bras_sim.STATE.messages.append(b"not json\n")
    record_wire.write_record = forged
    pub.publish(JointState(name=["epaule"], position=[0.1]))
    rclpy.shutdown()
