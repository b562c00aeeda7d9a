"""doctor --ros's verdicts on recorded looks, judged through the model of robot_state_publisher and RViz.

Each look is built as the probe records one (tests/data/live/bras.urdf on /robot_description, the
messages a node of each kind sends); the expected verdict follows from robot_state_publisher
3.3.3's callbackJointState and tf2's buffer, worked by hand in the comments. The same states
on real rclpy nodes: tests/doctor/test_live_doctor_model.py.
"""

from __future__ import annotations

import math

import pytest
from recorded_looks import NODE, RSP, T0, URDF, at_20_hz, codes, look, message, tutorial  # noqa: F401

from bras_kit.live.doctor import diagnose
from bras_kit.ros.graph import snapshot_from_json


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


def test_a_typo_topic_is_named_not_a_missing_node():
    typo = {"/joint_state": {"types": ["sensor_msgs/msg/JointState"], "publishers": [NODE], "subscribers": []},
            "/joint_states": {"types": ["sensor_msgs/msg/JointState"], "publishers": [],
                              "subscribers": [{**RSP, "reliability": "best_effort", "durability": "volatile"}]}}
    snapshot = look([], topics=typo)
    assert codes(snapshot, "error") == ["BK810"]
    assert "but /joint_state is published by '/animation_bras'" in message(snapshot, "BK810")


def test_a_robot_under_another_namespace_is_named_with_its_topic():
    moved = {"/robot_description": None,
             "/arm/robot_description": {"types": ["std_msgs/msg/String"],
                                        "publishers": [{**RSP, "node": "/arm/robot_state_publisher"}],
                                        "subscribers": []}}
    snapshot = look([tutorial(at) for at in at_20_hz()], topics=moved, descriptions=[])
    assert "BK801" in codes(snapshot, "error")
    assert "/arm/robot_state_publisher" in message(snapshot, "BK801") and "/arm/robot_description" in message(
        snapshot, "BK801")


def test_the_wrong_type_on_joint_states_is_named_not_a_silent_timer():
    wrong = {"/joint_states": {"types": ["std_msgs/msg/Float64MultiArray"], "publishers": [NODE], "subscribers": []}}
    snapshot = look([], topics=wrong)
    assert codes(snapshot, "error") == ["BK812"]
    assert "std_msgs/msg/Float64MultiArray" in message(snapshot, "BK812")


WRIST = URDF.replace("</robot>", """  <link name="main"/>
  <joint name="poignet" type="revolute"><parent link="avant_bras"/><child link="main"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/><limit effort="5" lower="-1.5" upper="1.5" velocity="1"/></joint>
</robot>""")
WRIST_NODE = {"node": "/animation_poignet", "reliability": "reliable", "durability": "volatile"}


def test_a_second_node_animating_the_wrist_is_not_a_jumping_arm():
    messages = []
    for at in at_20_hz():
        messages.append(tutorial(at))
        messages.append((at + 0.01, T0 + at + 0.01, ("poignet",), (0.5 * math.sin(at),)))
    snapshot = look(messages, publishers=(NODE, WRIST_NODE),
                    descriptions=[{"text": WRIST, "received": T0 + 0.1, "length": len(WRIST)}])
    assert [c for c in codes(snapshot) if c.startswith("BK8")] == []  # (BK308: the hand has no visual)


def test_two_sources_of_the_same_joints_still_jump():
    messages = []
    for at in at_20_hz():
        messages.append(tutorial(at))
        messages.append((at + 0.01, T0 + at + 0.01, ("epaule", "coude"), (0.0, 0.0)))
    assert "BK811" in codes(look(messages, publishers=(NODE, WRIST_NODE)), "warning")


def test_old_stamps_are_said_to_be_drawn_still():
    snapshot = look([tutorial(at, T0 + at - 30) for at in at_20_hz()])
    assert codes(snapshot) == ["BK815"]
    assert "RViz still draws the latest transforms" in message(snapshot, "BK815")


def test_degrees_where_radians_are_meant_are_named_as_degrees():
    messages = [(at, T0 + at, ("epaule", "coude"), (math.degrees(0.8 * math.sin(at)), math.degrees(0.1)))
                for at in at_20_hz()]
    snapshot = look(messages)
    found = [f for r in diagnose(snapshot) for f in r.findings]
    assert [f.code for f in found] == ["BK818", "BK818"]  # coude's 5.7 is past 2 rad too: degrees both
    assert all("a number of degrees" in str(f.message) for f in found)


def test_radians_past_the_limits_stay_limit_overruns():
    snapshot = look([(at, T0 + at, ("epaule", "coude"), (2.4 * math.sin(at), 0.1)) for at in at_20_hz()])
    assert codes(snapshot) == ["BK818"] and "above its upper limit" in message(snapshot, "BK818")


def test_two_nodes_of_one_name_are_counted_and_named():
    snapshot = look([tutorial(at) for at in at_20_hz()])
    shared = snapshot_from_json({"kind": "snapshot", "nodes": ["/animation_bras"], "started": T0, "ended": T0 + 3,
                                 "shared_names": {"/animation_bras": 2}})
    assert "BK844" not in codes(snapshot)
    assert "BK844" in codes(shared, "warning") and "2 nodes are named /animation_bras" in message(shared, "BK844")


def test_two_description_publishers_with_different_robots_are_named_with_what_differs():
    old = {**RSP, "node": "/old/robot_state_publisher"}
    topics = {"/robot_description": {"types": ["std_msgs/msg/String"], "publishers": [RSP, old], "subscribers": []}}
    descriptions = [{"text": URDF, "received": T0 + 0.1, "length": len(URDF)},
                    {"text": WRIST, "received": T0 + 0.2, "length": len(WRIST)}]
    snapshot = look([tutorial(at) for at in at_20_hz()], topics=topics, descriptions=descriptions)
    assert "BK845" in codes(snapshot, "error")
    assert "main, poignet" in message(snapshot, "BK845")
    # the same order or the other: the same verdict
    swapped = look([tutorial(at) for at in at_20_hz()], topics=topics, descriptions=descriptions[::-1])
    assert message(swapped, "BK845") == message(snapshot, "BK845")


def test_french_words_for_one_silent_node_do_not_speak_of_several():
    from bras_kit.core.i18n import say

    snapshot = look([])  # /animation_bras publishes, nothing came
    found = next(f for r in diagnose(snapshot) for f in r.findings if f.code == "BK812")
    text = say(found.message, "fr")
    assert "'/animation_bras'" in text and "publient" not in text and "n'ont" not in text


def test_a_joint_the_running_description_lacks_points_to_rebuild_and_relaunch():
    from bras_kit.core.i18n import say

    messages = [(at, T0 + at, ("epaule", "coude", "poignet"), (0.1, 0.2, 0.3)) for at in at_20_hz()]
    found = next(f for r in diagnose(look(messages)) for f in r.findings if f.code == "BK816")
    assert "colcon build" in say(found.hint, "en") and "recompilez" in say(found.hint, "fr")


def test_a_node_that_dies_after_its_first_message_is_named_too():
    snapshot = look([tutorial(0.5)], publishers=())
    assert codes(snapshot, "error") == ["BK842"]
