"""Prints 2 GB (2,000 blocks of 1 MB, each a thousand lines), between a first and a last line."""
import sys

BLOCK = ("y" * 999 + "\n") * 1000


def main():
    print("FIRST LINE OF THE NODE")
    for _ in range(2000):
        sys.stdout.write(BLOCK)
    print("LAST LINE OF THE NODE")
