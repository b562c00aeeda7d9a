"""Joint states -> a rosbag2 folder, as ``ros2 bag record`` would have written it.

Topics (what ``robot_state_publisher`` and the tutorial's node publish while the arm moves):

* ``/robot_description`` (std_msgs/msg/String): the URDF, once, offered *transient local*
  so a late subscriber (RViz, Foxglove) still gets it when the bag is played;
* ``/tf_static`` (tf2_msgs/msg/TFMessage): every fixed joint's child frame, once, transient local;
* ``/tf`` (tf2_msgs/msg/TFMessage): every moving joint's child frame, per sample, from
  bras-kit's forward kinematics (parent link -> child link, like robot_state_publisher);
* ``/joint_states`` (sensor_msgs/msg/JointState): every movable joint in every message.

Messages are stamped on the motion's clock: a sample at t seconds has ``header.stamp`` and the
bag's receive time both at t (so the bag starts at 0, the epoch, like a simulated clock).
Metadata is written in rosbag2 format version 8 (numeric QoS), which Humble, Iron and Jazzy read.
"""

from __future__ import annotations

import contextlib
import os
import shutil
import tempfile
from collections.abc import Iterator
from dataclasses import dataclass
from typing import Any, Literal

import numpy as np

from ...core.errors import OutputExistsError, ParameterError
from ...core.message import M
from ...kinematics.frames import fk_batch, matrix_to_quat_xyzw, tf_tree
from ...model.robot import Robot
from ...trust.outputs import OutputError
from ..core import JointStates

BAG_SUFFIXES = (".mcap", ".db3")
METADATA = "metadata.yaml"
ROSBAG2_VERSION: Literal[8] = 8  # numeric QoS enums: readable by Humble (rosbag2 0.15) up to Jazzy
TYPESTORE = "ROS2_HUMBLE"  # the message definitions of sensor_msgs, tf2_msgs, std_msgs (same in later distros)


@dataclass(frozen=True)
class BagSummary:
    """What :func:`write_bag` wrote: the bag folder, its storage file and messages per topic."""

    folder: str
    storage_file: str
    storage: str  # "mcap" or "sqlite3"
    counts: dict[str, int]
    duration: float

    @property
    def messages(self) -> int:
        return sum(self.counts.values())


def bag_folder(path: str) -> tuple[str, str]:
    """The bag folder ``-o`` names, and its storage: ``run.mcap`` -> (``run``, "mcap"),
    ``run.db3`` -> (``run``, "sqlite3"), ``run/`` -> (``run``, "mcap")."""
    text = os.fspath(path)
    suffix = os.path.splitext(text)[1].lower()
    if suffix == ".mcap":
        return text[: -len(suffix)], "mcap"
    if suffix == ".db3":
        return text[: -len(suffix)], "sqlite3"
    if text.endswith(("/", os.sep)) and text.strip("/" + os.sep):
        return text.rstrip("/" + os.sep), "mcap"
    raise ParameterError(M("'{path}' does not name a ROS 2 bag", path=text),
                         hint=M("end the name in .mcap (or .db3 for the SQLite storage), or in / for a bag folder"))


def check_bag_output(path: str, force: bool, option: str = "-o") -> str:
    """Raise unless the bag folder of ``path`` may be written; returns the folder.

    An existing folder is replaced only with ``force`` and only when it is a bag (it holds a
    metadata.yaml): bras-kit never deletes a folder of other files.
    """
    folder, _ = bag_folder(path)
    name = os.path.basename(folder)
    if name in ("", ".", ".."):
        raise ParameterError(M("'{path}' does not name a ROS 2 bag", path=path),
                             hint=M("give the bag a name, e.g. {option} run.mcap", option=option))
    if os.path.lexists(folder):
        if os.path.islink(folder) or not os.path.isdir(folder):
            raise OutputError(M("{folder} exists and is not a bag folder", folder=folder),
                              hint=M("choose another name for {option}", option=option))
        if not force:
            raise OutputExistsError(M("the bag {folder} already exists", folder=folder),
                                    hint=M("pass --force to replace it, or choose another {option}", option=option))
        if not os.path.isfile(os.path.join(folder, METADATA)):
            raise OutputError(M("{folder} is a folder but not a ROS 2 bag (no metadata.yaml): not replaced",
                                folder=folder), hint=M("choose another name for {option}", option=option))
    parent = os.path.dirname(os.path.abspath(folder))
    if not os.path.isdir(parent):
        raise OutputError(M("cannot write {path}: the folder {folder} does not exist", path=path, folder=parent),
                          hint=M("create it first, or check the spelling of {option}", option=option))
    return folder


def _typestore() -> Any:
    from rosbags.typesys import Stores, get_typestore

    return get_typestore(getattr(Stores, TYPESTORE))


def _qos(latched: bool, depth: int) -> Any:
    from rosbags.interfaces import (
        Qos,
        QosDurability,
        QosHistory,
        QosLiveliness,
        QosReliability,
        QosTime,
    )

    durability = QosDurability.TRANSIENT_LOCAL if latched else QosDurability.VOLATILE
    zero = QosTime(0, 0)
    return Qos(QosHistory.KEEP_LAST, depth, QosReliability.RELIABLE, durability, zero, zero,
               QosLiveliness.AUTOMATIC, zero, False)


def _time(store: Any, seconds: float) -> Any:
    ns = int(round(seconds * 1e9))
    return store.types["builtin_interfaces/msg/Time"](sec=ns // 1_000_000_000, nanosec=ns % 1_000_000_000)


def _transforms(store: Any, stamp: Any, frames: list[tuple[str, str]], matrices: np.ndarray) -> Any:
    """One TFMessage: parent -> child for each (parent, child) with its 4x4 transform."""
    types = store.types
    header, transform_stamped = types["std_msgs/msg/Header"], types["geometry_msgs/msg/TransformStamped"]
    transform, vector, quaternion = (types["geometry_msgs/msg/Transform"], types["geometry_msgs/msg/Vector3"],
                                     types["geometry_msgs/msg/Quaternion"])
    out = []
    for (parent, child), matrix in zip(frames, matrices):
        x, y, z = (float(v) for v in matrix[:3, 3])
        qx, qy, qz, qw = matrix_to_quat_xyzw(matrix)
        out.append(transform_stamped(header=header(stamp=stamp, frame_id=parent), child_frame_id=child,
                                     transform=transform(translation=vector(x=x, y=y, z=z),
                                                         rotation=quaternion(x=qx, y=qy, z=qz, w=qw))))
    return types["tf2_msgs/msg/TFMessage"](transforms=out)


def _frame_split(robot: Robot) -> tuple[Any, list[int], list[int]]:
    """The TF tree, and the links whose joint moves (-> /tf) and those whose joint does not (-> /tf_static)."""
    tree = tf_tree(robot)
    moving: list[int] = []
    fixed: list[int] = []
    for i in range(1, len(tree.links)):
        (moving if tree.joint_motion(i).kind != "fixed" else fixed).append(i)
    return tree, moving, fixed


def _relative(world: np.ndarray, tree: Any, links: list[int]) -> np.ndarray:
    """Parent -> child transforms of ``links`` from world transforms (..., L, 4, 4)."""
    parents = [tree.parent[i] for i in links]
    return np.linalg.inv(world[..., parents, :, :]) @ world[..., links, :, :]


def write_bag(robot: Robot, states: JointStates, path: str, *, force: bool = False,
              option: str = "-o", sent: list[dict] | None = None) -> BagSummary:
    """Write ``states`` of ``robot`` as a ROS 2 bag at ``path`` (see the module's topics).

    ``path`` ending in ``.mcap`` (or ``/``) gives an MCAP bag, ``.db3`` an SQLite 3 bag (the
    default storage of Humble); either way the bag is the folder named without the suffix,
    holding ``metadata.yaml`` and ``NAME.mcap`` / ``NAME.db3``. The folder is written under a
    temporary name and moved into place at the end. An existing bag is replaced only with ``force``.
    """
    from rosbags.rosbag2 import StoragePlugin, Writer
    from rosbags.rosbag2.errors import WriterError

    folder = check_bag_output(path, force, option)
    _, storage = bag_folder(path)
    tree, moving, fixed = _frame_split(robot)
    q = np.zeros((len(states), len(tree.dof)))
    for column, name in enumerate(tree.dof):  # the bag lists every movable joint, in the tree's order
        if name in states.names:
            q[:, column] = states.positions[:, states.column(name)]
    world = fk_batch(tree, q) if len(states) else np.zeros((0, len(tree.links), 4, 4))
    store = _typestore()
    types = store.types
    name = os.path.basename(folder)
    plugin = StoragePlugin.MCAP if storage == "mcap" else StoragePlugin.SQLITE3
    counts = {"/robot_description": 0, "/tf_static": 0, "/tf": 0, "/joint_states": 0}
    with _staging(folder, force) as staging:
        target = os.path.join(staging, name)
        writer = Writer(target, version=ROSBAG2_VERSION, storage_plugin=plugin)
        try:
            writer.open()
            description = writer.add_connection("/robot_description", "std_msgs/msg/String", typestore=store,
                                                offered_qos_profiles=[_qos(True, 1)])
            static = writer.add_connection("/tf_static", "tf2_msgs/msg/TFMessage", typestore=store,
                                           offered_qos_profiles=[_qos(True, 1)])
            tf = writer.add_connection("/tf", "tf2_msgs/msg/TFMessage", typestore=store,
                                       offered_qos_profiles=[_qos(False, 100)])
            joints = writer.add_connection("/joint_states", "sensor_msgs/msg/JointState", typestore=store,
                                           offered_qos_profiles=[_qos(False, 10)])
            start = float(states.times[0]) if len(states) else 0.0
            stamp0 = _time(store, start)
            ns0 = int(round(start * 1e9))
            if robot.source_text:
                text = types["std_msgs/msg/String"](data=robot.source_text)
                writer.write(description, ns0, store.serialize_cdr(text, "std_msgs/msg/String"))
                counts["/robot_description"] += 1
            if fixed:
                zero_world = fk_batch(tree, np.zeros(len(tree.dof)))
                frames = [(tree.links[tree.parent[i]], tree.links[i]) for i in fixed]
                message = _transforms(store, stamp0, frames, _relative(zero_world, tree, fixed))
                writer.write(static, ns0, store.serialize_cdr(message, "tf2_msgs/msg/TFMessage"))
                counts["/tf_static"] += 1
            frames = [(tree.links[tree.parent[i]], tree.links[i]) for i in moving]
            relative = _relative(world, tree, moving) if moving else None
            header, joint_state = types["std_msgs/msg/Header"], types["sensor_msgs/msg/JointState"]
            efforts = getattr(states, "efforts", None)
            names = list(tree.dof)
            velocities = np.zeros_like(q)
            for column, joint in enumerate(names):
                if joint in states.names:
                    velocities[:, column] = states.velocities[:, states.column(joint)]
            effort_rows = None
            if efforts is not None and len(efforts) == len(states) and list(states.names) == names:
                effort_rows = np.asarray(efforts, dtype=float)
            empty = np.zeros(0)
            for k, t in enumerate(states.times):
                stamp, ns = _time(store, float(t)), int(round(float(t) * 1e9))
                if relative is not None:
                    message = _transforms(store, stamp, frames, relative[k])
                    writer.write(tf, ns, store.serialize_cdr(message, "tf2_msgs/msg/TFMessage"))
                    counts["/tf"] += 1
                if sent is not None:
                    continue  # /joint_states holds what the node sent (below)
                state = joint_state(header=header(stamp=stamp, frame_id=""), name=names,
                                    position=np.ascontiguousarray(q[k]), velocity=np.ascontiguousarray(velocities[k]),
                                    effort=effort_rows[k] if effort_rows is not None else empty)
                writer.write(joints, ns, store.serialize_cdr(state, "sensor_msgs/msg/JointState"))
                counts["/joint_states"] += 1
            for message in sent or []:  # bras-kit run -o: the node's own messages, stamps as it stamped them
                stamp = types["builtin_interfaces/msg/Time"](sec=message["stamp"]["sec"],
                                                             nanosec=message["stamp"]["nanosec"])
                state = joint_state(header=header(stamp=stamp, frame_id=message["frame_id"]), name=message["name"],
                                    position=np.array(message["position"], dtype=float),
                                    velocity=np.array(message["velocity"], dtype=float),
                                    effort=np.array(message["effort"], dtype=float))
                writer.write(joints, int(round(message["time"] * 1e9)),
                             store.serialize_cdr(state, "sensor_msgs/msg/JointState"))
                counts["/joint_states"] += 1
            writer.close()
        except WriterError as exc:
            with contextlib.suppress(Exception):
                writer.abort()
            raise OutputError(M("cannot write the bag {folder}: {why}", folder=folder, why=str(exc))) from None
        except BaseException:
            with contextlib.suppress(Exception):
                writer.abort()
            raise
        storage_name = next(n for n in os.listdir(target) if n != METADATA)
    duration = float(states.times[-1] - states.times[0]) if len(states) else 0.0
    return BagSummary(folder, os.path.join(folder, storage_name), storage, counts, duration)


@contextlib.contextmanager
def _staging(folder: str, force: bool) -> Iterator[str]:
    """A temporary folder beside ``folder``; its ``NAME`` child replaces ``folder`` when the block succeeds."""
    parent = os.path.dirname(os.path.abspath(folder))
    name = os.path.basename(folder)
    try:
        staging = tempfile.mkdtemp(prefix=f".{name}.", dir=parent)
    except OSError as exc:
        raise OutputError(M("cannot write {path}: {why}", path=folder, why=exc.strerror or str(exc))) from None
    try:
        yield staging
        built = os.path.join(staging, name)
        if os.path.lexists(folder):
            if not force:
                raise OutputExistsError(M("the bag {folder} already exists", folder=folder),
                                        hint=M("pass --force to replace it, or choose another {option}", option="-o"))
            os.replace(folder, os.path.join(staging, ".replaced"))
        os.replace(built, folder)
    except OSError as exc:
        raise OutputError(M("cannot write {path}: {why}", path=folder, why=exc.strerror or str(exc))) from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)
