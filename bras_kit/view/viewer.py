"""The live viewer: a viser server on 127.0.0.1 showing the arm, one Session per browser, the
motion player and the file watcher that reloads the model when the learner saves."""

from __future__ import annotations

import contextlib
import os
import threading
import time
import warnings
from collections.abc import Callable, Iterator, Sequence
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any

from ..core import backends
from ..core.errors import BrasKitError
from ..core.message import M
from ..model.robot import Robot
from .model import ViewModel, view_model
from .origin import refuse_other_origins
from .session import Session

if TYPE_CHECKING:
    from ..ros.evaluation import LaunchEvaluation

LOCAL_HOST = "127.0.0.1"
TICK_SECONDS = 1 / 30  # playback frame period
WATCH_SECONDS = 0.25  # how often the files are looked at
# a node publishing /joint_states beside the launch is gone after this long without a message
# (the tutorial's node publishes every 0.05 s; joint_state_publisher every 0.1 s by default)
PUBLISHING_SECONDS = 1.5
NO_JOINT_STATES = "BK620"  # "nothing publishes /joint_states"


@dataclass
class Source:
    """Where the model comes from: a file (reloaded when it changes) or a ready robot."""

    path: str | None = None
    robot: Robot | None = None
    mappings: dict[str, str] = field(default_factory=dict)
    package_paths: tuple[str, ...] = ()

    def load(self) -> Robot:
        if self.path is None:
            assert self.robot is not None
            return self.robot
        from ..model.authoring import load

        return load(self.path, mappings=self.mappings, package_paths=self.package_paths)

    def watched(self) -> list[str]:
        """The file, the robot files beside it and every file it includes."""
        if self.path is None:
            return []
        from .watch import watched_files

        return watched_files(self.path, self.package_paths)


class Viewer:
    """Serve ``source`` at ``http://host:port``; :meth:`stop` ends it (also a context manager)."""

    def __init__(self, source: Source, *, host: str = LOCAL_HOST, port: int = 8080, lang: str = "en",
                 motion_specs: Sequence[str] = (), loop_seconds: float = 10.0, watch: bool = True,
                 geometry: str = "visual", motion_topic: str | None = None, recorded: Any = None,
                 autoplay: bool = False, fixed_frame: str | None = None,
                 refuse: Callable[[Robot], None] | None = None, launch: LaunchEvaluation | None = None) -> None:
        viser = backends.viser()

        from .session import GEOMETRIES

        if geometry not in GEOMETRIES:
            from ..core.errors import ParameterError

            raise ParameterError(M("geometry '{value}' is not one of {choices}", value=geometry, choices=list(GEOMETRIES)),
                                 hint=M("visual (the default), collision or both, as RViz's Visual/Collision Enabled"))
        self.source = source
        self.refuse = refuse  # raises for a model holding a value the viewer cannot use (on every reload)
        self.lang = lang
        self.geometry = geometry
        self.motion_specs = list(motion_specs)
        self.motion_topic = motion_topic  # the JointState topic of a bag given as a motion
        self.recorded = recorded  # (label, JointStates) a node published (--node), taken as the motion
        self.autoplay = autoplay  # pages start playing (the tutorial's node moves the arm by itself)
        self.fixed_frame = fixed_frame  # the Fixed Frame pages start with (rviz2 -d's Global Options)
        self.loop_seconds = loop_seconds
        self.error: BaseException | None = None  # why the saved file does not read, while it does not
        self.checks: list[tuple[str, Any]] = []  # (file, finding): the file is "" for the model's own
        self.checking = False  # a launch's checks not shown yet: the terminal says them first (show_checks)
        # bras-kit launch: the one evaluation the terminal printed, shown as RViz would show it
        # (its robot, findings, Fixed Frame and slider window); None for bras-kit view
        self.launch: LaunchEvaluation | None = None
        self.rviz_state: Any = None  # bras-kit launch: RViz's configuration as the learner edits it (view.rviz_state)
        self.reloads = 0
        self.loaded_at = time.time()
        self.heard_at = 0.0  # when a node beside the launch last published /joint_states (monotonic)
        self.publishing = False  # one did within PUBLISHING_SECONDS
        self.on_publishing: Callable[[bool], None] | None = None  # the terminal's word on it (bras-kit launch)
        self.model: ViewModel = self._build(source.load())  # a first model that cannot load is an error
        self.source_label: Any = source.path or M("built-in tutorial arm")
        if launch is None:
            self._check(self.model.robot)
        else:
            self._take(launch)
        # a tab closed during playback: the frame being sent to it is dropped, and viser says so
        # with a UserWarning on the terminal; for bras-kit a browser leaving is no event
        warnings.filterwarnings("ignore", message=r"Queued a \w+ on a closed connection", category=UserWarning)
        self.sessions: dict[int, Session] = {}
        self._lock = threading.RLock()
        self._stopping = threading.Event()
        with quiet():
            self.server = viser.ViserServer(host=host, port=port, verbose=False)
        never_share(self.server)
        refuse_other_origins(self.server)  # a page of another site may not open its websocket
        # viser's logo opens its own "About" text, in English only: shown in English pages alone
        self.server.gui.configure_theme(control_width="large", show_share_button=False, show_logo=lang == "en")
        self._frame_camera(self.model)
        self.server.on_client_connect(self._connect)
        self.server.on_client_disconnect(self._disconnect)
        self._threads = [threading.Thread(target=self._play_loop, daemon=True, name="bras-kit-play")]
        if watch and source.path is not None:
            self._threads.append(threading.Thread(target=self._watch_loop, daemon=True, name="bras-kit-watch"))
        for thread in self._threads:
            thread.start()

    # -- model ---------------------------------------------------------------------------------
    def _build(self, robot: Robot) -> ViewModel:
        model = view_model(robot, self.source.package_paths)
        self.motion = self._motion(robot)
        return model

    def _motion(self, robot: Robot) -> Any:
        from ..motion import motion_from_specs

        if not self.motion_specs and self.recorded is None:
            return None
        return motion_from_specs(robot, self.motion_specs, topic=self.motion_topic, recorded=self.recorded)

    def show_joint_state(self, names: Sequence[str], positions: Sequence[float]) -> None:
        """A JointState published by a node (``bras-kit run`` beside ``bras-kit launch``): every
        page shows it at once, as robot_state_publisher turns it into TF for RViz; playback pauses
        (the node drives the arm now)."""
        values = {n: float(p) for n, p in zip(names, positions)}
        with self._lock:
            sessions = list(self.sessions.values())
        self.heard_at = time.monotonic()
        state = self.rviz_state
        # the robot's joints among them (rsp ignores the others): a bounded set, whatever a node sends
        known = set(values) & {j.name for j in self.model.robot.joints}
        new_names = state is not None and not known <= state.heard_names
        if state is not None and (not state.heard or new_names):  # rsp moves the links of the joints heard
            state.heard = True
            state.heard_names |= known
            for session in sessions:
                with contextlib.suppress(Exception):
                    session.rviz_changed(False)
        if not self.publishing:
            self._publishing(True)
        for session in sessions:
            with contextlib.suppress(Exception):  # a browser that left mid-frame
                session.take_joint_state(values)

    @property
    def findings(self) -> list[Any]:
        return [finding for _, finding in self.shown_checks()]

    def shown_checks(self) -> list[tuple[str, Any]]:
        """The findings the page lists: the launch's, less BK620 ("nothing publishes /joint_states")
        while a node beside the launch publishes it (the tutorial's step 7: ros2 run beside ros2
        launch); the terminal says so when it starts and when it stops (``on_publishing``)."""
        if not self.publishing:
            return self.checks
        return [(file, finding) for file, finding in self.checks if finding.code != NO_JOINT_STATES]

    def _publishing(self, publishing: bool) -> None:
        """A node beside the launch started (or stopped, PUBLISHING_SECONDS without a message)
        publishing /joint_states: every page lists the findings anew, the terminal is told."""
        self.publishing = publishing
        with self._lock:
            sessions = list(self.sessions.values())
        for session in sessions:
            with contextlib.suppress(Exception):
                session.show_checks()
        if self.on_publishing is not None and any(f.code == NO_JOINT_STATES for _, f in self.checks):
            self.on_publishing(publishing)

    @property
    def sliders(self) -> bool:
        """Whether the page has joint sliders: in a launch, only when joint_state_publisher(_gui)
        is started (that is the slider window); bras-kit view is that window."""
        return self.launch is None or self.launch.sliders

    def _check(self, robot: Robot) -> None:
        from ..validate import validate

        self.checks = [("", finding) for finding in validate(robot, package_paths=self.source.package_paths)]

    def _take(self, launch: LaunchEvaluation) -> None:
        self.launch = launch
        if self.rviz_state is None:
            from .rviz_state import RvizState

            self.rviz_state = RvizState(launch)
        else:
            self.rviz_state.take(launch)
        self.fixed_frame = launch.fixed_frame
        self.checks = launch.findings()
        self.checking = not launch.checked
        self.error = None
        if launch.robot_file is not None:
            self.source_label = launch.robot_file

    # -- RViz, as the launch starts it (bras-kit launch) -----------------------------------------
    def rviz_on(self) -> bool:
        """Whether the page shows RViz's panel: a launch that starts rviz2."""
        return self.rviz_state is not None and self.rviz_state.active

    @property
    def rviz(self) -> Any:
        return self.rviz_state.config

    def rviz_shown(self) -> Any:
        return self.rviz_state.shown()

    def rviz_save_name(self) -> str:
        return str(self.rviz_state.save_name())

    def set_rviz(self, config: Any, rebuild: bool = False, by: Any = None) -> None:  # noqa: ARG002 - who acted
        """The learner changed RViz's configuration in one page: every page shows it."""
        with self._lock:
            self.rviz_state.config = config
            sessions = list(self.sessions.values())
        for session in sessions:
            with contextlib.suppress(Exception):  # a browser that left mid-change
                session.rviz_changed(rebuild)

    def save_rviz(self, name: str, force: bool) -> Any:
        return self.rviz_state.save(name, force)

    def show_checks(self) -> None:
        """The launch's findings are in (its checks run once the page is open) and said in the
        terminal: every page shows them."""
        with self._lock:
            if self.launch is not None:
                self.checks = self.launch.findings()
            self.checking = False
            for session in list(self.sessions.values()):
                session.show_checks()

    def show_launch(self, launch: LaunchEvaluation, package_paths: tuple[str, ...] | None = None) -> None:
        """A new evaluation of the launch (a file of the package saved, built and launched again):
        every page shows it, its robot if robot_state_publisher loads one (the install tree's, as
        built now), else the last one hidden, with the reason. Call it while its install tree
        exists: the robot's meshes are read from there."""
        with self._lock:
            self._take(launch)
            model = self.model
            if launch.robot is not None:
                paths = self.source.package_paths if package_paths is None else package_paths
                self.source = Source(robot=launch.robot, package_paths=paths)
                model = self._build(launch.robot)
            resized = _size_changed(self.model, model)
            if resized:
                self._frame_camera(model)
            self.loaded_at = time.time()
            for session in list(self.sessions.values()):
                session.fixed_name = launch.fixed_frame
                session.show_model(model)
                if resized:
                    session.frame_camera()
            self.model = model
            self.reloads += 1

    def reload(self) -> bool:
        """Read the source again; on success show the new model in every browser, else keep the
        last good one and show why. Returns whether the new model is shown."""
        try:
            robot = self.source.load()
            if self.refuse is not None:
                self.refuse(robot)
            model = self._build(robot)
            self._check(robot)
        except Exception as exc:  # noqa: BLE001 - whatever the file does, the viewer keeps running
            self.error = exc if isinstance(exc, BrasKitError) else BrasKitError(
                M("{kind}: {detail}", kind=type(exc).__name__, detail=str(exc)), path=self.source.path)
            with self._lock:
                for session in list(self.sessions.values()):
                    session.show_checks()
            return False
        self.error = None
        resized = _size_changed(self.model, model)
        if resized:
            self._frame_camera(model)
        self.loaded_at = time.time()
        with self._lock:  # a browser connecting meanwhile waits, then gets the new model
            for session in list(self.sessions.values()):
                session.show_model(model)
                if resized:
                    session.frame_camera()
            self.model = model  # once every browser shows it
        self.reloads += 1  # counted once every browser has the new model
        return True

    def _frame_camera(self, model: ViewModel) -> None:
        """Where a new browser's camera starts (and "Reset View" returns): on the robot's bounding
        box, left of the control panel, from the pictures' iso direction."""
        from .framing import SWEPT_MARGIN, place_camera, reach_points

        placement = place_camera(reach_points(model, motion=self.motion), margin=SWEPT_MARGIN)
        camera = self.server.initial_camera
        camera.fov = placement.fov
        camera.near = placement.near
        camera.far = placement.far
        camera.position = placement.position
        camera.look_at = placement.look_at

    # -- browsers ------------------------------------------------------------------------------
    def _connect(self, client: Any) -> None:
        with self._lock:
            self.sessions[client.client_id] = Session(client, self, self.lang)

    def _disconnect(self, client: Any) -> None:
        with self._lock:
            self.sessions.pop(client.client_id, None)

    @property
    def url(self) -> str:
        return f"http://{self.server.get_host()}:{self.server.get_port()}"

    # -- background work -----------------------------------------------------------------------
    def _play_loop(self) -> None:
        last = time.perf_counter()
        while not self._stopping.wait(TICK_SECONDS):
            now = time.perf_counter()
            with self._lock:
                sessions = list(self.sessions.values())
            for session in sessions:
                with contextlib.suppress(Exception):  # a browser that left mid-frame
                    session.advance(now - last)
            last = now
            if self.publishing and time.monotonic() - self.heard_at > PUBLISHING_SECONDS:
                self._publishing(False)  # the node beside the launch stopped: BK620 holds again

    def _watch_loop(self) -> None:
        files = self.source.watched()
        stamps = _stamps(files)
        while not self._stopping.wait(WATCH_SECONDS):
            current = _stamps(files)
            if current != stamps:
                self.reload()
                files = self.source.watched()  # the saved file may include new files
                # stamps from before the reload: a save during the reload is seen next time
                stamps = {**_stamps(files), **{k: v for k, v in current.items() if k in files}}

    def stop(self) -> None:
        self._stopping.set()
        for thread in self._threads:  # a reload under way finishes before the server goes
            if thread is not threading.current_thread():
                thread.join(timeout=10)
        with quiet():
            self.server.stop()

    def __enter__(self) -> Viewer:
        return self

    def __exit__(self, *exc: object) -> None:
        self.stop()

    def wait(self, until: Callable[[], bool] | None = None) -> None:
        """Block until Ctrl-C (or ``until()`` is true)."""
        with contextlib.suppress(KeyboardInterrupt):
            while not self._stopping.wait(0.2):
                if until is not None and until():
                    break


@contextlib.contextmanager
def quiet() -> Iterator[None]:
    """viser prints a banner and a goodbye on standard output: bras-kit prints its own line."""
    import io

    with contextlib.redirect_stdout(io.StringIO()):
        yield


def never_share(server: Any) -> None:
    """A browser may ask the server for a public share URL (a tunnel to the internet): refused."""
    server.request_share_url = lambda *args, **kwargs: None


def _size_changed(old: ViewModel, new: ViewModel) -> bool:
    """Whether the robot grew, shrank or moved enough that the camera must frame it again."""
    import numpy as np

    a, b = old.box_points(), new.box_points()
    low_a, high_a, low_b, high_b = a.min(axis=0), a.max(axis=0), b.min(axis=0), b.max(axis=0)
    size = max(float(np.max(high_a - low_a)), 1e-6)
    return bool(np.max(np.abs(low_a - low_b)) > 0.2 * size or np.max(np.abs(high_a - high_b)) > 0.2 * size)


def _stamps(paths: Sequence[str]) -> dict[str, tuple[int, int]]:
    out = {}
    for path in paths:
        with contextlib.suppress(OSError):
            info = os.stat(path)
            out[path] = (info.st_mtime_ns, info.st_size)
    return out


@contextlib.contextmanager
def serving(source: Source, **options: Any) -> Iterator[Viewer]:
    viewer = Viewer(source, **options)
    try:
        yield viewer
    finally:
        viewer.stop()
