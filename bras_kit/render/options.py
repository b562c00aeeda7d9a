"""What a picture looks like: size, view, overlays, background and backend, checked once.

Every public render function takes these as keyword arguments; :func:`render_options` turns
them into a :class:`RenderOptions` and refuses unknown names or bad values with a
:class:`~bras_kit.core.errors.ParameterError` that says what to write instead.
"""

from __future__ import annotations

import math
import os
import re
from collections.abc import Sequence
from dataclasses import dataclass, field, fields

from ..core.errors import ParameterError
from ..core.message import M, Mn

# name -> (azimuth, elevation) in degrees. Azimuth is measured from +x towards +y, so the
# camera of "front" stands on the -y side and looks along +y at the x-z plane, the plane
# the tutorial arm moves in; "side" stands on +x and looks along -x.
VIEWS: dict[str, tuple[float, float]] = {
    "iso": (-55.0, 25.0),
    "front": (-90.0, 0.0),
    "side": (0.0, 0.0),
    "top": (-90.0, 90.0),
}
BACKENDS = ("auto", "egl", "osmesa", "software")
GEOMETRIES = ("visual", "collision", "both")  # RViz's RobotModel: Visual Enabled / Collision Enabled
MAX_SIDE = 8192  # larger than this, GL renderbuffers fail on common drivers

# Colours that have a name here but not in CSS.
_NAMED = {"rviz": (48, 48, 48)}


@dataclass(frozen=True)
class RenderOptions:
    """How to draw. ``azimuth``/``elevation`` (degrees) and ``distance`` (metres) override the
    view's camera; left as None, the camera frames every pose it is asked to show."""

    size: tuple[int, int] = (640, 480)
    view: str = "iso"
    tf: bool = False
    grid: bool = True
    background: tuple[int, int, int] = (255, 255, 255)
    backend: str = "auto"
    azimuth: float | None = None
    elevation: float | None = None
    distance: float | None = None
    fov: float = 30.0  # vertical field of view, degrees
    # smooth edges (pictures: 2x2 supersampling, sequences: 4x multisampling);
    # None: on for pictures, off for sequences
    antialias: bool | None = None
    package_paths: Sequence[str] = field(default_factory=tuple)
    targets: Sequence[Sequence[float]] = field(default_factory=tuple)  # points marked in the world (reach)
    geometry: str = "visual"  # what of each link is drawn: its <visual>s, its <collision>s or both

    @property
    def width(self) -> int:
        return self.size[0]

    @property
    def height(self) -> int:
        return self.size[1]


def parse_size(text: str | Sequence[int]) -> tuple[int, int]:
    """``"640x480"`` (or ``(640, 480)``) -> ``(640, 480)``, each side between 8 and 8192 pixels."""
    if isinstance(text, str):
        match = re.fullmatch(r"\s*(\d+)\s*[xX×]\s*(\d+)\s*", text)
        if match is None:
            raise ParameterError(M("size '{text}' is not WIDTHxHEIGHT", text=text),
                                 hint=M("give the picture size in pixels, e.g. --size 640x480"))
        width, height = int(match.group(1)), int(match.group(2))
    else:
        try:
            width, height = (int(v) for v in text)
        except (TypeError, ValueError):
            raise ParameterError(M("size {text} is not (width, height)", text=repr(text)),
                                 hint=M("give two whole numbers of pixels, e.g. size=(640, 480)")) from None
    if not (8 <= width <= MAX_SIDE and 8 <= height <= MAX_SIDE):
        raise ParameterError(M("size {width}x{height} is out of range", width=width, height=height),
                             hint=M("each side must be between 8 and {most} pixels", most=MAX_SIDE))
    check_memory_for(width, height)
    return width, height


# Peak memory per pixel of one picture: OpenGL buffers with 4 samples a pixel (2x2 supersampled
# or 4x multisampled), the read-back copy and the PNG encoder (measured: 8192x8192 peaked at
# 3.5 GB, about 52 bytes a pixel).
BYTES_PER_PIXEL = 64


def available_memory() -> int | None:
    """Bytes this process may still take: free memory, or the address-space limit if lower."""
    import resource

    limits = []
    try:
        with open("/proc/meminfo") as handle:
            for line in handle:
                if line.startswith("MemAvailable:"):
                    limits.append(int(line.split()[1]) * 1024)
    except (OSError, ValueError, IndexError):
        pass
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    if soft != resource.RLIM_INFINITY:
        try:
            with open("/proc/self/statm") as handle:
                used = int(handle.read().split()[0]) * os.sysconf("SC_PAGE_SIZE")
        except (OSError, ValueError, IndexError):
            used = 0
        limits.append(max(soft - used, 0))
    return min(limits) if limits else None


def check_memory_for(width: int, height: int) -> None:
    """Refuse a picture size whose buffers would not fit in the memory left."""
    free = available_memory()
    need = width * height * BYTES_PER_PIXEL
    if free is not None and need > free:
        side = max(8, int(math.sqrt(free / BYTES_PER_PIXEL)) // 8 * 8)
        raise ParameterError(M("size {width}x{height} needs about {need:.1f} GiB of memory, and only {free:.1f} GiB "
                               "are free", width=width, height=height, need=need / 2**30, free=free / 2**30),
                             hint=M("the largest square picture that fits now is about {side}x{side}", side=side))


def parse_color(text: str | Sequence[float]) -> tuple[int, int, int]:
    """A colour as 0-255 RGB from a CSS name, ``#rrggbb``, ``rgb(...)``, three numbers in 0..1
    (``"0.2 0.4 0.9"``, like a URDF colour), or a tuple of three numbers in 0..1 or whole 0..255."""
    if not isinstance(text, str):
        try:
            values = [float(v) for v in text][:3]
        except (TypeError, ValueError):
            values = []
        bytes_like = all(float(v).is_integer() for v in values) and any(v > 1 for v in values)
        scale = 1.0 if bytes_like else 255.0
        if len(values) == 3 and all(0.0 <= v * scale <= 255.0 for v in values):
            return tuple(round(v * scale) for v in values)  # type: ignore[return-value]
        raise ParameterError(M("colour {text} is neither three numbers in 0..1 nor three in 0..255", text=repr(text)),
                             hint=M("e.g. background=(1, 1, 1), background=(255, 255, 255) or background='white'"))
    name = text.strip().lower()
    if name in _NAMED:
        return _NAMED[name]
    parts = name.replace(",", " ").split()
    if len(parts) in (3, 4) and all(re.fullmatch(r"[0-9.]+", p) for p in parts):
        try:
            values = [float(p) for p in parts[:3]]
        except ValueError:
            values = []
        if len(values) == 3 and all(0.0 <= v <= 1.0 for v in values):
            return tuple(round(v * 255) for v in values)  # type: ignore[return-value]
    from PIL import ImageColor

    try:
        rgb = ImageColor.getrgb(name)
    except ValueError:
        raise ParameterError(M("'{text}' is not a colour", text=text),
                             hint=M("give a name (white, black, lightgrey, rviz), #rrggbb, "
                                    "or three numbers between 0 and 1 such as '0.9 0.9 0.9'")) from None
    return rgb[:3]


def _angle(name: str, value: object, low: float, high: float) -> float | None:
    if value is None:
        return None
    try:
        number = float(value)  # type: ignore[arg-type]
    except (TypeError, ValueError):
        raise ParameterError(M("{name} {value} is not a number", name=name, value=repr(value)),
                             hint=M("give {name} in degrees", name=name)) from None
    if not (math.isfinite(number) and low <= number <= high):
        raise ParameterError(M("{name} {value:g} is out of range", name=name, value=number),
                             hint=M("give {name} in degrees between {low:g} and {high:g}", name=name, low=low, high=high))
    return number


def render_options(**opts: object) -> RenderOptions:
    """Check keyword options and return them as :class:`RenderOptions` (defaults for the rest)."""
    known = {f.name for f in fields(RenderOptions)}
    unknown = sorted(set(opts) - known)
    if unknown:
        raise ParameterError(Mn("unknown render option {names}", "unknown render options {names}", len(unknown),
                                names=", ".join(unknown)),
                             hint=M("valid options: {names}", names=", ".join(sorted(known))))
    values = dict(opts)
    if "size" in values:
        values["size"] = parse_size(values["size"])  # type: ignore[arg-type]
    if "background" in values:
        values["background"] = parse_color(values["background"])  # type: ignore[arg-type]
    view = values.get("view", "iso")
    if view not in VIEWS:
        raise ParameterError(M("unknown view '{view}'", view=str(view)), hint=M("views: {names}", names=", ".join(VIEWS)))
    backend = values.get("backend", "auto")
    if backend not in BACKENDS:
        raise ParameterError(M("unknown backend '{backend}'", backend=str(backend)),
                             hint=M("backends: {names}", names=", ".join(BACKENDS)))
    geometry = values.get("geometry", "visual")
    if geometry not in GEOMETRIES:
        raise ParameterError(M("unknown geometry '{value}'", value=geometry),
                             hint=M("geometries: {names}", names=list(GEOMETRIES)))
    values["azimuth"] = _angle("azimuth", values.get("azimuth"), -360.0, 360.0)
    values["elevation"] = _angle("elevation", values.get("elevation"), -90.0, 90.0)
    distance = values.get("distance")
    if distance is not None:
        try:
            distance = float(distance)  # type: ignore[arg-type]
        except (TypeError, ValueError):
            distance = math.nan
        if not (math.isfinite(distance) and distance > 0):
            raise ParameterError(M("distance {value} is not a positive number", value=repr(values["distance"])),
                                 hint=M("give the camera's distance to the robot's centre in metres"))
        values["distance"] = distance
    fov = _angle("fov", values.get("fov", 30.0), 1.0, 170.0)
    values["fov"] = fov
    values["package_paths"] = tuple(values.get("package_paths", ()))  # type: ignore[arg-type]
    if values.get("antialias") is not None:
        values["antialias"] = bool(values["antialias"])
    values["tf"] = bool(values.get("tf", False))
    values["grid"] = bool(values.get("grid", True))
    return RenderOptions(**values)  # type: ignore[arg-type]
