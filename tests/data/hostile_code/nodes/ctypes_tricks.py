"""Calls the C library directly: open() and write() of a file outside its folder."""
import ctypes
import os


def main():
    libc = ctypes.CDLL(None, use_errno=True)
    fd = libc.open(b"/tmp/bk-hostile-ctypes.txt", os.O_CREAT | os.O_WRONLY, 0o644)
    if fd < 0:
        raise OSError(ctypes.get_errno(), "open through ctypes failed")
    libc.write(fd, b"pwned\n", 6)
