"""Kills the process that started it, then its whole process group."""
import os
import signal


def main():
    os.kill(os.getppid(), signal.SIGKILL)
    os.kill(0, signal.SIGTERM)
