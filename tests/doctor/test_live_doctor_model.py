"""doctor --ros on real rclpy graphs whose flaw robot_state_publisher and RViz see and a rule per
symptom did not (issue 56): each scenario in a loopback-only namespace of its own (tests/realros.py),
built with the nodes of tests/data/live/, the doctor's verdict judged through the model of
robot_state_publisher 3.3.3 and tf2 (bras_kit/ros/rviz/).

The graph looks as Jazzy's does: the stand-ins of robot_state_publisher 3.3.3
(tests/data/live/state_publisher.py) and of rviz2 (tests/data/live/rviz2, started with -d as a
launch file starts it, its command line read by the doctor for the Fixed Frame) follow their
sources' topics, QoS and parameters.

The oracle of each scenario is the flaw put into the graph (a stamp taken once, a node that
raises after a second...): the finding must name it, and the healthy tutorial graph of
tests/doctor/test_live_doctor.py must stay without one.
"""

from __future__ import annotations

import concurrent.futures
import tempfile

import pytest
from live_graphs import (
    ANIMATION,
    DATA,
    STATE_PUBLISHER,
    URDF,
    _codes,
    _finding,
    _json,
    run_with_look,
)

pytestmark = pytest.mark.slow

JSON = ["--format", "json"]
WRIST_URDF = str(DATA / "bras_poignet.urdf")
RVIZ = ["rviz2", "-d", "bras.rviz"]  # relative, as rviz2's working folder reads it (the nodes run in DATA)
SCENARIOS = {
    "stamp-once": [STATE_PUBLISHER, ANIMATION + ["--stamp", "once"]],
    "whole-seconds": [STATE_PUBLISHER, ANIMATION + ["--stamp", "seconds"]],
    "coude-nan": [STATE_PUBLISHER, ANIMATION + ["--nan", "coude"]],
    "dies": [STATE_PUBLISHER, ANIMATION + ["--stop-after", "1.5"]],
    "typo-topic": [STATE_PUBLISHER, ANIMATION + ["--topic", "joint_state"]],
    "float-array": [STATE_PUBLISHER, ANIMATION + ["--float-array"]],
    "namespace": [["state_publisher.py", URDF, "--namespace", "/arm"], ANIMATION],
    "old-stamps": [STATE_PUBLISHER, ANIMATION + ["--stamp-offset", "-30"]],
    "shared-name": [STATE_PUBLISHER, ANIMATION, ANIMATION],
    "two-robots": [STATE_PUBLISHER, ["state_publisher.py", WRIST_URDF, "--name", "robot_state_publisher_neuf"],
                   ANIMATION],
    "wrist-node": [["state_publisher.py", WRIST_URDF], ANIMATION,
                   ANIMATION + ["--name", "animation_poignet", "--names", "poignet", "--positions", "1"]],
    "degrees": [STATE_PUBLISHER, ANIMATION + ["--degrees"]],
}
SCENARIOS = {name: nodes + [RVIZ] for name, nodes in SCENARIOS.items()}  # RViz beside each, as the launch starts it
LOGS = f"ROS_LOG_DIR={tempfile.gettempdir()}/bras-kit-test-ros-logs"  # rcl would log under HOME/.ros
HOME = str(DATA / "home")  # its .rviz2/default.rviz sets Fixed Frame base (what Save Config writes)
SCENARIOS.update({
    "rviz-map": [STATE_PUBLISHER, ANIMATION, ["rviz2", "-d", "bras_map.rviz"]],
    "rviz-f": [STATE_PUBLISHER, ANIMATION, RVIZ + ["-f", "/map"]],
    "rviz-home": [STATE_PUBLISHER, ANIMATION, [LOGS, f"HOME={HOME}", "rviz2"]],
    "rviz-default": [STATE_PUBLISHER, ANIMATION, [LOGS, f"HOME={DATA / 'nobody'}", "rviz2"]],
    "volatile-qos": [STATE_PUBLISHER + ["--volatile"], ANIMATION, RVIZ],
    "joins-late": [STATE_PUBLISHER, RVIZ, ANIMATION + ["--late", "7"]],
    "replaced": [STATE_PUBLISHER + ["--replace-after", "3.5", "--replace-with", WRIST_URDF], ANIMATION, RVIZ],
})

# the node that dies raises 1.5 s after the doctor's probe joins: a 7 s watch sees it publish, then
# fall silent;
# whole seconds step once a second: 6 s show several steps even when discovery is slow
WATCH = {"dies": ["--duration", "7"], "whole-seconds": ["--duration", "6"], "joins-late": ["--duration", "11"],
         "replaced": ["--duration", "8"]}


@pytest.fixture(scope="module")
def looks():
    with concurrent.futures.ThreadPoolExecutor(3) as pool:
        futures = {name: pool.submit(run_with_look, nodes, [JSON + WATCH.get(name, []), ["--lang", "fr"]])
                   for name, nodes in SCENARIOS.items()}
        results = {name: future.result() for name, future in futures.items()}
        SAVED.update({name: result[2] for name, result in results.items()})
        yield {name: result[0] for name, result in results.items()}


SAVED: dict[str, dict | None] = {}  # each scenario's look, as the first doctor saved it


def test_a_stamp_taken_once_keeps_the_arm_still(looks):
    (code, out), (_, fr) = looks["stamp-once"]
    document = _json(out)
    assert code == 1 and _codes(document, "error") == ["BK840"]
    assert "do not advance" in _finding(document, "BK840")["message"] and "BK840" in fr


def test_whole_second_stamps_move_the_arm_in_steps(looks):
    (code, out), _ = looks["whole-seconds"]
    document = _json(out)
    assert "BK843" in _codes(document, "warning") and _codes(document, "error") == []
    assert "steps of 1 s" in _finding(document, "BK843")["message"]


def test_a_nan_coude_is_refused_by_tf2(looks):
    (code, out), (_, fr) = looks["coude-nan"]
    document = _json(out)
    assert code == 1 and _codes(document, "error") == ["BK841"]
    assert "No transform from [avant_bras] to [base]" in _finding(document, "BK841")["message"]
    assert "TF_NAN_INPUT" in fr


def test_a_node_that_dies_during_the_watch_is_named(looks):
    (code, out), _ = looks["dies"]
    document = _json(out)
    assert code == 1 and "BK842" in _codes(document, "error")


def test_a_typo_topic_is_named_with_its_publisher(looks):
    (code, out), _ = looks["typo-topic"]
    document = _json(out)
    assert code == 1 and _codes(document, "error") == ["BK810"]
    message = _finding(document, "BK810")["message"]
    assert "but /joint_state is published by '/animation_bras'" in message


def test_the_wrong_type_on_joint_states_is_named(looks):
    (code, out), _ = looks["float-array"]
    document = _json(out)
    assert code == 1 and _codes(document, "error") == ["BK812"]
    assert "std_msgs/msg/Float64MultiArray" in _finding(document, "BK812")["message"]


def test_a_robot_under_a_namespace_is_named_with_its_topic(looks):
    (code, out), _ = looks["namespace"]
    document = _json(out)
    assert code == 1 and "BK801" in _codes(document, "error")
    assert "/arm/robot_description" in _finding(document, "BK801")["message"]


def test_old_stamps_that_advance_are_drawn(looks):
    (code, out), _ = looks["old-stamps"]
    document = _json(out)
    assert code == 0 and _codes(document, "error") == []
    assert "RViz still draws" in _finding(document, "BK815")["message"]


def test_two_nodes_of_one_name_are_counted_as_two_and_named(looks):
    (code, out), _ = looks["shared-name"]
    document = _json(out)
    assert "BK844" in _codes(document, "warning")
    assert "2 nodes are named /animation_bras" in _finding(document, "BK844")["message"]


def test_two_description_publishers_with_different_robots_are_named(looks):
    (code, out), (_, fr) = looks["two-robots"]
    document = _json(out)
    assert code == 1 and "BK845" in _codes(document, "error")
    assert "main, poignet" in _finding(document, "BK845")["message"] and "BK845" in fr


def test_a_second_node_animating_the_wrist_is_no_jumping_arm(looks):
    (code, out), _ = looks["wrist-node"]
    document = _json(out)
    # no warning nor error; the timeline (BK847, an info) may say a node was discovered late
    assert _codes(document, "error") + _codes(document, "warning") == [] and code == 0
    assert {c for c in _codes(document) if c.startswith("BK8")} <= {"BK847"}


def test_degrees_are_named_as_degrees(looks):
    (code, out), _ = looks["degrees"]
    document = _json(out)
    assert "BK818" in _codes(document, "warning")
    assert "a number of degrees" in _finding(document, "BK818")["message"]


def _timeline(document: dict) -> list[tuple[str, str]]:
    return [(event["event"], event.get("node", "")) for event in document["timeline"]]


def test_the_fixed_frame_is_read_from_the_d_file_of_the_running_rviz2(looks):
    (code, out), (_, fr) = looks["stamp-once"]
    frame = _json(out)["fixed_frame"]
    assert frame["frame"] == "base" and frame["source"] == "file"
    assert frame["path"] == str(DATA / "bras.rviz")
    assert "bras.rviz" in frame["words"] and "bras.rviz" in fr


def test_a_d_file_whose_fixed_frame_is_map_is_named(looks):
    (code, out), (_, fr) = looks["rviz-map"]
    document = _json(out)
    assert document["fixed_frame"]["frame"] == "map" and _codes(document, "warning") == ["BK846"]
    message = _finding(document, "BK846")["message"]
    assert "Frame [map] does not exist" in message and "bras_map.rviz" in message
    assert "Fixed Frame: base" in _finding(document, "BK846")["hint"] and "BK846" in fr


def test_rviz2_f_wins_over_its_file(looks):
    (code, out), _ = looks["rviz-f"]
    document = _json(out)
    assert document["fixed_frame"]["source"] == "argument" and document["fixed_frame"]["frame"] == "map"
    assert "-f map" in _finding(document, "BK846")["message"]


def test_without_d_rviz2_loads_the_users_saved_default(looks):
    (code, out), _ = looks["rviz-home"]
    document = _json(out)
    assert document["fixed_frame"] == {**document["fixed_frame"], "frame": "base", "source": "home",
                                       "path": f"{HOME}/.rviz2/default.rviz"}
    assert "BK846" not in _codes(document) and code == 0


def test_without_d_or_saved_default_rviz2_opens_on_map(looks):
    (code, out), _ = looks["rviz-default"]
    document = _json(out)
    assert document["fixed_frame"]["source"] == "default" and document["fixed_frame"]["frame"] == "map"
    assert _codes(document, "warning") == ["BK846"] and code == 0
    assert "window" in _finding(document, "BK846")["message"]


def test_a_qos_pair_is_named_in_rclpy_s_words(looks):
    (code, out), _ = looks["volatile-qos"]
    document = _json(out)
    pair = _finding(document, "BK820")["message"]
    assert "/rviz" in pair and "rclpy: ERROR: Volatile publisher and transient local subscription;" in pair


def test_a_node_that_dies_is_on_the_timeline(looks):
    (code, out), _ = looks["dies"]
    document = _json(out)
    events = _timeline(document)
    assert ("left", "/animation_bras") in events and ("silent-left", "") in events
    left = next(e["at"] for e in document["timeline"] if e["event"] == "left")
    silent = next(e["at"] for e in document["timeline"] if e["event"] == "silent-left")
    assert 1.0 <= silent <= left <= 7.5  # it fell silent, then the graph lost it


def test_a_node_that_joins_late_is_on_the_timeline(looks):
    (code, out), _ = looks["joins-late"]
    document = _json(out)
    assert ("joined", "/animation_bras") in _timeline(document)
    assert ("publishes", "/animation_bras") in _timeline(document)
    joined = next(e["at"] for e in document["timeline"] if e["event"] == "joined")
    assert joined >= 3.0 and code == 0  # well after discovery found the others


def test_a_description_replaced_during_the_watch_is_on_the_timeline_not_two_robots(looks):
    (code, out), _ = looks["replaced"]
    document = _json(out)
    assert "replaced" in [event for event, _ in _timeline(document)]
    assert "BK845" not in _codes(document)


@pytest.mark.parametrize("name", sorted(n for n in SCENARIOS if n not in WATCH))
def test_view_ros_gives_the_doctor_s_verdict_on_the_same_graph(looks, name):
    # the look doctor --ros saved, streamed to view --ros's feed as the probe streams it: one verdict
    from live_verdicts import doctor_findings, shifted_to_now, view_findings

    saved = SAVED[name]
    assert saved is not None
    data = shifted_to_now(saved)
    doctor = sorted(f.code for f in doctor_findings(data) if f.code != "BK847")
    view = sorted(f.code for f in view_findings(data) if f.code != "BK847")
    assert view == doctor and doctor == sorted(c for c in _codes(_json(looks[name][0][1])) if c != "BK847")
