"""Adds entries to the stand-in's own lists: nodes, publishers, timers, messages, logs, split
strings, each with text a terminal would obey or a value of the wrong type."""
import _bras_sim
import rclpy
from rclpy.node import Node

PLANTED = "\x1b]0;pwned\x07"


def main():
    rclpy.init()
    node = Node("bras_node")
    state = _bras_sim.STATE
    state.node_names.append(PLANTED)
    state.publishers.append((PLANTED, "/joint_states", "sensor_msgs/msg/JointState", "", 0))
    state.publishers.append(("bras_node", "/joint_states" + PLANTED, "sensor_msgs/msg/JointState", "", 0))
    state.subscriptions.append(("bras_node", "/x", "not a type" + PLANTED, "", 0))
    state.timers.append(("bras_node", "every now and then", "", 0))
    state.split_strings.append((PLANTED, "/joint_states", "name", "abc", "", 0))
    state.messages.append(b'["m",0,"bras_node","/joint_states","sensor_msgs/msg/JointState",'
                          b'{"name":["epaule"],"position":["0.1; rm -rf"]}]\n')
    state.messages.append(b'["m",0,"' + PLANTED.encode() + b'","/joint_states","sensor_msgs/msg/JointState",'
                          b'{"name":["epaule"],"position":[0.1]}]\n')
    state.messages.append(("old", "tuple"))
    state.logs.append(b'["l",0,"INFO","' + PLANTED.encode() + b'","hello"]\n')
    node.get_logger().info("a log of its own")
    rclpy.shutdown()
