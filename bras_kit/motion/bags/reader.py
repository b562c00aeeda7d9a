"""A recorded JointState topic, read from a ROS 2 bag (folder, ``.mcap`` or ``.db3``), checked as untrusted input.

What is refused (a :class:`BagError`: the file, what is wrong, what to do), before or while
``rosbags`` reads the bytes:

* a folder without metadata.yaml, a metadata.yaml over :data:`MAX_METADATA_BYTES` or not YAML;
* a storage file named outside the folder (absolute, ``..``, a link leading out), missing or
  not a regular file; more than :data:`MAX_BAG_BYTES` of storage in all;
* compressed bags (``compression_mode`` file or message): ``ros2 bag convert`` them first;
* MCAP chunks declaring more than :data:`MAX_CHUNK_BYTES` once decompressed;
* more than :data:`MAX_MESSAGES` messages on the topic; any damage the reader finds
  (truncated file, lying record lengths, bad checksums, an SQLite file that is not one);
* a topic that is missing or does not carry sensor_msgs/msg/JointState.

What is kept, with a note (the motion checks then see the recording as it is): messages that
do not decode or whose lengths disagree are skipped, NaN and infinite positions are left out,
stamps out of order are sorted, gaps are reported, joints the robot lacks are ignored and
joints the recording lacks stay at 0.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterator, Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from ...core.errors import BrasKitError, ParameterError
from ...core.message import M, Message, Mn

JOINT_STATE_TYPE = "sensor_msgs/msg/JointState"
DEFAULT_TOPIC = "/joint_states"
MAX_METADATA_BYTES = 1 << 20  # 1 MiB: a metadata.yaml lists topics and files, not data
MAX_BAG_BYTES = 1 << 30  # 1 GiB of storage files: hours of joint states at 1 kHz
MAX_CHUNK_BYTES = 256 << 20  # an MCAP chunk holds a few MiB; ros2 bag's default is 768 KiB
MAX_MESSAGES = 2_000_000  # messages read from the topic (about 28 hours at 20 Hz)
GAP_FACTOR = 5.0  # a pause longer than 5 typical periods is a gap
BAG_SUFFIXES = (".mcap", ".db3")


class BagError(BrasKitError):
    """A bag that cannot be read: missing, too big, damaged, or without the topic asked for."""


@dataclass
class Recording:
    """One JointState topic of a bag: each joint's samples, seconds after the first stamp.

    ``series[joint]`` is (times, positions), times increasing; ``start`` is the first stamp in
    seconds (as recorded); ``notes`` say what was odd in the recording.
    """

    path: str
    topic: str
    series: dict[str, tuple[np.ndarray, np.ndarray]]
    start: float
    messages: int
    notes: list[Message] = field(default_factory=list)

    @property
    def duration(self) -> float:
        ends = [float(times[-1]) for times, _ in self.series.values() if len(times)]
        return max(ends) if ends else 0.0


def bag_suffix(path: str) -> bool:
    """True when ``path`` names a bag by its form: ``.mcap``, ``.db3``, or a metadata.yaml."""
    text = os.fspath(path).rstrip("/" + os.sep)
    return text.lower().endswith(BAG_SUFFIXES) or os.path.basename(text) == "metadata.yaml"


def is_bag(path: str) -> bool:
    """True for a bag folder (holding metadata.yaml) or a ``.mcap``/``.db3`` file name."""
    text = os.fspath(path)
    return bag_suffix(text) or os.path.isfile(os.path.join(text, "metadata.yaml"))


# ------------------------------------------------------------------ opening, as untrusted input

def _fail(path: str, what: Message, hint: Message | None = None) -> BagError:
    return BagError(what, path=path, hint=hint or M("record it again, or check it with ros2 bag info"))


def _resolve(path: str) -> tuple[str, str | None]:
    """(what rosbags opens, the bag folder or None for a bare file), after the safety checks."""
    text = os.fspath(path).rstrip("/" + os.sep) or os.fspath(path)
    if os.path.basename(text) == "metadata.yaml":
        text = os.path.dirname(text) or "."
    if os.path.isdir(text):
        _check_folder(text)
        return text, text
    if not os.path.exists(text):
        raise _fail(text, M("no such bag"),
                    M("give a bag folder (with metadata.yaml), or its .mcap or .db3 file"))
    if not text.lower().endswith(BAG_SUFFIXES):
        raise _fail(text, M("not a ROS 2 bag"), M("give a bag folder (with metadata.yaml), or its .mcap or .db3 file"))
    if not os.path.isfile(text):
        raise _fail(text, M("not a regular file"))
    _check_size(text, os.path.getsize(text))
    return text, None


def _check_size(path: str, size: int) -> None:
    if size > MAX_BAG_BYTES:
        raise _fail(path, M("the bag holds {size} MiB, over the {limit} MiB bras-kit reads",
                            size=size >> 20, limit=MAX_BAG_BYTES >> 20),
                    M("cut it with ros2 bag convert (start and end times), or keep only the topic you need"))


def _check_folder(folder: str) -> None:
    import yaml

    metadata = os.path.join(folder, "metadata.yaml")
    if not os.path.isfile(metadata):
        raise _fail(folder, M("this folder is not a ROS 2 bag: it has no metadata.yaml"),
                    M("give the folder ros2 bag record wrote, or the .mcap or .db3 file itself"))
    if os.path.getsize(metadata) > MAX_METADATA_BYTES:
        raise _fail(metadata, M("metadata.yaml is over {limit} KiB", limit=MAX_METADATA_BYTES >> 10))
    from ...trust import yaml_gate
    from ...trust.learner_files import read_text

    try:
        # the one reader (a regular file of at most the limit, checked once open), then the bounded loader
        data = yaml_gate.load(read_text(os.path.abspath(metadata), (os.path.abspath(folder),), limit=MAX_METADATA_BYTES))
    except (OSError, UnicodeDecodeError, yaml.YAMLError) as exc:
        raise _fail(metadata, M("metadata.yaml cannot be read: {why}", why=str(exc).splitlines()[0])) from None
    info = data.get("rosbag2_bagfile_information") if isinstance(data, dict) else None
    if not isinstance(info, dict):
        raise _fail(metadata, M("metadata.yaml has no rosbag2_bagfile_information"))
    mode = str(info.get("compression_mode") or "").lower()
    if mode not in ("", "none"):
        raise _fail(metadata, M("the bag is compressed ({mode} mode): bras-kit reads uncompressed bags",
                                mode=mode),
                    M("write an uncompressed copy with ros2 bag convert, then give that one"))
    files = info.get("relative_file_paths")
    if not isinstance(files, list) or not files or not all(isinstance(f, str) for f in files):
        raise _fail(metadata, M("metadata.yaml lists no storage files (relative_file_paths)"))
    root = os.path.realpath(folder)
    total = 0
    for name in files:
        where = os.path.realpath(os.path.join(folder, name))
        if os.path.isabs(name) or ".." in name.replace("\\", "/").split("/") or \
                os.path.commonpath([root, where]) != root:
            raise _fail(metadata, M("storage file '{name}' lies outside the bag folder: refused", name=name),
                        M("a bag's files sit in its own folder; fix relative_file_paths"))
        if not os.path.isfile(where):
            raise _fail(metadata, M("storage file '{name}' is missing", name=name),
                        M("copy the whole bag folder, with every file metadata.yaml lists"))
        total += os.path.getsize(where)
    _check_size(folder, total)


def _mcap_storages(reader: Any) -> list[Any]:
    storage = reader.storage
    inner = getattr(storage, "storages", [storage])
    return [s for s in inner if hasattr(s, "chunks")]


def _check_chunks(reader: Any, path: str) -> None:
    for storage in _mcap_storages(reader):
        for chunk in storage.chunks:
            if chunk.uncompressed_size > MAX_CHUNK_BYTES or chunk.compressed_size > MAX_BAG_BYTES:
                raise _fail(str(storage.path), M("an MCAP chunk declares {size} MiB once decompressed, over "
                                                 "the {limit} MiB bras-kit accepts",
                                                 size=chunk.uncompressed_size >> 20, limit=MAX_CHUNK_BYTES >> 20))


def _damaged(path: str, exc: BaseException) -> BagError:
    why = str(exc).strip().splitlines()[0] if str(exc).strip() else type(exc).__name__
    if os.path.isdir(path) or not path.lower().endswith(".mcap"):
        hint = M("record it again; an SQLite bag cut short can be rebuilt with ros2 bag reindex")
    else:
        hint = M("record it again; an MCAP file cut short can be rescued with Foxglove's mcap recover")
    return _fail(path, M("the bag is damaged or not a ROS 2 bag: {why}", why=why), hint)


def _messages(path: str, topic: str) -> Iterator[tuple[int, bytes] | tuple[str, Any]]:
    """First ("type", msgtype), then (timestamp ns, raw CDR bytes) for each message of ``topic``."""
    from rosbags.rosbag2 import Reader

    from ._compat import bounded_decompression

    bounded_decompression()
    opened, _ = _resolve(path)
    try:
        reader = Reader(opened)
        reader.open()
    except BrasKitError:
        raise
    except Exception as exc:  # noqa: BLE001  (any failure on untrusted bytes is a damaged bag)
        raise _damaged(opened, exc) from None
    try:
        _check_chunks(reader, opened)
        connections = [c for c in reader.connections if c.topic == topic]
        if not connections:
            names = sorted({c.topic for c in reader.connections})
            raise _fail(opened, M("the bag has no topic {topic}", topic=topic),
                        M("its topics are {names}; choose one with --topic", names=names) if names else
                        M("the bag holds no topic at all"))
        types = sorted({c.msgtype for c in connections})
        if types != [JOINT_STATE_TYPE]:
            raise _fail(opened, M("topic {topic} carries {types}, not {expected}", topic=topic, types=types,
                                  expected=JOINT_STATE_TYPE),
                        M("give the topic the joint states were recorded on with --topic"))
        count = sum(c.msgcount for c in connections)
        if count > MAX_MESSAGES:
            raise _fail(opened, M("topic {topic} holds {count} messages, over the {limit} bras-kit reads",
                                  topic=topic, count=count, limit=MAX_MESSAGES),
                        M("cut the bag with ros2 bag convert (start and end times)"))
        yield ("type", JOINT_STATE_TYPE)
        try:
            for seen, (_, timestamp, data) in enumerate(reader.messages(connections=connections)):
                if seen >= MAX_MESSAGES:
                    raise _fail(opened, M("topic {topic} holds more than {limit} messages", topic=topic,
                                          limit=MAX_MESSAGES),
                                M("cut the bag with ros2 bag convert (start and end times)"))
                yield timestamp, data
        except BrasKitError:
            raise
        except Exception as exc:  # noqa: BLE001
            raise _damaged(opened, exc) from None
    finally:
        try:
            reader.close()
        except Exception:  # noqa: BLE001,S110  (closing a damaged file: nothing more to say)
            pass


def read_recording(path: str, topic: str | None = None) -> Recording:
    """Read the JointState messages of ``topic`` (default ``/joint_states``) from a bag.

    Times are ``header.stamp`` (the receive time when a message has no stamp), in seconds
    after the first one. Raises :class:`BagError` for a bag that cannot be trusted or read.
    """
    from rosbags.typesys import Stores, get_typestore

    topic = topic or DEFAULT_TOPIC
    store = get_typestore(Stores.ROS2_HUMBLE)
    stream = _messages(path, topic)
    next(stream)  # the checks before the first message
    samples: dict[str, list[tuple[int, float]]] = {}
    undecodable = mismatched = not_finite = backwards = 0
    previous = -(1 << 63)
    count = 0
    stamps: list[int] = []
    for timestamp, data in stream:
        count += 1
        try:
            message: Any = store.deserialize_cdr(data, JOINT_STATE_TYPE)
            names = [str(n) for n in message.name]
            positions = np.asarray(message.position, dtype=float)
            stamp = int(message.header.stamp.sec) * 1_000_000_000 + int(message.header.stamp.nanosec)
        except Exception:  # noqa: BLE001  (a message that does not decode is skipped and counted)
            undecodable += 1
            continue
        if len(positions) != len(names) or len(set(names)) != len(names):
            mismatched += 1
            continue
        time = stamp if stamp else int(timestamp)  # ns, kept whole: an epoch stamp in float loses 0.1 µs
        if time < previous:
            backwards += 1
        previous = max(previous, time)
        stamps.append(time)
        for name, value in zip(names, positions):
            if not math.isfinite(value):
                not_finite += 1
                continue
            samples.setdefault(name, []).append((time, float(value)))
    if not samples:
        raise _fail(path, M("topic {topic} holds no usable joint state ({count})", topic=topic,
                            count=Mn("{n} message", "{n} messages", count)))
    start = min(t for values in samples.values() for t, _ in values)  # ns
    notes: list[Message] = []
    if undecodable:
        notes.append(Mn("{n} message of {topic} does not decode as a JointState: skipped",
                        "{n} messages of {topic} do not decode as a JointState: skipped", undecodable, topic=topic))
    if mismatched:
        notes.append(Mn("{n} message names a different number of joints than it gives positions: skipped",
                        "{n} messages name a different number of joints than they give positions: skipped",
                        mismatched))
    if not_finite:
        notes.append(Mn("{n} position is NaN or infinite: left out (the motion passes straight over it)",
                        "{n} positions are NaN or infinite: left out (the motion passes straight over them)",
                        not_finite))
    if backwards:
        notes.append(Mn("{n} message is stamped earlier than the one before: sorted by stamp",
                        "{n} messages are stamped earlier than the ones before: sorted by stamp", backwards))
    series = {}
    duplicates = 0
    for name, values in samples.items():
        stamped = np.array([t - start for t, _ in values], dtype=np.int64)
        order = np.argsort(stamped, kind="stable")
        times = stamped[order] * 1e-9
        positions = np.array([v for _, v in values])[order]
        keep = np.append(np.diff(times) > 0, True)  # one value per stamp: the last one recorded
        duplicates += int((~keep).sum())
        series[name] = (times[keep], positions[keep])
    if duplicates:
        notes.append(Mn("{n} sample repeats a stamp already seen: the last one is kept",
                        "{n} samples repeat a stamp already seen: the last one is kept", duplicates))
    notes.extend(_gap_notes(np.unique(np.array(stamps, dtype=np.int64) - start) * 1e-9))
    return Recording(os.fspath(path), topic, series, start * 1e-9, count, notes)


def _gap_notes(times: np.ndarray) -> list[Message]:
    if len(times) < 3:
        return []
    steps = np.diff(times)
    period = float(np.median(steps))
    if period <= 0:
        return []
    gaps = np.flatnonzero(steps > GAP_FACTOR * period)
    if not len(gaps):
        return []
    widest = int(gaps[np.argmax(steps[gaps])])
    return [Mn("{n} gap in the recording, the longest {gap:.3g} s from t={time:.3g} s (messages every {period:.3g} s "
               "otherwise): the motion passes straight across",
               "{n} gaps in the recording, the longest {gap:.3g} s from t={time:.3g} s (messages every {period:.3g} s "
               "otherwise): the motion passes straight across",
               len(gaps), gap=float(steps[widest]), time=float(times[widest]), period=period)]


# ------------------------------------------------------------------ a recording as motion tracks

def recorded_tracks(robot_dof: Sequence[str], joint_ok: Any, path: str,
                    topic: str | None = None) -> tuple[dict[str, Any], float, list[Message], str]:
    """The tracks a bag gives the movable joints ``robot_dof`` (linear between samples).

    ``joint_ok(name)`` raises for a name that is not a drivable joint (the motion's own check);
    joints it refuses are left out with a note. Returns (tracks by joint, duration, notes, label).
    """
    from ..core import Track
    from ..interpolation import interpolator

    recording = read_recording(path, topic)
    notes = list(recording.notes)
    label = f"{os.path.basename(os.fspath(path).rstrip('/' + os.sep))} {recording.topic}"
    tracks = {}
    unknown = []
    for name, (times, positions) in recording.series.items():
        try:
            joint_ok(name)
        except ParameterError:
            unknown.append(name)
            continue
        tracks[name] = Track(name, interpolator(times, positions, "linear"), label)
    if unknown:
        notes.append(M("the recording names joints this robot cannot move: {names} (ignored)", names=unknown))
    missing = [name for name in robot_dof if name not in tracks]
    if missing:
        notes.append(M("the recording has no position for {names}: they follow the other motion specs, else stay at 0",
                       names=missing))
    if not tracks:
        raise _fail(path, M("no joint of {topic} is a movable joint of this robot ({names})", topic=recording.topic,
                            names=sorted(recording.series)),
                    M("check the robot file matches the recording, or choose the topic with --topic"))
    return tracks, recording.duration, notes, label
