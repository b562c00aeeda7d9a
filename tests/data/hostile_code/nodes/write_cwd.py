"""Writes in the folder bras-kit was started from, and next to its own run folder."""
import os


def main():
    try:
        open("../bk_pwned.txt", "w").close()
    except OSError:
        pass
    with open(os.path.join(os.environ["PWD"], "bk_pwned.txt"), "w") as handle:
        handle.write("pwned\n")
