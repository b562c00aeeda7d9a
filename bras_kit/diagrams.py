"""Diagrams of a robot: the TF tree as text, the frame tree (DOT or drawn), and motion plots.

* :func:`tree_text` prints the tree the way ``bras-kit tree`` shows it.
* :func:`frames_dot` and :func:`frame_diagram` give the picture ``tf2_tools view_frames`` and
  ``urdf_to_graphviz`` give: links as boxes, joints as labelled edges. No Graphviz is needed to
  draw it: :func:`tidy_layout` places the tree (depth = row, parents centred over their
  children) and matplotlib draws it.
* :func:`plot_motion` plots joint angles against their limits and the path of the tool tip
  (:func:`tip_point`, :func:`tip_path`).

Everything walks the tree through the flat arrays of :class:`~bras_kit.kinematics.TFTree`
(links in topological order, parent indices), never by recursion, so deep chains work.
matplotlib is imported inside the drawing functions only.
"""

from __future__ import annotations

import math
import os
from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING, Any

import numpy as np

from .errors import ParameterError
from .kinematics import TFTree, fk_batch, tf_tree
from .model import Joint, Robot

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

FIGURE_FORMATS = (".png", ".svg", ".pdf")
FRAME_FORMATS = (".png", ".svg", ".pdf", ".dot")
# a PNG's longest side and pixel count; bigger figures get a lower resolution instead
MAX_RASTER_SIDE, MAX_RASTER_PIXELS = 16000, 40_000_000

# ---------------------------------------------------------------- numbers and joint facts


def format_number(value: float | None) -> str:
    """A short, stable rendering of a number: 4 significant digits, no ``-0``, ``?`` when missing."""
    if value is None:
        return "?"
    if not math.isfinite(value):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf")
    if abs(value) < 1e-12:
        return "0"
    return f"{value:.4g}"


def format_vector(values: Sequence[float] | None) -> str:
    return " ".join(format_number(v) for v in values) if values is not None else "?"


def _unit(joint: Joint) -> str:
    return "m" if joint.type == "prismatic" else "rad"


def _range_text(joint: Joint, separator: str = "..") -> str | None:
    """``-1.57..1.57`` for a bounded joint, None when there is nothing to show."""
    if joint.type in ("revolute", "prismatic"):
        if joint.limit is None:
            return "no <limit>"
        return f"{format_number(joint.limit.lower)}{separator}{format_number(joint.limit.upper)}"
    return None


def _axis_text(joint: Joint) -> str:
    text = format_vector(joint.axis_or_default)
    return text if joint.axis is not None else text + " (default)"


def joint_summary(joint: Joint) -> str:
    """One line about a joint: ``revolute, axis 0 1 0, -1.57..1.57``."""
    parts = [joint.type or "no type"]
    if joint.type in ("revolute", "continuous", "prismatic"):
        parts.append("axis " + _axis_text(joint))
    limits = _range_text(joint)
    if limits is not None:
        parts.append(limits)
    if joint.mimic is not None:
        parts.append(f"mimics {joint.mimic.joint}")
    return ", ".join(parts)


def joint_label_lines(joint: Joint, value: float | None = None) -> list[str]:
    """The detail lines under a joint's name in the frame diagram (origin, axis, limits, value)."""
    lines = [joint.type or "no type"]
    if joint.mimic is not None:
        lines[0] += (f", mimics {joint.mimic.joint} x{format_number(joint.mimic.multiplier)}"
                     f" {'+' if joint.mimic.offset >= 0 else '-'}{format_number(abs(joint.mimic.offset))}")
    lines.append("xyz " + format_vector(joint.origin.xyz))
    lines.append("rpy " + format_vector(joint.origin.rpy))
    if joint.type in ("revolute", "continuous", "prismatic"):
        lines.append("axis " + _axis_text(joint))
    limits = _range_text(joint, " .. ")
    if limits is not None:
        lines.append(f"limits {limits} {_unit(joint)}" if joint.limit is not None else limits)
    elif joint.type == "continuous":
        lines.append("no position limits")
    if joint.limit is not None and joint.type in ("revolute", "continuous", "prismatic"):
        lines.append(f"effort {format_number(joint.limit.effort)}, "
                     f"velocity {format_number(joint.limit.velocity)}")
    if value is not None:
        text = f"value {format_number(value)} {_unit(joint)}"
        if joint.type != "prismatic":
            text += f" ({format_number(math.degrees(value))} deg)"
        if _out_of_limits(joint, value):
            text += " OUT OF LIMITS"
        lines.append(text)
    return lines


def _out_of_limits(joint: Joint, value: float) -> bool:
    lower, upper = joint.bounds()
    return bool(value < lower or value > upper)


def joint_values(tree: TFTree, config: Mapping[str, float] | None) -> dict[str, float]:
    """Every driven joint's value for ``config``: the movable ones, and mimic joints from their leader.

    Unknown or fixed joint names in ``config`` raise :class:`~bras_kit.errors.ParameterError`.
    """
    q = tree.config_vector(config)
    values = {name: float(v) for name, v in zip(tree.dof, q)}
    robot = tree.robot
    for joint in robot.joints:
        if joint.mimic is None or joint.name is None or joint.type not in ("revolute", "continuous", "prismatic"):
            continue
        gain, offset, steps = 1.0, 0.0, 0
        current: Joint | None = joint
        while current is not None and current.mimic is not None and steps <= len(robot.joints):
            offset += gain * current.mimic.offset
            gain *= current.mimic.multiplier
            current = robot.joint(current.mimic.joint or "")
            steps += 1
        if current is not None and current.name in values:
            values[joint.name] = gain * values[current.name] + offset
    return values


def _children(parent: Sequence[int]) -> list[list[int]]:
    """Children of each node, in index order; requires parents to come before children."""
    out: list[list[int]] = [[] for _ in parent]
    for i, p in enumerate(parent):
        if p >= 0:
            if p >= i:
                raise ValueError("nodes must be in topological order (each parent before its children)")
            out[p].append(i)
    return out


def _depths(parent: Sequence[int]) -> list[int]:
    depth = [0] * len(parent)
    for i, p in enumerate(parent):
        if p >= 0:
            depth[i] = depth[p] + 1
    return depth


# ---------------------------------------------------------------- the tree as text


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


def tree_text(robot: Robot, config: Mapping[str, float] | None = None, *, ascii: bool = False) -> str:
    """The TF tree as indented text, one link per line (the root first), each child under its joint.

    ``config`` adds each movable joint's value. Each level is indented by three characters, so a
    line's indentation is 3 x the depth of its link. Raises :class:`~bras_kit.errors.ModelError`
    when the links do not form a tree.
    """
    tree = tf_tree(robot)
    values = joint_values(tree, config) if config else {}
    glyphs = ASCII_GLYPHS if ascii else UNICODE_GLYPHS
    children = _children(tree.parent)
    lines = [tree.links[0]]
    # depth-first, pre-order, with an explicit stack: (link index, prefix of its line, is last child)
    stack = [(child, "", k == len(children[0]) - 1) for k, child in enumerate(children[0])][::-1]
    while stack:
        index, prefix, last = stack.pop()
        joint = tree.joints[index]
        assert joint is not None
        text = f"{joint.name or '?'} ({joint_summary(joint)})"
        if joint.name in values:
            value = values[joint.name]  # type: ignore[index]
            text += f" = {format_number(value)}"
            if _out_of_limits(joint, value):
                text += " (out of limits)"
        lines.append(f"{prefix}{glyphs.last if last else glyphs.branch}{text} {glyphs.arrow} {tree.links[index]}")
        below = prefix + (glyphs.blank if last else glyphs.pipe)
        kids = children[index]
        stack.extend((child, below, k == len(kids) - 1) for k, child in reversed(list(enumerate(kids))))
    return "\n".join(lines) + "\n"


# ---------------------------------------------------------------- DOT


def _dot_string(text: str) -> str:
    """A DOT double-quoted string; line breaks become ``\\n`` (centred lines)."""
    escaped = text.replace("\\", "\\\\").replace('"', '\\"')
    escaped = "".join(c if c >= " " or c == "\n" else " " for c in escaped)
    return '"' + escaped.replace("\n", "\\n") + '"'


def _graph_title(robot: Robot, tree: TFTree, config: Mapping[str, float] | None) -> str:
    joints = len(tree.links) - 1
    title = (f"{robot.name or 'robot'}: frame tree, {len(tree.links)} links, {joints} joints "
             f"({len(tree.dof)} movable)")
    if config:
        title += "\npose: " + ", ".join(f"{k}={format_number(v)}" for k, v in config.items())
    return title


def _link_label(name: str, position: np.ndarray | None) -> str:
    if position is None:
        return name
    return f"{name}\nat {format_vector(position.tolist())}"


def frames_dot(robot: Robot, config: Mapping[str, float] | None = None) -> str:
    """The frame tree in Graphviz DOT: links as boxes, joints as edges parent -> child.

    Edge labels hold the joint's name, type, origin (xyz, rpy), axis and limits; with ``config``
    they also hold its current value and each link box its position in the root frame.
    Render it with Graphviz (``dot -Tpdf frames.dot -o frames.pdf``) or use :func:`frame_diagram`.
    """
    tree = tf_tree(robot)
    values = joint_values(tree, config) if config else {}
    positions = fk_batch(tree, tree.config_vector(config))[:, :3, 3] if config else None
    out = [
        f"digraph {_dot_string(robot.name or 'robot')} {{",
        f"  // bras-kit frames: the TF tree of '{robot.name or 'robot'}', root '{tree.root}'",
        f"  graph [rankdir=TB, labelloc=t, fontname=\"Helvetica\", label={_dot_string(_graph_title(robot, tree, config))}];",
        '  node [shape=box, style="rounded,filled", fillcolor="#dbe8fb", color="#1f4e8c", fontname="Helvetica"];',
        '  edge [fontname="Helvetica", fontsize=9, color="#555555", arrowhead=normal];',
    ]
    for i, link in enumerate(tree.links):
        label = _link_label(link, positions[i] if positions is not None else None)
        extra = ', penwidth=2' if i == 0 else ""
        out.append(f"  {_dot_string(link)} [label={_dot_string(label)}{extra}];")
    for i in range(1, len(tree.links)):
        joint = tree.joints[i]
        assert joint is not None
        value = values.get(joint.name or "")
        label = "\n".join([joint.name or "?", *joint_label_lines(joint, value)])
        style = ', color="#c0392b", fontcolor="#c0392b"' if value is not None and _out_of_limits(joint, value) else ""
        if joint.type == "fixed":
            style += ", style=dashed"
        out.append(f"  {_dot_string(tree.links[tree.parent[i]])} -> {_dot_string(tree.links[i])} "
                   f"[label={_dot_string(label)}{style}];")
    out.append("}")
    return "\n".join(out) + "\n"


# ---------------------------------------------------------------- tidy tree layout


@dataclass(frozen=True)
class TreeLayout:
    """Horizontal centres and rows of a drawn tree, in the units of the widths given."""

    x: tuple[float, ...]
    depth: tuple[int, ...]
    width: float  # total width, from 0


def tidy_layout(parent: Sequence[int], widths: Sequence[float] | None = None, gap: float = 1.0) -> TreeLayout:
    """Place a tree in rows: depth = row, siblings left to right, each parent centred over its children.

    ``parent[i]`` is node i's parent index (-1 for the root), parents listed before children;
    ``widths`` are the nodes' box widths (default 1). Reingold-Tilford style: each subtree is
    pushed right just enough that, row by row, its left outline clears the right outline of its
    elder siblings by ``gap``; the parent then sits at the midpoint of its first and last child.
    Outlines are shared lists (deepest row first) with lazy offsets, so a merge costs the height
    of the shallower subtree: linear time overall, and no recursion (a 10,000-link chain is fine).
    """
    n = len(parent)
    if n == 0:
        return TreeLayout((), (), 0.0)
    w = [1.0] * n if widths is None else [float(v) for v in widths]
    if len(w) != n:
        raise ValueError("one width per node expected")
    if parent[0] >= 0 or any(p < 0 for p in parent[1:]):
        raise ValueError("expected one root, listed first")
    children = _children(parent)
    rel = [0.0] * n  # centre relative to the parent's centre
    # outline of each subtree: rows deepest first; true position = stored + offset (relative to the root)
    left_rows: list[list[float]] = [[] for _ in range(n)]
    right_rows: list[list[float]] = [[] for _ in range(n)]
    left_off = [0.0] * n
    right_off = [0.0] * n
    for v in range(n - 1, -1, -1):  # children before parents
        half = w[v] / 2
        kids = children[v]
        if not kids:
            left_rows[v], right_rows[v] = [-half], [half]
            continue
        first = kids[0]
        lrows, loff, rrows, roff = left_rows[first], left_off[first], right_rows[first], right_off[first]
        positions = [0.0]  # children's centres, relative to the first child
        for child in kids[1:]:
            clrows, crrows = left_rows[child], right_rows[child]
            common = min(len(rrows), len(clrows))
            shift = max(rrows[-1 - d] + roff - clrows[-1 - d] - left_off[child] + gap for d in range(common))
            positions.append(shift)
            cloff, croff = left_off[child] + shift, right_off[child] + shift
            if len(crrows) >= len(rrows):  # the new child reaches every row of its elders
                rrows, roff = crrows, croff
            else:
                for d in range(len(crrows)):
                    rrows[-1 - d] = crrows[-1 - d] + croff - roff
            if len(clrows) > len(lrows):  # rows below the elders are outlined by the new child
                for d in range(len(lrows)):
                    clrows[-1 - d] = lrows[-1 - d] + loff - cloff
                lrows, loff = clrows, cloff
            left_rows[child] = right_rows[child] = []  # merged: release
        middle = (positions[0] + positions[-1]) / 2
        for child, position in zip(kids, positions):
            rel[child] = position - middle
        loff -= middle
        roff -= middle
        lrows.append(-half - loff)
        rrows.append(half - roff)
        left_rows[v], left_off[v], right_rows[v], right_off[v] = lrows, loff, rrows, roff
        left_rows[first] = right_rows[first] = []
    x = [0.0] * n
    for v in range(1, n):
        x[v] = x[parent[v]] + rel[v]
    low = min(x[v] - w[v] / 2 for v in range(n))
    high = max(x[v] + w[v] / 2 for v in range(n))
    return TreeLayout(tuple(c - low for c in x), tuple(_depths(parent)), high - low)


# ---------------------------------------------------------------- the frame diagram, drawn

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


def frame_diagram(robot: Robot, config: Mapping[str, float] | None = None,
                  path: str | os.PathLike[str] | None = None) -> Figure:
    """Draw the frame tree with matplotlib (no Graphviz): link boxes, joint labels on the edges.

    The figure is sized to the tree (1 unit = 1 point). With ``path`` it is also saved; the
    format follows the suffix (.png, .svg, .pdf, or .dot for the DOT text of :func:`frames_dot`).
    """
    suffix = output_suffix(path, FRAME_FORMATS) if path is not None else None
    tree = tf_tree(robot)
    values = joint_values(tree, config) if config else {}
    positions = fk_batch(tree, tree.config_vector(config))[:, :3, 3] if config else None
    n = len(tree.links)
    link_lines = [_link_label(link, positions[i] if positions is not None else None).split("\n")
                  for i, link in enumerate(tree.links)]
    joint_lines: list[list[str]] = [[]]
    for i in range(1, n):
        joint = tree.joints[i]
        assert joint is not None
        joint_lines.append([joint.name or "?", *joint_label_lines(joint, values.get(joint.name or ""))])
    link_size = [_text_box(lines, _LINK_FONT) for lines in link_lines]
    joint_size = [_text_box(lines, _JOINT_FONT) if lines else (0.0, 0.0) for lines in joint_lines]
    layout = tidy_layout(tree.parent, [max(a[0], b[0]) for a, b in zip(link_size, joint_size)], _SIBLING_GAP)
    rows = max(layout.depth) + 1
    label_band, box_band = [0.0] * rows, [0.0] * rows
    for i in range(n):
        d = layout.depth[i]
        label_band[d] = max(label_band[d], joint_size[i][1])
        box_band[d] = max(box_band[d], link_size[i][1])
    title = _graph_title(robot, tree, config)
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
        alert = value is not None and _out_of_limits(joint, value)
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
                handle.write(frames_dot(robot, config))
        else:
            save_figure(figure, path)
    return figure


# ---------------------------------------------------------------- saving figures


def output_suffix(path: str | os.PathLike[str], allowed: Sequence[str]) -> str:
    suffix = os.path.splitext(os.fspath(path))[1].lower()
    if suffix not in allowed:
        raise ParameterError(f"cannot write '{os.fspath(path)}': unknown format '{suffix or '(none)'}'",
                             hint="end the file name with " + ", ".join(allowed))
    return suffix


def save_figure(figure: Figure, path: str | os.PathLike[str], dpi: float = 100.0) -> None:
    """Save a figure as PNG, SVG or PDF (from the suffix), text kept as text in SVG and PDF.

    A PNG's size is capped (:data:`MAX_RASTER_SIDE`, :data:`MAX_RASTER_PIXELS`) by lowering its resolution.
    """
    import matplotlib

    suffix = output_suffix(path, FIGURE_FORMATS)
    width, height = figure.get_size_inches()
    if suffix == ".png":
        dpi = min(dpi, MAX_RASTER_SIDE / max(width, height), math.sqrt(MAX_RASTER_PIXELS / (width * height)))
    folder = os.path.dirname(os.fspath(path))
    if folder:
        os.makedirs(folder, exist_ok=True)
    with matplotlib.rc_context({"svg.fonttype": "none", "pdf.fonttype": 42}):
        figure.savefig(path, dpi=dpi, format=suffix[1:], facecolor="white")


# ---------------------------------------------------------------- the tool tip


def tip_point(robot: Robot) -> tuple[str, np.ndarray]:
    """The tool tip: the end link and the tip's offset in its frame (see :mod:`bras_kit.tip`)."""
    from .tip import tool_tip

    return tool_tip(tf_tree(robot))


def states_matrix(tree: TFTree, states: Any) -> np.ndarray:
    """Joint positions as an (T, dof) array in ``tree.dof`` order.

    ``states`` is a JointStates (``names`` and ``positions``) or an array already in dof order.
    Joints missing from ``states`` stay at 0; unknown names raise ParameterError.
    """
    if isinstance(states, np.ndarray):
        q = np.atleast_2d(np.asarray(states, dtype=float))
        if q.shape[1] != len(tree.dof):
            raise ParameterError(f"expected {len(tree.dof)} joint columns ({', '.join(tree.dof)}), got {q.shape[1]}")
        return q
    positions = np.atleast_2d(np.asarray(states.positions, dtype=float))
    q = np.zeros((positions.shape[0], len(tree.dof)))
    columns = {name: k for k, name in enumerate(tree.dof)}
    for k, name in enumerate(states.names):
        if name not in columns:
            raise ParameterError(f"the motion drives '{name}', which is not a movable joint of this robot",
                                 hint="movable joints: " + (", ".join(tree.dof) or "none"))
        q[:, columns[name]] = positions[:, k]
    return q


def tip_path(robot: Robot, states: Any) -> np.ndarray:
    """World (root frame) positions of the tool tip for every sample: shape (T, 3)."""
    tree = tf_tree(robot)
    link, offset = tip_point(robot)
    transforms = fk_batch(tree, states_matrix(tree, states))[:, tree.index(link)]
    return transforms[:, :3, :3] @ offset + transforms[:, :3, 3]


@dataclass(frozen=True)
class MotionPlane:
    """The plane the arm moves in: its normal and two in-plane axes with their labels."""

    normal: np.ndarray
    u: np.ndarray
    v: np.ndarray
    u_label: str
    v_label: str
    common_axis: bool  # False: the revolute axes differ and this is a default side view


def motion_plane(robot: Robot) -> MotionPlane:
    """The plane normal to the revolute joints' common axis (at the zero pose).

    The tutorial arm turns about y, so it moves in x-z. When the axes are not all parallel
    (or there are none) the side view x-z is used and ``common_axis`` is False.
    """
    tree = tf_tree(robot)
    zero = fk_batch(tree, np.zeros(len(tree.dof)))
    axes = []
    for i in range(1, len(tree.links)):
        joint = tree.joints[i]
        if joint is not None and joint.type in ("revolute", "continuous"):
            axis = np.asarray(joint.axis_or_default, dtype=float)
            if np.linalg.norm(axis) > 0:
                axes.append(zero[i][:3, :3] @ (axis / np.linalg.norm(axis)))
    normal, common = np.array([0.0, 1.0, 0.0]), False
    if axes and all(np.linalg.norm(np.cross(axes[0], a)) < 1e-6 for a in axes):
        normal, common = axes[0] / np.linalg.norm(axes[0]), True
    named = {0: (np.array([0.0, 1, 0]), np.array([0.0, 0, 1]), "y", "z"),
             1: (np.array([1.0, 0, 0]), np.array([0.0, 0, 1]), "x", "z"),
             2: (np.array([1.0, 0, 0]), np.array([0.0, 1, 0]), "x", "y")}
    dominant = int(np.argmax(np.abs(normal)))
    if abs(normal[dominant]) > 1 - 1e-9:
        u, v, u_name, v_name = named[dominant]
    else:
        up = np.array([0.0, 0.0, 1.0]) - normal[2] * normal
        if np.linalg.norm(up) < 1e-6:
            up = np.array([0.0, 1.0, 0.0]) - normal[1] * normal
        v = up / np.linalg.norm(up)
        u = np.cross(v, normal)
        u_name, v_name = f"u = ({format_vector(u.tolist())})", f"v = ({format_vector(v.tolist())})"
    return MotionPlane(normal, u, v, f"{u_name} (m)", f"{v_name} (m)", common)


# ---------------------------------------------------------------- motion plot

_BAND = "#f6cccc"
_LIMIT_LINE = "#b03a2e"
_VIOLATION = "#d62728"


def out_of_limits_mask(robot: Robot, names: Sequence[str], positions: np.ndarray,
                       tolerance: float | None = None) -> np.ndarray:
    """(T, n) booleans: where each joint's position is past its limits by more than ``tolerance``.

    The tolerance defaults to :data:`bras_kit.motion.TOLERANCE`, so the plot marks the samples
    that :func:`bras_kit.motion.check_limits` reports.
    """
    if tolerance is None:
        from .motion import TOLERANCE

        tolerance = TOLERANCE
    positions = np.atleast_2d(np.asarray(positions, dtype=float))
    mask = np.zeros(positions.shape, dtype=bool)
    for k, name in enumerate(names):
        joint = robot.joint(name)
        if joint is not None:
            lower, upper = joint.bounds()
            mask[:, k] = (positions[:, k] < lower - tolerance) | (positions[:, k] > upper + tolerance)
    return mask


def _skeleton(tree: TFTree, transforms: np.ndarray, tip: np.ndarray, end: int) -> list[tuple[np.ndarray, np.ndarray]]:
    """Segments parent origin -> child origin, and the end link's origin -> the tip."""
    segments = [(transforms[tree.parent[i]][:3, 3], transforms[i][:3, 3]) for i in range(1, len(tree.links))]
    segments.append((transforms[end][:3, 3], tip))
    return segments


def _plot_joint(ax: Any, robot: Robot, name: str, times: np.ndarray, values: np.ndarray) -> None:
    joint = robot.joint(name)
    lower, upper = joint.bounds() if joint is not None else (-math.inf, math.inf)
    finite = [b for b in (lower, upper) if math.isfinite(b)]
    low = min([float(values.min()), *finite]) if values.size else -1.0
    high = max([float(values.max()), *finite]) if values.size else 1.0
    pad = 0.12 * (high - low) if high > low else 0.5
    bottom, top = low - pad, high + pad
    ax.set_ylim(bottom, top)
    ax.plot(times, values, color="#1f4e8c", linewidth=1.4, label="position", zorder=3,
            marker="o" if values.size == 1 else None)
    if math.isfinite(upper):
        ax.axhspan(upper, top, color=_BAND, zorder=0, linewidth=0, label="out of limits", gid=f"band:{name}:upper")
        ax.axhline(upper, color=_LIMIT_LINE, linestyle="--", linewidth=1.0, label="limits", zorder=2)
    if math.isfinite(lower):
        ax.axhspan(bottom, lower, color=_BAND, zorder=0, linewidth=0, gid=f"band:{name}:lower")
        ax.axhline(lower, color=_LIMIT_LINE, linestyle="--", linewidth=1.0, zorder=2)
    outside = out_of_limits_mask(robot, [name], values[:, None])[:, 0]
    if outside.any():
        ax.plot(times[outside], values[outside], "o", color=_VIOLATION, markersize=3, label="violation",
                zorder=4, gid=f"violations:{name}")
        excess = np.where(values > upper, values - upper, lower - values)
        worst = int(np.argmax(excess))
        ax.annotate(f"{format_number(excess[worst])} {_unit(joint) if joint else ''} beyond limit "
                    f"at t={format_number(times[worst])} s", (times[worst], values[worst]),
                    xytext=(6, 6), textcoords="offset points", fontsize=8, color=_VIOLATION)
    unit = _unit(joint) if joint is not None else "rad"
    ax.set_ylabel(f"{name} ({unit})")
    ax.grid(True, linewidth=0.4, alpha=0.6)


def plot_motion(robot: Robot, states: Any, path: str | os.PathLike[str] | None = None) -> Figure:
    """Joint angles over time against their limits, and the tool tip's path in the arm's plane and in 3D.

    ``states`` is a JointStates (``times``, ``names``, ``positions``). Out-of-limit regions are
    shaded, limits dashed and samples beyond them marked in red. With ``path`` the figure is
    saved (.png, .svg or .pdf).
    """
    if path is not None:
        output_suffix(path, FIGURE_FORMATS)
    tree = tf_tree(robot)
    times = np.asarray(states.times, dtype=float)
    names = list(states.names)
    positions = np.atleast_2d(np.asarray(states.positions, dtype=float))
    q = states_matrix(tree, states)
    transforms = fk_batch(tree, q)
    link, offset = tip_point(robot)
    end = tree.index(link)
    tip = transforms[:, end, :3, :3] @ offset + transforms[:, end, :3, 3]
    bad = out_of_limits_mask(robot, names, positions).any(axis=1)
    plane = motion_plane(robot)

    from matplotlib.collections import LineCollection
    from matplotlib.figure import Figure
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    rows = max(len(names), 1)
    figure = Figure(figsize=(13.0, max(6.5, 2.1 * rows + 1.0)), layout="constrained")
    grid = figure.add_gridspec(1, 2, width_ratios=[1.35, 1.0])
    left = grid[0].subgridspec(rows, 1)
    right = grid[1].subgridspec(2, 1)
    duration = float(times[-1] - times[0]) if times.size > 1 else 0.0
    figure.suptitle(f"{robot.name or 'robot'}: {len(times)} sample{'s' if len(times) != 1 else ''} over "
                    f"{format_number(duration)} s, "
                    f"tip = end of '{link}'", fontsize=12)
    first_ax = None
    for k, name in enumerate(names):
        ax = figure.add_subplot(left[k, 0], sharex=first_ax)
        first_ax = first_ax or ax
        _plot_joint(ax, robot, name, times, positions[:, k])
        if k == len(names) - 1:
            ax.set_xlabel("time (s)")
    if not names:
        ax = figure.add_subplot(left[0, 0])
        ax.text(0.5, 0.5, "no movable joints", ha="center", va="center")
        ax.set_axis_off()

    figure.legend(handles=[Line2D([], [], color="#1f4e8c", label="joint position"),
                           Line2D([], [], color=_LIMIT_LINE, linestyle="--", label="limit"),
                           Patch(color=_BAND, label="out of limits"),
                           Line2D([], [], color=_VIOLATION, marker="o", linestyle="", markersize=3,
                                  label="sample beyond a limit")],
                  loc="outside lower center", ncol=4, fontsize=8, frameon=False)

    start_skeleton = _skeleton(tree, transforms[0], tip[0], end)
    flat = figure.add_subplot(right[0, 0])
    uv = np.stack([tip @ plane.u, tip @ plane.v], axis=1)
    if len(uv) > 1:
        lines = LineCollection(list(np.stack([uv[:-1], uv[1:]], axis=1)), cmap="viridis", linewidth=2.0, zorder=3)
        lines.set_array(times[:-1])
        flat.add_collection(lines)
        figure.colorbar(lines, ax=flat, label="time (s)", shrink=0.85)
    for a, b in start_skeleton:
        flat.plot([a @ plane.u, b @ plane.u], [a @ plane.v, b @ plane.v], color="#999999", linewidth=2.5,
                  solid_capstyle="round", zorder=1)
    flat.plot(*uv[0], "o", color="black", markersize=5, label="start", zorder=4)
    flat.plot(*uv[-1], "s", color="black", markersize=5, label="end", zorder=4)
    if bad.any():
        flat.plot(uv[bad, 0], uv[bad, 1], "x", color=_VIOLATION, markersize=4, label="joint out of limits", zorder=5)
    flat.set_xlabel(plane.u_label)
    flat.set_ylabel(plane.v_label)
    kind = "plane of the joint axes" if plane.common_axis else "side view (joint axes differ)"
    flat.set_title(f"tip path, {kind}", fontsize=10)
    flat.set_aspect("equal", adjustable="datalim")
    flat.autoscale_view()
    flat.grid(True, linewidth=0.4, alpha=0.6)
    flat.legend(loc="best", fontsize=7)

    space = figure.add_subplot(right[1, 0], projection="3d")
    space.plot(tip[:, 0], tip[:, 1], tip[:, 2], color="#1f4e8c", linewidth=1.5)
    for a, b in start_skeleton:
        space.plot([a[0], b[0]], [a[1], b[1]], [a[2], b[2]], color="#999999", linewidth=2.5)
    space.scatter(*tip[0], color="black", marker="o", s=12)
    if bad.any():
        space.scatter(tip[bad, 0], tip[bad, 1], tip[bad, 2], color=_VIOLATION, marker="x", s=10)
    points = np.concatenate([tip, np.array([p for segment in start_skeleton for p in segment])])
    centre = (points.max(axis=0) + points.min(axis=0)) / 2
    half = max(float((points.max(axis=0) - points.min(axis=0)).max()) / 2, 0.05) * 1.05
    space.set_xlim(centre[0] - half, centre[0] + half)
    space.set_ylim(centre[1] - half, centre[1] + half)
    space.set_zlim(centre[2] - half, centre[2] + half)
    space.set_box_aspect((1, 1, 1))
    space.set_xlabel("x (m)")
    space.set_ylabel("y (m)")
    space.set_zlabel("z (m)")
    space.set_title("tip path in 3D (grey: arm at the first sample)", fontsize=10)
    if path is not None:
        save_figure(figure, path)
    return figure
