"""Reads the private key in ~/.ssh and prints it."""
import os


def main():
    with open(os.path.expanduser("~/.ssh/id_rsa")) as handle:
        print(handle.read())
