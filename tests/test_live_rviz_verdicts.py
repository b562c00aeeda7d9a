"""doctor --ros's verdicts on recorded looks, judged through the model of robot_state_publisher and RViz.

Each look is built as the probe records one (tests/data/live/bras.urdf on /robot_description, the
messages a node of each kind sends); the expected verdict follows from robot_state_publisher
3.3.3's callbackJointState and tf2's buffer, worked by hand in the comments. The same states
on real rclpy nodes: tests/test_live_doctor_model.py.
"""

from __future__ import annotations

import math
from pathlib import Path

import pytest

from bras_kit.live.doctor import diagnose
from bras_kit.ros.graph import snapshot_from_json

URDF = (Path(__file__).parent / "data" / "live" / "bras.urdf").read_text()
T0 = 1_800_000_000.0  # the watch starts here (seconds, the probe's clock)
RSP = {"node": "/robot_state_publisher", "reliability": "reliable", "durability": "transient_local"}
NODE = {"node": "/animation_bras", "reliability": "reliable", "durability": "volatile"}


def look(messages, *, seconds=3.0, publishers=(NODE,), topics=None, nodes=None, descriptions=None):
    """A snapshot as the probe prints it: ``messages`` are (received offset, stamp s, names, positions)."""
    states = [{"received": T0 + at, "stamp": [int(stamp), round((stamp - int(stamp)) * 1e9)],
               "name": list(names), "position": list(positions)} for at, stamp, names, positions in messages]
    all_topics = {"/robot_description": {"types": ["std_msgs/msg/String"], "publishers": [RSP], "subscribers": []},
                  "/joint_states": {"types": ["sensor_msgs/msg/JointState"], "publishers": list(publishers),
                                    "subscribers": [{**RSP, "reliability": "best_effort",
                                                     "durability": "volatile"}]}}
    all_topics.update(topics or {})
    return snapshot_from_json({
        "kind": "snapshot", "domain": 7, "range": "LOCALHOST", "rmw": "rmw_fastrtps_cpp",
        "started": T0, "ended": T0 + seconds,
        "nodes": nodes or ["/robot_state_publisher", "/animation_bras"],
        "topics": {k: v for k, v in all_topics.items() if v is not None},
        "descriptions": descriptions if descriptions is not None else [
            {"text": URDF, "received": T0 + 0.1, "length": len(URDF)}],
        "joint_states": states})


def tutorial(at: float, stamp: float | None = None, *, t: float | None = None, names=("epaule", "coude")):
    angle = at if t is None else t
    return (at, T0 + at if stamp is None else stamp, names, (0.8 * math.sin(angle), 1.2 * math.sin(0.7 * angle)))


def codes(snapshot, severity=None):
    found = [f for r in diagnose(snapshot) for f in r.findings]
    return sorted(f.code for f in found if severity is None or f.severity == severity)


def message(snapshot, code) -> str:
    from bras_kit.core.i18n import say

    found = next(f for r in diagnose(snapshot) for f in r.findings if f.code == code)
    return say(found.message, "en")


def at_20_hz(seconds=3.0, start=0.05):
    return [start + i * 0.05 for i in range(int(seconds / 0.05) - 1)]


def test_the_tutorial_node_is_healthy():
    assert codes(look([tutorial(at) for at in at_20_hz()])) == []


def test_an_unchanging_stamp_keeps_the_arm_still():
    # stamp taken once at start: the first message passes (a new joint, 0 + 50 ms), then never again
    snapshot = look([tutorial(at, T0) for at in at_20_hz()])
    assert codes(snapshot, "error") == ["BK840"]
    assert "1 of the 59" in message(snapshot, "BK840") and "do not advance" in message(snapshot, "BK840")


def test_whole_second_stamps_move_the_arm_in_steps():
    # 20 messages a second, stamps cut to the second: one passes per second, 3 or 4 in the watch
    snapshot = look([tutorial(at, float(int(T0 + at))) for at in at_20_hz()])
    assert codes(snapshot) == ["BK843"]
    assert "steps of 1 s" in message(snapshot, "BK843")


def test_stamps_30_s_old_but_advancing_are_fine():
    snapshot = look([tutorial(at, T0 + at - 30) for at in at_20_hz()])
    assert "BK840" not in codes(snapshot) and "BK843" not in codes(snapshot)
    assert codes(snapshot, "error") == []


@pytest.mark.parametrize("bad", [math.nan, math.inf])
def test_a_coude_not_finite_is_refused_by_tf2(bad):
    snapshot = look([(at, T0 + at, ("epaule", "coude"), (0.1 * at, bad)) for at in at_20_hz()])
    assert codes(snapshot, "error") == ["BK841"]
    text = message(snapshot, "BK841")
    assert "'coude'" in text and "TF_NAN_INPUT" in text and "No transform from [avant_bras] to [base]" in text


def test_a_nan_now_and_then_keeps_the_last_valid_angle():
    messages = [(at, T0 + at, ("epaule", "coude"), (0.1, math.nan if i % 10 == 9 else 0.1 * i))
                for i, at in enumerate(at_20_hz())]
    snapshot = look(messages)
    assert codes(snapshot, "error") == ["BK841"] and "last valid angle" in message(snapshot, "BK841")


def test_a_node_that_dies_during_the_watch_stopped_the_arm():
    snapshot = look([tutorial(at) for at in at_20_hz() if at < 1.2], publishers=())
    assert "BK842" in codes(snapshot, "error")
    assert "nothing publishes /joint_states any more" in message(snapshot, "BK842")


def test_a_node_that_stops_publishing_but_stays_is_named_too():
    snapshot = look([tutorial(at) for at in at_20_hz() if at < 1.2])
    assert codes(snapshot, "error") == ["BK842"]


def test_a_5_hz_node_has_not_stopped():
    snapshot = look([tutorial(0.05 + i * 0.2) for i in range(14)])
    assert codes(snapshot) == ["BK813"]


def test_sizes_zero_stamps_unknown_names_are_named_once_by_their_own_rule():
    assert codes(look([(at, T0 + at, ("epaule", "coude"), (0.1,)) for at in at_20_hz()]), "error") == ["BK819"]
    assert codes(look([tutorial(at, 0.0) for at in at_20_hz()]), "error") == ["BK814"]
    assert "BK840" not in codes(look([tutorial(at, names=("shoulder", "elbow")) for at in at_20_hz()]))
