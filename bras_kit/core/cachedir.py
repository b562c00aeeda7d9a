"""The user's cache folder for bras-kit (``$XDG_CACHE_HOME/bras-kit``, else ``~/.cache/bras-kit``),
shared by the xacro expansion of the built-in arm and the decoded meshes."""

from __future__ import annotations

import os


def cache_home() -> str:
    """The folder bras-kit keeps what it can compute again (it may not exist yet)."""
    base = os.environ.get("XDG_CACHE_HOME") or os.path.join(os.path.expanduser("~"), ".cache")
    return os.path.join(base, "bras-kit")
