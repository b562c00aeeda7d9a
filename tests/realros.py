"""The real rclpy of ROS 2 Jazzy, for the tests: the stand-in's oracle and the live side's runtime.

Its PyPI wheels (``ros-jazzy-rclpy[fastrtps]`` and the message packages, pinned in constraints.txt by
the ``ros`` extra) live in a venv of their own, made on first use under the user's cache folder (the
wheels' ``.pth`` re-executes every Python process of their venv once: bras-kit's own venv stays
without them). ``BRAS_KIT_RCLPY_PYTHON`` names another interpreter that imports rclpy (a sourced
apt ROS, say).

DDS never leaves this machine: every process that uses the real rclpy runs in a network namespace
of its own with loopback only (``unshare -rnm``, ``ip link set lo up``), with
``ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST`` and a ``ROS_DOMAIN_ID`` of its own. Its ``/dev/shm``
is a tmpfs of its own too (the ``m``: a mount namespace): Fast DDS's shared-memory transport leaves
its segments there when a process is killed (about 0.5 MB each, hundreds per run of the suite),
and they go with the namespace instead of filling the machine's ``/dev/shm``. Processes that must
see each other run in one namespace: start them from one command (a shell line or a driver script).
"""

from __future__ import annotations

import fcntl
import itertools
import os
import shlex
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
WHEELS = ("ros-jazzy-rclpy[fastrtps]", "ros-jazzy-sensor-msgs", "ros-jazzy-std-msgs", "ros-jazzy-std-srvs")
_domains = itertools.count((os.getpid() % 40) * 2 + 1)


def _cache() -> Path:
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return Path(base) / "bras-kit"


def oracle_python() -> str:
    """An interpreter that imports the real rclpy of Jazzy: made once, then reused."""
    given = os.environ.get("BRAS_KIT_RCLPY_PYTHON")
    if given:
        return given
    minor = f"{sys.version_info[0]}.{sys.version_info[1]}"
    venv = _cache() / f"rclpy-jazzy-py{minor}"
    python = venv / "bin" / "python"
    venv.parent.mkdir(parents=True, exist_ok=True)
    with open(venv.parent / f"rclpy-jazzy-py{minor}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # two test sessions at once make it once
        ready = venv / "bras-kit-ready"
        if not ready.exists():
            base = getattr(sys, "_base_executable", sys.executable)
            subprocess.run([base, "-m", "venv", "--clear", str(venv)], check=True)
            # empy 4.2 (needed by the wheels' rosidl) is a pure-Python source archive, like PyOpenGL
            done = subprocess.run(
                [str(python), "-m", "pip", "install", "--quiet", "--disable-pip-version-check",
                 "--only-binary=:all:", "--no-binary=empy", "-c", str(ROOT / "constraints.txt"), *WHEELS],
                capture_output=True, text=True,
            )
            if done.returncode:
                raise RuntimeError(
                    "the real rclpy of Jazzy is the oracle of these tests and could not be installed from PyPI "
                    f"into {venv}:\n{done.stderr[-2000:]}"
                )
            ready.write_text("\n".join(WHEELS) + "\n")
    return str(python)


def new_domain() -> int:
    """A ROS_DOMAIN_ID of its own for one scenario (1-101: the ports of every one fit on Linux)."""
    return next(_domains) % 100 + 1


def graph_env(domain: int, **extra: str) -> dict[str, str]:
    """The environment of a process of one scenario: its domain, localhost discovery, English logs."""
    env = {k: v for k, v in os.environ.items() if not k.startswith(("ROS_", "RMW_", "FASTRTPS_", "FASTDDS_"))}
    env.update(ROS_DOMAIN_ID=str(domain), ROS_AUTOMATIC_DISCOVERY_RANGE="LOCALHOST", PYTHONUNBUFFERED="1")
    env.update(extra)
    return env


def in_loopback_namespace(argv: list[str]) -> list[str]:
    """``argv`` run in a new network namespace whose only interface is loopback, brought up first,
    with a ``/dev/shm`` of its own (a new mount namespace, private)."""
    return ["unshare", "-rnm", "sh", "-c",
            'ip link set lo up || exit 97; mount -t tmpfs -o size=256m,mode=1777 tmpfs /dev/shm || exit 98; exec "$@"',
            "sh", *argv]


def shell_in_loopback_namespace(script: str) -> list[str]:
    """A shell script (several processes that must see each other) run in one such namespace."""
    return in_loopback_namespace(["sh", "-c", script])


def run_isolated(argv: list[str], *, domain: int, timeout: float, **env: str) -> subprocess.CompletedProcess[str]:
    """Run ``argv`` to its end in its own loopback-only namespace, on ``domain``."""
    return subprocess.run(
        in_loopback_namespace(argv), env=graph_env(domain, **env), capture_output=True, text=True, timeout=timeout
    )


def quote(argv: list[str]) -> str:
    return shlex.join(argv)
