"""``bras-kit doctor`` beyond the install: the workspace it is typed in, this shell, this machine.

The checks themselves read files and the environment in :mod:`bras_kit.ros.surroundings`; here
they are gathered for the folder the command is typed in (a workspace's root or any folder
below it) and the renderer RViz would get is found for the graphics check: GLX's on the display
(``glxinfo -B``), else EGL's.
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


def glx_renderer(environ: Mapping[str, str] | None = None) -> str | None:
    """GL_RENDERER as ``glxinfo -B`` reports it on this terminal's display: the context RViz gets
    (rviz_rendering's Ogre opens its OpenGL context through GLX on X11 and XWayland, WSLg's included).
    None when there is no display or no glxinfo (mesa-utils)."""
    import os
    import re
    import shutil
    import subprocess

    env = dict(os.environ if environ is None else environ)
    glxinfo = shutil.which("glxinfo", path=env.get("PATH"))
    if not env.get("DISPLAY") or glxinfo is None:
        return None
    try:
        done = subprocess.run([glxinfo, "-B"], env=env, capture_output=True, text=True, timeout=15)
    except (OSError, subprocess.SubprocessError):
        return None
    found = re.search(r"^OpenGL renderer string: (.+)$", done.stdout, re.MULTILINE)
    return found.group(1).strip() if done.returncode == 0 and found else None


def rviz_renderer(environ: Mapping[str, str] | None = None) -> str | None:
    """The renderer RViz would draw with: GLX's on the display when glxinfo can ask it ("..., GLX"),
    else the one an EGL context gets ("..., EGL"), else None."""
    glx = glx_renderer(environ)
    if glx is not None:
        return f"{glx}, GLX"
    egl = egl_renderer()
    return f"{egl}, EGL" if egl is not None else None


def look(start: str = ".", environ: Mapping[str, str] | None = None, *, renderer: str | None = None,
         graphics: bool = True) -> list[Concern]:
    """Every concern for a command typed in ``start``: the workspace and the shell when ``start``
    is in a workspace (or one is sourced), the machine always (graphics when ``graphics``; ``renderer`` given, else
    asked of GLX, else of EGL: :func:`rviz_renderer`)."""
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
        concerns += graphics_concerns(renderer if renderer is not None else rviz_renderer(environ), environ)
    elif is_wsl():  # doctor --ros opens no OpenGL context, but RViz's crash under WSL2 is still worth a word
        concerns += graphics_concerns(renderer, environ)
    return concerns
