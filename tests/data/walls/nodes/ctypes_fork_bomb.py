"""Forks through the C library, which Python's audit hooks never see, and keeps every child
alive: prints how many children it made and the errno of the fork that failed."""
import ctypes
import time


def main():
    libc = ctypes.CDLL(None, use_errno=True)
    made, refused = 0, 0
    for _ in range(200):
        pid = libc.fork()
        if pid == 0:
            time.sleep(60)
            libc._exit(0)
        if pid < 0:
            refused = ctypes.get_errno()
            break
        made += 1
    print(f"made {made} refused {refused}")
