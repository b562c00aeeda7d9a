"""The system packages the tests lean on (system-packages.txt), and what happens when one is missing.

On a contributor's machine a missing package skips its tests, with the Debian package to install
in the reason (``pytest -ra`` lists them at the end). In CI (``BRAS_KIT_CI=1``, which .ci/run
exports after installing every package of the list) the same absence fails the test: there a
skipped test would stand for a feature nobody checked.
"""

from __future__ import annotations

import os
import shutil

import pytest


def in_ci() -> bool:
    """True under .ci/run, which installs every system package and exports BRAS_KIT_CI=1."""
    return os.environ.get("BRAS_KIT_CI", "") not in ("", "0")


def missing(package: str, what: str) -> None:
    """Skip the test (fail it in CI): ``what`` is not on this machine; Debian's ``package`` brings it."""
    words = f"{what} is missing: sudo apt-get install {package} (system-packages.txt)"
    if in_ci():
        pytest.fail(f"{words}; .ci/run installs it, so CI must have it", pytrace=False)
    pytest.skip(words)


def program(name: str, package: str) -> str:
    """The path of the program ``name`` on PATH, or the test skips (fails in CI) naming ``package``."""
    found = shutil.which(name)
    if found is None:
        missing(package, f"the program {name}")
    assert found is not None
    return found


def file(path: str, package: str) -> str:
    """``path`` when it exists, or the test skips (fails in CI) naming ``package``."""
    if not os.path.exists(path):
        missing(package, path)
    return path
