"""Writes a file in the home folder."""
import os


def main():
    with open(os.path.expanduser("~/bk_pwned.txt"), "w") as handle:
        handle.write("pwned\n")
