"""The TF tree as indented text, the way ``bras-kit tree`` prints it."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass

from ..core.i18n import say
from ..core.message import M
from ..kinematics.frames import tf_tree
from ..model.robot import Robot
from ._labels import beyond_limits, format_number, joint_summary, joint_values
from ._tree import children_of


@dataclass(frozen=True)
class TreeGlyphs:
    """The characters that draw the text tree."""

    branch: str  # a child with siblings after it
    last: str  # the last child
    pipe: str  # continues an ancestor's branch
    blank: str  # under an ancestor that was the last child
    arrow: str  # joint -> child link


UNICODE_GLYPHS = TreeGlyphs("├─ ", "└─ ", "│  ", "   ", "→")
ASCII_GLYPHS = TreeGlyphs("|- ", "`- ", "|  ", "   ", "->")


MAX_INDENT = 64  # levels of indentation drawn; deeper links carry their depth instead


def tree_text(robot: Robot, config: Mapping[str, float] | None = None, *, ascii: bool = False,
              lang: str | None = None) -> str:
    """The TF tree as indented text, one link per line (the root first), each child under its joint.

    ``config`` adds each movable joint's value. Each level is indented by three characters, so a
    line's indentation is 3 x the depth of its link. Raises :class:`~bras_kit.core.errors.ModelError`
    when the links do not form a tree.
    """
    tree = tf_tree(robot)
    values = joint_values(tree, config) if config else {}
    glyphs = ASCII_GLYPHS if ascii else UNICODE_GLYPHS
    children = children_of(tree.parent)
    lines = [tree.links[0]]
    # depth-first, pre-order, with an explicit stack: (link index, prefix of its line, is last child, depth).
    # Past MAX_INDENT levels the indentation stops growing and the depth is written instead, so a
    # chain of 100,000 links gives 100,000 short lines, not gigabytes of spaces.
    stack = [(child, "", k == len(children[0]) - 1, 1) for k, child in enumerate(children[0])][::-1]
    while stack:
        index, prefix, last, depth = stack.pop()
        joint = tree.joints[index]
        assert joint is not None
        text = f"{joint.name or '?'} ({joint_summary(joint, lang)})"
        if joint.name in values:
            value = values[joint.name]
            text += f" = {format_number(value)}"
            if beyond_limits(joint, value):
                text += " (" + say(M("out of limits"), lang) + ")"
        deep = "[" + say(M("depth {depth}", depth=depth), lang) + "] " if depth > MAX_INDENT else ""
        lines.append(f"{prefix}{deep}{glyphs.last if last else glyphs.branch}{text} {glyphs.arrow} {tree.links[index]}")
        below = prefix if depth >= MAX_INDENT else prefix + (glyphs.blank if last else glyphs.pipe)
        kids = children[index]
        stack.extend((child, below, k == len(kids) - 1, depth + 1) for k, child in reversed(list(enumerate(kids))))
    return "\n".join(lines) + "\n"
