"""The one place each heavy backend is imported: pyrender/OpenGL, MuJoCo, viser, matplotlib, Dask.

Every function here imports its library on first call (never at start-up: ``bras-kit --help``
loads none of them) and returns the module. A library that is missing or cannot load becomes
one :class:`~bras_kit.core.errors.BackendError` naming what to install (the pip package or extra,
and the system package when a shared library is what failed), instead of a traceback::

    from .. import backends

    mujoco = backends.mujoco()          # BackendError: MuJoCo cannot be loaded ... pip install mujoco

The table :data:`BACKENDS` is what ``bras-kit doctor`` reports on, so the two never disagree.
"""

from __future__ import annotations

import importlib
from dataclasses import dataclass
from types import ModuleType
from typing import Any

from .errors import BackendError
from .message import M

OPENGL_SYSTEM_PACKAGES = "libegl1 libegl-mesa0 libgl1 libgl1-mesa-dri libgbm1"


@dataclass(frozen=True)
class Backend:
    """A heavy optional library: its name for people, its import name, and how to install it."""

    name: str
    module: str
    pip: str  # the pip command that brings it
    system: str | None = None  # the Debian/Ubuntu packages its shared libraries need, if any
    extra_modules: tuple[str, ...] = ()  # submodules loaded with it (what callers use)


BACKENDS: dict[str, Backend] = {
    "pyrender": Backend("pyrender (OpenGL)", "pyrender", "pip install pyrender", OPENGL_SYSTEM_PACKAGES),
    "opengl": Backend("PyOpenGL", "OpenGL", "pip install pyrender", OPENGL_SYSTEM_PACKAGES),
    "mujoco": Backend("MuJoCo", "mujoco", "pip install mujoco"),
    "viser": Backend("viser", "viser", "pip install viser"),
    "matplotlib": Backend("matplotlib", "matplotlib", "pip install matplotlib",
                          extra_modules=("matplotlib.figure",)),
    "dask_distributed": Backend("Dask distributed", "distributed", "pip install 'bras-kit[cluster]'"),
}


def load(key: str) -> Any:
    """The module of backend ``key`` (see :data:`BACKENDS`), or a :class:`BackendError` saying
    what to install. A module missing altogether is a pip install; one that is there but fails
    to load (a shared library such as libEGL absent) is a system package when one is known."""
    backend = BACKENDS[key]
    try:
        module = importlib.import_module(backend.module)
        for name in backend.extra_modules:
            importlib.import_module(name)
    except ImportError as exc:
        raise _error(backend, exc) from None
    return module


def _error(backend: Backend, exc: ImportError) -> BackendError:
    missing = isinstance(exc, ModuleNotFoundError)
    reason = f"{type(exc).__name__}: {exc}".splitlines()[0]
    if missing or backend.system is None:
        hint = M("install it: {command}", command=backend.pip)
    else:
        hint = M("on Debian/Ubuntu install the system libraries: sudo apt-get install {packages}",
                 packages=backend.system)
    return BackendError(M("{backend} cannot be loaded ({reason})", backend=backend.name, reason=reason),
                        hint=hint)


def pyrender() -> ModuleType:
    """pyrender, plain (``bras_kit.render._pyrender.import_pyrender`` calls this while its
    light-loading stand-ins are in place)."""
    return load("pyrender")


def opengl() -> ModuleType:
    """The PyOpenGL package alone (its platform is chosen by ``PYOPENGL_PLATFORM`` before ``OpenGL.GL``)."""
    return load("opengl")


def mujoco() -> Any:
    return load("mujoco")


def viser() -> Any:
    return load("viser")


def matplotlib() -> Any:
    """matplotlib with ``matplotlib.figure`` loaded (bras-kit draws on Figure objects, never
    through pyplot, so no GUI toolkit is looked for)."""
    return load("matplotlib")


def dask_distributed() -> Any:
    return load("dask_distributed")

