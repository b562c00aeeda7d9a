"""ROS 2 bag speed: recording and replaying 60 s of the tutorial motion at 20 Hz (1201 samples).

Run: python benchmarks/bags_speed.py [--seconds 60] [--rate 20] [--repeat 5]

Record: bras-kit's ``write_bag`` (FK for /tf, CDR, MCAP, metadata.yaml; 2 x 1201 + 1 messages)
against the same messages (same QoS profiles) written straight with rosbags (the library bras-kit uses) and with
Foxglove's mcap_ros2 writer (the peer; dict messages, zstd chunks by default).
Replay: bras-kit's ``read_recording`` of /joint_states (decode, checks, per-joint series)
against reading and decoding the same topic with rosbags and with mcap_ros2.
Figures are messages per second (best of --repeat); sizes compare the bag with bras-kit's CSV.
"""

from __future__ import annotations

import argparse
import os
import tempfile
import time
from collections.abc import Callable

import numpy as np

from bras_kit.kinematics.frames import fk_batch, matrix_to_quat_xyzw
from bras_kit.model.authoring import arm
from bras_kit.motion import sample, states_to_csv, tutorial_motion
from bras_kit.motion.bags import read_recording, write_bag
from bras_kit.motion.bags.writer import _frame_split, _qos, _relative

JOINT_STATE = """std_msgs/Header header
string[] name
float64[] position
float64[] velocity
float64[] effort
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
"""

TF_MESSAGE = """geometry_msgs/TransformStamped[] transforms
================================================================================
MSG: geometry_msgs/TransformStamped
std_msgs/Header header
string child_frame_id
Transform transform
================================================================================
MSG: geometry_msgs/Transform
Vector3 translation
Quaternion rotation
================================================================================
MSG: geometry_msgs/Vector3
float64 x
float64 y
float64 z
================================================================================
MSG: geometry_msgs/Quaternion
float64 x
float64 y
float64 z
float64 w
================================================================================
MSG: std_msgs/Header
builtin_interfaces/Time stamp
string frame_id
================================================================================
MSG: builtin_interfaces/Time
int32 sec
uint32 nanosec
"""


def best(repeat: int, make: Callable[[str], object]) -> float:
    """Seconds of the fastest of ``repeat`` runs, each in a fresh temporary folder."""
    times = []
    for _ in range(repeat):
        with tempfile.TemporaryDirectory() as folder:
            start = time.perf_counter()
            make(folder)
            times.append(time.perf_counter() - start)
    return min(times)


def _stamp(t: float) -> dict:
    ns = round(t * 1e9)
    return {"sec": ns // 10**9, "nanosec": ns % 10**9}


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--seconds", type=float, default=60.0)
    parser.add_argument("--rate", type=float, default=20.0)
    parser.add_argument("--repeat", type=int, default=5)
    args = parser.parse_args()

    robot = arm()
    states = sample(tutorial_motion(robot), args.seconds, args.rate)
    tree, moving, _ = _frame_split(robot)
    relative = _relative(fk_batch(tree, states.positions), tree, moving)
    frames = [(tree.links[tree.parent[i]], tree.links[i]) for i in moving]
    count = len(states)
    written = 2 * count + 1  # /tf and /joint_states per sample, /robot_description once

    def bras_kit_record(folder: str) -> None:
        write_bag(robot, states, os.path.join(folder, "run.mcap"))

    def rosbags_record(folder: str) -> None:
        from rosbags.rosbag2 import StoragePlugin, Writer
        from rosbags.typesys import Stores, get_typestore

        store = get_typestore(Stores.ROS2_HUMBLE)
        types = store.types
        time_, header = types["builtin_interfaces/msg/Time"], types["std_msgs/msg/Header"]
        with Writer(os.path.join(folder, "run"), version=8, storage_plugin=StoragePlugin.MCAP) as writer:
            text = writer.add_connection("/robot_description", "std_msgs/msg/String", typestore=store,
                                         offered_qos_profiles=[_qos(True, 1)])
            tf = writer.add_connection("/tf", "tf2_msgs/msg/TFMessage", typestore=store,
                                       offered_qos_profiles=[_qos(False, 100)])
            js = writer.add_connection("/joint_states", "sensor_msgs/msg/JointState", typestore=store,
                                       offered_qos_profiles=[_qos(False, 10)])
            writer.write(text, 0, store.serialize_cdr(types["std_msgs/msg/String"](data=robot.source_text),
                                                      "std_msgs/msg/String"))
            for k, t in enumerate(states.times):
                ns = round(float(t) * 1e9)
                stamp = time_(sec=ns // 10**9, nanosec=ns % 10**9)
                transforms = []
                for (parent, child), matrix in zip(frames, relative[k]):
                    x, y, z = (float(v) for v in matrix[:3, 3])
                    qx, qy, qz, qw = matrix_to_quat_xyzw(matrix)
                    transforms.append(types["geometry_msgs/msg/TransformStamped"](
                        header=header(stamp=stamp, frame_id=parent), child_frame_id=child,
                        transform=types["geometry_msgs/msg/Transform"](
                            translation=types["geometry_msgs/msg/Vector3"](x=x, y=y, z=z),
                            rotation=types["geometry_msgs/msg/Quaternion"](x=qx, y=qy, z=qz, w=qw))))
                writer.write(tf, ns, store.serialize_cdr(types["tf2_msgs/msg/TFMessage"](transforms=transforms),
                                                         "tf2_msgs/msg/TFMessage"))
                message = types["sensor_msgs/msg/JointState"](
                    header=header(stamp=stamp, frame_id=""), name=list(states.names), position=states.positions[k],
                    velocity=states.velocities[k], effort=np.zeros(0))
                writer.write(js, ns, store.serialize_cdr(message, "sensor_msgs/msg/JointState"))

    def mcap_record(folder: str) -> None:
        from mcap_ros2.writer import Writer

        with open(os.path.join(folder, "run.mcap"), "wb") as handle:
            writer = Writer(handle)
            text = writer.register_msgdef("std_msgs/msg/String", "string data\n")
            tf = writer.register_msgdef("tf2_msgs/msg/TFMessage", TF_MESSAGE)
            js = writer.register_msgdef("sensor_msgs/msg/JointState", JOINT_STATE)
            writer.write_message("/robot_description", text, {"data": robot.source_text}, log_time=0)
            for k, t in enumerate(states.times):
                ns, stamp = round(float(t) * 1e9), _stamp(float(t))
                transforms = []
                for (parent, child), matrix in zip(frames, relative[k]):
                    x, y, z = (float(v) for v in matrix[:3, 3])
                    qx, qy, qz, qw = matrix_to_quat_xyzw(matrix)
                    transforms.append({"header": {"stamp": stamp, "frame_id": parent}, "child_frame_id": child,
                                       "transform": {"translation": {"x": x, "y": y, "z": z},
                                                     "rotation": {"x": qx, "y": qy, "z": qz, "w": qw}}})
                writer.write_message("/tf", tf, {"transforms": transforms}, log_time=ns)
                writer.write_message("/joint_states", js, {
                    "header": {"stamp": stamp, "frame_id": ""}, "name": list(states.names),
                    "position": list(map(float, states.positions[k])),
                    "velocity": list(map(float, states.velocities[k])), "effort": []}, log_time=ns)
            writer.finish()

    rows = [("record", "bras-kit write_bag", best(args.repeat, bras_kit_record)),
            ("record", "rosbags directly", best(args.repeat, rosbags_record)),
            ("record", "mcap_ros2 (peer)", best(args.repeat, mcap_record))]

    with tempfile.TemporaryDirectory() as folder:
        summary = write_bag(robot, states, os.path.join(folder, "run.mcap"))
        bag_bytes = sum(os.path.getsize(os.path.join(summary.folder, n)) for n in os.listdir(summary.folder))
        mcap_only = os.path.getsize(summary.storage_file)
        csv_bytes = len(states_to_csv(states).encode())

        def bras_kit_replay() -> None:
            read_recording(summary.folder)

        def rosbags_replay() -> None:
            from rosbags.rosbag2 import Reader
            from rosbags.typesys import Stores, get_typestore

            store = get_typestore(Stores.ROS2_HUMBLE)
            with Reader(summary.folder) as reader:
                connections = [c for c in reader.connections if c.topic == "/joint_states"]
                for connection, _, data in reader.messages(connections=connections):
                    store.deserialize_cdr(data, connection.msgtype)

        def mcap_replay() -> None:
            from mcap.reader import make_reader
            from mcap_ros2.decoder import DecoderFactory

            with open(summary.storage_file, "rb") as handle:
                reader = make_reader(handle, decoder_factories=[DecoderFactory()])
                for _ in reader.iter_decoded_messages(topics=["/joint_states"]):
                    pass

        for name, func in (("bras-kit read_recording", bras_kit_replay), ("rosbags directly", rosbags_replay),
                           ("mcap_ros2 (peer)", mcap_replay)):
            rows.append(("replay", name, best(args.repeat, lambda _folder, f=func: f())))

    print(f"{args.seconds:g} s at {args.rate:g} Hz: {count} samples x {len(states.names)} joints; "
          f"record = {written} messages (/robot_description, /tf, /joint_states), replay = {count} /joint_states")
    print(f"{'':8}{'':26}{'seconds':>10}{'messages/s':>14}")
    for what, name, seconds in rows:
        messages = written if what == "record" else count
        print(f"{what:8}{name:26}{seconds:10.4f}{messages / seconds:14,.0f}")
    print(f"bag folder {bag_bytes:,} bytes (MCAP {mcap_only:,}, all four topics); "
          f"CSV of the joint states {csv_bytes:,} bytes; bag/CSV = {bag_bytes / csv_bytes:.2f}")


if __name__ == "__main__":
    main()
