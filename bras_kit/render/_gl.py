"""PyOpenGL 3.1.0 as bras-kit needs it: the platform it committed to in this process, its
version, and the ``ctypes.byref`` argument type registered under Python 3.12's name
(:func:`register_byref_type`)."""

from __future__ import annotations

import ctypes
import sys

from ..core import backends

_PLATFORM_CLASSES = {"EGLPlatform": "egl", "OSMesaPlatform": "osmesa"}


def loaded_platform() -> str | None:
    """The platform PyOpenGL already committed to in this process ('egl', 'osmesa', other), or None."""
    module = sys.modules.get("OpenGL.platform")
    if module is None:
        return None
    platform = getattr(module, "PLATFORM", None)
    return _PLATFORM_CLASSES.get(type(platform).__name__, type(platform).__name__)


def pyopengl_version() -> tuple[int, ...]:
    OpenGL = backends.opengl()  # noqa: N806  (the package alone: the platform is chosen by OpenGL.platform)
    return tuple(int(p) for p in OpenGL.__version__.split(".")[:3] if p.isdigit())


def register_byref_type() -> None:
    """Make PyOpenGL 3.1.0 find its handler for ``ctypes.byref(...)`` arguments on every Python.

    PyOpenGL picks an array handler by the argument type's ``module.name``. 3.1.0 registers
    ``ctypes.byref``'s type as ``builtins.CArgObject`` (``OpenGL/__init__.py``, the
    ``ctypesparameter`` FormatHandler), which it is up to Python 3.11; Python 3.12 moved it to
    ``_ctypes.CArgObject``, and ``glGenTextures(1)`` (any textured primitive) failed with "No
    array-type handler for type _ctypes.type". PyOpenGL 3.1.7 added that name to the same list;
    this adds it to 3.1.0's (pyrender pins 3.1.0), on every Python alike.
    """
    from OpenGL import plugins

    byref_type = type(ctypes.byref(ctypes.c_int()))
    name = f"{byref_type.__module__}.{byref_type.__name__}"
    handler = plugins.FormatHandler.by_name("ctypesparameter")
    if handler is None or handler.check is None:
        raise RuntimeError("PyOpenGL no longer registers a 'ctypesparameter' array handler")
    if name not in handler.check:
        handler.check.append(name)
