"""What learners copy, answered as Jazzy answers it (issue 44, the node categories).

Each behaviour is decided by rclpy 7.1.6 (the PyPI wheel's source, cited) and checked against
the real rclpy by tests/ros/test_rclpy_oracle.py, which runs these same nodes under both.
"""

from __future__ import annotations

import json

import pytest
from paths import TESTS

from bras_kit.run import run_node
from bras_kit.run.findings import run_findings

JAZZY = TESTS / "data" / "run" / "jazzy"


def _codes(recording, robot=None, lang="en"):
    return [(f.code, f.line) for f in run_findings(recording, robot, lang=lang)]


def test_init_args_remapping_sends_on_the_remapped_topic():
    # rclpy 7.1.6 context.py:99-101 hands init's args to rcl_init: global remap rules, applied by
    # rcl_node_resolve_name when the publisher is made
    recording = run_node(str(JAZZY / "init_args_remap.py"), duration=1.0)
    assert recording.ended == "duration"
    assert [p.topic for p in recording.publishers] == ["/joint_states"]
    assert len(recording.on("/joint_states")) == 20
    assert not [c for c, _ in _codes(recording) if c == "BK644"]


def test_an_unknown_ros_argument_given_to_init_is_rclpys_unknown_ros_args_error():
    # rclpy/src/rclpy/context.cpp:119 -> utils.cpp:277: the unparsed words, by their repr
    recording = run_node(str(JAZZY / "init_unknown_ros_arg.py"), duration=1.0)
    assert recording.failure.kind == "UnknownROSArgsError"
    assert recording.failure.detail == "['--log-level warn']"
    assert recording.failure.frames[-1].line == 7


def test_a_service_nobody_calls_lets_the_node_run_and_publish():
    recording = run_node(str(JAZZY / "service_never_called.py"), duration=1.0)
    assert recording.ended == "duration" and recording.failure is None
    assert len(recording.on("/joint_states")) == 20
    assert _codes(recording) == []


@pytest.mark.parametrize("lang, words", [("en", "JointState is not in std_msgs.msg but in sensor_msgs.msg"),
                                         ("fr", "JointState n'est pas dans std_msgs.msg mais dans sensor_msgs.msg")])
def test_a_type_imported_from_the_wrong_package_is_named_with_the_package_it_lives_in(lang, words):
    recording = run_node(str(JAZZY / "wrong_import_type.py"), duration=1.0)
    assert recording.failure.kind == "ImportError"
    assert recording.failure.detail.startswith("cannot import name 'JointState' from 'std_msgs.msg'")
    [finding] = run_findings(recording, None, lang=lang)
    assert (finding.code, finding.line) == ("BK652", 5)
    assert words in finding.text(lang)
    assert "from sensor_msgs.msg import JointState" in finding.hint_text(lang)


def test_a_name_given_one_string_goes_out_as_its_letters_and_is_named():
    # rosidl_generator_py (Jazzy) keeps the str, the C conversion iterates it (PySequence_Fast)
    recording = run_node(str(JAZZY / "names_as_one_string.py"), duration=1.0)
    assert recording.ended == "duration"
    messages = recording.on("/joint_states")
    assert len(messages) == 20
    assert messages[0].fields["name"] == list("epaule, coude")
    found = run_findings(recording, None, lang="en")
    assert [(f.code, f.line) for f in found] == [("BK646", 21)]
    assert "'epaule, coude'" in found[0].text() and "['epaule', 'coude']" in found[0].hint_text()
    [french] = run_findings(recording, None, lang="fr")
    assert "13 lettres" in french.text("fr") and "['epaule', 'coude']" in french.hint_text("fr")


def test_the_recording_holds_what_the_node_sent():
    recording = run_node(str(JAZZY / "velocity_left_unset.py"), duration=0.3)
    messages = recording.on("/joint_states")
    assert [m.fields["velocity"] for m in messages] == [[]] * 6
    assert [m.fields["effort"] for m in messages] == [[], [], [0.5], [], [], [0.5]]
    stamps = [m.fields["header"]["stamp"] for m in messages]
    assert stamps[1] == {"sec": 0, "nanosec": 0}  # left unset on even ticks
    assert stamps[0] == {"sec": recording.start_ns // 10**9, "nanosec": 50_000_000}


def test_run_output_json_holds_the_messages_as_sent(run_cli, tmp_path):
    out = tmp_path / "states.json"
    code, _, err = run_cli("run", str(JAZZY / "velocity_left_unset.py"), "--duration", "0.3", "--quiet",
                           "-o", str(out), "--lang", "en")
    assert code == 0, err
    sent = json.loads(out.read_text(encoding="utf-8"))
    assert [m["velocity"] for m in sent] == [[]] * 6
    assert [m["effort"] for m in sent] == [[], [], [0.5], [], [], [0.5]]
    assert [m["stamp"]["sec"] == 0 for m in sent] == [False, True] * 3


def test_run_output_bag_holds_the_messages_as_sent(run_cli, tmp_path):
    from rosbags.highlevel import AnyReader

    out = tmp_path / "states.mcap"
    code, _, err = run_cli("run", str(JAZZY / "velocity_left_unset.py"), "--duration", "0.3", "--quiet",
                           "-o", str(out), "--lang", "en")
    assert code == 0, err
    with AnyReader([tmp_path / "states"]) as reader:
        connections = [c for c in reader.connections if c.topic == "/joint_states"]
        sent = [reader.deserialize(raw, c.msgtype) for c, _, raw in reader.messages(connections)]
    assert [len(m.velocity) for m in sent] == [0] * 6
    assert [list(m.effort) for m in sent] == [[], [], [0.5], [], [], [0.5]]
    assert [(m.header.stamp.sec, m.header.stamp.nanosec) for m in sent][:2] == [(1_767_225_600, 50_000_000), (0, 0)]
    assert [list(m.name) for m in sent] == [["epaule", "coude"]] * 6


def test_validate_run_takes_a_single_node_file(run_cli):
    code, out, err = run_cli("validate", str(JAZZY / "names_as_one_string.py"), "--run", "--duration", "1",
                             "--lang", "en")
    assert code == 1, err
    assert "BK646" in out and "BK100" not in out
    assert "names_as_one_string.py:21" in out


@pytest.mark.parametrize("node, words, fix", [
    # Python's ImportError names the module Jazzy's apt install holds: sensor_msgs/__init__.py is empty
    ("import_without_msg.py", "JointState is not in sensor_msgs but in sensor_msgs.msg",
     "from sensor_msgs.msg import JointState"),
    ("import_misspelt_type.py", "Jazzy has no JointSate; the closest is JointState, in sensor_msgs.msg",
     "write from sensor_msgs.msg import JointState"),
])
def test_other_failing_imports_of_a_message_are_named(node, words, fix):
    recording = run_node(str(JAZZY / node), duration=1.0)
    assert recording.failure.kind == "ImportError"
    [finding] = run_findings(recording, None, lang="en")
    assert (finding.code, finding.line) == ("BK652", 5)
    assert words in finding.text("en") and fix in finding.hint_text("en")


def test_validate_without_run_says_a_node_file_is_checked_by_running_it(run_cli):
    code, out, err = run_cli("validate", str(JAZZY / "names_as_one_string.py"), "--lang", "en")
    assert code == 2 and "BK100" not in out
    assert "a node is checked by running it" in err and "--run" in err
