"""The torque and tracking plot of a run: per joint, position against the reference, and torque
against the effort limit (the forbidden region shaded, like the joint-limit bands of ``bras-kit plot``).
"""

from __future__ import annotations

import math
import os
from typing import TYPE_CHECKING, Any

import numpy as np

from ..core import backends
from ..core.i18n import say
from ..core.message import M
from ..diagrams.output import FIGURE_FORMATS, output_suffix, save_figure
from ..model.robot import Robot

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

_BAND = "#f6cccc"
_LIMIT_LINE = "#b03a2e"

def torque_figure(robot: Robot, states: Any, lang: str | None = None) -> Figure:
    """Two rows per run: positions (measured, reference) and torques with +-effort, one column per joint."""
    backends.matplotlib()
    from matplotlib.figure import Figure

    position, torque = say(M("position"), lang), say(M("torque"), lang)
    count = max(1, len(states.names))
    columns = min(count, 4)  # a 7-joint arm wraps onto two bands of rows
    bands = math.ceil(count / columns)
    figure = Figure(figsize=(3.6 * columns + 1.0, 5.0 * bands + 1.0), layout="constrained")
    axes = figure.subplots(2 * bands, columns, squeeze=False, sharex=True)
    for k in range(count, bands * columns):
        axes[2 * (k // columns)][k % columns].set_visible(False)
        axes[2 * (k // columns) + 1][k % columns].set_visible(False)
    times = np.asarray(states.times)
    for k, name in enumerate(states.names):
        joint = robot.joint(name)
        linear = joint is not None and joint.type == "prismatic"
        top, bottom = axes[2 * (k // columns)][k % columns], axes[2 * (k // columns) + 1][k % columns]
        top.plot(times, states.targets[:, k], "--", color="#888888", label=say(M("reference"), lang))
        top.plot(times, states.positions[:, k], color="#1f77b4", label=position)
        lower, upper = joint.bounds() if joint is not None else (-math.inf, math.inf)
        for bound in (lower, upper):
            if math.isfinite(bound):
                top.axhline(bound, color=_LIMIT_LINE, linewidth=0.8)
        top.set_title(name)
        top.set_ylabel(f"{position} ({'m' if linear else 'rad'})")
        bottom.plot(times, states.efforts[:, k], color="#2ca02c", label=torque)
        effort = float(states.effort_limits[k])
        if math.isfinite(effort):
            peak = max(effort * 1.3, float(np.abs(states.efforts[:, k]).max()) * 1.1)
            bottom.axhspan(effort, peak, color=_BAND, label=say(M("effort limit"), lang))
            bottom.axhspan(-peak, -effort, color=_BAND)
            bottom.axhline(effort, color=_LIMIT_LINE, linewidth=0.8)
            bottom.axhline(-effort, color=_LIMIT_LINE, linewidth=0.8)
            bottom.set_ylim(-peak, peak)
        bottom.set_ylabel(f"{torque} ({'N' if linear else 'N·m'})")
        bottom.set_xlabel(say(M("time (s)"), lang))
        if k == 0:
            top.legend(loc="upper right", fontsize="small")
            bottom.legend(loc="upper right", fontsize="small")
    figure.suptitle(say(M("{robot}: {control} control", robot=robot.name or "robot", control=states.control), lang))
    return figure


def save_torque_plot(robot: Robot, states: Any, path: str | os.PathLike[str], lang: str | None = None) -> None:
    output_suffix(path, FIGURE_FORMATS)
    save_figure(torque_figure(robot, states, lang), path)
