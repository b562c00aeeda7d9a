"""The launch page's RViz: the configuration the learner is editing (one per launch, shared by every
browser, kept across a reload), what RViz shows from it, and Save Config.

Save Config writes into the package's ``rviz/`` folder through :mod:`bras_kit.trust.outputs`:
never over a file unless the learner says so (the page asks), never through a link."""

from __future__ import annotations

import os
import re
import threading
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from ..core.message import M, Message
from ..ros.rviz import config as rviz

_NAME = re.compile(r"[A-Za-z0-9_][A-Za-z0-9_.-]{0,80}\.rviz")


@dataclass(frozen=True)
class Saved:
    state: str  # "saved", "exists" (the page asks before replacing), "refused"
    message: Message | str
    path: str | None = None

    @property
    def asks(self) -> bool:
        return self.state == "exists"

    @property
    def failed(self) -> bool:
        return self.state == "refused"


class RvizState:
    """What RViz is set to show in this launch, and what it shows."""

    def __init__(self, launch: Any) -> None:
        self.lock = threading.RLock()
        self.started: Any = None  # the configuration the launch started rviz2 with
        self.config: rviz.RvizConfig = rviz.default_config()
        self.heard = False  # a node beside the launch published /joint_states (bras-kit run)
        self.heard_names: set[str] = set()  # the joints its messages named: rsp moves those only
        self.on_saved: Callable[[str, str], None] | None = None  # (package-relative path, package) -> terminal
        self.written: set[str] = set()  # files Save Config wrote: the rebuild loop ignores them
        self.take(launch)

    def take(self, launch: Any) -> None:
        """A launch (again): RViz restarted with the configuration the launch gives it. The same
        configuration as before: the learner's edits stay (the page did not restart RViz for them)."""
        with self.lock:
            self.launch = launch
            started = getattr(launch, "rviz", None)
            # a build that fails starts no rviz2: the learner's RViz waits for the next one that does
            if started is not None and started != self.started:
                self.config = started
                self.started = started

    @property
    def active(self) -> bool:
        return self.started is not None

    def shown(self) -> rviz.Shown:
        from ..ros.rviz.started import description_topics, launch_transforms

        launch = self.launch
        robot = launch.robot
        plan = launch.launched.plan
        joint_states = bool(launch.sliders or self.heard)
        # the slider window names every movable joint; a node alone, the joints it sends
        names = None if launch.sliders else sorted(self.heard_names)
        return rviz.shown(self.config, robot, launch_transforms(robot, joint_states, names=names),
                          description_topics(plan), files=self._files())

    def _files(self) -> dict[str, str]:
        """The description file a RobotModel names (Description Source File), read as RViz would."""
        from ..trust.learner_files import read_text

        out = {}
        for display in self.config.displays:
            path = display.description_file
            if display.kind == rviz.ROBOT_MODEL and display.description_source == "File" and path:
                try:
                    out[path] = read_text(path, (os.path.dirname(os.path.abspath(path)),), limit=1 << 22)
                except (OSError, UnicodeDecodeError, ValueError):
                    continue
        return out

    def why(self, seen: rviz.Shown) -> Message | None:
        from ..ros.rviz.started import description_topics

        return rviz.why_not_drawn(seen, self.launch.robot, description_topics(self.launch.launched.plan))

    def save_name(self) -> str:
        launch = self.launch
        return f"{launch.package}.rviz" if launch is not None else "config.rviz"

    def save(self, name: str, force: bool) -> Saved:
        """Save Config into the package's rviz/ folder; an existing file only with ``force``."""
        from ..core.errors import BrasKitError, OutputExistsError
        from ..trust.outputs import write_text

        name = name.strip()
        if not _NAME.fullmatch(name):
            return Saved("refused", M("'{name}' is not a file name for rviz/: letters, digits, _ . - and the "
                                      ".rviz ending (e.g. {example})", name=name, example=self.save_name()))
        root = os.path.abspath(self.launch.root)
        folder = os.path.join(root, "rviz")
        if os.path.islink(folder) or (os.path.lexists(folder) and not os.path.isdir(folder)):
            return Saved("refused", M("rviz/ in {root} is not a folder of the package: nothing is written",
                                      root=root))
        path = os.path.join(folder, name)
        relative = os.path.join("rviz", name)
        with self.lock:
            text = rviz.write_config(self.config)
            # named before it is written: the rebuild loop, looking meanwhile, never takes it for a
            # save; a write refused leaves a name an earlier save put there (not yet seen by the loop)
            pending = path in self.written
            self.written.add(path)
            try:
                write_text(path, text, force, make_parents=True)
            except OutputExistsError:
                if not pending:
                    self.written.discard(path)
                return Saved("exists", M("{file} already exists: Overwrite replaces it", file=relative), path)
            except BrasKitError as exc:
                if not pending:
                    self.written.discard(path)
                return Saved("refused", exc.message, path)
        if self.on_saved is not None:
            self.on_saved(relative, self.launch.package)
        return Saved("saved", M("{file} saved: the terminal shows the two lines that make the launch use it",
                                file=relative), path)
