"""Makes empty files in the folder it runs in until the folder refuses one: prints how many."""
import os


def main():
    made = 0
    try:
        while made < 1_000_000:
            os.close(os.open(f"empty-{made}", os.O_CREAT | os.O_WRONLY, 0o600))
            made += 1
    except OSError as exc:
        print(f"made {made} errno {exc.errno}")
        raise
