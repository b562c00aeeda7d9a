"""The frame tree as Graphviz DOT text, and the labels the drawn diagram shares with it."""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np

from ..core.i18n import say
from ..core.message import M, Mn
from ..kinematics.frames import TFTree, fk_batch, tf_tree
from ..model.robot import Joint, Robot
from ._labels import beyond_limits, format_number, format_vector, joint_label_lines, joint_values


def pose_facts(tree: TFTree, config: Mapping[str, float] | None) -> tuple[dict[str, float], np.ndarray | None]:
    """Joint values and link positions (root frame) for ``config``; empty and None without one."""
    if not config:
        return {}, None
    return joint_values(tree, config), fk_batch(tree, tree.config_vector(config))[:, :3, 3]


def graph_title(robot: Robot, tree: TFTree, config: Mapping[str, float] | None, lang: str | None = None) -> str:
    joints = len(tree.links) - 1
    title = say(M("{robot}: frame tree, {links}, {joints} ({movable})", robot=robot.name or M("robot"),
                  links=Mn("{n} link", "{n} links", len(tree.links)), joints=Mn("{n} joint", "{n} joints", joints),
                  movable=Mn("{n} movable", "{n} movable", len(tree.dof))), lang)
    if config:
        title += "\n" + say(M("pose"), lang) + ": " + ", ".join(f"{k}={format_number(v)}" for k, v in config.items())
    return title


def link_label(name: str, position: np.ndarray | None, lang: str | None = None) -> str:
    if position is None:
        return name
    return f"{name}\n" + say(M("at {position}", position=format_vector(position.tolist())), lang)


def joint_label(joint: Joint, value: float | None, lang: str | None = None) -> list[str]:
    """The joint's name, then its detail lines."""
    return [joint.name or "?", *joint_label_lines(joint, value, lang)]


def _dot_string(text: str) -> str:
    """A DOT double-quoted string; line breaks become ``\\n`` (centred lines)."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"')
    escaped = "".join(c if c >= " " or c == "\n" else " " for c in escaped)
    return '"' + escaped.replace("\n", "\\n") + '"'


def frames_dot(robot: Robot, config: Mapping[str, float] | None = None, lang: str | None = None) -> str:
    """The frame tree in Graphviz DOT: links as boxes, joints as edges parent -> child.

    Edge labels hold the joint's name, type, origin (xyz, rpy), axis and limits; with ``config``
    they also hold its current value and each link box its position in the root frame.
    Render it with Graphviz (``dot -Tpdf frames.dot -o frames.pdf``) or draw it with
    :func:`~bras_kit.diagrams.frame_diagram`.
    """
    tree = tf_tree(robot)
    values, positions = pose_facts(tree, config)
    out = [
        f"digraph {_dot_string(robot.name or 'robot')} {{",
        f"  // bras-kit frames: the TF tree of '{robot.name or 'robot'}', root '{tree.root}'",
        f"  graph [rankdir=TB, labelloc=t, fontname=\"Helvetica\", label={_dot_string(graph_title(robot, tree, config, lang))}];",
        '  node [shape=box, style="rounded,filled", fillcolor="#dbe8fb", color="#1f4e8c", fontname="Helvetica"];',
        '  edge [fontname="Helvetica", fontsize=9, color="#555555", arrowhead=normal];',
    ]
    for i, link in enumerate(tree.links):
        label = link_label(link, positions[i] if positions is not None else None)
        extra = ', penwidth=2' if i == 0 else ""
        out.append(f"  {_dot_string(link)} [label={_dot_string(label)}{extra}];")
    for i in range(1, len(tree.links)):
        joint = tree.joints[i]
        assert joint is not None
        value = values.get(joint.name or "")
        label = "\n".join(joint_label(joint, value))
        style = ', color="#c0392b", fontcolor="#c0392b"' if value is not None and beyond_limits(joint, value) else ""
        if joint.type == "fixed":
            style += ", style=dashed"
        out.append(f"  {_dot_string(tree.links[tree.parent[i]])} -> {_dot_string(tree.links[i])} "
                   f"[label={_dot_string(label)}{style}];")
    out.append("}")
    return "\n".join(out) + "\n"
