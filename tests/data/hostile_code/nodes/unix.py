"""Connects to a Unix socket of this machine (a path, like /var/run/docker.sock)."""
import json
import os
import socket

TARGETS = json.load(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "targets.json")))


def main():
    client = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    client.connect(TARGETS["socket"])
    client.sendall(b"pwned")
