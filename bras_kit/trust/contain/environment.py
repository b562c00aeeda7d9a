"""What the contained code finds in its process: the environment variables it keeps, its
temporary folder, and the folders of ``sys.path`` it can still reach."""

from __future__ import annotations

import os
import sys

# the environment variables the contained code keeps (tokens and keys in the others stay outside)
ENVIRONMENT = frozenset({"PATH", "HOME", "USER", "LOGNAME", "LANG", "LANGUAGE", "TZ", "TERM", "PWD",
                         "PYTHONIOENCODING", "PYTHONUTF8", "NO_COLOR"})
ENVIRONMENT_PREFIXES = ("LC_", "ROS_", "RMW_", "RCUTILS_", "AMENT_", "COLCON_", "BRAS_KIT_")


def _environment(workdir: str) -> None:
    """Only the variables a program needs to run and ROS's own are kept; ``tempfile`` and the
    programs it starts make their temporary files in the run's folder."""
    import tempfile

    for name in list(os.environ):
        if name not in ENVIRONMENT and not name.startswith(ENVIRONMENT_PREFIXES):
            del os.environ[name]  # unsetenv() too: gone for the C library and for programs it starts
    os.environ["TMPDIR"] = workdir
    tempfile.tempdir = workdir


def _visible_sys_path() -> None:
    """Folders of ``sys.path`` the walls hide are dropped (the caller's current folder, a test
    runner's folder...): a library that lists every folder of ``sys.path`` (setuptools looking
    for entry points) would otherwise be stopped there, at the learner's line, for nothing
    the learner did."""
    sys.path[:] = [p for p in sys.path if not p or os.path.isdir(p) or os.path.isfile(p)]
    sys.path_importer_cache.clear()
