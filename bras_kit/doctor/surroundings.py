"""``bras-kit doctor`` beyond the install: the workspace it is typed in, this shell, this machine.

The checks themselves read files and the environment in :mod:`bras_kit.ros.surroundings`; here
they are gathered for the folder the command is typed in (a workspace's root or any folder
below it) and the renderer EGL reports is found for the graphics check.
"""

from __future__ import annotations

from collections.abc import Mapping

from ..core.errors import BrasKitError
from ..core.message import M
from ..ros.surroundings import (
    FAIL,
    Concern,
    graphics_concerns,
    is_wsl,
    machine_concerns,
    shell_concerns,
    workspace_concerns,
)

AREAS = ("workspace", "shell", "machine")


def egl_renderer() -> str | None:
    """GL_RENDERER of an EGL context, as the OpenGL check opens one (None: no EGL here)."""
    from ..model.authoring import arm
    from ..render import Renderer
    from .install import TEST_PICTURE, TEST_POSE, _gl_renderer_name

    try:
        with Renderer(arm(), size=TEST_PICTURE, backend="egl") as renderer:
            renderer.render(TEST_POSE)
            return _gl_renderer_name() or None
    except BrasKitError:
        return None


def look(start: str = ".", environ: Mapping[str, str] | None = None, *, renderer: str | None = None,
         graphics: bool = True) -> list[Concern]:
    """Every concern for a command typed in ``start``: the workspace and the shell when ``start``
    is in a workspace (or one is sourced), the machine always (graphics when ``graphics``; ``renderer`` given, else
    asked of EGL)."""
    from ..ros.workspace import find_workspace, sourced_workspace

    concerns: list[Concern] = []
    try:  # outside any workspace, the one this shell sourced (as ros2 launch finds its packages from anywhere)
        workspace = find_workspace(start) or sourced_workspace(environ)
    except BrasKitError as exc:  # two packages of one name: colcon builds none
        concerns.append(Concern("workspace", FAIL, M("packages"), exc.message, exc.hint))
        workspace = None
    if workspace is not None:
        concerns += workspace_concerns(workspace) + shell_concerns(workspace, environ)
    concerns += machine_concerns(environ)
    if graphics:
        concerns += graphics_concerns(renderer if renderer is not None else egl_renderer(), environ)
    elif is_wsl():  # doctor --ros opens no OpenGL context, but RViz's crash under WSL2 is still worth a word
        concerns += graphics_concerns(renderer, environ)
    return concerns
