"""Showing pictures and animations inline in Jupyter (IPython is imported only when called)."""

from __future__ import annotations

import io
import os
from collections.abc import Iterable
from typing import Any

import numpy as np

from .sequence import gif_bytes, save_png


def show_image(image: np.ndarray | str | os.PathLike[str]) -> Any:
    """An ``IPython.display.Image`` of a rendered picture (array) or an image file."""
    from IPython.display import Image

    if isinstance(image, (str, os.PathLike)):
        return Image(filename=os.fspath(image))
    buffer = io.BytesIO()
    save_png(image, buffer)
    return Image(data=buffer.getvalue(), format="png")


def show_gif(animation: Iterable[np.ndarray] | str | os.PathLike[str], fps: float = 20.0) -> Any:
    """An animation inline: a GIF file, or frames (e.g. :func:`render_motion`'s) encoded in memory."""
    from IPython.display import Image

    if isinstance(animation, (str, os.PathLike)):
        with open(animation, "rb") as handle:
            data = handle.read()
    else:
        data = gif_bytes(animation, fps)
    return Image(data=data, format="gif")


def show_video(path: str | os.PathLike[str], width: int | None = None) -> Any:
    """An MP4 file inline, embedded in the notebook so it travels with it."""
    from IPython.display import Video

    return Video(os.fspath(path), embed=True, width=width, mimetype="video/mp4")
