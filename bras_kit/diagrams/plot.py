"""The motion plot: joint angles against their limits, and the tool tip's path in the plane and in 3D."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core import backends
from ..core.i18n import say
from ..core.message import M, Mn
from ..kinematics.frames import TFTree, fk_batch, tf_tree
from ..kinematics.tip import tool_tip
from ..model.robot import Robot
from ..motion import TOLERANCE, joint_unit
from ._labels import format_number
from .output import FIGURE_FORMATS, output_suffix, save_figure
from .trajectory import motion_plane, states_matrix, tip_positions

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

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


def _plot_joint(ax: Any, robot: Robot, name: str, times: np.ndarray, values: np.ndarray, lang: str | None) -> None:
    joint = robot.joint(name)
    lower, upper = joint.bounds() if joint is not None else (-math.inf, math.inf)
    finite = [b for b in (lower, upper) if math.isfinite(b)]
    low = min([float(values.min()), *finite]) if values.size else -1.0
    high = max([float(values.max()), *finite]) if values.size else 1.0
    pad = 0.12 * (high - low) if high > low else 0.5
    bottom, top = low - pad, high + pad
    ax.set_ylim(bottom, top)
    ax.plot(times, values, color="#1f4e8c", linewidth=1.4, label=say(M("position"), lang), zorder=3,
            marker="o" if values.size == 1 else None)
    if math.isfinite(upper):
        ax.axhspan(upper, top, color=_BAND, zorder=0, linewidth=0, label=say(M("out of limits"), lang), gid=f"band:{name}:upper")
        ax.axhline(upper, color=_LIMIT_LINE, linestyle="--", linewidth=1.0, label=say(M("limits"), lang), zorder=2)
    if math.isfinite(lower):
        ax.axhspan(bottom, lower, color=_BAND, zorder=0, linewidth=0, gid=f"band:{name}:lower")
        ax.axhline(lower, color=_LIMIT_LINE, linestyle="--", linewidth=1.0, zorder=2)
    outside = out_of_limits_mask(robot, [name], values[:, None])[:, 0]
    if outside.any():
        ax.plot(times[outside], values[outside], "o", color=_VIOLATION, markersize=3, label=say(M("violation"), lang),
                zorder=4, gid=f"violations:{name}")
        excess = np.where(values > upper, values - upper, lower - values)
        worst = int(np.argmax(excess))
        ax.annotate(say(M("{excess} {unit} beyond limit at t={time} s", excess=format_number(excess[worst]),
                          unit=joint_unit(joint) if joint else "", time=format_number(times[worst])), lang),
                    (times[worst], values[worst]),
                    xytext=(6, 6), textcoords="offset points", fontsize=8, color=_VIOLATION)
    unit = joint_unit(joint)
    ax.set_ylabel(f"{name} ({unit})")
    ax.grid(True, linewidth=0.4, alpha=0.6)


def plot_motion(robot: Robot, states: Any, path: str | os.PathLike[str] | None = None, *,
                lang: str | None = None) -> Figure:
    """Joint angles over time against their limits, and the tool tip's path in the arm's plane and in 3D.

    ``states`` is a JointStates (``times``, ``names``, ``positions``). Out-of-limit regions are
    shaded, limits dashed and samples beyond them marked in red. With ``path`` the figure is
    saved (.png, .svg or .pdf). Its words are in ``lang`` (default: the library's language).
    """
    if path is not None:
        output_suffix(path, FIGURE_FORMATS)
    tree = tf_tree(robot)
    times = np.asarray(states.times, dtype=float)
    names = list(states.names)
    positions = np.atleast_2d(np.asarray(states.positions, dtype=float))
    q = states_matrix(tree, states)
    transforms = fk_batch(tree, q)
    link, offset = tool_tip(tree)
    end = tree.index(link)
    tip = tip_positions(transforms, end, offset)
    bad = out_of_limits_mask(robot, names, positions).any(axis=1)
    plane = motion_plane(robot)

    backends.matplotlib()
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
    figure.suptitle(say(Mn("{robot}: {n} sample over {duration} s, tip = end of '{link}'",
                           "{robot}: {n} samples over {duration} s, tip = end of '{link}'", len(times),
                           robot=robot.name or M("robot"), duration=format_number(duration), link=link), lang),
                    fontsize=12)
    first_ax = None
    for k, name in enumerate(names):
        ax = figure.add_subplot(left[k, 0], sharex=first_ax)
        first_ax = first_ax or ax
        _plot_joint(ax, robot, name, times, positions[:, k], lang)
        if k == len(names) - 1:
            ax.set_xlabel(say(M("time (s)"), lang))
    if not names:
        ax = figure.add_subplot(left[0, 0])
        ax.text(0.5, 0.5, say(M("no movable joints"), lang), ha="center", va="center")
        ax.set_axis_off()

    handles = [Line2D([], [], color="#1f4e8c", label=say(M("joint position"), lang)),
               Line2D([], [], color=_LIMIT_LINE, linestyle="--", label=say(M("limit"), lang)),
               Patch(color=_BAND, label=say(M("out of limits"), lang))]
    if bad.any():  # the marker's entry only when a sample is marked
        handles.append(Line2D([], [], color=_VIOLATION, marker="o", linestyle="", markersize=3,
                              label=say(M("sample beyond a limit"), lang)))
    figure.legend(handles=handles, loc="outside lower center", ncol=len(handles), fontsize=8, frameon=False)

    start_skeleton = _skeleton(tree, transforms[0], tip[0], end)
    flat = figure.add_subplot(right[0, 0])
    uv = np.stack([tip @ plane.u, tip @ plane.v], axis=1)
    if len(uv) > 1:
        lines = LineCollection(list(np.stack([uv[:-1], uv[1:]], axis=1)), cmap="viridis", linewidth=2.0, zorder=3)
        lines.set_array(times[:-1])
        flat.add_collection(lines)
        figure.colorbar(lines, ax=flat, label=say(M("time (s)"), lang), shrink=0.85)
    for a, b in start_skeleton:
        flat.plot([a @ plane.u, b @ plane.u], [a @ plane.v, b @ plane.v], color="#999999", linewidth=2.5,
                  solid_capstyle="round", zorder=1)
    flat.plot(*uv[0], "o", color="black", markersize=5, label=say(M("start"), lang), zorder=4)
    flat.plot(*uv[-1], "s", color="black", markersize=5, label=say(M("end"), lang), zorder=4)
    if bad.any():
        flat.plot(uv[bad, 0], uv[bad, 1], "x", color=_VIOLATION, markersize=4, label=say(M("joint out of limits"), lang), zorder=5)
    flat.set_xlabel(plane.u_label)
    flat.set_ylabel(plane.v_label)
    # the arm moves in the plane perpendicular to its (parallel) joint axes
    kind = M("plane perpendicular to the joint axes") if plane.common_axis else M("side view (joint axes differ)")
    flat.set_title(say(M("tip path, {kind}", kind=kind), lang), fontsize=10)
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
    space.set_title(say(M("tip path in 3D (grey: arm at the first sample)"), lang), fontsize=10)
    if path is not None:
        save_figure(figure, path)
    return figure
