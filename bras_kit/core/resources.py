"""Where the shipped templates live: ``bras_kit/templates``, installed or in a checkout."""

from __future__ import annotations

from pathlib import Path


def templates_dir() -> Path:
    """The folder holding ``robot/`` (xacro), ``package/`` and ``empty/`` (jinja2) templates."""
    return Path(__file__).resolve().parents[1] / "templates"


def robot_template() -> Path:
    return templates_dir() / "robot" / "bras.urdf.xacro"
