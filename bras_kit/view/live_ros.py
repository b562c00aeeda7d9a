"""bras-kit view --ros: the viewer fed by the learner's live ROS 2 graph, RViz's companion.

The probe (:mod:`bras_kit.live._probe`, stream mode) runs beside the viewer and prints JSON lines:
the text of /robot_description when it arrives (the page shows that robot, and shows the new one
when it is replaced), every JointState as it arrives (every page moves at once, as
robot_state_publisher turns it into TF for RViz, and only as it does: each message goes through
the model of robot_state_publisher 3.3.3, :mod:`bras_kit.ros.rviz.frames`, so a message it ignores
or a stamp that does not advance leaves the arm where RViz leaves it), and the graph every two seconds (the doctor's
findings, the same rules as ``bras-kit doctor --ros``, on the page's "Checks"). A record that
does not fit, a node leaving, a description that is not a URDF: each shows as a finding, the
page keeps the last robot it could draw, never a traceback.

::

    feed = RosFeed(python).start()
    robot = feed.wait_for_robot(10.0)    # None: why is in feed.results()
    viewer = Viewer(Source(robot=robot), ...); feed.attach(viewer)
"""

from __future__ import annotations

import collections
import contextlib
import math
import subprocess
import threading
import time
from typing import Any

from ..live.watch import look_elsewhere, open_stream, read_records
from ..model.robot import Robot
from ..ros.graph import merge_stream

WINDOW = 3.0  # seconds of joint states the live findings judge (as doctor --ros watches 3 s)
MAX_SAMPLES = 4000
MAX_TEXTS = 4  # descriptions kept (each up to a few MB)


class RosFeed:
    """The probe's stream, read on a thread; :meth:`attach` hands it to a viewer."""

    def __init__(self, python: str, every: float = 2.0) -> None:
        self.python = python
        self.every = every
        self.process: subprocess.Popen[str] | None = None
        self.hello: dict[str, Any] = {}
        self.graph: dict[str, Any] | None = None
        self.description: dict[str, Any] | None = None
        # every different text received, the last one last: two robot_state_publishers with two robots
        # are named on the page as doctor --ros names them (BK845)
        self.descriptions: list[dict[str, Any]] = []
        self.samples: collections.deque[dict[str, Any]] = collections.deque(maxlen=MAX_SAMPLES)
        self.started = time.time()
        self.robot: Robot | None = None
        self.viewer: Any = None
        self.latencies: collections.deque[float] = collections.deque(maxlen=1000)  # s, publish -> page
        # nodes seen on other domains or with the other discovery range while this one is empty:
        # the same search as doctor --ros's (live.watch.look), so both commands give one verdict
        self.elsewhere: list[dict[str, Any]] = []
        self._searching = False
        self.events: collections.deque[dict[str, Any]] = collections.deque(maxlen=500)  # the timeline's
        self.rviz: list[dict[str, Any]] = []  # the rviz2 processes of this graph (its Fixed Frame)
        from ..live.rviz_process import running_rviz

        self.find_rviz = lambda: list(running_rviz())  # read with each graph: an rviz2 started since
        self._rsp: Any = None  # robot_state_publisher as modelled, for self._rsp_robot
        self._rsp_robot: Robot | None = None
        self._robot_ready = threading.Event()
        self._lock = threading.Lock()
        self._thread: threading.Thread | None = None

    def start(self) -> RosFeed:
        self.process = open_stream(self.python, self.every)
        self._thread = threading.Thread(target=self._read, daemon=True, name="bras-kit-ros-feed")
        self._thread.start()
        return self

    @property
    def running(self) -> bool:
        return self.process is not None and self.process.poll() is None

    def wait_for_robot(self, seconds: float) -> Robot | None:
        """The robot of the first description that reads, or None after ``seconds``."""
        self._robot_ready.wait(seconds)
        return self.robot

    def attach(self, viewer: Any) -> None:
        """From now on, ``viewer`` shows what comes (a new description, joint states, findings)."""
        with self._lock:
            self.viewer = viewer
        self._show_findings()

    # -- what the probe says ---------------------------------------------------------------------
    def _read(self) -> None:
        assert self.process is not None and self.process.stdout is not None
        for record in read_records(self.process.stdout):
            try:
                self._take(record)
            except Exception:  # noqa: BLE001 - whatever the graph holds, the page keeps going
                continue

    def _take(self, record: dict[str, Any]) -> None:
        kind = record.get("kind")
        if kind == "joint_state":
            self._joint_state(record)
        elif kind == "description":
            self._description(record)
        elif kind == "graph":
            rviz = self.find_rviz()
            with self._lock:
                self.graph = record
                events = record.get("events")
                self.events.extend(e for e in (events if isinstance(events, list) else []) if isinstance(e, dict))
                self.rviz = rviz
                empty = not record.get("nodes")
                if not empty:
                    self.elsewhere = []
            if empty:
                self._search_elsewhere()
            self._show_findings()
        elif kind == "hello":
            self.hello = record

    def _joint_state(self, record: dict[str, Any]) -> None:
        names, positions = record.get("name"), record.get("position")
        if not isinstance(names, list) or not isinstance(positions, list):
            return
        with self._lock:
            self.samples.append(record)
            viewer = self.viewer
        if viewer is not None:
            pairs = [(n, float(p)) for n, p in zip(names, positions)
                     if isinstance(n, str) and isinstance(p, (int, float)) and not isinstance(p, bool)]
            moved = self._as_rsp_publishes(record, pairs)
            if moved:
                viewer.show_joint_state(list(moved), list(moved.values()))
            sent = record.get("sent")
            if isinstance(sent, int) and sent > 0:
                self.latencies.append(time.time() - sent * 1e-9)

    def _as_rsp_publishes(self, record: dict[str, Any], pairs: list[tuple[str, float]]) -> dict[str, float]:
        """The joint values robot_state_publisher would turn into transforms for this message, and
        tf2 keep (none when it ignores the message): what RViz's arm does with it."""
        from ..ros.rviz.frames import JointStateIn, RobotStatePublisher

        robot = self.robot
        if robot is None:
            return dict(pairs)
        if self._rsp is None or self._rsp_robot is not robot:  # a new description: a new node
            self._rsp, self._rsp_robot = RobotStatePublisher(robot), robot
        stamp, received = record.get("stamp"), record.get("received")
        if not (isinstance(stamp, list) and len(stamp) == 2 and all(isinstance(v, int) for v in stamp)):
            return {}
        names = tuple(n if isinstance(n, str) else "" for n in record["name"])
        positions = tuple(float(p) if isinstance(p, (int, float)) and not isinstance(p, bool) else math.nan
                          for p in record["position"])
        got = self._rsp.on_joint_state(JointStateIn(
            stamp[0] * 1_000_000_000 + stamp[1], names, positions,
            received_ns=int(received * 1e9) if isinstance(received, (int, float)) else None))
        movable = {j.name for j in robot.movable_joints()}
        return {tf.joint: tf.position for tf in got.published if not tf.nan and tf.joint in movable}

    def _description(self, record: dict[str, Any]) -> None:
        from ..live.doctor import robot_of

        with self._lock:
            self.description = record
            text = record.get("text")
            self.descriptions = [d for d in self.descriptions if d.get("text") != text][-(MAX_TEXTS - 1):] + [record]
        robot, _ = robot_of(self.snapshot())
        if robot is not None and robot.links:
            self.robot = robot
            self._robot_ready.set()
            viewer = self.viewer
            if viewer is not None:
                from .viewer import Source

                viewer.source = Source(robot=robot, package_paths=viewer.source.package_paths)
                viewer.source_label = "/robot_description"
                viewer.reload()
        self._show_findings()

    def _search_elsewhere(self) -> None:
        """Look for the nodes on the other domains in use here, once at a time, on a thread (a census
        takes seconds): the findings say where they are when it ends."""
        with self._lock:
            if self._searching:
                return
            self._searching = True

        def search() -> None:
            try:
                found = [{"domain": e.domain, "range": e.discovery_range, "nodes": list(e.nodes)}
                         for e in look_elsewhere(self.python, self.snapshot())]
                with self._lock:
                    self.elsewhere = found
            except Exception:  # noqa: BLE001 - a census that fails leaves the findings as they are
                pass
            finally:
                with self._lock:
                    self._searching = False
            self._show_findings()

        threading.Thread(target=search, daemon=True, name="bras-kit-ros-elsewhere").start()

    # -- what the doctor says of it ------------------------------------------------------------
    def snapshot(self) -> Any:
        """The graph as :func:`bras_kit.live.doctor.diagnose` reads it: the last graph, the last
        description, the joint states of the last :data:`WINDOW` seconds."""
        now = time.time()
        with self._lock:
            recent = [s for s in self.samples if isinstance(s.get("received"), (int, float))
                      and s["received"] >= now - WINDOW]
            graph = self.graph
            descriptions = list(self.descriptions)
            hello = {**self.hello, "elsewhere": list(self.elsewhere), "events": list(self.events),
                     "rviz": list(self.rviz), "origin": self.started}
        started = max(self.started, now - WINDOW)
        return merge_stream(hello, graph, descriptions, recent, started, now)

    def results(self) -> list[Any]:
        from ..live.doctor import diagnose

        return diagnose(self.snapshot())

    def _show_findings(self) -> None:
        viewer = self.viewer
        if viewer is None or self.graph is None:
            return
        checks = [(r.path, f) for r in self.results() for f in r.findings]
        viewer.checks = checks
        with contextlib.suppress(Exception):  # a browser that left mid-update
            viewer.show_checks()

    def stop(self) -> None:
        """Close the probe's stdin (it leaves the graph), then end it if it lingers."""
        process = self.process
        if process is None:
            return
        with contextlib.suppress(OSError, ValueError):
            if process.stdin is not None:
                process.stdin.close()
        try:
            process.wait(timeout=3)
        except subprocess.TimeoutExpired:
            process.kill()
            process.wait(timeout=3)
        if self._thread is not None:
            self._thread.join(timeout=3)
