"""Draw the arm off-screen: pictures of poses, animations of motions, as RViz would show them.

OpenGL through pyrender on EGL (works with Mesa's software rasteriser: no GPU, no display),
OSMesa next, and a pure-numpy rasteriser where there is no OpenGL at all. pyrender, PIL and
imageio are imported only when something is drawn or written; boxes, cylinders and spheres
are built with numpy, and trimesh is loaded only to read mesh files.

Fixed costs are paid once per process: OpenGL renderers (context, shaders, framebuffers) are
kept per picture size and reused by the next :class:`Renderer`, :func:`render_pose` or
:func:`render_motion` of that size, whatever the robot, and mesh files are read once while
unchanged. So a tool drawing many robots or poses just creates one :class:`Renderer` per
robot (or calls :func:`render_pose`) and pays the OpenGL start-up only the first time.

>>> from bras_kit import arm                                        # doctest: +SKIP
>>> image = render_pose(arm(), {"epaule": 0.8, "coude": 1.2}, view="front")
>>> save_gif(render_motion(arm(), states), "bras.gif", fps=20)
"""

from __future__ import annotations

from .display import show_gif, show_image, show_video
from .options import BACKENDS, VIEWS, RenderOptions, parse_color, parse_size, render_options
from .renderer import Frames, Renderer, configurations, render_motion, render_pose
from .sequence import (
    GifWriter,
    Mp4Writer,
    Progress,
    gif_bytes,
    save_frames,
    save_gif,
    save_mp4,
    save_png,
)

__all__ = [
    "BACKENDS",
    "VIEWS",
    "Frames",
    "GifWriter",
    "Mp4Writer",
    "Progress",
    "RenderOptions",
    "Renderer",
    "configurations",
    "gif_bytes",
    "parse_color",
    "parse_size",
    "render_motion",
    "render_options",
    "render_pose",
    "save_frames",
    "save_gif",
    "save_mp4",
    "save_png",
    "show_gif",
    "show_image",
    "show_video",
]
