"""Renderers freed without pyrender's finalizers, which would end the EGL display every context of
the process shares: :func:`delete_renderer`, :func:`release_renderer`, :func:`disown_renderer`."""

from __future__ import annotations

from typing import Any


def delete_renderer(renderer: Any) -> None:
    """Free an OffscreenRenderer's OpenGL objects and its context, leaving the display alone."""
    platform: Any = getattr(renderer, "_platform", None)
    inner: Any = getattr(renderer, "_renderer", None)
    try:
        if platform is not None and inner is not None:
            platform.make_current()
            spare = getattr(getattr(renderer, "_bras_kit_reader", None), "spare", None)
            if spare is not None:
                from OpenGL import GL

                GL.glDeleteFramebuffers(1, [spare[0]])
                GL.glDeleteRenderbuffers(2, [spare[1], spare[2]])
            inner.delete()
        context = getattr(platform, "_egl_context", None)
        if context is not None:
            from OpenGL.EGL import EGL_NO_CONTEXT, EGL_NO_SURFACE, eglDestroyContext, eglMakeCurrent

            eglMakeCurrent(platform._egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT)
            eglDestroyContext(platform._egl_display, context)
            platform._egl_context = None
        elif platform is not None and hasattr(platform, "delete_context"):
            platform.delete_context()  # OSMesa: a context of its own, nothing shared
    except Exception:  # noqa: BLE001 - the context may already be gone at exit
        pass
    disown_renderer(renderer)


def release_renderer(renderer: Any) -> None:
    """Make a kept EGL context current nowhere, so the next renderer may take it in any thread
    (a context current in one thread cannot be made current in another)."""
    platform: Any = getattr(renderer, "_platform", None)
    if getattr(platform, "_egl_context", None) is not None:
        try:
            from OpenGL.EGL import EGL_NO_CONTEXT, EGL_NO_SURFACE, eglMakeCurrent

            eglMakeCurrent(platform._egl_display, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT)
        except Exception:  # noqa: BLE001 - the next make_current reports a real problem
            pass


def disown_renderer(renderer: Any) -> None:
    """Leave pyrender's finalizers nothing to do. Three objects have one: the OffscreenRenderer,
    its inner renderer and its platform. Run later by the garbage collector, the inner one would
    delete OpenGL objects by number in whatever context is current then (another renderer's
    framebuffer 1, say), and the platform's would end the EGL display every context of the
    process shares. Both are switched off here, not only unlinked, since either may outlive
    the OffscreenRenderer."""
    inner, platform = getattr(renderer, "_renderer", None), getattr(renderer, "_platform", None)
    if inner is not None:
        inner.delete = _nothing  # its __del__ calls self.delete()
    if platform is not None:
        platform.delete_context = _nothing  # the platform's __del__ calls it: eglTerminate
    renderer._renderer = None
    renderer._platform = None


def _nothing() -> None:
    """Stands in for a pyrender clean-up already done, or not ours to do."""
