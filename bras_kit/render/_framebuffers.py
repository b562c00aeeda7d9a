"""pyrender's main framebuffers made by bras-kit (:func:`make_framebuffers`), and the
colour-only read-back that replaces ``Renderer._read_main_framebuffer`` (:class:`ColorReader`):
supersampling averaged in bands, and streams that read the frame before while this one draws."""

from __future__ import annotations

import ctypes

import numpy as np


def make_framebuffers(inner, width: int, height: int, samples: int,
                       spare: bool = False) -> tuple[int, int, int] | None:
    """Create pyrender's main framebuffers ourselves, before its first frame, with ``samples``
    samples per pixel (pyrender always asks 4; Mesa's llvmpipe takes about twice as long then,
    and resolving them costs 0.1 s on the first picture). With no samples, pyrender draws
    straight into the framebuffer that is read back: no copy between the two. ``spare``: a
    second framebuffer (name, colour, depth) for :class:`ColorReader`'s streams, returned."""
    from OpenGL import GL

    def framebuffer(samples: int) -> tuple[int, int, int]:
        colour, depth = GL.glGenRenderbuffers(2)
        for buffer, kind in ((colour, GL.GL_RGBA), (depth, GL.GL_DEPTH_COMPONENT24)):
            GL.glBindRenderbuffer(GL.GL_RENDERBUFFER, buffer)
            if samples:
                GL.glRenderbufferStorageMultisample(GL.GL_RENDERBUFFER, samples, kind, width, height)
            else:
                GL.glRenderbufferStorage(GL.GL_RENDERBUFFER, kind, width, height)
        name = GL.glGenFramebuffers(1)
        GL.glBindFramebuffer(GL.GL_DRAW_FRAMEBUFFER, name)
        GL.glFramebufferRenderbuffer(GL.GL_DRAW_FRAMEBUFFER, GL.GL_COLOR_ATTACHMENT0, GL.GL_RENDERBUFFER, colour)
        GL.glFramebufferRenderbuffer(GL.GL_DRAW_FRAMEBUFFER, GL.GL_DEPTH_ATTACHMENT, GL.GL_RENDERBUFFER, depth)
        return int(name), int(colour), int(depth)

    inner._main_fb, inner._main_cb, inner._main_db = framebuffer(0)
    if samples:
        inner._main_fb_ms, inner._main_cb_ms, inner._main_db_ms = framebuffer(samples)
    else:  # pyrender deletes both; OpenGL ignores a name deleted twice
        inner._main_fb_ms, inner._main_cb_ms, inner._main_db_ms = inner._main_fb, inner._main_cb, inner._main_db
    inner._main_fb_dims = (width, height)
    return framebuffer(0) if spare and not samples else None


class ColorReader:
    """Stands in for pyrender's ``Renderer._read_main_framebuffer``: reads the colour alone,
    straight into reused buffers, rows unpadded, as a ``height`` x ``width`` picture. With
    ``scale`` 2 the picture was drawn at twice the size and each 2x2 block is averaged
    (supersampling), read in bands so the read-back never holds the large picture at once.
    (pyrender also reads and converts the depth buffer, copies through PyOpenGL's wrapper, and
    fails on widths that are not a multiple of 4.)

    Streams (with a ``spare`` framebuffer): between :meth:`start` and :meth:`stop`, each frame
    is handed to Mesa's rasteriser threads (``glFlush``) and drawing moves to the other
    framebuffer; the call returns the frame before, whose pixels were drawn while Python
    prepared this one (None for the first), and :meth:`last` reads the final one. The same
    pictures, about 10 % more frames a second on two cores."""

    def __init__(self, width: int, height: int, scale: int = 1, spare: tuple[int, int, int] | None = None) -> None:
        self.width, self.height, self.scale, self.spare = width, height, scale, spare
        self.picture = np.empty((height, width, 3), dtype=np.uint8)
        self.rows = max(1, min(height, (1 << 22) // (width * 3 * scale * scale)))  # output rows per band
        self.band = np.empty((self.rows * scale, width * scale, 3), dtype=np.uint8)
        self.total = np.empty((self.rows, width, 3), dtype=np.uint16)
        self.streaming = False
        self.pending: int | None = None

    def __call__(self, inner, scene, flags):
        from OpenGL import GL

        if not (self.streaming and self.spare is not None):
            if inner._main_fb_ms != inner._main_fb:  # resolve the samples
                width, height = self.width * self.scale, self.height * self.scale
                GL.glBindFramebuffer(GL.GL_READ_FRAMEBUFFER, inner._main_fb_ms)
                GL.glBindFramebuffer(GL.GL_DRAW_FRAMEBUFFER, inner._main_fb)
                GL.glBlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL.GL_COLOR_BUFFER_BIT, GL.GL_NEAREST)
            return self.read(inner._main_fb), None
        GL.glFlush()
        drawn = (inner._main_fb, inner._main_cb, inner._main_db)
        inner._main_fb, inner._main_cb, inner._main_db = self.spare
        inner._main_fb_ms, inner._main_cb_ms, inner._main_db_ms = self.spare
        self.spare = drawn
        previous, self.pending = self.pending, drawn[0]
        return (None if previous is None else self.read(previous)), None

    def start(self) -> bool:
        """Start a stream; False when this reader cannot (no spare framebuffer)."""
        self.streaming, self.pending = self.spare is not None, None
        return self.streaming

    def last(self) -> np.ndarray | None:
        """The stream's final picture (the context must be current)."""
        pending, self.pending = self.pending, None
        return None if pending is None else self.read(pending)

    def stop(self) -> None:
        self.streaming, self.pending = False, None

    def read(self, framebuffer: int) -> np.ndarray:
        from OpenGL import GL
        from OpenGL.raw.GL.VERSION.GL_1_0 import glReadPixels

        width, height, scale, rows, picture = self.width, self.height, self.scale, self.rows, self.picture
        GL.glBindFramebuffer(GL.GL_READ_FRAMEBUFFER, framebuffer)
        GL.glPixelStorei(GL.GL_PACK_ALIGNMENT, 1)
        for top in range(0, height, rows):  # OpenGL's row 0 is the bottom one
            count = min(rows, height - top)
            part = self.band[:count * scale]
            glReadPixels(0, top * scale, width * scale, count * scale, GL.GL_RGB, GL.GL_UNSIGNED_BYTE,
                         ctypes.c_void_p(part.ctypes.data))
            if scale == 1:
                picture[height - top - count:height - top] = part[::-1]
                continue
            blocks = part.reshape(count, scale, width, scale, 3)
            sums = self.total[:count]
            np.add(blocks[:, 0, :, 0], blocks[:, 0, :, 1], out=sums, dtype=np.uint16)
            sums += blocks[:, 1, :, 0]
            sums += blocks[:, 1, :, 1]
            sums += 2  # round to nearest
            sums >>= 2
            picture[height - top - count:height - top] = sums[::-1]
        return picture.copy()
