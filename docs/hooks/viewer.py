"""Docs site hook: the tutorial arm's motion as a 3D page a reader can orbit (bras-kit view
--export), generated at build time rather than stored (it weighs about 1 MB)."""

from __future__ import annotations

from typing import Any

PAGE = "img/bras-3d.html"


def on_files(files: Any, config: Any) -> Any:
    from mkdocs.structure.files import File

    from bras_kit import arm
    from bras_kit.motion import sample, tutorial_motion
    from bras_kit.view import export_html

    robot = arm()
    page = export_html(robot, sample(tutorial_motion(robot), 9.0, 20.0))
    files.append(File.generated(config, PAGE, content=page))
    return files
