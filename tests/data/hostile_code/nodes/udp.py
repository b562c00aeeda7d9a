"""Sends a UDP datagram to this machine's loopback."""
import json
import os
import socket

TARGETS = json.load(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "targets.json")))


def main():
    sender = socket.socket(socket.AF_INET, socket.SOCK_DGRAM)
    sender.sendto(b"pwned", ("127.0.0.1", TARGETS["port"]))
