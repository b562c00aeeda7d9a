"""The workspace: tip positions sampled within the joint limits, and a figure of the region they fill."""

from __future__ import annotations

import math
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..core import backends
from ..core.errors import ParameterError
from ..core.i18n import say
from ..core.message import M
from ..kinematics.frames import TFTree, fk_batch
from ..model.robot import Robot
from ._inputs import Vector, _as_tree
from ._limits import _bounds
from .chain import _path_from_root, resolve_tip, tip_positions


def workspace_points(model: TFTree | Robot, samples: int = 100_000, *, limits: bool = True,
                     tip_link: str | None = None, tip_offset: Vector | None = None,
                     random_seed: int = 0) -> np.ndarray:
    """Tip positions (samples, 3) for configurations drawn uniformly within the joint limits.

    With ``limits=False`` revolute joints turn all the way round (-pi..pi); prismatic joints
    keep their limits. Forward kinematics runs in batches through :func:`fk_batch`.
    """
    tree = _as_tree(model)
    link, offset = resolve_tip(tree, tip_link, tip_offset)
    if samples < 1:
        raise ParameterError(M("--samples must be at least 1, not {samples}", samples=samples))
    lower, upper = _bounds(tree)
    revolute = np.array([j.type in ("revolute", "continuous") for j in tree.dof_joints()], dtype=bool)
    if not limits:
        lower = np.where(revolute, -math.pi, lower)
        upper = np.where(revolute, math.pi, upper)
    lower = np.where(np.isfinite(lower), lower, -math.pi)
    upper = np.where(np.isfinite(upper), upper, math.pi)
    rng = np.random.default_rng(random_seed)
    q = rng.uniform(lower, upper, size=(samples, len(tree.dof)))
    out = np.empty((samples, 3))
    for begin in range(0, samples, 50_000):
        out[begin:begin + 50_000] = tip_positions(tree, q[begin:begin + 50_000], link, offset)
    return out


def _occupancy(points: np.ndarray, x_edges: np.ndarray, y_edges: np.ndarray) -> np.ndarray:
    """Cells holding at least one point, with one-cell holes closed (dilate then erode)."""
    counts, _xs, _ys = np.histogram2d(points[:, 0], points[:, 1], bins=(x_edges, y_edges))
    cells = counts > 0

    def shift_any(grid: np.ndarray) -> np.ndarray:
        padded = np.pad(grid, 1)
        out = np.zeros_like(grid)
        for dx in (0, 1, 2):
            for dy in (0, 1, 2):
                out |= padded[dx:dx + grid.shape[0], dy:dy + grid.shape[1]]
        return out

    dilated = shift_any(cells)
    return cells | ~shift_any(~dilated)


def _smooth(field: np.ndarray, passes: int = 2) -> np.ndarray:
    """The occupancy blurred by a binomial 1-2-1 filter along each axis: its 0.5 level is a smooth
    curve through the cells' edges instead of a staircase."""
    out = field
    for _pass in range(passes):
        padded = np.pad(out, 1, mode="edge")
        out = (padded[:-2, 1:-1] + 2 * padded[1:-1, 1:-1] + padded[2:, 1:-1]) / 4
        padded = np.pad(out, 1, mode="edge")
        out = (padded[1:-1, :-2] + 2 * padded[1:-1, 1:-1] + padded[1:-1, 2:]) / 4
    return out


def _area(cells: np.ndarray, cell_area: float) -> float:
    """Area of a region drawn as occupied cells: a cell on the border (a side touching an empty
    cell) is on average half inside a smooth boundary, so it counts one half."""
    padded = np.pad(cells, 1)
    inner = cells & padded[:-2, 1:-1] & padded[2:, 1:-1] & padded[1:-1, :-2] & padded[1:-1, 2:]
    border = cells & ~inner
    return float((inner.sum() + 0.5 * border.sum()) * cell_area)


@dataclass
class WorkspaceSummary:
    """Figures of a drawn workspace: plane axes, areas (m^2) and the reach (m) from the first joint."""

    axes: tuple[str, str]
    area_within_limits: float
    area_without_limits: float
    max_reach: float
    samples: int


def _plane_axes(points: np.ndarray) -> tuple[int, int]:
    """Two world axes to draw: the widest spreads; z, if kept, is vertical."""
    spread = np.ptp(points, axis=0)
    keep = sorted(np.argsort(spread)[-2:].tolist())
    if 2 in keep:
        other = keep[0] if keep[1] == 2 else keep[1]
        return other, 2
    return keep[0], keep[1]


def workspace_figure(model: TFTree | Robot, samples: int = 100_000, *, tip_link: str | None = None,
                     tip_offset: Vector | None = None, size: tuple[float, float] = (7.0, 6.0),
                     dpi: int = 100, lang: str | None = None):
    """A matplotlib figure of the region the tip reaches, in the arm's plane.

    Faint: every joint turning freely; solid: within the limits; the base and the arm at its
    zero pose on top. Returns (figure, axes, :class:`WorkspaceSummary`).
    """
    backends.matplotlib()
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from matplotlib.figure import Figure
    from matplotlib.patches import Patch, Rectangle

    tree = _as_tree(model)
    link, offset = resolve_tip(tree, tip_link, tip_offset)
    free = workspace_points(tree, samples, limits=False, tip_link=link, tip_offset=offset)
    bounded = workspace_points(tree, samples, limits=True, tip_link=link, tip_offset=offset, random_seed=1)
    h, v = _plane_axes(free)
    names = ("x", "y", "z")
    zero = fk_batch(tree, np.zeros(len(tree.dof)))
    chain_links = _path_from_root(tree, tree.index(link))
    last = zero[chain_links[-1]]
    arm_points = np.array([zero[j][:3, 3] for j in chain_links] + [last[:3, :3] @ offset + last[:3, 3]])
    every = np.vstack([free, arm_points])
    low, high = every.min(axis=0), every.max(axis=0)
    span = max(float(np.max(high[[h, v]] - low[[h, v]])), 1e-3)
    margin = 0.08 * span
    cells = int(np.clip(math.sqrt(samples) / 2.5, 40, 250))
    x_edges = np.linspace(low[h] - margin, high[h] + margin, cells + 1)
    y_edges = np.linspace(low[v] - margin, high[v] + margin, cells + 1)
    free_cells = _occupancy(free[:, [h, v]], x_edges, y_edges)
    bounded_cells = _occupancy(bounded[:, [h, v]], x_edges, y_edges) & free_cells
    cell_area = float((x_edges[1] - x_edges[0]) * (y_edges[1] - y_edges[0]))

    figure = Figure(figsize=size, dpi=dpi)
    FigureCanvasAgg(figure)
    axes = figure.add_subplot(1, 1, 1)
    extent = (x_edges[0], x_edges[-1], y_edges[0], y_edges[-1])
    free_colour, bounded_colour = (0.55, 0.65, 0.85, 0.35), (0.15, 0.35, 0.80, 1.0)
    centres_x, centres_y = (x_edges[:-1] + x_edges[1:]) / 2, (y_edges[:-1] + y_edges[1:]) / 2
    for cells_on, colour, order in ((free_cells, free_colour, 1), (bounded_cells, bounded_colour, 2)):
        if cells_on.any():  # contour at half a cell: smooth edges, no blocky pixels
            axes.contourf(centres_x, centres_y, _smooth(cells_on.astype(float)).T, levels=[0.5, 1.5],
                          colors=[colour], antialiased=True, zorder=order)
    base = tree.robot.link(tree.root)
    for visual in base.visuals if base is not None else []:
        g = visual.geometry
        centre = np.asarray(visual.origin.xyz)
        if g is None:
            continue
        if g.kind == "box" and g.size:
            w, hh = g.size[h], g.size[v]
        elif g.kind == "cylinder" and g.radius is not None and g.length is not None:
            dims = (2 * g.radius, 2 * g.radius, g.length)
            w, hh = dims[h], dims[v]
        elif g.kind == "sphere" and g.radius is not None:
            w = hh = 2 * g.radius
        else:
            continue
        axes.add_patch(Rectangle((centre[h] - w / 2, centre[v] - hh / 2), w, hh, facecolor=(0.5, 0.5, 0.5),
                                 edgecolor="black", linewidth=0.8, zorder=3, label=say(M("base"), lang)))
    if v == 2:  # the floor the base stands on: the tip cannot go below it on a real arm
        bottoms = [patch.get_y() for patch in axes.patches if isinstance(patch, Rectangle)]
        floor = min(bottoms) if bottoms else float(zero[0][2, 3])
        axes.axhline(floor, color=(0.45, 0.3, 0.15), linewidth=2, zorder=3, label=say(M("floor"), lang))
        if (free[:, v] < floor - 1e-9).any():  # the model's tip reaches below the floor: say so on the figure
            axes.axhspan(y_edges[0], floor, facecolor="none", edgecolor=(0.45, 0.3, 0.15, 0.55), hatch="///",
                         linewidth=0, zorder=2.5)
            axes.text((x_edges[0] + x_edges[-1]) / 2, (y_edges[0] + floor) / 2,
                      say(M("below the floor: reached by the model, not by a real arm"), lang), ha="center", va="center",
                      fontsize=8, color=(0.35, 0.22, 0.1), zorder=6,
                      bbox={"facecolor": "white", "edgecolor": "none", "alpha": 0.85, "pad": 2})
    axes.plot(arm_points[:, h], arm_points[:, v], "-", color=(0.95, 0.5, 0.1), linewidth=3, zorder=4,
              label=say(M("arm at zero pose"), lang))
    axes.plot(arm_points[1:-1, h], arm_points[1:-1, v], "o", color="black", markersize=5, zorder=5)
    axes.plot(arm_points[-1, h], arm_points[-1, v], "*", color="black", markersize=9, zorder=5)
    shoulder = arm_points[1] if len(arm_points) > 2 else arm_points[0]
    reach = float(np.max(np.linalg.norm(free - shoulder, axis=1)))
    axes.set_xlim(extent[0], extent[1])
    axes.set_ylim(extent[2], extent[3])
    axes.set_aspect("equal")
    axes.set_xlabel(f"{names[h]} (m)")
    axes.set_ylabel(f"{names[v]} (m)")
    axes.grid(True, linewidth=0.3, alpha=0.5, zorder=0)
    tip_text = f"{link} + ({', '.join(f'{c:g}' for c in offset)})"
    axes.set_title(say(M("Workspace of {robot}: tip {tip}", robot=tree.robot.name or M("robot"), tip=tip_text), lang),
                   fontsize=10)
    handles: list[Any] = [Patch(facecolor=free_colour, label=say(M("reachable if joints turned freely"), lang)),
                          Patch(facecolor=bounded_colour, label=say(M("reachable within the joint limits"), lang))]
    handles += axes.get_legend_handles_labels()[0]
    axes.legend(handles=handles, loc="lower left", fontsize=8, framealpha=0.9)
    figure.tight_layout()
    summary = WorkspaceSummary((names[h], names[v]), _area(bounded_cells, cell_area),
                               _area(free_cells, cell_area), reach, samples)
    return figure, axes, summary
