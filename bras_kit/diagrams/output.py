"""Writing figures: the output format from the file name, and saving with a capped PNG size."""

from __future__ import annotations

import math
import os
from collections.abc import Sequence
from typing import TYPE_CHECKING

from ..core import backends
from ..core.errors import ParameterError
from ..core.message import M

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.figure import Figure

FIGURE_FORMATS = (".png", ".svg", ".pdf")
# a PNG's longest side and pixel count; bigger figures get a lower resolution instead
MAX_RASTER_SIDE, MAX_RASTER_PIXELS = 16000, 40_000_000


def output_suffix(path: str | os.PathLike[str], allowed: Sequence[str]) -> str:
    suffix = os.path.splitext(os.fspath(path))[1].lower()
    if suffix not in allowed:
        raise ParameterError(M("cannot write '{path}': unknown format '{suffix}'", path=os.fspath(path),
                               suffix=suffix or M("(none)")),
                             hint=M("end the file name with {suffixes}", suffixes=", ".join(allowed)))
    return suffix


def save_figure(figure: Figure, path: str | os.PathLike[str], dpi: float = 100.0) -> None:
    """Save a figure as PNG, SVG or PDF (from the suffix), text kept as text in SVG and PDF.

    A PNG's size is capped (:data:`MAX_RASTER_SIDE`, :data:`MAX_RASTER_PIXELS`) by lowering its resolution.
    """
    matplotlib = backends.matplotlib()

    suffix = output_suffix(path, FIGURE_FORMATS)
    width, height = figure.get_size_inches()
    if suffix == ".png":
        dpi = min(dpi, MAX_RASTER_SIDE / max(width, height), math.sqrt(MAX_RASTER_PIXELS / (width * height)))
        _check_text_fits(figure, dpi)
    folder = os.path.dirname(os.fspath(path))
    if folder:
        os.makedirs(folder, exist_ok=True)
    with matplotlib.rc_context({"svg.fonttype": "none", "pdf.fonttype": 42}):
        figure.savefig(path, dpi=dpi, format=suffix[1:], facecolor="white")


def _check_text_fits(figure: Figure, dpi: float) -> None:
    """Refuse a PNG whose capped resolution leaves text under one pixel (FreeType cannot draw it)."""
    from matplotlib.text import Text

    from ..core.message import M

    sizes = [float(text.get_fontsize()) for text in figure.findobj(Text) if text.get_text()]
    if sizes and min(sizes) * dpi / 72.0 < 1.0:
        raise ParameterError(M("at the {side} pixels a PNG may have on a side, this diagram's text would be smaller "
                               "than a pixel", side=MAX_RASTER_SIDE),
                             hint=M("write it as .svg or .pdf: vector pictures have no size limit"))
