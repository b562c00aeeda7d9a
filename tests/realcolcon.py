"""The real colcon, for the tests: the oracle of ``bras-kit build``.

colcon-common-extensions (colcon-core 0.21.3, colcon-ros 0.5.0, colcon-python-setup-py, colcon-bash...)
and Ubuntu 24.04's setuptools, pinned in ``tests/colcon-constraints.txt``, live in a venv of their own
made on first use under the user's cache folder, as the real rclpy's (``tests/realros.py``). No ROS is
needed: colcon-ros reads package.xml with catkin_pkg and runs an ament_python package's setup.py with
the venv's setuptools. ``BRAS_KIT_COLCON`` names another ``colcon`` executable (a sourced ROS, say).

:func:`colcon_build` runs it in a workspace with nothing of the user's: its own ``COLCON_HOME`` (no
defaults.yaml, no mixins), no ``AMENT_PREFIX_PATH``/``COLCON_PREFIX_PATH`` from the caller's shell, and
the event handlers that only decorate a terminal (desktop notification, title, status line) off.
"""

from __future__ import annotations

import fcntl
import os
import subprocess
import sys
from pathlib import Path

from realros import _cache

ROOT = Path(__file__).resolve().parents[1]
CONSTRAINTS = ROOT / "tests" / "colcon-constraints.txt"
WHEELS = ("colcon-common-extensions", "colcon-core", "colcon-ros", "setuptools")


def colcon_executable() -> str:
    """The ``colcon`` of the oracle venv: made once (under a lock), then reused."""
    given = os.environ.get("BRAS_KIT_COLCON")
    if given:
        return given
    minor = f"{sys.version_info[0]}.{sys.version_info[1]}"
    venv = _cache() / f"colcon-py{minor}"
    colcon = venv / "bin" / "colcon"
    pins = CONSTRAINTS.read_text()
    venv.parent.mkdir(parents=True, exist_ok=True)
    with open(venv.parent / f"colcon-py{minor}.lock", "w") as lock:
        fcntl.flock(lock, fcntl.LOCK_EX)  # two test sessions at once make it once
        ready = venv / "bras-kit-ready"
        if not ready.exists() or ready.read_text() != pins:  # the pins changed: made anew
            base = getattr(sys, "_base_executable", sys.executable)
            subprocess.run([base, "-m", "venv", "--clear", str(venv)], check=True)
            done = subprocess.run(
                [str(venv / "bin" / "python"), "-m", "pip", "install", "--quiet", "--disable-pip-version-check",
                 "--only-binary=:all:", "--no-binary=empy", "-c", str(CONSTRAINTS), *WHEELS],
                capture_output=True, text=True,
            )
            if done.returncode:
                raise RuntimeError(
                    "the real colcon is the oracle of these tests and could not be installed from PyPI "
                    f"into {venv}:\n{done.stderr[-2000:]}"
                )
            ready.write_text(pins)
    return str(colcon)


def colcon_env(home: Path) -> dict[str, str]:
    """The environment of one oracle build: nothing of the caller's ROS or colcon set-up."""
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("COLCON_", "AMENT_", "ROS_", "CMAKE_PREFIX_PATH", "PYTHONPATH", "VIRTUAL_ENV"))}
    env.update(COLCON_HOME=str(home), LANG="C.UTF-8", LC_ALL="C.UTF-8", PYTHONDONTWRITEBYTECODE="1",
               COLCON_EXTENSION_BLOCKLIST="colcon_core.event_handler.desktop_notification:"
                                          "colcon_core.event_handler.terminal_title")
    return env


def colcon_build(workspace: Path, *extra: str, timeout: float = 120) -> subprocess.CompletedProcess[str]:
    """``colcon build --base-paths src`` typed at ``workspace``'s root, with no log files
    (``--log-base /dev/null``, colcon-core's way to turn them off: colcon_core/command.py line 383,
    location.py line 91), which changes nothing the tests compare and saves a tenth of its time. The
    executor stays colcon's default, the parallel one: the sequential one words a failed job otherwise
    (``ERROR:colcon.colcon_core.executor.sequential:Exception in job execution``)."""
    home = workspace / ".colcon-home"
    home.mkdir(exist_ok=True)
    return subprocess.run([colcon_executable(), "--log-base", "/dev/null", "build", "--base-paths", "src",
                           *extra], cwd=workspace,
                          env=colcon_env(home), capture_output=True, text=True, timeout=timeout)
