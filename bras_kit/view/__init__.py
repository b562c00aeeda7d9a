"""The live browser viewer: RViz and the slider window in a web page, on viser.

``bras-kit view`` serves it on 127.0.0.1; :func:`view` starts it from Python (in Jupyter it
shows inline); :func:`export_html` writes a page that replays a motion with no server.
"""

from __future__ import annotations

import sys
import types
from typing import Any

from .export import export_html
from .model import ViewModel, view_model
from .viewer import Source, Viewer


def view(robot: Any = None, *, motion: Any = (), port: int = 8080, lang: str | None = None,
         height: int = 500, package_paths: tuple[str, ...] = (), geometry: str = "visual") -> Viewer:
    """Show ``robot`` (a :class:`~bras_kit.model.robot.Robot`, a file path, or the tutorial arm) live.

    In a Jupyter notebook with a local kernel the page appears inline; elsewhere the URL is
    printed. ``geometry``: "visual", "collision" or "both", what is shown first. Returns the
    :class:`Viewer` (``viewer.stop()`` ends it).
    """
    from ..core.i18n import resolve_language

    if robot is None:
        from ..model.authoring import arm

        robot = arm()
    source = Source(path=str(robot), package_paths=package_paths) if isinstance(robot, str) \
        else Source(robot=robot, package_paths=package_paths)
    specs = [motion] if isinstance(motion, str) else list(motion)
    viewer = Viewer(source, port=port, lang=resolve_language(lang), motion_specs=specs, geometry=geometry)
    try:
        from IPython import get_ipython
        from IPython.display import IFrame, display

        if get_ipython() is not None:
            display(IFrame(viewer.url, width="100%", height=height))
            return viewer
    except ImportError:
        pass
    print(viewer.url)
    return viewer


__all__ = ["Source", "ViewModel", "Viewer", "export_html", "view", "view_model"]


class _CallableModule(types.ModuleType):
    """``bras_kit.view(robot)`` works even once ``bras_kit.view`` the package is imported
    (importing a subpackage binds its name on the parent, hiding the function)."""

    def __call__(self, *args: Any, **kwargs: Any) -> Viewer:
        return view(*args, **kwargs)


sys.modules[__name__].__class__ = _CallableModule
