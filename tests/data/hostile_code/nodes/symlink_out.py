"""Makes a symbolic link in its folder that points at ~/.ssh, and reads through it."""
import os


def main():
    os.symlink(os.path.expanduser("~/.ssh/id_rsa"), "key")
    with open("key") as handle:
        print(handle.read())
