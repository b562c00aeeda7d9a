"""``ros2 launch PKG FILE`` without ROS: the package built as colcon builds it, its launch file
evaluated once, the nodes it starts said, the package's own nodes run for their findings, and
(with a page) the package relaunched at each save.

The command ``bras-kit launch`` is this package with a terminal and a browser page on top; a
notebook calls it directly::

    from bras_kit.launcher import launch
    launched = launch("bras_description", "affichage.launch.py", duration=2)
    launched.evaluation.robot                 # the robot robot_state_publisher loads
    for result in launched.results:           # the findings, as bras-kit launch prints them
        for finding in result.findings:
            print(finding.code, finding.text())
"""

from __future__ import annotations

from ..core.lazy import lazy_exports

# name -> module, imported on first use
_LAZY = {
    "COUNTERPARTS": ".session",
    "LaunchRequest": ".session",
    "Launched": ".session",
    "Superseded": ".session",
    "launch": ".session",
    "prepare": ".session",
    "LaunchPage": ".relaunch",
    "live": ".relaunch",
    "Reporter": ".reporter",
}


__getattr__ = lazy_exports(__name__, _LAZY)


__all__ = sorted(_LAZY)
