"""The Fixed Frame of the RViz that runs, as rviz2 sets it (github.com/ros2/rviz, jazzy, commit 591594e).

In the order rviz2 applies them (rviz_common/src/rviz_common/visualizer_app.cpp):

1. ``-f FRAME`` is set after the configuration is loaded (lines 101-103, 165-169): it wins;
2. ``-d FILE``: the file's Global Options > Fixed Frame (:func:`.config.read_config`); a file that
   cannot be read loads RViz's own default.rviz (visualization_frame.cpp:674-676);
3. no ``-d``: ``~/.rviz2/default.rviz`` of the user running rviz2 (visualization_frame.cpp:345-349,
   382), the file File > Save Config writes; when it does not exist, default.rviz (Fixed Frame map,
   default.rviz:54).

When no rviz2 runs on this machine, the rviz2 the workspace's launch file would start is read the
same way (its arguments as the launch evaluates them). With neither, the frame is RViz's default
(default.rviz's map) and :attr:`FixedFrame.source` says it was not seen. A Fixed Frame set in RViz's
window since it started is never seen from outside: the words say so.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from ...core.message import M, Message
from .config import DEFAULT_FRAME, read_config

ARGUMENT, FILE, MISSING, HOME, DEFAULT, NOT_SEEN = "argument", "file", "missing", "home", "default", "not-seen"


@dataclass(frozen=True)
class FixedFrame:
    frame: str
    source: str  # one of the six above
    path: str = ""  # the configuration file read (or asked for)
    pid: int | None = None
    launch: str = ""  # no rviz2 running: the launch file whose rviz2 this is

    @property
    def from_learner(self) -> bool:
        """Whether the frame comes from what the learner set (-f, a -d file, a saved default.rviz)."""
        return self.source in (ARGUMENT, FILE, HOME)

    def words(self) -> Message:
        """Where the frame comes from, for the report."""
        if self.launch:  # no rviz2 running: as the launch file would start it
            if self.source == ARGUMENT:
                return M("from -f {frame}, the argument of rviz2 in {launch} (no rviz2 seen running)",
                         frame=self.frame, launch=self.launch)
            if self.source == FILE:
                return M("from {path}, the -d file of rviz2 in {launch} (no rviz2 seen running)", path=self.path,
                         launch=self.launch)
            if self.source == HOME:
                return M("from {path}, which the rviz2 of {launch} loads without -d (no rviz2 seen running)",
                         path=self.path, launch=self.launch)
            return M("RViz's default: the rviz2 of {launch} has no -d file it can read (no rviz2 seen running)",
                     launch=self.launch)
        if self.source == ARGUMENT:
            return M("from rviz2 -f {frame} (process {pid})", frame=self.frame, pid=self.pid)
        if self.source == FILE:
            return M("from {path}, the -d file rviz2 was started with (process {pid})", path=self.path, pid=self.pid)
        if self.source == MISSING:
            return M("RViz's default: rviz2 (process {pid}) was started with -d {path}, which it cannot read",
                     path=self.path, pid=self.pid)
        if self.source == HOME:
            return M("from {path}, which rviz2 (process {pid}) loads without -d", path=self.path, pid=self.pid)
        if self.source == DEFAULT:
            return M("RViz's default: rviz2 (process {pid}) was started without -d and {path} does not exist; "
                     "a frame chosen in its window since is not seen from here", path=self.path or "~/.rviz2/default.rviz",
                     pid=self.pid)
        return M("RViz's default: no rviz2 was seen running on this machine with this ROS_DOMAIN_ID")


def _strip(frame: str) -> str:
    frame = frame.strip()
    return frame[1:] if frame.startswith("/") else frame  # tf_frame_property.cpp:70-73


def fixed_frame(processes: Sequence[Any]) -> FixedFrame:
    """The Fixed Frame of the first rviz2 in ``processes`` (:class:`bras_kit.ros.graph.RvizProcess`)."""
    if not processes:
        return FixedFrame(DEFAULT_FRAME, NOT_SEEN)
    process = processes[0]
    launch = process.launch
    if process.fixed_frame_argument.strip():
        return FixedFrame(_strip(process.fixed_frame_argument), ARGUMENT, process.config, process.pid, launch)
    if process.text is not None:
        return FixedFrame(read_config(process.text).fixed_frame, FILE if process.given else HOME, process.config,
                          process.pid, launch)
    return FixedFrame(DEFAULT_FRAME, MISSING if process.given else DEFAULT, process.config, process.pid, launch)
