"""A folder tree as data, to tell that a test left it as it was."""

from __future__ import annotations

import hashlib
import os
from pathlib import Path


def snapshot(*roots: Path) -> dict[str, tuple[str, int, str]]:
    """Every file, folder and link under ``roots``: kind, mode and content digest."""
    out: dict[str, tuple[str, int, str]] = {}
    for root in roots:
        for folder, dirs, files in os.walk(root):
            for name in dirs + files:
                path = os.path.join(folder, name)
                info = os.lstat(path)
                if os.path.islink(path):
                    out[path] = ("link", info.st_mode, os.readlink(path))
                elif os.path.isdir(path):
                    out[path] = ("dir", info.st_mode, "")
                elif not os.path.isfile(path):  # the Unix socket
                    out[path] = ("other", info.st_mode, "")
                else:
                    out[path] = ("file", info.st_mode, hashlib.sha256(Path(path).read_bytes()).hexdigest())
    return out
