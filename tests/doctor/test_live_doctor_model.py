"""doctor --ros on real rclpy graphs whose flaw robot_state_publisher and RViz see and a rule per
symptom did not (issue 56): each scenario in a loopback-only namespace of its own (tests/realros.py),
built with the nodes of tests/data/live/, the doctor's verdict judged through the model of
robot_state_publisher 3.3.3 and tf2 (bras_kit/ros/rviz/).

The oracle of each scenario is the flaw put into the graph (a stamp taken once, a node that
raises after a second...): the finding must name it, and the healthy tutorial graph of
tests/doctor/test_live_doctor.py must stay without one.
"""

from __future__ import annotations

import concurrent.futures

import pytest
from live_graphs import ANIMATION, DATA, STATE_PUBLISHER, URDF, _codes, _finding, _json, _run

pytestmark = pytest.mark.slow

JSON = ["--format", "json"]
WRIST_URDF = str(DATA / "bras_poignet.urdf")
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

# the node that dies raises 1.5 s after the doctor's probe joins: a 7 s watch sees it publish, then
# fall silent;
# whole seconds step once a second: 6 s show several steps even when discovery is slow
WATCH = {"dies": ["--duration", "7"], "whole-seconds": ["--duration", "6"]}


@pytest.fixture(scope="module")
def looks():
    with concurrent.futures.ThreadPoolExecutor(3) as pool:
        futures = {name: pool.submit(_run, nodes, [JSON + WATCH.get(name, []), ["--lang", "fr"]])
                   for name, nodes in SCENARIOS.items()}
        yield {name: future.result()[0] for name, future in futures.items()}


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
    assert [c for c in _codes(document) if c.startswith("BK8")] == [] and code == 0


def test_degrees_are_named_as_degrees(looks):
    (code, out), _ = looks["degrees"]
    document = _json(out)
    assert "BK818" in _codes(document, "warning")
    assert "a number of degrees" in _finding(document, "BK818")["message"]
