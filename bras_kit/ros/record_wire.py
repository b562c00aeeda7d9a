"""The record of a run as it crosses from the node's process to bras-kit's: typed, bounded, checked.

The stand-in for rclpy runs in the same process as the learner's node (:mod:`.child`), so the node
can reach everything the stand-in keeps (its lists, its functions, the serializer, the pipe
itself). What arrives is therefore a claim. It crosses as bytes, never as objects:

- **the wire**: UTF-8 JSON lines (no object references: a message sent 200,000 times is 200,000
  copies, each counted against the bounds). The first line is the summary (a JSON object), then
  one line per message (``["m", t_ns, node, topic, type, fields]``) and per log
  (``["l", t_ns, level, node, text]``);
- **in the child**, each message is serialised when it is published (:func:`message_line`: a
  copy, at publish time, under the same bounds), so what the node changes afterwards (its name,
  the message object) changes nothing already recorded;
- **in the parent**, :func:`read_record` takes at most :data:`MAX_RECORD_BYTES`, one line at a
  time (at most :data:`MAX_LINE_BYTES` each), checks every field's type and size, re-checks node
  names, topics and message types against ROS 2's rules (:mod:`.names`), and builds a fresh
  :class:`~.recording.Recording`. What does not pass is left out and counted
  (``Recording.refused``, rule BK658); what is past a bound is counted, not kept
  (``Recording.overflow``, BK658 too). Nothing the child says is trusted for identity or size.
"""

from __future__ import annotations

import io
import json
import math
import posixpath
import sys
from typing import Any

from .attempts import Attempt
from .names import is_full_topic_name, is_interface_type, is_node_name
from .recording import (
    Endpoint,
    Frame,
    NodeFailure,
    Published,
    Recording,
    Refusal,
    SplitString,
    TimerInfo,
)

MAX_RECORD_BYTES = 48 << 20  # the whole record, as the parent reads it
MAX_MESSAGE_BYTES = 32 << 20  # the messages' lines, kept by the child (more are counted)
MAX_LINE_BYTES = 1 << 20  # one message, one log, or the summary line
MAX_MESSAGES = 200_000
MAX_LOGS = 10_000
MAX_LOG_BYTES = 4 << 20  # the logs' lines together
MAX_TEXT = 4_000  # one log's text, one failure's detail, a field value of a split string
MAX_PATH = 1_024
MAX_ENTRIES = 1_000  # nodes, publishers, subscriptions, timers, split strings, attempts, frames
MAX_DEPTH = 12  # nesting of a message's fields (JointState: 4)
MAX_SAMPLES = 20  # refusals kept with their detail (all are counted)
ENDINGS = ("returned", "duration", "error", "stopped", "storm", "not_simulated")
LEVELS = ("DEBUG", "INFO", "WARN", "ERROR", "FATAL")
ATTEMPTS = ("write", "read", "network", "signal", "ctypes", "symlink", "process", "")


class WireError(ValueError):
    """The bytes are not a record at all (no summary line): the whole run is refused."""


# ------------------------------------------------------------------------------- the child's side

def _plain(value: Any) -> Any:
    """What json cannot write, as the data it stands for (bytes fields as their numbers)."""
    if isinstance(value, (bytes, bytearray, memoryview)):
        return list(bytes(value))
    if isinstance(value, (set, frozenset, tuple, range)):
        return list(value)
    return repr(value)[:MAX_TEXT]


def message_line(t_ns: int, node: str, topic: str, type_name: str, fields: Any) -> bytes | None:
    """One message as its wire line, made when it is published; None when larger than one line may be."""
    try:
        line = json.dumps(["m", t_ns, node, topic, type_name, fields], default=_plain, separators=(",", ":"),
                          check_circular=True)
    except (ValueError, TypeError, RecursionError):
        return None
    data = line.encode("utf-8", "replace") + b"\n"
    return data if len(data) <= MAX_LINE_BYTES else None


def log_line(t_ns: int, level: str, node: str, text: str) -> bytes:
    line = json.dumps(["l", t_ns, level, node, str(text)[:MAX_TEXT]], separators=(",", ":"))
    return line.encode("utf-8", "replace") + b"\n"


def write_record(summary: dict[str, Any], messages: Any, logs: Any) -> bytes:
    """The record as bytes: ``summary`` (plain data), then the message and log lines already made,
    taken while they fit the bounds (what does not fit is counted in the summary's ``overflow``)."""
    overflow = dict(summary.get("overflow") or {})
    kept: list[bytes] = []
    total = 0
    for kind, lines, most, most_bytes in (("messages", messages, MAX_MESSAGES, MAX_MESSAGE_BYTES),
                                          ("logs", logs, MAX_LOGS, MAX_LOG_BYTES)):
        count = size = 0
        for line in lines:
            if not isinstance(line, bytes) or count >= most or size + len(line) > most_bytes:
                overflow[kind] = overflow.get(kind, 0) + 1
                continue
            kept.append(line)
            count += 1
            size += len(line)
        total += size
    head = json.dumps({**summary, "overflow": overflow}, default=_plain, separators=(",", ":"))
    return head.encode("utf-8", "replace") + b"\n" + b"".join(kept)


# ------------------------------------------------------------------------------ the parent's side

class _Reader:
    """Checks one record's pieces, counting what it leaves out."""

    def __init__(self) -> None:
        self.refused: list[Refusal] = []
        self.refused_count = 0
        self.overflow: dict[str, int] = {}

    def refuse(self, what: str, detail: Any = "") -> None:
        self.refused_count += 1
        if len(self.refused) < MAX_SAMPLES:
            self.refused.append(Refusal(what, _sample(detail)))

    def over(self, kind: str, count: int = 1) -> None:
        self.overflow[kind] = self.overflow.get(kind, 0) + count

    # --- scalars
    def text(self, value: Any, what: str, most: int = MAX_TEXT) -> str:
        if not isinstance(value, str):
            self.refuse(what, value)
            return ""
        if len(value) > most:
            self.over("text")
            return value[:most]
        return value

    def number(self, value: Any, what: str, low: float = 0.0, high: float = math.inf) -> float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not low <= value <= high:
            self.refuse(what, value)
            return low
        return float(value)

    def count(self, value: Any, what: str, high: int = 1 << 62) -> int:
        if isinstance(value, bool) or not isinstance(value, int) or not 0 <= value <= high:
            self.refuse(what, value)
            return 0
        return value

    def path(self, value: Any, what: str) -> str:
        """A learner's file, relative to the package folder (or "" when unknown)."""
        text = self.text(value, what, MAX_PATH)
        if text and (text.startswith("/") or posixpath.normpath(text) != text or text.split("/")[0] == ".."
                     or not text.isprintable()):
            self.refuse(what, text)
            return ""
        return text

    def node(self, value: Any) -> str | None:
        if is_node_name(value):
            return str(value)
        self.refuse("node name", value)
        return None

    def topic(self, value: Any) -> str | None:
        if is_full_topic_name(value):
            return str(value)
        self.refuse("topic name", value)
        return None

    def kind(self, value: Any) -> str | None:
        if value == "?" or is_interface_type(value):
            return str(value)
        self.refuse("message type", value)
        return None

    def items(self, value: Any, what: str, most: int = MAX_ENTRIES) -> list[Any]:
        if not isinstance(value, list):
            if value is not None:
                self.refuse(what, value)
            return []
        if len(value) > most:
            self.over("entries", len(value) - most)
            return value[:most]
        return value


def read_record(data: Any) -> Recording:
    """The record a run's child sent, checked piece by piece (see the module's docstring)."""
    if not isinstance(data, bytes):
        raise WireError(f"the node's process sent {type(data).__name__[:40]}, not a record")
    reader = _Reader()
    if len(data) > MAX_RECORD_BYTES:
        reader.over("bytes", len(data) - MAX_RECORD_BYTES)
    stream = io.BytesIO(memoryview(data)[:MAX_RECORD_BYTES])
    first = stream.readline(MAX_LINE_BYTES + 1)
    summary = _json(first)
    if not isinstance(summary, dict):
        raise WireError("the record has no summary line")
    recording = _summary(summary, reader)
    messages: list[Published] = []
    logs: list[tuple[float, str, str, str]] = []
    while True:
        line = stream.readline(MAX_LINE_BYTES + 1)
        if not line:
            break
        if len(line) > MAX_LINE_BYTES:  # the rest of an over-long line is skipped, never held
            reader.over("line")
            while line and not line.endswith(b"\n"):
                line = stream.readline(MAX_LINE_BYTES)
            continue
        entry = _json(line)
        if isinstance(entry, list) and entry and entry[0] == "m" and len(entry) == 6:
            if len(messages) >= MAX_MESSAGES:
                reader.over("messages")
                continue
            message = _message(entry, reader)
            if message is not None:
                messages.append(message)
        elif isinstance(entry, list) and entry and entry[0] == "l" and len(entry) == 5:
            if len(logs) >= MAX_LOGS:
                reader.over("logs")
                continue
            log = _log(entry, reader)
            if log is not None:
                logs.append(log)
        else:
            reader.refuse("line", line[:80].decode("utf-8", "replace"))
    recording.messages, recording.logs = messages, logs
    recording.refused, recording.refused_count = reader.refused, reader.refused_count
    recording.overflow = {k: v for k, v in sorted(reader.overflow.items()) if v}
    return recording


def _json(line: bytes) -> Any:
    try:
        return json.loads(line)
    except (ValueError, RecursionError):
        return None


def _sample(value: Any) -> str:
    """A refused value as a short inert sample: its repr's ASCII form, cut (never the value itself)."""
    if isinstance(value, str):
        return ascii(value[:60])[1:-1] + ("..." if len(value) > 60 else "")
    return type(value).__name__[:40]


def _summary(raw: dict[str, Any], r: _Reader) -> Recording:
    ended = raw.get("ended")
    if ended not in ENDINGS:
        r.refuse("ending", ended)
        ended = "error"
    recording = Recording(
        target=r.text(raw.get("target"), "target", MAX_PATH), source=r.path(raw.get("source"), "source"),
        function=r.text(raw.get("function"), "function", 255),
        duration=r.number(raw.get("duration"), "duration", 0.0, 1e6), end=r.number(raw.get("end"), "end", 0.0, 1e7),
        ended=str(ended), failure=_failure(raw.get("failure"), r), dropped=r.count(raw.get("dropped"), "dropped"),
        rate_sleeps=r.count(raw.get("rate_sleeps"), "rate_sleeps"),
        wall_seconds=r.number(raw.get("wall_seconds"), "wall_seconds", 0.0, 1e7),
        start_ns=r.count(raw.get("start_ns"), "start_ns"),
        output=r.text(raw.get("output"), "output", 1 << 17), output_tail=r.text(raw.get("output_tail"), "output", 1 << 17),
        output_dropped=r.count(raw.get("output_dropped"), "output_dropped"),
        output_dropped_lines=r.count(raw.get("output_dropped_lines"), "output_dropped"),
    )
    for name in r.items(raw.get("nodes"), "nodes"):
        checked = r.node(name)
        if checked is not None:
            recording.nodes.append(checked)
    for key, out in (("publishers", recording.publishers), ("subscriptions", recording.subscriptions)):
        for entry in r.items(raw.get(key), key):
            if not (isinstance(entry, list) and len(entry) == 5):
                r.refuse(key, entry)
                continue
            node, topic, kind = r.node(entry[0]), r.topic(entry[1]), r.kind(entry[2])
            if node is not None and topic is not None and kind is not None:
                out.append(Endpoint(node, topic, kind, r.path(entry[3], "file"), r.count(entry[4], "line", 1 << 31)))
    for entry in r.items(raw.get("timers"), "timers"):
        if not (isinstance(entry, list) and len(entry) == 4) or not _real(entry[1], 0.0, 1e9):
            r.refuse("timer", entry[1] if isinstance(entry, list) and len(entry) == 4 else entry)
            continue
        node = r.node(entry[0])
        if node is not None:
            recording.timers.append(TimerInfo(node, float(entry[1]), r.path(entry[2], "file"),
                                              r.count(entry[3], "line", 1 << 31)))
    for entry in r.items(raw.get("split_strings"), "split_strings"):
        if not (isinstance(entry, list) and len(entry) == 7):
            r.refuse("split_strings", entry)
            continue
        node, topic = r.node(entry[0]), r.topic(entry[1])
        if node is not None and topic is not None:
            recording.split_strings.append(SplitString(node, topic, r.text(entry[2], "field", 255),
                                                       r.text(entry[3], "value", 200), r.path(entry[4], "file"),
                                                       r.count(entry[5], "line", 1 << 31),
                                                       r.count(entry[6], "count", MAX_MESSAGES * 100)))
    for entry in r.items(raw.get("blocked"), "blocked"):
        if not (isinstance(entry, list) and len(entry) == 4) or entry[0] not in ATTEMPTS:
            r.refuse("blocked", entry)
            continue
        recording.blocked.append(Attempt(entry[0], r.text(entry[1], "detail", MAX_PATH), r.path(entry[2], "file"),
                                         r.count(entry[3], "line", 1 << 31)))
    overflow = raw.get("overflow")
    for kind, count in (overflow.items() if isinstance(overflow, dict) else ()):
        if kind in ("messages", "logs", "too_big", "entries"):
            r.over(kind, r.count(count, "overflow"))
    return recording


def _failure(raw: Any, r: _Reader) -> NodeFailure | None:
    if raw is None:
        return None
    if not isinstance(raw, dict):
        r.refuse("failure", raw)
        return NodeFailure("?", "", [], 0.0)
    frames = []
    for entry in r.items(raw.get("frames"), "frames", 100):
        if isinstance(entry, list) and len(entry) == 4:
            frames.append(Frame(r.path(entry[0], "file"), r.count(entry[1], "line", 1 << 31),
                                r.text(entry[2], "function", 255), r.text(entry[3], "text", 500)))
        else:
            r.refuse("frames", entry)
    context: dict[str, Any] = {}
    raw_context = raw.get("context")
    for key, value in (raw_context.items() if isinstance(raw_context, dict) else ()):
        if not isinstance(key, str) or len(key) > 40 or len(context) >= 40:
            r.refuse("context", key)
        elif key.endswith(("_path", "path")) and isinstance(value, str):
            context[key] = r.path(value, key)
        elif isinstance(value, (str, bool)) or (isinstance(value, (int, float)) and math.isfinite(value)):
            context[key] = r.text(value, key, 500) if isinstance(value, str) else value
        elif isinstance(value, list) and len(value) <= 50 and all(isinstance(v, (str, int, float)) for v in value):
            context[key] = [v[:255] if isinstance(v, str) else v for v in value]
        else:
            r.refuse("context", key)
    kind = r.text(raw.get("kind"), "kind", 100)
    if not kind.isidentifier():
        r.refuse("exception", kind)
        kind = "?"
    return NodeFailure(kind, r.text(raw.get("detail"), "detail", 2000), frames,
                       r.number(raw.get("time"), "time", 0.0, 1e7), context)


def _message(entry: list[Any], r: _Reader) -> Published | None:
    _, t_ns, node, topic, kind, fields = entry
    time = r.number(t_ns, "time", 0.0, 1e19) / 1e9
    checked_node, checked_topic, checked_kind = r.node(node), r.topic(topic), r.kind(kind)
    if checked_node is None or checked_topic is None or checked_kind is None:
        return None
    if checked_kind == "sensor_msgs/msg/JointState":  # the one type bras-kit reads field by field
        if not (isinstance(fields, dict) and _joint_state(fields)):
            r.refuse("JointState", str(fields)[:60])
            return None
    elif not isinstance(fields, dict) or _depth(fields) > MAX_DEPTH:
        r.refuse("message", checked_kind)
        return None
    return Published(time, checked_node, checked_topic, checked_kind, fields)


def _log(entry: list[Any], r: _Reader) -> tuple[float, str, str, str] | None:
    _, t_ns, level, node, text = entry
    if level not in LEVELS or not isinstance(node, str) or not all(is_node_name(p) for p in node.split(".")):
        r.refuse("log", node if isinstance(node, str) else level)
        return None
    return (r.number(t_ns, "time", 0.0, 1e19) / 1e9, level, node, r.text(text, "log"))


def _depth(value: Any) -> int:
    """How deep ``value`` nests (iteratively: a forged message cannot make this recurse)."""
    deepest, stack = 0, [(value, 1)]
    while stack:
        item, depth = stack.pop()
        if depth > MAX_DEPTH:
            return depth
        deepest = max(deepest, depth)
        if isinstance(item, dict):
            stack.extend((v, depth + 1) for v in item.values())
        elif isinstance(item, list):
            stack.extend((v, depth + 1) for v in item if isinstance(v, (dict, list)))
    return deepest


def _real(value: Any, low: float, high: float) -> bool:
    return isinstance(value, (int, float)) and not isinstance(value, bool) and low <= value <= high


_NUMBER_TYPES = frozenset({int, float})


def _numbers(value: Any) -> bool:
    """A list of numbers (JSON's true and false are not), checked at C speed: a 2,000-joint message
    has 8,000 of them."""
    return isinstance(value, list) and set(map(type, value)) <= _NUMBER_TYPES


def _joint_state(fields: dict[str, Any]) -> bool:
    """sensor_msgs/msg/JointState's fields with their types (the parent reads them as such); the
    names are interned, so the same joint names in many messages are held once."""
    header = fields.get("header", {})
    stamp = header.get("stamp", {}) if isinstance(header, dict) else None
    if not (isinstance(header, dict) and isinstance(stamp, dict) and isinstance(header.get("frame_id", ""), str)
            and all(type(stamp.get(k, 0)) is int for k in ("sec", "nanosec"))
            and all(_numbers(fields.get(k, [])) for k in ("position", "velocity", "effort"))):
        return False
    names = fields.get("name", [])
    if not isinstance(names, list):
        return False
    try:
        fields["name"] = list(map(sys.intern, names))  # TypeError for anything but text
    except TypeError:
        return False
    return True
