"""The options several commands share, each with one meaning, written here once.

An option string two commands both take means one thing in both (issue 52: ``--no-browser``
served the page in ``view`` and ran a batch without a page in ``launch``). :data:`MEANINGS` is
that one thing, and the parsers are built from it: once a command's ``configure`` has added its
options, :func:`apply` gives every option found here its meaning as the first words of its help,
and what the command said of it becomes the detail after them (dropped when it only repeated the
meaning). A command that adds an option another command already has, and that is not here, fails
``tests/cli/test_cli_options.py``: its meaning is then written here, for every command at once.

A deprecated spelling hidden from the help (``argparse.SUPPRESS``) that warns and names its
replacement when used (``urdf --set``, see :func:`bras_kit.cli._common.template_values`) offers
no meaning and is left alone.
"""

from __future__ import annotations

import argparse

# option string -> its meaning, one line of help that holds in every command taking it
MEANINGS: dict[str, str] = {
    "--lang": "language of messages and pictures (default: BRAS_KIT_LANG, else French when the locale is French)",
    "--force": "overwrite files that already exist",
    "--no-cache": "decode mesh files again, without the cache of decoded meshes",
    "--no-browser": "serve the page and print its address, without opening a browser",
    "--port": "port of the page (default 8080; the next free one if taken)",
    "--package-path": "folder holding ROS packages, for $(find pkg) and package:// (repeatable)",
    "--xacro-arg": "xacro argument when FILE is a .xacro (repeatable)",
    "--wrist": "built-in arm: add the wrist joint 'poignet' (the tutorial's exercise)",
    "--inertials": "built-in arm: add <inertial> mass and inertia to every link",
    "--collisions": "built-in arm: add <collision> shapes equal to the visuals (on with --inertials)",
    "--param": "give a parameter a value (repeatable)",
    "--set": "a joint value in rad (revolute) or m (prismatic); repeatable",
    "--motion": "how the arm moves: 'tutorial', JOINT=FORMULA or a file (repeatable)",
    "--topic": "with a ROS 2 bag as --motion: the JointState topic to replay (default: /joint_states)",
    "--node": "the motion is what your node publishes on /joint_states (run with bras-kit run's stand-in for rclpy, "
              "simulated time); the robot is the package's URDF unless FILE is given",
    "--duration": "how long, in seconds",
    "--rate": "samples per second",
    "--fps": "frames per second",
    "--interpolation": "how the arm moves between waypoints",
    "--output": "where to write",
    "--format": "how the result is written",
    "--json": "print the result as JSON, for programs",
    "--gif": "draw the motion as an animated GIF",
    "--size": "picture size in pixels, WxH",
    "--backend": "how pictures are drawn (default: auto)",
    "--geometry": "which shapes are drawn: the links' <visual>, their <collision>, or both",
    "--strict": "exit with status 1 on more than errors",
    "--from": "where the command starts from",
    "--link": "the link whose pose is asked for",
    "--tip-offset": "the tip point in the link's frame",
    "--control": "how the motors are driven",
    "--kp": "stiffness of every motor, N·m/rad (default: 100)",
    "--kd": "damping of every motor, N·m·s/rad (default: 10)",
    "--ros": "this terminal's live ROS 2 graph (needs rclpy: ROS 2 sourced or the 'ros' extra)",
    "--verbose": "also say which folder each ROS package ($(find), package://) was taken from",
}
# a short spelling means what its long one means
ALIASES = {"-o": "--output", "-m": "--motion", "-v": "--verbose", "-p": "--param"}

# how a meaning and a command's detail are joined (a ``cli`` catalog entry: French puts a space before the colon)
JOINED = "{meaning}: {detail}"


def meaning_of(option: str) -> str | None:
    """The one meaning of an option string, or None for an option of one command only."""
    return MEANINGS.get(ALIASES.get(option, option))


def _meaning(action: argparse.Action) -> str | None:
    found = {meaning_of(option) for option in action.option_strings} - {None}
    if len(found) > 1:
        raise LookupError(f"{action.option_strings} hold two meanings: {sorted(found)}")  # type: ignore[type-var]
    return found.pop() if found else None


def apply(parser: argparse.ArgumentParser) -> None:
    """Every option of ``parser`` (and of its sub-parsers) found in :data:`MEANINGS`: its help is
    that meaning, and the command's own words become the detail (``action.detail``)."""
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            for sub in action.choices.values():
                apply(sub)
            continue
        if action.help == argparse.SUPPRESS or getattr(action, "meaning", None) is not None:
            continue
        meaning = _meaning(action)
        if meaning is None:
            continue
        own = action.help
        action.meaning = meaning  # type: ignore[attr-defined]
        action.detail = own if own and own != meaning else None  # type: ignore[attr-defined]
        action.help = meaning


def help_text(action: argparse.Action, word) -> str | None:
    """What ``--help`` shows for ``action``, each part looked up by ``word`` (the catalog)."""
    if not action.help:
        return action.help
    detail = getattr(action, "detail", None)
    if detail is None:
        return word(action.help)
    return word(JOINED).format(meaning=word(action.help), detail=word(detail))
