"""ROS 2 bags: what bras-kit records, read back by Foxglove's own libraries (mcap, mcap-ros2-support),
and recordings written by those libraries (or in Humble's SQLite 3 storage, by hand) replayed.

Oracles: the mcap/mcap_ros2 readers and writers (not the rosbags library bras-kit uses), poses
computed by hand for the tutorial arm, the tutorial's formulas, Python's sqlite3 and yaml.
"""

from __future__ import annotations

import math
import os
import sqlite3
import struct

import numpy as np
import pytest
import yaml
from paths import DATA as DATA_DIR

DATA = os.path.join(DATA_DIR, "bags")


def _msgdef(name: str) -> str:
    with open(os.path.join(DATA, name), encoding="utf-8") as handle:
        return "".join(line for line in handle if not line.startswith("#"))


def _tutorial(t: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    return 0.8 * np.sin(t), 1.2 * np.sin(0.7 * t)


def _joint_state(ns: int, names, positions) -> dict:
    return {"header": {"stamp": {"sec": ns // 10**9, "nanosec": ns % 10**9}, "frame_id": ""},
            "name": list(names), "position": [float(p) for p in positions], "velocity": [], "effort": []}


def _foxglove_bag(path: str, samples, *, topic: str = "/joint_states", start: int = 1714550400 * 10**9,
                  chunk_size: int = 1024 * 1024, received=None) -> str:
    """An MCAP file written by Foxglove's mcap_ros2 writer: ``samples`` is [(t, names, positions)].

    The bag's receive times (log times) are the stamps, or ``received`` seconds when given.
    """
    from mcap_ros2.writer import Writer

    with open(path, "wb") as handle:
        writer = Writer(handle, chunk_size=chunk_size)
        schema = writer.register_msgdef("sensor_msgs/msg/JointState", _msgdef("JointState.msg"))
        for k, (t, names, positions) in enumerate(samples):
            ns = start + round(t * 1e9)  # an epoch stamp, like a real recording
            log = ns if received is None else start + round(received[k] * 1e9)
            writer.write_message(topic, schema, _joint_state(ns, names, positions), log_time=log, publish_time=log)
        writer.finish()
    return path


def _tutorial_samples(duration: float = 2.0, rate: float = 20.0):
    times = np.arange(int(duration * rate) + 1) / rate
    epaule, coude = _tutorial(times)
    return [(float(t), ["epaule", "coude"], [e, c]) for t, e, c in zip(times, epaule, coude)]


def _read_foxglove(path: str) -> dict[str, list]:
    """topic -> [(schema name, log time ns, decoded message)] read by mcap_ros2 (Foxglove's decoder)."""
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    topics: dict[str, list] = {}
    with open(path, "rb") as handle:
        reader = make_reader(handle, decoder_factories=[DecoderFactory()])
        for schema, channel, message, decoded in reader.iter_decoded_messages():
            topics.setdefault(channel.topic, []).append((schema.name, message.log_time, decoded))
    return topics


@pytest.fixture(scope="module")
def recorded(tmp_path_factory):
    """bras-kit motion -o run.mcap: the tutorial's 10 s at 20 Hz, as a bag folder."""
    from bras_kit.cli import main

    folder = tmp_path_factory.mktemp("recorded")
    assert main(["motion", "-o", str(folder / "run.mcap")]) == 0
    return folder / "run"


# ------------------------------------------------------------------ recording

def test_motion_writes_a_bag_folder_with_metadata_and_mcap(recorded):
    assert sorted(os.listdir(recorded)) == ["metadata.yaml", "run.mcap"]
    with open(recorded / "metadata.yaml", encoding="utf-8") as handle:
        info = yaml.safe_load(handle)["rosbag2_bagfile_information"]
    assert info["storage_identifier"] == "mcap"
    assert info["relative_file_paths"] == ["run.mcap"]
    counts = {t["topic_metadata"]["name"]: t["message_count"] for t in info["topics_with_message_count"]}
    assert counts == {"/robot_description": 1, "/tf_static": 0, "/tf": 201, "/joint_states": 201}
    assert info["message_count"] == 403
    assert info["duration"]["nanoseconds"] == 10 * 10**9


def test_latched_topics_are_offered_transient_local(recorded):
    with open(recorded / "metadata.yaml", encoding="utf-8") as handle:
        info = yaml.safe_load(handle)["rosbag2_bagfile_information"]
    durability = {}
    for topic in info["topics_with_message_count"]:
        profiles = yaml.safe_load(topic["topic_metadata"]["offered_qos_profiles"])
        durability[topic["topic_metadata"]["name"]] = profiles[0]["durability"]
    # rosbag2's numeric QoS (metadata version 8): 1 = transient local, 2 = volatile
    assert durability == {"/robot_description": 1, "/tf_static": 1, "/tf": 2, "/joint_states": 2}


def test_foxglove_reads_every_topic_with_its_type_and_count(recorded):
    topics = _read_foxglove(str(recorded / "run.mcap"))
    assert {name: (items[0][0], len(items)) for name, items in topics.items()} == {
        "/robot_description": ("std_msgs/msg/String", 1),
        "/tf": ("tf2_msgs/msg/TFMessage", 201),
        "/joint_states": ("sensor_msgs/msg/JointState", 201),
    }


def test_joint_states_carry_the_tutorial_angles_stamped_on_the_motion_clock(recorded):
    states = _read_foxglove(str(recorded / "run.mcap"))["/joint_states"]
    for k, (_, log_time, message) in enumerate(states):
        t = k / 20
        assert log_time == round(t * 1e9)
        assert message.header.stamp.sec * 10**9 + message.header.stamp.nanosec == round(t * 1e9)
        assert list(message.name) == ["epaule", "coude"]
        assert message.position == pytest.approx(list(_tutorial(np.array(t))), abs=1e-12)
        assert message.velocity == pytest.approx([0.8 * math.cos(t), 0.84 * math.cos(0.7 * t)], abs=1e-12)


def _quaternion_about_y(angle: float) -> list[float]:
    return [0.0, math.sin(angle / 2), 0.0, math.cos(angle / 2)]


def _same_rotation(q, expected) -> bool:
    q, expected = np.array(q), np.array(expected)
    return bool(np.allclose(q, expected, atol=1e-9) or np.allclose(q, -expected, atol=1e-9))


def test_tf_gives_the_hand_computed_pose_of_each_moving_link(recorded):
    tf = _read_foxglove(str(recorded / "run.mcap"))["/tf"]
    for k in (0, 7, 31, 120, 200):
        t = k / 20
        epaule, coude = _tutorial(np.array(t))
        _, log_time, message = tf[k]
        assert log_time == round(t * 1e9)
        by_child = {item.child_frame_id: item for item in message.transforms}
        assert sorted(by_child) == ["avant_bras", "bras"]
        for child, parent, height, angle in (("bras", "base", 0.05, epaule), ("avant_bras", "bras", 0.6, coude)):
            item = by_child[child]
            assert item.header.frame_id == parent
            translation = item.transform.translation
            assert [translation.x, translation.y, translation.z] == pytest.approx([0, 0, height], abs=1e-12)
            rotation = item.transform.rotation
            assert _same_rotation([rotation.x, rotation.y, rotation.z, rotation.w], _quaternion_about_y(float(angle)))


def test_robot_description_is_the_urdf(recorded):
    from bras_kit.model.authoring import arm_urdf

    (_, log_time, message), = _read_foxglove(str(recorded / "run.mcap"))["/robot_description"]
    assert message.data == arm_urdf()
    assert log_time == 0


def test_fixed_joints_go_once_to_tf_static_and_every_movable_joint_to_joint_states(tmp_path, run_cli):
    folder = tmp_path / "fixed"
    folder.mkdir()
    urdf = folder / "tool.urdf"
    urdf.write_text(open(os.path.join(DATA, "tool_arm.urdf")).read())
    code, _, err = run_cli("motion", str(urdf), "--duration", "1", "-o", str(tmp_path / "tool.mcap"))
    assert code == 0, err
    topics = _read_foxglove(str(tmp_path / "tool" / "tool.mcap"))
    (_, _, static), = topics["/tf_static"]
    (item,) = static.transforms
    assert (item.header.frame_id, item.child_frame_id) == ("avant_bras", "outil")
    translation = item.transform.translation
    assert [translation.x, translation.y, translation.z] == pytest.approx([0, 0, 0.5])
    assert all(list(m.name) == ["epaule", "coude"] for _, _, m in topics["/joint_states"])
    assert all({t.child_frame_id for t in m.transforms} == {"bras", "avant_bras"} for _, _, m in topics["/tf"])


def test_sqlite_storage_is_written_for_db3(tmp_path, run_cli):
    code, _, err = run_cli("motion", "--duration", "1", "-o", str(tmp_path / "humble.db3"))
    assert code == 0, err
    with sqlite3.connect(tmp_path / "humble" / "humble.db3") as db:
        counts = dict(db.execute("SELECT topics.name, COUNT(messages.id) FROM topics LEFT JOIN messages "
                                 "ON topics.id = messages.topic_id GROUP BY topics.name"))
    assert counts == {"/robot_description": 1, "/tf_static": 0, "/tf": 21, "/joint_states": 21}


def test_an_existing_bag_is_kept_without_force_and_replaced_with_it(tmp_path, run_cli):
    assert run_cli("motion", "--duration", "1", "-o", str(tmp_path / "b.mcap"))[0] == 0
    code, _, err = run_cli("motion", "--duration", "2", "-o", str(tmp_path / "b.mcap"))
    assert code == 2 and "already exists" in err and "--force" in err
    assert run_cli("motion", "--duration", "2", "-o", str(tmp_path / "b.mcap"), "--force")[0] == 0
    assert len(_read_foxglove(str(tmp_path / "b" / "b.mcap"))["/joint_states"]) == 41
    assert sorted(os.listdir(tmp_path)) == ["b"]  # no staging folder left behind


def test_a_folder_that_is_not_a_bag_is_never_replaced(tmp_path, run_cli):
    (tmp_path / "notes").mkdir()
    (tmp_path / "notes" / "mine.txt").write_text("keep me")
    code, _, err = run_cli("motion", "-o", str(tmp_path / "notes.mcap"), "--force")
    assert code == 2 and "not a ROS 2 bag" in err
    assert (tmp_path / "notes" / "mine.txt").read_text() == "keep me"


def test_render_records_the_states_it_draws(tmp_path, run_cli):
    code, _, err = run_cli("render", "--duration", "1", "--size", "64x48", "--gif", str(tmp_path / "a.gif"),
                           "--record", str(tmp_path / "drawn.mcap"))
    assert code == 0, err
    states = _read_foxglove(str(tmp_path / "drawn" / "drawn.mcap"))["/joint_states"]
    assert len(states) == 20  # one per GIF frame
    assert states[5][2].position == pytest.approx(list(_tutorial(np.array(0.25))), abs=1e-12)


def test_write_bag_is_a_library_function_for_other_commands(tmp_path, tutorial_robot):
    from bras_kit.motion import sample, tutorial_motion
    from bras_kit.motion.states_io import write_states

    states = sample(tutorial_motion(tutorial_robot), 1.0, 10.0)
    written = write_states(tutorial_robot, states, str(tmp_path / "lib.mcap"))
    assert "lib" in str(written)
    assert len(_read_foxglove(str(tmp_path / "lib" / "lib.mcap"))["/joint_states"]) == 11


# ------------------------------------------------------------------ replaying

def test_foxglove_recording_replays_at_the_recorded_angles(tmp_path, tutorial_robot):
    from bras_kit.motion import motion_from_specs, sample

    bag = _foxglove_bag(str(tmp_path / "fox.mcap"), _tutorial_samples())
    motion = motion_from_specs(tutorial_robot, [bag])
    assert motion.duration == pytest.approx(2.0)
    assert motion.notes == []
    states = sample(motion, rate=20)
    epaule, coude = _tutorial(states.times)
    assert states.times[-1] == pytest.approx(2.0)
    assert states.positions[:, 0] == pytest.approx(epaule, abs=1e-9)
    assert states.positions[:, 1] == pytest.approx(coude, abs=1e-9)


def test_render_gif_of_a_recording_shows_the_arm_at_the_recorded_angles(tmp_path, run_cli):
    """Frames of the replayed recording equal the frames of the tutorial's formulas drawn directly."""
    from PIL import Image

    bag = _foxglove_bag(str(tmp_path / "fox.mcap"), _tutorial_samples())
    for name, motion in (("replayed", [bag]), ("formulas", ["epaule=0.8*sin(t)", "coude=1.2*sin(0.7*t)"])):
        options = [item for spec in motion for item in ("--motion", spec)]
        code, _, err = run_cli("render", *options, "--duration", "2", "--size", "96x72",
                               "--frames-dir", str(tmp_path / name), "--gif", str(tmp_path / f"{name}.gif"))
        assert code == 0, err
    assert len(os.listdir(tmp_path / "replayed")) == 40

    def frame(folder: str, k: int) -> np.ndarray:
        return np.asarray(Image.open(tmp_path / folder / f"frame_{k:04d}.png").convert("RGB"), dtype=int)

    for k in (0, 13, 30, 39):
        assert np.abs(frame("replayed", k) - frame("formulas", k)).max() <= 2, k
    assert np.abs(frame("replayed", 30) - frame("formulas", 10)).max() > 50  # another pose differs


def _humble_sqlite_bag(folder, samples) -> str:
    """A Humble-style SQLite 3 bag: the tables made by hand, CDR bytes encoded by Foxglove's writer."""
    from mcap.reader import make_reader

    scratch = _foxglove_bag(str(folder) + ".scratch.mcap", samples)
    with open(scratch, "rb") as handle:
        raw = [(message.log_time, message.data) for _, _, message in make_reader(handle).iter_messages()]
    os.unlink(scratch)
    folder.mkdir()
    with open(os.path.join(DATA, "humble_schema.sql"), encoding="utf-8") as handle:
        schema = handle.read()
    db = sqlite3.connect(folder / "rec_0.db3")
    db.executescript(schema)
    with open(os.path.join(DATA, "humble_metadata.yaml"), encoding="utf-8") as handle:
        topic = yaml.safe_load(handle)["rosbag2_bagfile_information"]["topics_with_message_count"][0]
    qos = topic["topic_metadata"]["offered_qos_profiles"]  # Humble keeps the same text in both places
    db.execute("INSERT INTO topics VALUES (1, '/joint_states', 'sensor_msgs/msg/JointState', 'cdr', ?)", (qos,))
    db.executemany("INSERT INTO messages (topic_id, timestamp, data) VALUES (1, ?, ?)", raw)
    db.commit()
    db.close()
    with open(os.path.join(DATA, "humble_metadata.yaml"), encoding="utf-8") as handle:
        metadata = handle.read().replace("FILE", "rec_0.db3").replace("COUNT", str(len(raw)))
    (folder / "metadata.yaml").write_text(metadata)
    return str(folder)


def test_humble_sqlite_bag_replays_in_plot_at_the_recorded_angles(tmp_path, run_cli, tutorial_robot):
    from bras_kit.motion import motion_from_specs, sample

    bag = _humble_sqlite_bag(tmp_path / "rec", _tutorial_samples())
    for spec in (bag, os.path.join(bag, "rec_0.db3"), os.path.join(bag, "metadata.yaml")):
        states = sample(motion_from_specs(tutorial_robot, [spec]), rate=10)
        epaule, coude = _tutorial(states.times)
        assert len(states) == 21
        assert states.positions[:, 0] == pytest.approx(epaule, abs=1e-9)
        assert states.positions[:, 1] == pytest.approx(coude, abs=1e-9)
    code, _, err = run_cli("plot", "--motion", bag, "-o", str(tmp_path / "plot.png"))
    assert code == 0, err
    assert "41 samples over 2 s" in err


def test_motion_checks_limits_on_a_recording(tmp_path, run_cli):
    samples = [(t, ["epaule", "coude"], [e, 2.5 * math.sin(t)]) for t, _, (e, _) in _tutorial_samples(3.0)]
    bag = _foxglove_bag(str(tmp_path / "far.mcap"), samples)
    code, out, err = run_cli("motion", "--motion", bag, "--strict")
    assert code == 1
    assert "coude goes past its upper limit 2" in err
    assert "/joint_states" in out


def test_topic_option_picks_another_joint_state_topic(tmp_path, run_cli):
    bag = _foxglove_bag(str(tmp_path / "arm.mcap"), _tutorial_samples(), topic="/arm/joint_states")
    code, _, err = run_cli("motion", "--motion", bag)
    assert code == 2 and "no topic /joint_states" in err and "/arm/joint_states" in err
    code, out, err = run_cli("motion", "--motion", bag, "--topic", "/arm/joint_states")
    assert code == 0, err


def test_odd_recordings_get_findings_not_tracebacks(tmp_path, run_cli, tutorial_robot):
    from bras_kit.motion import motion_from_specs

    samples = []
    for t, _, (e, c) in _tutorial_samples(2.0):
        if 0.5 < t < 1.2:
            continue  # a gap
        samples.append((t, ["epaule", "coude", "pince"], [e, float("nan") if t == 0.25 else c, 0.1]))
    received = [t for t, _, _ in samples]
    samples[3], samples[4] = samples[4], samples[3]  # stamped out of order, received in order
    bag = _foxglove_bag(str(tmp_path / "odd.mcap"), samples, received=received)
    motion = motion_from_specs(tutorial_robot, [bag])
    text = " | ".join(str(note) for note in motion.notes)
    assert "'pince'" in text and "NaN" in text and "earlier than" in text and "gap" in text
    positions = motion.positions(np.array([0.25, 0.2, 0.3]))
    assert positions[0, 1] == pytest.approx((1.2 * math.sin(0.7 * 0.2) + 1.2 * math.sin(0.7 * 0.3)) / 2)
    code, _, err = run_cli("motion", "--motion", bag)
    assert code == 0 and "Traceback" not in err
    assert err.count("warning:") >= 4


def test_a_recording_of_joints_the_robot_lacks_is_refused(tmp_path, run_cli):
    samples = [(t, ["shoulder_pan_joint"], [0.1]) for t in (0.0, 0.1)]
    bag = _foxglove_bag(str(tmp_path / "ur.mcap"), samples)
    code, _, err = run_cli("motion", "--motion", bag)
    assert code == 2 and "shoulder_pan_joint" in err and "Traceback" not in err


# ------------------------------------------------------------------ hostile bags

def _hostile(run_cli, spec: str, *words: str) -> str:
    code, _, err = run_cli("motion", "--motion", spec)
    assert code == 2, err
    assert "Traceback" not in err and "internal error" not in err, err
    for word in words:
        assert word in err, err
    return err


def _chunk_index_fields(data: bytes) -> dict[str, int]:
    """Offsets of the first ChunkIndex record's fields in the summary section (MCAP spec, by hand)."""
    (summary,) = struct.unpack_from("<Q", data, len(data) - 8 - 4 - 8 - 8)  # footer: summary start
    position = summary
    while data[position] != 0x08:  # ChunkIndex
        (length,) = struct.unpack_from("<Q", data, position + 1)
        position += 9 + length
    body = position + 9
    offsets = {"chunk_start_offset": body + 16, "chunk_length": body + 24}
    (map_length,) = struct.unpack_from("<I", data, body + 32)
    after_map = body + 36 + map_length + 8  # message_index_length
    (compression_length,) = struct.unpack_from("<I", data, after_map)
    offsets["compressed_size"] = after_map + 4 + compression_length
    offsets["uncompressed_size"] = offsets["compressed_size"] + 8
    return offsets


def _patched(path: str, **values: int) -> None:
    data = bytearray(open(path, "rb").read())
    fields = _chunk_index_fields(bytes(data))
    for name, value in values.items():
        struct.pack_into("<Q", data, fields[name], value)
    open(path, "wb").write(bytes(data))


def test_truncated_bag_is_refused_with_the_file_named(tmp_path, run_cli):
    bag = _foxglove_bag(str(tmp_path / "cut.mcap"), _tutorial_samples())
    data = open(bag, "rb").read()
    with open(bag, "wb") as handle:
        handle.write(data[: len(data) // 2])
    _hostile(run_cli, bag, "cut.mcap", "damaged", "hint")


def test_chunk_with_a_lying_length_is_refused(tmp_path, run_cli):
    bag = _foxglove_bag(str(tmp_path / "lie.mcap"), _tutorial_samples())
    size = struct.unpack_from("<Q", open(bag, "rb").read(), _chunk_index_fields(open(bag, "rb").read())["compressed_size"])[0]
    _patched(bag, compressed_size=size + 700)  # the index says the chunk's data is longer than it is
    _hostile(run_cli, bag, "lie.mcap", "damaged")


def test_chunk_declaring_a_huge_size_is_refused(tmp_path, run_cli):
    bag = _foxglove_bag(str(tmp_path / "huge.mcap"), _tutorial_samples())
    _patched(bag, uncompressed_size=1 << 40)  # 1 TiB once decompressed
    _hostile(run_cli, bag, "huge.mcap", "1048576 MiB", "256 MiB")


def test_chunk_pointing_past_the_end_of_the_file_is_refused(tmp_path, run_cli):
    bag = _foxglove_bag(str(tmp_path / "far.mcap"), _tutorial_samples())
    _patched(bag, chunk_start_offset=1 << 50)
    _hostile(run_cli, bag, "far.mcap", "damaged")


def test_topic_with_a_wrong_type_is_refused(tmp_path, run_cli):
    from mcap_ros2.writer import Writer

    bag = str(tmp_path / "wrong.mcap")
    with open(bag, "wb") as handle:
        writer = Writer(handle)
        schema = writer.register_msgdef("std_msgs/msg/String", _msgdef("String.msg"))
        writer.write_message("/joint_states", schema, {"data": "epaule=1"}, log_time=1, publish_time=1)
        writer.finish()
    _hostile(run_cli, bag, "std_msgs/msg/String", "sensor_msgs/msg/JointState", "--topic")


def test_bag_naming_a_file_outside_its_folder_is_refused(tmp_path, run_cli):
    bag = _humble_sqlite_bag(tmp_path / "escape", _tutorial_samples())
    os.replace(os.path.join(bag, "rec_0.db3"), tmp_path / "rec_0.db3")
    metadata = os.path.join(bag, "metadata.yaml")
    text = open(metadata).read().replace("- rec_0.db3", "- ../rec_0.db3")
    open(metadata, "w").write(text)
    _hostile(run_cli, bag, "outside the bag folder")


def test_bag_whose_file_links_outside_is_refused(tmp_path, run_cli):
    bag = _humble_sqlite_bag(tmp_path / "linked", _tutorial_samples())
    os.replace(os.path.join(bag, "rec_0.db3"), tmp_path / "elsewhere.db3")
    os.symlink(tmp_path / "elsewhere.db3", os.path.join(bag, "rec_0.db3"))
    _hostile(run_cli, bag, "outside the bag folder")


def test_compressed_bag_is_refused_with_what_to_do(tmp_path, run_cli):
    bag = _humble_sqlite_bag(tmp_path / "zipped", _tutorial_samples())
    metadata = os.path.join(bag, "metadata.yaml")
    text = open(metadata).read().replace('compression_mode: ""', "compression_mode: FILE")
    open(metadata, "w").write(text)
    _hostile(run_cli, bag, "compressed", "ros2 bag convert")


def test_not_a_bag_and_not_sqlite_are_refused(tmp_path, run_cli):
    noise = tmp_path / "noise.mcap"
    noise.write_bytes(b"not an mcap file at all" * 10)
    _hostile(run_cli, str(noise), "noise.mcap", "damaged")
    fake = tmp_path / "fake.db3"
    fake.write_bytes(b"SQLite format 3\x00" + b"\xff" * 200)
    _hostile(run_cli, str(fake), "fake.db3", "damaged")
    _hostile(run_cli, str(tmp_path / "absent.mcap"), "no such bag")


def test_rosbags_decompressor_table_is_still_what_bras_kit_patches():
    from rosbags.rosbag2 import storage_mcap

    from bras_kit.motion.bags._compat import PATCHED_KEYS

    assert sorted(storage_mcap.DECOMPRESSORS) == sorted(PATCHED_KEYS)


def test_decompression_bomb_is_refused_without_filling_memory(tmp_path, run_cli):
    """A chunk declaring 1 KiB that would expand to 64 MiB: refused after reading at most the declared size."""
    import tracemalloc

    from backports import zstd

    from bras_kit.model.authoring import arm
    from bras_kit.motion import motion_from_specs

    bag = _foxglove_bag(str(tmp_path / "bomb.mcap"), _tutorial_samples(20.0), chunk_size=64 << 20)
    bomb = zstd.compress(b"\0" * (64 << 20))
    data = bytearray(open(bag, "rb").read())
    fields = _chunk_index_fields(bytes(data))
    (start,) = struct.unpack_from("<Q", data, fields["chunk_start_offset"])
    (compressed,) = struct.unpack_from("<Q", data, fields["compressed_size"])
    (declared,) = struct.unpack_from("<Q", data, fields["uncompressed_size"])
    assert len(bomb) < compressed  # the bomb fits where the real chunk was
    records = start + 9 + 8 + 8 + 8 + 4 + 4 + len("zstd") + 8
    data[records: records + len(bomb)] = bomb
    struct.pack_into("<Q", data, fields["compressed_size"], len(bomb))
    struct.pack_into("<Q", data, records - 8, len(bomb))
    open(bag, "wb").write(bytes(data))
    assert declared < 1 << 20
    tracemalloc.start()
    try:
        with pytest.raises(Exception) as caught:
            motion_from_specs(arm(), [bag])
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert "damaged" in str(caught.value) and "bomb.mcap" in str(caught.value)
    assert peak < 16 << 20
    _hostile(run_cli, bag, "bomb.mcap", "damaged")


def test_a_name_ending_in_a_slash_is_the_bag_folder(tmp_path, run_cli):
    code, _, err = run_cli("motion", "--duration", "0.5", "-o", str(tmp_path / "trial") + "/")
    assert code == 0, err
    assert sorted(os.listdir(tmp_path / "trial")) == ["metadata.yaml", "trial.mcap"]
    assert len(_read_foxglove(str(tmp_path / "trial" / "trial.mcap"))["/joint_states"]) == 11


def test_bag_errors_and_findings_speak_french(tmp_path, run_cli):
    bag = _foxglove_bag(str(tmp_path / "pince.mcap"),
                        [(t, ["epaule", "coude", "pince"], [0.1, 0.2, 0.3]) for t in (0.0, 0.05, 0.1)])
    code, _, err = run_cli("--lang", "fr", "motion", "--motion", bag)
    assert code == 0, err
    assert "l'enregistrement nomme des articulations que ce robot ne peut pas bouger : 'pince'" in err
    code, _, err = run_cli("--lang", "fr", "motion", "--motion", bag, "--topic", "/autre")
    assert code == 2 and "le bag n'a pas de sujet /autre" in err and "choisissez-en un avec --topic" in err


def test_simulate_records_measured_states_with_their_torques(tmp_path, run_cli):
    code, _, err = run_cli("simulate", "--inertials", "--duration", "1", "-o", str(tmp_path / "sim.mcap"))
    assert code == 0, err
    topics = _read_foxglove(str(tmp_path / "sim" / "sim.mcap"))
    states = [message for _, _, message in topics["/joint_states"]]
    assert len(states) == 21 and len(topics["/tf"]) == 21
    assert all(list(m.name) == ["epaule", "coude"] and len(m.effort) == 2 for m in states)
    assert any(abs(e) > 0.01 for m in states for e in m.effort)  # the motors work against gravity


def test_run_records_what_the_tutorial_node_published(tmp_path, run_cli):
    """bras-kit run -o run.mcap: the node's /joint_states, with the package's URDF and its TF."""
    node = os.path.join(DATA_DIR, "tutorial_package")
    code, _, err = run_cli("run", node, "animation", "--duration", "1", "--quiet", "-o", str(tmp_path / "node.mcap"))
    assert code == 0, err
    topics = _read_foxglove(str(tmp_path / "node" / "node.mcap"))
    states = topics["/joint_states"]
    assert len(states) == 20 and len(topics["/tf"]) == 20
    for _, log_time, message in states:
        t = log_time * 1e-9
        assert message.position == pytest.approx(list(_tutorial(np.array(t))), abs=1e-9)
    (_, _, description), = topics["/robot_description"]
    with open(os.path.join(node, "urdf", "bras.urdf"), encoding="utf-8") as handle:
        assert description.data == handle.read()


def test_validate_finds_a_recording_past_the_limits(tmp_path, run_cli):
    samples = [(t, ["epaule", "coude"], [e, 2.5 * math.sin(t)]) for t, _, (e, _) in _tutorial_samples(3.0)]
    bag = _foxglove_bag(str(tmp_path / "far.mcap"), samples)
    code, out, err = run_cli("validate", "--motion", bag, "--lang", "en")
    assert code == 1, out + err
    assert "BK304" in out and "coude" in out


def test_view_exports_a_page_replaying_a_recording_on_another_topic(tmp_path, run_cli):
    bag = _foxglove_bag(str(tmp_path / "arm.mcap"), _tutorial_samples(), topic="/arm/joint_states")
    code, _, err = run_cli("view", "--motion", bag, "--topic", "/arm/joint_states", "--export",
                           str(tmp_path / "replay.html"))
    assert code == 0, err
    assert "41 frames" in err and "arm.mcap /arm/joint_states" in err
    assert (tmp_path / "replay.html").stat().st_size > 0
