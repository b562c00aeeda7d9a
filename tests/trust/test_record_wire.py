"""The record of a run as it crosses from the node's process (the learner's) to bras-kit's: typed,
bounded, names re-checked; and the node's prints kept as a bounded head and tail.

Oracles: ROS 2's name rules written here as regular expressions from rmw's headers
(validate_node_name.h, validate_full_topic_name.h: 255 and 255 - 8 characters) and rmw's own
test cases; hand-made records with their expected values; for the head and tail, the whole text
kept by the test and sliced.
"""

from __future__ import annotations

import json
import re

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from bras_kit.ros import record_wire
from bras_kit.ros.capture import HeadTail
from bras_kit.ros.record_wire import WireError, read_record, write_record

NODE = re.compile(r"[A-Za-z_][A-Za-z0-9_]{0,254}")
TOPIC = re.compile(r"(/[A-Za-z_][A-Za-z0-9_]*)+")
SUMMARY = {"target": "bras_description animation", "source": "bras_description/animation.py",
           "function": "main", "duration": 10.0, "end": 10.0, "ended": "duration", "failure": None,
           "dropped": 0, "nodes": ["animation"], "rate_sleeps": 0, "wall_seconds": 0.5, "start_ns": 17,
           "publishers": [["animation", "/joint_states", "sensor_msgs/msg/JointState", "bras_description/animation.py", 12]],
           "subscriptions": [], "timers": [["animation", 0.05, "bras_description/animation.py", 14]],
           "output": "hello\n", "output_tail": "", "output_dropped": 0, "output_dropped_lines": 0,
           "split_strings": [], "blocked": [["write", "/home/x", "bras_description/animation.py", 20]]}
JOINT_STATE = {"header": {"stamp": {"sec": 3, "nanosec": 50}, "frame_id": ""}, "name": ["epaule", "coude"],
               "position": [0.1, -0.2], "velocity": [], "effort": []}


def line(*entry) -> bytes:
    return json.dumps(list(entry)).encode() + b"\n"


def record(summary=None, lines=(), logs=()) -> bytes:
    return write_record(dict(SUMMARY if summary is None else summary), list(lines), list(logs))


def test_a_record_reads_back_as_the_stand_in_wrote_it():
    data = record(lines=[line("m", 50_000_000, "animation", "/joint_states", "sensor_msgs/msg/JointState", JOINT_STATE)],
                  logs=[record_wire.log_line(10**9, "INFO", "animation", "started")])
    r = read_record(data)
    assert (r.target, r.source, r.function, r.ended, r.end, r.start_ns) == (
        "bras_description animation", "bras_description/animation.py", "main", "duration", 10.0, 17)
    assert r.nodes == ["animation"] and r.publishers[0].topic == "/joint_states" and r.publishers[0].line == 12
    assert r.timers[0].period == 0.05 and r.blocked[0].detail == "/home/x" and r.output == "hello\n"
    assert [(m.time, m.node, m.topic, m.fields) for m in r.messages] == [(0.05, "animation", "/joint_states", JOINT_STATE)]
    assert r.logs == [(1.0, "INFO", "animation", "started")]
    assert (r.refused_count, r.overflow) == (0, {})


@pytest.mark.parametrize("name, valid", [  # rmw/test/test_validate_node_name.cpp, test_validate_full_topic_name.cpp
    ("my_node_42", True), ("_private", True), ("42node", False), ("my-node", False), ("my node", False),
    ("", False), ("n" * 255, True), ("n" * 256, False), ("nœud", False), ("a\x1b]0;x\x07", False)])
def test_node_names_are_kept_as_rmw_validates_them(name, valid):
    r = read_record(record(dict(SUMMARY, nodes=[name])))
    assert r.nodes == ([name] if valid else [])
    assert r.refused_count == (0 if valid else 1)


@pytest.mark.parametrize("topic, valid", [
    ("/joint_states", True), ("/ns/joint_states", True), ("/_a/b_1", True), ("joint_states", False),
    ("/", False), ("/joint_states/", False), ("/a//b", False), ("/1abc", False), ("/a/~/b", False),
    ("/{node}", False), ("/a b", False), ("/" + "t" * 246, True), ("/" + "t" * 247, False),
    ("/joint_states\x1b[2J", False), ("/joint\u202estates", False)])
def test_topics_are_kept_as_rmw_validates_full_names(topic, valid):
    endpoint = ["animation", topic, "sensor_msgs/msg/JointState", "", 0]
    r = read_record(record(dict(SUMMARY, publishers=[endpoint]),
                           lines=[line("m", 0, "animation", topic, "sensor_msgs/msg/JointState", JOINT_STATE)]))
    assert [p.topic for p in r.publishers] == ([topic] if valid else [])
    assert [m.topic for m in r.messages] == ([topic] if valid else [])


@settings(max_examples=150, deadline=None)
@given(st.text(max_size=300))
def test_any_name_is_kept_exactly_when_rmw_would_take_it(name):
    r = read_record(record(dict(SUMMARY, nodes=[name], publishers=[["animation", name, "std_msgs/msg/String", "", 1]])))
    assert r.nodes == ([name] if NODE.fullmatch(name) else [])
    assert [p.topic for p in r.publishers] == ([name] if TOPIC.fullmatch(name) and len(name) <= 247 else [])


JSON = st.recursive(st.none() | st.booleans() | st.integers() | st.floats(allow_nan=False) | st.text(max_size=20),
                    lambda inner: st.lists(inner, max_size=5) | st.dictionaries(st.text(max_size=8), inner, max_size=5),
                    max_leaves=30)
FIELDS = ["target", "source", "function", "duration", "end", "ended", "failure", "dropped", "nodes", "publishers",
          "subscriptions", "timers", "rate_sleeps", "wall_seconds", "start_ns", "output", "output_tail",
          "output_dropped", "split_strings", "blocked", "overflow"]


@settings(max_examples=60, deadline=None)
@given(st.dictionaries(st.sampled_from(FIELDS), JSON), st.lists(JSON, max_size=6))
def test_a_forged_record_is_typed_and_checked_whatever_it_holds(summary, entries):
    """Whatever the node's process writes, the parent gets a Recording of the declared types, with
    valid ROS names only, or WireError; never another exception."""
    lines = [json.dumps(e).encode() + b"\n" for e in entries]
    lines += [line("m", 1, "n", "/t", "sensor_msgs/msg/JointState", e) for e in entries]
    data = json.dumps(summary).encode() + b"\n" + b"".join(lines)
    r = read_record(data)
    assert all(NODE.fullmatch(n) for n in r.nodes + [p.node for p in r.publishers + r.subscriptions])
    assert all(TOPIC.fullmatch(p.topic) for p in r.publishers + r.subscriptions)
    assert isinstance(r.target, str) and isinstance(r.end, float) and r.ended in record_wire.ENDINGS
    assert all(isinstance(t.period, float) for t in r.timers) and isinstance(r.rate_sleeps, int)
    assert all(not p.path.startswith(("/", "..")) for p in r.publishers)
    for m in r.messages:
        assert all(isinstance(n, str) for n in m.fields.get("name", []))
        assert all(type(v) in (int, float) for k in ("position", "velocity", "effort") for v in m.fields.get(k, []))
    if r.failure is not None:
        assert isinstance(r.failure.detail, str) and r.failure.kind.isidentifier() or r.failure.kind == "?"


def test_bytes_that_are_no_record_are_refused_whole():
    for data in (b"", b"not json\n", b"[1, 2]\n", b"[" * 100_000 + b"\n"):
        with pytest.raises(WireError):
            read_record(data)
    with pytest.raises(WireError):
        read_record({"target": "a Recording sent as an object"})


def test_references_to_one_big_line_count_against_the_bounds_as_copies(monkeypatch):
    monkeypatch.setattr(record_wire, "MAX_MESSAGE_BYTES", 4 << 20)  # the bound's arithmetic, quicker
    big = line("m", 0, "n", "/joint_states", "sensor_msgs/msg/JointState",
               {"name": [f"joint_{k}" for k in range(2000)], "position": [0.5] * 2000})
    data = write_record(dict(SUMMARY), [big] * 200_000, [])
    kept = record_wire.MAX_MESSAGE_BYTES // len(big)
    assert len(data) < record_wire.MAX_MESSAGE_BYTES + 4096
    r = read_record(data)
    assert len(r.messages) == kept and r.overflow == {"messages": 200_000 - kept}
    assert r.messages[0].fields["name"] is not r.messages[1].fields["name"]  # fresh objects, not references


def test_an_over_long_line_is_skipped_and_the_next_one_read():
    data = (record() + b'["m",0,"n","/t","std_msgs/msg/String",{"data":"' + b"x" * (3 << 20) + b'"}]\n'
            + line("m", 0, "n", "/t", "std_msgs/msg/String", {"data": "ok"}))
    r = read_record(data)
    assert [m.fields for m in r.messages] == [{"data": "ok"}] and r.overflow == {"line": 1}


def test_a_joint_state_of_the_wrong_types_is_left_out():
    wrong = [dict(JOINT_STATE, position=["0.1"]), dict(JOINT_STATE, name=[1, 2]), dict(JOINT_STATE, position=[True]),
             dict(JOINT_STATE, header={"stamp": {"sec": "3"}}), dict(JOINT_STATE, name="epaule")]
    r = read_record(record(lines=[line("m", 0, "n", "/joint_states", "sensor_msgs/msg/JointState", w) for w in wrong]))
    assert r.messages == [] and r.refused_count == len(wrong)


def test_paths_out_of_the_package_are_left_out():
    frames = [["../../etc/passwd", 1, "main", ""], ["/etc/passwd", 2, "main", ""], ["a/./b.py", 3, "f", ""],
              ["bras_description/animation.py", 4, "tick", "x = 1"]]
    failure = {"kind": "ValueError", "detail": "boom", "time": 1.0, "frames": frames, "context": {}}
    r = read_record(record(dict(SUMMARY, source="../x.py", failure=failure)))
    assert r.source == "" and [f.path for f in r.failure.frames] == ["", "", "", "bras_description/animation.py"]
    assert r.refused_count == 4


def test_logs_past_their_count_are_counted_not_kept():
    logs = [record_wire.log_line(k, "INFO", "n", "x") for k in range(record_wire.MAX_LOGS + 5)]
    r = read_record(record(logs=logs))
    assert len(r.logs) == record_wire.MAX_LOGS and r.overflow == {"logs": 5}


# ------------------------------------------------------------------------------ the head and the tail

@settings(max_examples=200, deadline=None)
@given(st.lists(st.text(alphabet="ab\n", max_size=40), max_size=40), st.integers(0, 30), st.integers(0, 30))
def test_the_head_and_tail_are_the_first_and_last_characters_written(writes, head, tail):
    stream = HeadTail(head, tail)
    for text in writes:
        assert stream.write(text) == len(text)
    whole = "".join(writes)
    kept = stream.kept()
    assert kept.head == whole[:head]
    rest = whole[len(kept.head):]
    assert kept.tail == (rest[len(rest) - tail:] if len(rest) > tail else rest)
    middle = rest[:len(rest) - len(kept.tail)]
    assert (kept.dropped_chars, kept.dropped_lines) == (len(middle), middle.count("\n"))


def test_the_head_and_tail_refuse_what_print_would_refuse():
    with pytest.raises(TypeError):
        HeadTail().write(b"bytes")  # type: ignore[arg-type]
