"""Takes memory without end, touching every page."""


def main():
    kept = []
    while True:
        kept.append(b"\x01" * (64 << 20))
