"""The frame tree drawn with matplotlib (no Graphviz): link boxes, joint labels on the edges."""

from __future__ import annotations

import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

from ..core import backends
from ..core.errors import ModelError
from ..core.message import M
from ..kinematics.frames import tf_tree
from ..model.robot import Robot
from ._labels import beyond_limits
from .dot import frames_dot, graph_title, joint_label, link_label, pose_facts
from .layout import tidy_layout
from .output import output_suffix, save_figure

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

FRAME_FORMATS = (".png", ".svg", ".pdf", ".dot")

_CHAR = 0.61  # advance of DejaVu Sans Mono, in em
_LINK_FONT, _JOINT_FONT = 10.0, 7.5
_LINE = 1.3  # line height, in em
_PAD = 4.0  # inside boxes, points
_EDGE_GAP, _CONNECTOR, _SIBLING_GAP, _MARGIN = 34.0, 10.0, 14.0, 18.0
_JOINT_COLOURS = {"revolute": "#fde9d3", "continuous": "#fdf5c9", "prismatic": "#dff3dc",
                  "fixed": "#eeeeee"}
_LINK_FILL, _LINK_EDGE, _ALERT = "#dbe8fb", "#1f4e8c", "#c0392b"


def _text_box(lines: Sequence[str], size: float) -> tuple[float, float]:
    """Width and height (points) of a monospaced block of lines with padding."""
    chars = max((len(line) for line in lines), default=0)
    return chars * _CHAR * size + 2 * _PAD, len(lines) * _LINE * size + 2 * _PAD


@dataclass(frozen=True)
class _Box:
    x: float  # centre
    top: float  # distance from the top of the figure, points
    width: float
    height: float


MAX_DIAGRAM_LINKS = 2000


def frame_diagram(robot: Robot, config: Mapping[str, float] | None = None,
                  path: str | os.PathLike[str] | None = None, lang: str | None = None) -> Figure:
    """Draw the frame tree with matplotlib (no Graphviz): link boxes, joint labels on the edges.

    The figure is sized to the tree (1 unit = 1 point). With ``path`` it is also saved; the
    format follows the suffix (.png, .svg, .pdf, or .dot for the DOT text of :func:`~bras_kit.diagrams.frames_dot`).
    """
    suffix = output_suffix(path, FRAME_FORMATS) if path is not None else None
    tree = tf_tree(robot)
    n = len(tree.links)
    if n > MAX_DIAGRAM_LINKS:
        raise ModelError(M("the robot has {count:,} links: a frame diagram of more than {most} cannot be read "
                           "(nor drawn in reasonable memory)", count=n, most=MAX_DIAGRAM_LINKS),
                         hint=M("use 'bras-kit tree' for the text tree, or 'bras-kit frames -o tree.dot' for Graphviz"))
    values, positions = pose_facts(tree, config)
    link_lines = [link_label(link, positions[i] if positions is not None else None, lang).split("\n")
                  for i, link in enumerate(tree.links)]
    joint_lines: list[list[str]] = [[]]
    for i in range(1, n):
        joint = tree.joints[i]
        assert joint is not None
        joint_lines.append(joint_label(joint, values.get(joint.name or ""), lang))
    link_size = [_text_box(lines, _LINK_FONT) for lines in link_lines]
    joint_size = [_text_box(lines, _JOINT_FONT) if lines else (0.0, 0.0) for lines in joint_lines]
    layout = tidy_layout(tree.parent, [max(a[0], b[0]) for a, b in zip(link_size, joint_size)], _SIBLING_GAP)
    rows = max(layout.depth) + 1
    label_band, box_band = [0.0] * rows, [0.0] * rows
    for i in range(n):
        d = layout.depth[i]
        label_band[d] = max(label_band[d], joint_size[i][1])
        box_band[d] = max(box_band[d], link_size[i][1])
    title = graph_title(robot, tree, config, lang)
    title_height = (title.count("\n") + 1) * _LINE * 11 + 10
    box_top = [0.0] * rows
    label_bottom = [0.0] * rows
    y = _MARGIN + title_height
    for d in range(rows):
        if d > 0:
            y += box_band[d - 1] + _EDGE_GAP + label_band[d]
            label_bottom[d] = y
            y += _CONNECTOR
        box_top[d] = y
    title_width = max(len(line) for line in title.split("\n")) * 0.62 * 11
    total_width = max(layout.width, title_width, 160.0) + 2 * _MARGIN
    total_height = y + box_band[-1] + _MARGIN
    left = (total_width - layout.width) / 2  # centres the tree under a wider title
    links = [_Box(left + layout.x[i], box_top[layout.depth[i]], *link_size[i]) for i in range(n)]
    labels = [_Box(left + layout.x[i], label_bottom[layout.depth[i]] - joint_size[i][1], *joint_size[i])
              for i in range(n)]

    backends.matplotlib()
    from matplotlib.figure import Figure
    from matplotlib.patches import FancyArrowPatch, FancyBboxPatch

    figure = Figure(figsize=(total_width / 72, total_height / 72))
    ax = figure.add_axes((0, 0, 1, 1))
    ax.set_xlim(0, total_width)
    ax.set_ylim(-total_height, 0)
    ax.set_axis_off()
    ax.text(total_width / 2, -_MARGIN, title, ha="center", va="top", fontsize=11,
            linespacing=_LINE / 1.17)
    mono: dict[str, Any] = {"family": "DejaVu Sans Mono", "linespacing": _LINE / 1.17}
    for i in range(n):
        box = links[i]
        ax.add_artist(FancyBboxPatch((box.x - box.width / 2, -box.top - box.height), box.width, box.height,
                                    boxstyle="round,pad=0,rounding_size=4", facecolor=_LINK_FILL,
                                    edgecolor=_LINK_EDGE, linewidth=2.0 if i == 0 else 1.0, zorder=3))
        ax.text(box.x, -box.top - _PAD, link_lines[i][0], ha="center", va="top", fontsize=_LINK_FONT,
                fontweight="bold", zorder=4, gid=f"link:{tree.links[i]}", **mono)
        if len(link_lines[i]) > 1:
            ax.text(box.x, -box.top - _PAD - _LINE * _LINK_FONT, "\n".join(link_lines[i][1:]), ha="center",
                    va="top", fontsize=_JOINT_FONT, zorder=4, **mono)
        if i == 0:
            continue
        joint = tree.joints[i]
        assert joint is not None
        label, parent = labels[i], links[tree.parent[i]]
        value = values.get(joint.name or "")
        alert = value is not None and beyond_limits(joint, value)
        edge = _ALERT if alert else "#555555"
        style = "--" if joint.type == "fixed" else "-"
        ax.add_artist(FancyArrowPatch((parent.x, -parent.top - parent.height), (label.x, -label.top),
                                     arrowstyle="-", color=edge, linestyle=style, linewidth=1.0, zorder=1))
        ax.add_artist(FancyArrowPatch((label.x, -label.top - label.height), (box.x, -box.top),
                                     arrowstyle="-|>", mutation_scale=10, color=edge, linewidth=1.0,
                                     shrinkA=0, shrinkB=0, zorder=1))
        ax.add_artist(FancyBboxPatch((label.x - label.width / 2, -label.top - label.height), label.width,
                                    label.height, boxstyle="round,pad=0,rounding_size=3",
                                    facecolor=_JOINT_COLOURS.get(joint.type or "", "#f6d5d5"),
                                    edgecolor=edge, linewidth=1.2 if alert else 0.6, zorder=2))
        ax.text(label.x, -label.top - _PAD, joint_lines[i][0], ha="center", va="top", fontsize=_JOINT_FONT,
                fontweight="bold", zorder=4, gid=f"joint:{joint.name}", **mono)
        ax.text(label.x, -label.top - _PAD - _LINE * _JOINT_FONT, "\n".join(joint_lines[i][1:]), ha="center",
                va="top", fontsize=_JOINT_FONT, color=_ALERT if alert else "black", zorder=4, **mono)
    if path is not None:
        if suffix == ".dot":
            with open(path, "w", encoding="utf-8") as handle:
                handle.write(frames_dot(robot, config, lang))
        else:
            save_figure(figure, path)
    return figure
