"""A setup.py that attacks while colcon runs it: each attack tried, its failure ignored."""
import json
import os
import socket

from setuptools import setup

TARGETS = json.load(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "targets.json")))

try:
    with open(os.path.expanduser("~/bk_pwned_setup.txt"), "w") as handle:
        handle.write("pwned\n")
except OSError:
    pass
try:
    socket.create_connection(("127.0.0.1", TARGETS["port"]), timeout=2)
except OSError:
    pass

setup(name="bras_description", version="0.0.0", packages=[])
