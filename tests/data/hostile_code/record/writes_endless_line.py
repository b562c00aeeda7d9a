"""Live beside a launch: finds the pipe to bras-kit's relay among its open files (the first pipe
past the standard ones: made before the one the answer goes back through) and writes one line
that never ends (256 MiB, no line end), then a joint state of its own."""
import json
import os
import stat


def main():
    for fd in range(3, 64):
        try:
            if stat.S_ISFIFO(os.fstat(fd).st_mode):
                block = b"x" * (1 << 20)
                for _ in range(256):
                    os.write(fd, block)
                os.write(fd, b"\n" + json.dumps({"name": ["epaule"], "position": [0.25], "stamp": 1.0}).encode() + b"\n")
                return
        except OSError:
            continue
