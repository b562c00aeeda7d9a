"""Writing frame sequences: GIF, MP4 and numbered PNGs, one frame at a time, with a progress bar.

Frames are streamed: each writer keeps at most the previous frame, so memory stays flat
however long the motion is. The GIF writer maps every frame onto one adaptive palette
(computed once from a few frames) and stores only the rectangle that changed since the
previous frame, which keeps animations of an arm on a still background small and fast.
"""

from __future__ import annotations

import io
import os
import queue
import struct
import sys
import threading
import time
from collections.abc import Iterable, Iterator, Sequence
from typing import IO, Any, Protocol

import numpy as np

from ..core.errors import BackendError, ParameterError
from ..core.i18n import say
from ..core.message import M, Message
from ..trust.inert import LINE_START, emit

PALETTE_SAMPLES = 4  # frames the GIF palette is computed from
TRANSPARENT = 255  # GIF palette index left for "unchanged since the previous frame"
QUEUED_FRAMES = 8  # frames waiting for the GIF worker at most (memory stays flat)
_LUT_BITS = 5  # colour -> palette index table: 5 bits per channel (32768 entries)


class FrameWriter(Protocol):
    def write(self, frame: np.ndarray) -> None: ...
    def close(self) -> None: ...


class Progress:
    """A one-line progress bar on stderr, drawn only when stderr is a terminal."""

    def __init__(self, total: int, label: str = "rendering", *, stream: IO[str] | None = None,
                 enabled: bool | None = None) -> None:
        self.stream = stream if stream is not None else sys.stderr
        if enabled is None:
            isatty = getattr(self.stream, "isatty", None)
            enabled = bool(isatty and isatty())
        self.enabled = enabled
        self.total, self.done = max(total, 1), 0
        self.label: Message | str = M("rendering") if label == "rendering" else label
        self._start = self._last = time.monotonic()

    def update(self, count: int = 1) -> None:
        self.done += count
        now = time.monotonic()
        if self.enabled and (now - self._last >= 0.1 or self.done >= self.total):
            self._last = now
            self._draw(now)

    def _draw(self, now: float) -> None:
        share = min(self.done / self.total, 1.0)
        filled = int(share * 30)
        elapsed = now - self._start
        left = elapsed / share - elapsed if share > 0 else 0.0
        emit(self.stream, LINE_START, f"{say(self.label)} [{'#' * filled}{'.' * (30 - filled)}] "
             + say(M("{done}/{total} frames, {left:4.1f} s left ", done=self.done, total=self.total, left=left)),
             end="")
        self.stream.flush()

    def close(self) -> None:
        if self.enabled:
            elapsed = time.monotonic() - self._start
            emit(self.stream, LINE_START, f"{say(self.label)} [{'#' * 30}] "
                 + say(M("{done}/{total} frames in {elapsed:.1f} s", done=self.done, total=self.total,
                         elapsed=elapsed)) + " " * 8)
            self.stream.flush()


def _rgb(frame: np.ndarray) -> np.ndarray:
    frame = np.asarray(frame)
    if frame.ndim != 3 or frame.shape[2] not in (3, 4) or frame.dtype != np.uint8:
        raise ParameterError(M("a frame must be an (H, W, 3) uint8 image, got {dtype} {shape}", dtype=str(frame.dtype),
                               shape=str(frame.shape)))
    return frame[..., :3]


# ---------------------------------------------------------------- GIF


def gif_delay(fps: float) -> int:
    """Frame delay in hundredths of a second (GIF's unit) for ``fps``; at least 2, as browsers require."""
    return max(2, round(100.0 / fps))


class _PaletteMap:
    """An adaptive 255-colour palette (the 256th entry is transparent) and a table taking any
    colour to its nearest entry."""

    def __init__(self, samples: Sequence[np.ndarray]) -> None:
        from PIL import Image

        tiles = [_rgb(s)[::2, ::2] for s in samples]
        width = max(t.shape[1] for t in tiles)
        stacked = np.concatenate([np.pad(t, ((0, 0), (0, width - t.shape[1]), (0, 0)), mode="edge") for t in tiles])
        quantised = Image.fromarray(np.ascontiguousarray(stacked)).quantize(
            colors=TRANSPARENT, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
        used = np.array(sorted(int(index) for _, index in quantised.getcolors(256) or [(0, 0)]))  # type: ignore[arg-type]
        palette = np.asarray(quantised.getpalette() or [0, 0, 0], dtype=np.uint8).reshape(-1, 3)[used]
        self.palette = np.zeros((256, 3), dtype=np.uint8)
        self.palette[: len(palette)] = palette
        levels = (np.arange(1 << _LUT_BITS) << (8 - _LUT_BITS)) + (1 << (7 - _LUT_BITS))
        r, g, b = np.meshgrid(levels, levels, levels, indexing="ij")
        cube = np.stack([r.ravel(), g.ravel(), b.ravel()], axis=1)
        self._table = _nearest(cube, palette).astype(np.uint8)

    def indices(self, frame: np.ndarray) -> np.ndarray:
        shift = 8 - _LUT_BITS
        rgb = _rgb(frame)
        key = ((rgb[..., 0].astype(np.uint16) >> shift) << (2 * _LUT_BITS)) \
            | ((rgb[..., 1].astype(np.uint16) >> shift) << _LUT_BITS) | (rgb[..., 2].astype(np.uint16) >> shift)
        return self._table[key]


def _nearest(points: np.ndarray, palette: np.ndarray, chunk: int = 4096) -> np.ndarray:
    """Index of the nearest ``palette`` row (Euclidean) for each of ``points``: exact, by blocks,
    as |c|^2 - 2 p.c (the same for every c); integers below 2^24 throughout, so float32 is exact.

    The dot products are three element-wise products, not a matrix product: this runs in the
    GIF writer's thread, and there a matrix product (OpenBLAS and its thread pool) was seen to
    hang for good, one run in four, while the drawing thread started ffmpeg for ``--mp4``.
    Element-wise, 32,768 colours against 255 take about 30 ms, once per GIF."""
    points, palette = np.asarray(points, dtype=np.float32), np.asarray(palette, dtype=np.float32)
    squares = (palette ** 2).sum(axis=1)
    out = np.empty(len(points), dtype=np.int64)
    for start in range(0, len(points), chunk):
        block = points[start:start + chunk]
        scores = block[:, 0:1] * palette[:, 0]
        scores += block[:, 1:2] * palette[:, 1]
        scores += block[:, 2:3] * palette[:, 2]
        scores *= -2.0
        scores += squares
        out[start:start + chunk] = np.argmin(scores, axis=1)
    return out


class GifWriter:
    """Streams frames into a looping GIF (a path or a binary file object).

    Encoding runs in a worker thread, so the next frames draw while earlier ones are mapped to
    the palette, compressed and written; the palette itself (from ``palette_samples``) is also
    computed there. :meth:`write` copies the frame, checks it at once (type, size) and returns;
    an error while encoding or writing is raised by the next :meth:`write` or by :meth:`close`,
    which waits for the last frame and ends the file.
    """

    def __init__(self, target: str | os.PathLike[str] | IO[bytes], fps: float,
                 palette_samples: Sequence[np.ndarray]) -> None:
        if not palette_samples:
            raise ParameterError(M("a GIF palette needs at least one sample frame"))
        samples = [np.array(_rgb(s)) for s in palette_samples]
        from PIL import GifImagePlugin, Image  # noqa: F401 - loaded here, not in the worker
        self._delay = gif_delay(fps)
        self._own = not hasattr(target, "write")
        self._file: IO[bytes] | None = open(target, "wb") if self._own else target  # type: ignore[arg-type,assignment]
        self._shape: tuple[int, ...] | None = None
        self._error: BaseException | None = None
        self._queue: queue.Queue[np.ndarray | None] = queue.Queue(maxsize=QUEUED_FRAMES)
        self._thread = threading.Thread(target=self._work, args=(samples,), name="gif-writer", daemon=True)
        self._thread.start()
        self.frames = 0

    def write(self, frame: np.ndarray) -> None:
        rgb = _rgb(frame)
        if self._shape is None:
            self._shape = rgb.shape
        elif rgb.shape != self._shape:
            raise ParameterError(M("all frames of a GIF must have the same size"))
        self._raise_failure()
        self._queue.put(np.array(rgb))
        self.frames += 1

    def close(self) -> None:
        if self._file is None:
            return
        self._queue.put(None)
        self._thread.join()
        try:
            self._raise_failure()
            self._file.write(b";")
        finally:
            if self._own:
                self._file.close()
            self._file = None

    def _raise_failure(self) -> None:
        if self._error is not None:
            error, self._error = self._error, None
            raise error

    # ---- in the worker thread

    def _work(self, samples: list[np.ndarray]) -> None:
        try:
            encoder = _GifFrames(_PaletteMap(samples), self._delay, self._file)  # type: ignore[arg-type]
            while (frame := self._queue.get()) is not None:
                encoder.add(frame)
        except BaseException as exc:  # handed to the drawing thread
            self._error = exc
            while self._queue.get() is not None:  # let write() and close() go on
                pass


class _GifFrames:
    """The GIF's header and frames: each frame stores only the rectangle that changed."""

    def __init__(self, palette: _PaletteMap, delay: int, file: IO[bytes]) -> None:
        self._palette, self._delay, self._file = palette, delay, file
        self._previous: np.ndarray | None = None

    def _header(self, width: int, height: int) -> bytes:
        loop = b"!\xff\x0bNETSCAPE2.0\x03\x01" + struct.pack("<H", 0) + b"\x00"
        return (b"GIF89a" + struct.pack("<HHBBB", width, height, 0xF7, 0, 0)
                + self._palette.palette.tobytes() + loop)

    def add(self, frame: np.ndarray) -> None:
        from PIL import GifImagePlugin, Image

        index = self._palette.indices(frame)
        if self._previous is None:
            self._file.write(self._header(index.shape[1], index.shape[0]))
            top, left, patch = 0, 0, index
        else:
            changed = index != self._previous
            rows, cols = np.flatnonzero(changed.any(axis=1)), np.flatnonzero(changed.any(axis=0))
            if len(rows) == 0:
                top, left, patch = 0, 0, np.full((1, 1), TRANSPARENT, dtype=np.uint8)
            else:
                top, bottom, left, right = int(rows[0]), int(rows[-1]) + 1, int(cols[0]), int(cols[-1]) + 1
                # inside the changed rectangle, unchanged pixels are transparent: long runs, small file
                patch = np.where(changed[top:bottom, left:right], index[top:bottom, left:right], TRANSPARENT)
        image = Image.fromarray(np.ascontiguousarray(patch, dtype=np.uint8), mode="L")
        # disposal 1: keep this frame under the next one, which only paints what changed
        for chunk in GifImagePlugin.getdata(image, (left, top), duration=self._delay * 10, disposal=1,
                                            transparency=TRANSPARENT):
            self._file.write(chunk)
        self._previous = index


# ---------------------------------------------------------------- MP4


class Mp4Writer:
    """H.264 in yuv420p (plays everywhere) through imageio-ffmpeg; odd sizes are padded to even."""

    def __init__(self, path: str | os.PathLike[str], fps: float) -> None:
        self._path, self._fps = os.fspath(path), fps
        self._pipe: Any = None
        self.frames = 0

    def write(self, frame: np.ndarray) -> None:
        rgb = _rgb(frame)
        height, width = rgb.shape[:2]
        pad_h, pad_w = height % 2, width % 2
        if pad_h or pad_w:
            rgb = np.pad(rgb, ((0, pad_h), (0, pad_w), (0, 0)), mode="edge")
        if self._pipe is None:
            try:
                import imageio_ffmpeg
            except ImportError:
                raise BackendError(M("MP4 needs imageio-ffmpeg"), hint=M("pip install imageio-ffmpeg")) from None
            self._pipe = imageio_ffmpeg.write_frames(
                self._path, (rgb.shape[1], rgb.shape[0]), fps=self._fps, codec="libx264",
                pix_fmt_in="rgb24", pix_fmt_out="yuv420p", quality=None, macro_block_size=1,
                ffmpeg_log_level="error", output_params=["-preset", "veryfast", "-crf", "20"])
            self._pipe.send(None)
        self._pipe.send(np.ascontiguousarray(rgb))
        self.frames += 1

    def close(self) -> None:
        if self._pipe is not None:
            self._pipe.close()
            self._pipe = None


# ---------------------------------------------------------------- PNG


def frame_name(index: int, total: int) -> str:
    return f"frame_{index:0{max(4, len(str(max(total - 1, 0))))}d}.png"


def save_png(image: np.ndarray, path: str | os.PathLike[str] | IO[bytes]) -> None:
    """Write one picture; the format follows the file's extension (PNG when writing to a file object)."""
    from PIL import Image

    picture = Image.fromarray(np.ascontiguousarray(_rgb(image)))
    if hasattr(path, "write"):
        picture.save(path, format="PNG")
        return
    try:
        picture.save(os.fspath(path), compress_level=3) if str(path).lower().endswith(".png") \
            else picture.save(os.fspath(path))
    except (KeyError, ValueError):
        raise ParameterError(M("cannot tell the picture format of '{path}'", path=str(path)),
                             hint=M("end the name with .png (or .jpg, .bmp)")) from None


class FramesDirWriter:
    """Numbered PNGs (frame_0000.png ...) in a folder, for video editors and slides."""

    def __init__(self, folder: str | os.PathLike[str], total: int) -> None:
        self.folder, self.total, self.frames = os.fspath(folder), total, 0
        os.makedirs(self.folder, exist_ok=True)

    def write(self, frame: np.ndarray) -> None:
        path = os.path.join(self.folder, frame_name(self.frames, self.total))
        if os.path.islink(path):  # replace the link itself, never write through it
            os.unlink(path)
        save_png(frame, path)
        self.frames += 1

    def close(self) -> None:
        pass


# ---------------------------------------------------------------- whole sequences


def palette_samples(frames: Iterable[np.ndarray], count: int = PALETTE_SAMPLES) -> tuple[list[np.ndarray], Iterator[np.ndarray]]:
    """Frames to compute a GIF palette from, and an iterator over all frames.

    A sequence that can draw any frame (``sample`` method, like the frames of
    :func:`~bras_kit.render.render_motion`) gives frames spread over the whole motion; any
    other iterable lends its first ``count`` frames, which are put back in front.
    """
    sample = getattr(frames, "sample", None)
    if callable(sample):
        return list(sample(count)), iter(frames)
    iterator = iter(frames)
    head = []
    for frame in iterator:
        head.append(frame)
        if len(head) == count:
            break

    def chained() -> Iterator[np.ndarray]:
        yield from head
        yield from iterator

    return head, chained()


def write_frames(frames: Iterable[np.ndarray], writers: Sequence[FrameWriter]) -> int:
    """Feed each frame to every writer, then close them; returns the number of frames."""
    count = 0
    try:
        for frame in frames:
            for writer in writers:
                writer.write(frame)
            count += 1
    finally:
        for writer in writers:
            writer.close()
    return count


def save_gif(frames: Iterable[np.ndarray], path: str | os.PathLike[str] | IO[bytes], fps: float = 20.0) -> int:
    """Write ``frames`` as a looping GIF at ``fps`` frames per second; returns the frame count."""
    _check_fps(fps)
    samples, stream = palette_samples(frames)
    if not samples:
        raise ParameterError(M("no frames to write"), hint=M("give at least one frame"))
    return write_frames(stream, [GifWriter(path, fps, samples)])


def save_mp4(frames: Iterable[np.ndarray], path: str | os.PathLike[str], fps: float = 20.0) -> int:
    """Write ``frames`` as an H.264 MP4 at ``fps`` frames per second; returns the frame count."""
    _check_fps(fps)
    return write_frames(frames, [Mp4Writer(path, fps)])


def save_frames(frames: Iterable[np.ndarray], folder: str | os.PathLike[str]) -> int:
    """Write ``frames`` as frame_0000.png, frame_0001.png ... in ``folder``; returns the count."""
    total = len(frames) if hasattr(frames, "__len__") else 10_000  # type: ignore[arg-type]
    return write_frames(frames, [FramesDirWriter(folder, total)])


def gif_bytes(frames: Iterable[np.ndarray], fps: float = 20.0) -> bytes:
    """A GIF in memory (for notebooks)."""
    buffer = io.BytesIO()
    save_gif(frames, buffer, fps)
    return buffer.getvalue()


def _check_fps(fps: float) -> None:
    if not (isinstance(fps, (int, float)) and 0 < fps <= 120):
        raise ParameterError(M("fps {fps} is out of range", fps=repr(fps)),
                             hint=M("give frames per second between 1 and 120, e.g. 20"))
