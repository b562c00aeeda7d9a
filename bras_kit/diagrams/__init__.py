"""Diagrams of a robot: the TF tree as text, the frame tree (DOT or drawn), and motion plots.

Modules: :mod:`.text` (``bras-kit tree``), :mod:`.dot` (Graphviz text), :mod:`.layout` (tidy tree
placement), :mod:`.frames` (the frame tree drawn with matplotlib), :mod:`.trajectory` (tool tip
path, motion plane), :mod:`.plot` (joint angles and tip path), :mod:`.output` (formats, saving).
Trees are walked through :class:`~bras_kit.kinematics.frames.TFTree`'s flat arrays, never by recursion;
matplotlib is imported inside the drawing functions only.
"""

from __future__ import annotations

from ._labels import format_number, format_vector, joint_label_lines, joint_summary, joint_values
from .dot import frames_dot
from .frames import FRAME_FORMATS, frame_diagram
from .layout import TreeLayout, tidy_layout
from .output import FIGURE_FORMATS, MAX_RASTER_PIXELS, MAX_RASTER_SIDE, output_suffix, save_figure
from .plot import out_of_limits_mask, plot_motion
from .text import ASCII_GLYPHS, UNICODE_GLYPHS, TreeGlyphs, tree_text
from .trajectory import MotionPlane, motion_plane, states_matrix, tip_path, tip_point

__all__ = [
    "ASCII_GLYPHS", "FIGURE_FORMATS", "FRAME_FORMATS", "MAX_RASTER_PIXELS", "MAX_RASTER_SIDE",
    "UNICODE_GLYPHS", "MotionPlane", "TreeGlyphs", "TreeLayout", "format_number", "format_vector",
    "frame_diagram", "frames_dot", "joint_label_lines", "joint_summary", "joint_values",
    "motion_plane", "out_of_limits_mask", "output_suffix", "plot_motion", "save_figure",
    "states_matrix", "tidy_layout", "tip_path", "tip_point", "tree_text",
]
