"""Stand-in for launch_ros (Jazzy); see _core.py."""

from . import actions, descriptions, parameter_descriptions, substitutions  # noqa: F401
