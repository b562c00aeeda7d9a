"""Fills the folder it runs in, 1 MiB at a time, in files of 32 MiB (under the per-file cap),
until a write fails: prints the bytes written and the errno, then raises the error."""
import os


def main():
    chunk = b"\xa5" * (1 << 20)
    written, number = 0, 0
    try:
        while True:
            with open(f"fill-{number}.bin", "wb") as handle:
                for _ in range(32):
                    handle.write(chunk)
                    handle.flush()
                    written += len(chunk)
            number += 1
    except OSError as exc:
        print(f"written {written} errno {exc.errno}")
        raise
