"""Writes in /tmp, outside its own folder, and removes a file there."""
import json
import os

TARGETS = json.load(open(os.path.join(os.path.dirname(os.path.abspath(__file__)), "targets.json")))


def main():
    try:
        os.remove(TARGETS["victim"])
    except OSError:
        pass
    with open("/tmp/bk-hostile-pwned.txt", "w") as handle:
        handle.write("pwned\n")
