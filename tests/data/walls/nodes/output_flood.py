"""Prints without end, and lets no simulated time pass."""


def main():
    line = "flood " * 100
    while True:
        print(line)
