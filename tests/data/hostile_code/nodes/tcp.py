"""Connects to a TCP server on this machine's loopback."""
import json
import os
import socket

TARGETS = json.load(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "targets.json")))


def main():
    connection = socket.create_connection(("127.0.0.1", TARGETS["port"]), timeout=2)
    connection.sendall(b"pwned")
