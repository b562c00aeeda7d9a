"""A launch file that attacks while ros2 launch reads it (before it imports launch), each attack
tried and its failure ignored."""
import json
import os
import socket

TARGETS = json.load(open(os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "targets.json")))

try:
    socket.socket(socket.AF_INET, socket.SOCK_DGRAM).sendto(b"pwned", ("127.0.0.1", TARGETS["port"]))
except OSError:
    pass
try:
    with open(os.path.expanduser("~/bk_pwned_launch.txt"), "w") as handle:
        handle.write("pwned\n")
except OSError:
    pass

from launch import LaunchDescription  # noqa: E402


def generate_launch_description():
    return LaunchDescription([])
