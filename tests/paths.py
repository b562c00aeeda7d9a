"""The places the tests read from: the tests folder (its helper modules and data/) and the
repository's root, whatever layer folder (tests/<layer>/) a test file sits in."""

from pathlib import Path

TESTS = Path(__file__).resolve().parent
REPO = TESTS.parent
DATA = TESTS / "data"
