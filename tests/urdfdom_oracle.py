"""urdfdom's own reader, ``check_urdf`` (Debian's liburdfdom-tools): the oracle of the URDF tests."""

from __future__ import annotations

import subprocess

import system


def check_urdf(path) -> subprocess.CompletedProcess:
    """``check_urdf PATH`` run; the test skips (fails in CI) when liburdfdom-tools is not installed."""
    program = system.program("check_urdf", "liburdfdom-tools")
    return subprocess.run([program, str(path)], capture_output=True, text=True, timeout=60)
