"""``bras-kit run``: the learner's own node runs, with no ROS install, and moves the arm.

The counterpart of ``ros2 run PKG EXE``: the executable is found in ``setup.py``
(:mod:`.locate`), its ``main()`` runs in a child process under the sandbox's limits against a
stand-in for the part of rclpy beginner nodes use (``_standin/``, injected in that child
only), on a simulated clock, and every message it publishes is recorded (:mod:`.recording`).
:mod:`.findings` turns the recording into validator findings (BK640-BK659).

::

    from bras_kit.run import joint_states, robot_of, run_findings, run_node
    recording = run_node("bras_description", "animation", duration=5)
    states = joint_states(recording)          # what /joint_states carried, as JointStates
    for finding in run_findings(recording, robot_of("bras_description")):
        print(finding.code, finding.text())
"""

from __future__ import annotations

import mmap
import struct
import tempfile
from typing import Any

from ..errors import BrasKitError
from ..message import M
from .findings import robot_of, run_findings
from .locate import Target, locate
from .recording import JOINT_STATES, NodeFailure, Published, Recording, joint_states, stamp_seconds

__all__ = ["JOINT_STATES", "NodeFailure", "NodeRunError", "Published", "Recording", "Target",
           "joint_states", "locate", "robot_of", "run_findings", "run_node", "stamp_seconds"]

DEFAULT_DURATION = 10.0
MAX_DURATION = 3600.0
CPU_SECONDS = 20
WALL_SECONDS = 60.0
MEMORY_BYTES = 1 << 30


class NodeRunError(BrasKitError):
    """The node could not be run to the end: it was stopped by a limit of the sandbox.
    ``kind`` is the limit ("cpu", "wall", "memory"...), ``time`` the simulated seconds reached."""

    def __init__(self, message, *, kind: str = "", time: float = 0.0, **where) -> None:  # type: ignore[no-untyped-def]
        super().__init__(message, **where)
        self.kind = kind
        self.time = time


def _child(target: Target, duration: float, echo: bool, workdir: str, shared: mmap.mmap,  # type: ignore[no-untyped-def]
           parameters: dict[str, Any]):
    from .child import run_node_here

    def watch(t_ns: int) -> None:
        shared[:8] = struct.pack("<q", t_ns)

    return run_node_here(target, duration, echo, workdir, watch, parameters)


def parse_parameters(items: list[str]) -> dict[str, Any]:
    """``NAME:=VALUE`` items, as ``ros2 run ... --ros-args -p NAME:=VALUE`` reads them: the value
    is YAML (``0.5`` a float, ``3`` an integer, ``true`` a boolean, ``[1.0, 2.0]`` a list, else text)."""
    import yaml

    out: dict[str, Any] = {}
    for item in items:
        name, sep, text = item.partition(":=")
        if not sep or not name.strip():
            raise BrasKitError(M("'{item}' is not NAME:=VALUE", item=item),
                               hint=M("write a parameter as -p amplitude:=0.5, as after ros2 run ... --ros-args"))
        try:
            value = yaml.safe_load(text) if text.strip() else ""
        except yaml.YAMLError:
            value = text
        if not isinstance(value, (bool, int, float, str, list)):
            value = text
        out[name.strip()] = value
    return out


def run_node(where: str, executable: str | None = None, *, duration: float = DEFAULT_DURATION,
             echo: bool = False, parameters: dict[str, Any] | None = None, cpu_seconds: int = CPU_SECONDS,
             memory_bytes: int = MEMORY_BYTES, wall_seconds: float = WALL_SECONDS) -> Recording:
    """Run the node ``where`` names (a package folder and an executable of its console_scripts,
    or a ``.py`` file) for ``duration`` simulated seconds and return its recording.

    ``echo`` shows the node's logs and prints live (as ``ros2 run`` does); otherwise they are
    kept in the recording. ``parameters`` are the values ``--ros-args -p NAME:=VALUE`` would
    give the node's declared parameters. The node runs in a child process with a CPU, memory and wall-clock
    limit, in a temporary working folder.
    """
    from ..sandbox import ResourceLimitError, run_limited

    if not 0 < duration <= MAX_DURATION:
        raise BrasKitError(M("the duration must be between 0 and {max} s of simulated time", max=MAX_DURATION),
                           hint=M("for example --duration 10"))
    target = locate(where, executable)
    shared = mmap.mmap(-1, 8)
    try:
        with tempfile.TemporaryDirectory(prefix="bras-kit-run-") as workdir:
            try:
                return run_limited(_child, target, duration, echo, workdir, shared, dict(parameters or {}),
                                   cpu_seconds=cpu_seconds,
                                   memory_bytes=memory_bytes, wall_seconds=wall_seconds,
                                   what=f"the node {target.shown}")
            except ResourceLimitError as exc:
                reached = struct.unpack("<q", shared[:8])[0] / 1e9
                raise _limit_error(exc.kind, target, reached, cpu_seconds, wall_seconds, memory_bytes) from None
    finally:
        shared.close()


def _limit_error(kind: str, target: Target, reached: float, cpu: int, wall: float, memory: int) -> NodeRunError:
    place = {"path": target.path}
    if kind == "cpu":
        return NodeRunError(
            M("the node used {cpu} s of CPU while its simulated clock stood still at t={time} s, and was stopped",
              cpu=cpu, time=reached),
            hint=M("a loop that never calls time.sleep(), rate.sleep() or rclpy.spin_once() runs flat out and "
                   "lets no time pass; publish from a timer (create_timer) and spin"),
            kind=kind, time=reached, **place)
    if kind == "wall":
        return NodeRunError(
            M("the node took more than {wall} s of real time (simulated clock at t={time} s) and was stopped",
              wall=wall, time=reached),
            hint=M("a loop that never sleeps nor spins (the clock cannot move), or a wait for something that "
                   "never comes (input(), a thread, a socket)"),
            kind=kind, time=reached, **place)
    if kind == "memory":
        return NodeRunError(
            M("the node needed more than {mib} MiB of memory (simulated clock at t={time} s) and was stopped",
              mib=memory >> 20, time=reached),
            hint=M("a list that grows at every tick without end, or a very deep recursion?"),
            kind=kind, time=reached, **place)
    return NodeRunError(M("the node's process died (simulated clock at t={time} s)", time=reached),
                        hint=M("it may use a library that crashes; try it with ros2 run on a ROS 2 machine"),
                        kind=kind, time=reached, **place)
