"""Connects to an abstract Unix socket of this machine (no file: a name in the network namespace)."""
import json
import os
import socket

TARGETS = json.load(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "targets.json")))


def main():
    client = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    client.connect("\0" + TARGETS["abstract"])
    client.sendall(b"pwned")
