"""The prefixes searched, in the order AMENT_PREFIX_PATH gives them (search_paths.py)."""

import os

from .constants import AMENT_PREFIX_PATH_ENV_VAR


def get_search_paths():
    """The existing folders of AMENT_PREFIX_PATH; unset or empty is an EnvironmentError."""
    listed = os.environ.get(AMENT_PREFIX_PATH_ENV_VAR)
    if not listed:
        raise OSError(f"Environment variable '{AMENT_PREFIX_PATH_ENV_VAR}' is not set or empty")
    return [folder for folder in listed.split(os.pathsep) if folder and os.path.exists(folder)]
