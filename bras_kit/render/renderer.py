"""The renderer: a robot's scene, a camera framing the poses to show, and a backend drawing them.

One :class:`Renderer` keeps one backend (one OpenGL context) for any number of pictures, so
a sequence or a notebook slider only moves the links between frames.
"""

from __future__ import annotations

import functools
import math
import sys
from collections.abc import Iterator, Mapping, Sequence
from typing import Any

import numpy as np

from ..core.errors import BackendError, ParameterError
from ..core.message import M
from ..core.wording import quoted
from ..kinematics.frames import TFTree, fk_batch, movable_joints_hint, tf_tree
from ..model.robot import Robot
from .camera import Camera, fit_camera
from .options import RenderOptions, render_options
from .scene import Scene, build_scene
from .sequence import Progress

WORKSPACE_SAMPLES = 256
_announced_fallback = False


def configurations(tree: TFTree, value: Any) -> np.ndarray:
    """Joint values as an (N, dof) array in ``tree.dof`` order.

    ``value``: a {joint: value} dict, an array (N, dof) or (dof,), a list of dicts, or joint
    states with ``names`` and ``positions`` (columns in any order; missing joints stay at 0).
    """
    if value is None:
        return np.zeros((1, len(tree.dof)))
    if isinstance(value, Mapping):
        return tree.config_vector(value)[None, :]
    names, positions = getattr(value, "names", None), getattr(value, "positions", None)
    if names is not None and positions is not None and not callable(positions):
        positions = np.atleast_2d(np.asarray(positions, dtype=float))
        out = np.zeros((len(positions), len(tree.dof)))
        for column, name in enumerate(names):
            if name not in tree.dof:
                raise ParameterError(M("joint states name '{name}', which is not a movable joint of the robot", name=name),
                                     hint=movable_joints_hint(tree.dof))
            out[:, tree.dof.index(name)] = positions[:, column]
        return out
    if isinstance(value, (list, tuple)) and value and isinstance(value[0], Mapping):
        return np.stack([tree.config_vector(item) for item in value])
    q = np.asarray(value, dtype=float)
    if q.ndim == 1:
        q = q[None, :]
    if q.ndim != 2 or q.shape[1] != len(tree.dof):
        raise ParameterError(M("expected joint values with {count} columns ({names}), got shape {shape}",
                               count=len(tree.dof), names=", ".join(tree.dof), shape=str(q.shape)))
    return q


def workspace_samples(tree: TFTree, count: int = WORKSPACE_SAMPLES) -> np.ndarray:
    """Poses spread over the joint limits (a grid for up to 3 joints, random beyond), with the zero pose."""
    bounds = []
    for joint in tree.dof_joints():
        low, high = joint.bounds()
        if not (math.isfinite(low) and math.isfinite(high)):
            low, high = (-math.pi, math.pi) if joint.type != "prismatic" else (0.0, 0.0)
        bounds.append((low, high))
    if not bounds:
        return np.zeros((1, 0))
    if len(bounds) <= 3:
        axes = [np.linspace(low, high, 7) for low, high in bounds]
        grid = np.stack(np.meshgrid(*axes, indexing="ij"), axis=-1).reshape(-1, len(bounds))
    else:
        rng = np.random.default_rng(0)
        low, high = np.array(bounds).T
        grid = low + rng.random((count, len(bounds))) * (high - low)
    return np.vstack([np.zeros((1, len(bounds))), grid])


def open_backend(scene: Scene, camera: Camera, options: RenderOptions,
                 sequence: bool = False):
    """The backend asked for; with 'auto', OpenGL (EGL, then OSMesa) or else, saying so once, software.
    ``sequence``: many frames will follow (antialiasing then favours the time per frame over the
    time to the first one)."""
    from ._software import SoftwareBackend

    if options.backend == "software":
        return SoftwareBackend(scene, camera, options.background)
    try:
        from ._pyrender import PyrenderBackend, choose_platform

        platform = choose_platform(options.backend)
        return PyrenderBackend(scene, camera, options.background, platform,
                               antialias=options.antialias is not False, supersample=not sequence)
    except ImportError as exc:
        error = BackendError(M("cannot load pyrender: {reason}", reason=quoted(str(exc))),
                             hint=M("pip install pyrender, or use backend software"))
    except BackendError as exc:
        error = exc
    if options.backend != "auto":
        raise error
    global _announced_fallback
    if not _announced_fallback:
        _announced_fallback = True
        from ..core.i18n import say

        print(say(M("bras-kit render: no OpenGL here ({reason}); using the software renderer, slower",
                    reason=error.message)), file=sys.stderr)
    return SoftwareBackend(scene, camera, options.background)


def used_software_fallback() -> bool:
    """Whether backend 'auto' fell back to the pure-CPU renderer in this process (no OpenGL here)."""
    return _announced_fallback


MAX_RENDER_LINKS = 5000  # real robots have a few hundred at most; each link costs a scene node
MAX_DRAWN_METRES = 1e6  # a joint offset past this is a typo or a fuzzer: no camera frames it


def check_drawable(robot: Robot) -> None:
    """Refuse, naming the joint and its line, an origin a picture cannot hold (nan, inf, 1e308).

    urdfdom and the validator accept such numbers; drawing them would divide by infinity
    when the camera and the ground grid are fitted.
    """
    from ..core.errors import ModelError
    from ..core.message import M

    for joint in robot.joints:
        xyz, rpy = joint.origin.xyz, joint.origin.rpy
        if all(math.isfinite(v) for v in rpy) and all(math.isfinite(v) and abs(v) <= MAX_DRAWN_METRES for v in xyz):
            continue
        raise ModelError(M("joint '{joint}' has the origin xyz=\"{xyz}\" rpy=\"{rpy}\": bras-kit cannot draw "
                           "a robot whose parts are not a number or more than {limit} m away",
                           joint=joint.name, xyz=list(xyz), rpy=list(rpy), limit=MAX_DRAWN_METRES),
                         path=robot.path, line=joint.origin.line or joint.line, element="origin",
                         hint=M("write finite lengths in metres in <origin xyz> and angles in radians in rpy"))


MAX_NAMED_FRAMES = 60  # past that, names would hide the robot


def frame_names(image: np.ndarray, camera: Any, names: Any, origins: np.ndarray) -> np.ndarray:
    """``image`` with each frame's name written beside its origin, over everything, like RViz's TF
    display with "Show Names" on: dark text with a light outline, readable on any colour. A name
    that would cover one already written moves up until it is clear (frames that coincide, such
    as a link and the base it sits on, get one name above the other). A legend in the lower left
    corner gives the axes' colours: x red, y green, z blue."""
    from PIL import Image, ImageDraw

    points = np.hstack([origins, np.ones((len(origins), 1))]) @ (camera.projection() @ camera.view()).T
    picture = Image.fromarray(np.ascontiguousarray(image))
    draw = ImageDraw.Draw(picture)
    size = max(9, min(16, camera.height // 30))
    font = label_font(size)
    placed: list[tuple[float, float, float, float]] = []
    for name, (x, y, _depth, w) in zip(names, points):
        if w <= 1e-9:  # behind the camera
            continue
        column = (x / w + 1.0) / 2.0 * camera.width + 4
        row = (1.0 - y / w) / 2.0 * camera.height - size - 2
        for _ in range(len(placed) + 1):
            left, top, right, bottom = draw.textbbox((column, row), str(name), font=font, stroke_width=2)
            clash = next((box for box in placed if left < box[2] and box[0] < right and top < box[3] and box[1] < bottom),
                         None)
            if clash is None:
                break
            row -= bottom - clash[1] + 1  # just above the name it covered
        placed.append(draw.textbbox((column, row), str(name), font=font, stroke_width=2))
        draw.text((column, row), str(name), fill=(20, 20, 20), font=font, stroke_width=2,
                  stroke_fill=(255, 255, 255))
    axes_legend(draw, font, size, camera.height)
    return np.asarray(picture)


LABEL_MASKS_KEPT = 1024


@functools.lru_cache(maxsize=8)
def label_font(size: int) -> Any:
    """Pillow's default font at ``size`` for frame names and the legend, kept for the process,
    remembering the masks it renders: a class of robots with the same names at the same places
    (a grading worker) has them rendered once. A mask is a pure function of the font and of
    the arguments of ``getmask2`` (text, mode, stroke, sub-pixel start...), so the pixels are
    those of a new font's; Pillow without FreeType sizes gets its fixed default font."""
    import io

    from PIL import ImageFont

    try:
        default = ImageFont.load_default(size=size)
    except TypeError:  # Pillow without FreeType sizes
        return ImageFont.load_default()
    data = getattr(default, "font_bytes", None)
    if not isinstance(default, ImageFont.FreeTypeFont) or not isinstance(data, bytes):
        return default

    class LabelFont(ImageFont.FreeTypeFont):
        def getmask2(self, text: Any, *args: Any, **kwargs: Any) -> Any:
            mode = args[0] if args else kwargs.get("mode", "")
            key: Any = (text, args, tuple(sorted(kwargs.items())))
            try:
                hash(key)
            except TypeError:  # features given as a list: not remembered
                key = None
            if mode == "RGBA" or key is None:  # Pillow writes into colour masks: never shared
                return super().getmask2(text, *args, **kwargs)
            found = masks.get(key)
            if found is None:
                if len(masks) >= LABEL_MASKS_KEPT:
                    masks.clear()
                found = masks[key] = super().getmask2(text, *args, **kwargs)
            return found

    masks: dict[Any, Any] = {}
    return LabelFont(io.BytesIO(data), size, layout_engine=default.layout_engine)


LEGEND_COLOURS = (("x", (255, 0, 0)), ("y", (0, 255, 0)), ("z", (0, 0, 255)))  # the triads' (scene.AXIS_COLORS)


def axes_legend(draw: Any, font: Any, size: int, height: int) -> None:
    """"— x  — y  — z" in the axes' colours, in the lower left corner (no words: no language)."""
    column, row = 8, height - size - 8
    for letter, colour in LEGEND_COLOURS:
        draw.line([(column, row + size * 0.6), (column + 2 * size, row + size * 0.6)], fill=colour, width=max(2, size // 5))
        column += 2 * size + 4
        draw.text((column, row), letter, fill=colour, font=font, stroke_width=2, stroke_fill=(255, 255, 255))
        column += size + 8


class Renderer:
    """Draws one robot again and again with the same camera and backend.

    ``fit`` chooses what the camera keeps in view: poses (any form :func:`configurations`
    takes), or None for poses spread over the joint limits, so a slider never moves the arm
    out of the picture. Use it as a context manager, or call :meth:`close`.

    ``sequence=True`` says many frames will follow (:class:`Frames` sets it).

    >>> with Renderer(arm(), view="front") as renderer:   # doctest: +SKIP
    ...     image = renderer.render({"epaule": 0.5})
    """

    def __init__(self, robot: Robot, *, fit: Any = None, sequence: bool = False, **opts: Any) -> None:
        self.options = render_options(**opts)
        self.tree = tf_tree(robot)
        if len(self.tree.links) > MAX_RENDER_LINKS:
            from ..core.errors import ModelError

            raise ModelError(M("the robot has {count:,} links, more than the {most:,} bras-kit draws",
                               count=len(self.tree.links), most=MAX_RENDER_LINKS),
                             hint=M("'bras-kit tree' and 'bras-kit validate' work on models of any size"))
        check_drawable(robot)
        fit_q = workspace_samples(self.tree) if fit is None else configurations(self.tree, fit)
        self.scene, points = build_scene(self.tree, fk_batch(self.tree, fit_q), tf=self.options.tf,
                                         grid=self.options.grid, package_paths=self.options.package_paths,
                                         targets=self.options.targets, geometry=self.options.geometry)
        self.camera = fit_camera(points, self.options)
        self._backend = open_backend(self.scene, self.camera, self.options, sequence)

    @property
    def backend(self) -> str:
        """The backend in use: 'egl', 'osmesa' or 'software'."""
        return self._backend.name

    def render(self, config: Any = None) -> np.ndarray:
        """The picture of one pose ({joint: value} or a vector in ``tree.dof`` order): (H, W, 3) uint8."""
        q = configurations(self.tree, config)
        if len(q) != 1:
            raise ParameterError(M("render draws one pose, got {count}", count=len(q)),
                                 hint=M("use frames() for a sequence"))
        return self._draw(fk_batch(self.tree, q[0]))

    def frames(self, positions: Any) -> Iterator[np.ndarray]:
        """Pictures of each pose of ``positions`` (any form :func:`configurations` takes), one at a time."""
        q = configurations(self.tree, positions)
        poses = (transforms for start in range(0, len(q), 256)
                 for transforms in fk_batch(self.tree, q[start:start + 256]))
        stream = getattr(self._backend, "frames", None)
        if stream is None or (self.options.tf and len(self.tree.links) <= MAX_NAMED_FRAMES):
            for transforms in poses:
                yield self._draw(transforms)
            return
        yield from stream(poses)

    def _draw(self, transforms: np.ndarray) -> np.ndarray:
        image = self._backend.render(transforms)
        if self.options.tf and len(self.tree.links) <= MAX_NAMED_FRAMES:
            image = frame_names(image, self.camera, self.tree.links, transforms[:, :3, 3])
        return image

    def close(self) -> None:
        backend, self._backend = getattr(self, "_backend", None), None
        if backend is not None:
            backend.close()

    def __enter__(self) -> Renderer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


class Frames:
    """The pictures of a motion, drawn when iterated (memory stays flat), with a progress bar.

    ``len(frames)`` is the number of poses; iterate as often as needed (each pass draws again),
    ``frames[i]`` draws one, ``sample(k)`` draws k spread over the motion. One renderer serves
    them all until the end of a pass or :meth:`close`.
    """

    def __init__(self, robot: Robot, positions: Any, *, progress: bool | None = None,
                 label: str = "rendering", **opts: Any) -> None:
        self._tree = tf_tree(robot)
        self.positions = configurations(self._tree, positions)
        # sequences leave antialiasing off unless asked: twice the frame rate on Mesa's llvmpipe
        self._opts = {**opts, "antialias": bool(opts.get("antialias"))}
        self._robot, self._progress, self._label = robot, progress, label
        render_options(**self._opts)  # refuse bad options now, not at the first frame
        self._renderer: Renderer | None = None

    def __len__(self) -> int:
        return len(self.positions)

    @property
    def renderer(self) -> Renderer:
        if self._renderer is None:
            self._renderer = Renderer(self._robot, fit=self.positions, sequence=True, **self._opts)
        return self._renderer

    def __getitem__(self, index: int) -> np.ndarray:
        return self.renderer.render(self.positions[index])

    def sample(self, count: int) -> list[np.ndarray]:
        picks = np.unique(np.linspace(0, len(self) - 1, max(1, min(count, len(self)))).round().astype(int))
        return [self[int(i)] for i in picks]

    def __iter__(self) -> Iterator[np.ndarray]:
        progress = Progress(len(self), self._label, enabled=self._progress)
        try:
            for frame in self.renderer.frames(self.positions):
                yield frame
                progress.update()
        finally:
            progress.close()
            self.close()

    def close(self) -> None:
        renderer, self._renderer = self._renderer, None
        if renderer is not None:
            renderer.close()

    def __enter__(self) -> Frames:
        return self

    def __exit__(self, *exc: object) -> None:
        self.close()


def render_pose(robot: Robot, config: Mapping[str, float] | Sequence[float] | None = None, **opts: Any) -> np.ndarray:
    """One picture of ``robot`` at ``config`` (missing joints at 0), framed on that pose: (H, W, 3) uint8."""
    with Renderer(robot, fit={} if config is None else config, **opts) as renderer:  # {}: the zero pose
        return renderer.render(config)


def render_motion(robot: Robot, states: Any, *, progress: bool | None = None, **opts: Any) -> Frames:
    """The pictures of a motion (joint states, or an (N, dof) array), framed so the arm never leaves them.

    Returns a :class:`Frames` sequence drawn lazily: pass it to :func:`save_gif` /
    :func:`save_mp4`, iterate it, or ``list()`` it to keep every picture in memory.
    """
    return Frames(robot, states, progress=progress, **opts)
