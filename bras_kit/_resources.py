"""Where the shipped templates live (``bras_kit/templates`` when installed, ``templates/`` in a checkout)."""

from __future__ import annotations

from importlib import resources
from pathlib import Path


def templates_dir() -> Path:
    """The folder holding ``robot/`` (xacro) and ``package/`` (jinja2) templates."""
    try:
        return Path(str(resources.files("bras_kit.templates")))
    except ModuleNotFoundError:  # running from a source tree that was never installed
        return Path(__file__).resolve().parent.parent / "templates"


def robot_template() -> Path:
    return templates_dir() / "robot" / "bras.urdf.xacro"
