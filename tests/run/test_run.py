"""bras-kit run: the learner's own node, with no ROS install, against the stand-in for rclpy.

Oracles: the tutorial's formulas (0.8 sin t, 1.2 sin 0.7t at t = 0.05 k), the 20 Hz timer's
stamps, the scaffolded package's own motion.py, and what real rclpy does with each beginner
node of the table below (with the file of rclpy or rosidl that says so).
"""

from __future__ import annotations

import importlib.util
import math
import sys

import pytest
from paths import TESTS

from bras_kit.model.authoring import load
from bras_kit.run import NodeRunError, joint_states, run_node
from bras_kit.run.findings import run_findings
from bras_kit.run.node import robot_of

DATA = TESTS / "data" / "run"
TUTORIAL = DATA.parent / "tutorial_package"  # the tutorial's package exactly as printed (shared with the validator's tests)
NODES = DATA / "nodes"
START = 1_767_225_600  # the simulated wall clock's start, in seconds


@pytest.fixture(scope="module")
def tutorial_run():
    return run_node(str(TUTORIAL), "animation", duration=10.0)


@pytest.fixture(scope="module")
def robot():
    return load(str(TUTORIAL / "urdf" / "bras.urdf"))


def test_tutorial_node_positions_follow_its_two_sines_tick_by_tick(tutorial_run):
    messages = tutorial_run.joint_state_messages()
    assert len(messages) == 200  # 10 s at 20 Hz, the first tick at t = 0.05 s
    for k, message in enumerate(messages, start=1):
        t = 0.05 * k
        assert message.time == pytest.approx(t, abs=1e-12)
        assert message.fields["name"] == ["epaule", "coude"]
        # the node adds 0.05 to t at each tick, so its t carries float rounding: 1e-12
        assert message.fields["position"] == pytest.approx([0.8 * math.sin(t), 1.2 * math.sin(0.7 * t)], abs=1e-12)


def test_tutorial_node_stamps_are_50_ms_apart_on_the_node_clock(tutorial_run):
    stamps = [m.fields["header"]["stamp"] for m in tutorial_run.joint_state_messages()]
    nanoseconds = [s["sec"] * 10**9 + s["nanosec"] for s in stamps]
    assert nanoseconds[0] == START * 10**9 + 50_000_000
    assert {b - a for a, b in zip(nanoseconds, nanoseconds[1:])} == {50_000_000}


def test_tutorial_node_runs_ten_simulated_seconds_and_is_stopped_like_ctrl_c(tutorial_run):
    assert tutorial_run.ended == "duration" and tutorial_run.end == 10.0
    assert tutorial_run.nodes == ["animation_bras"]
    assert [(p.topic, p.type, p.path, p.line) for p in tutorial_run.publishers] == [
        ("/joint_states", "sensor_msgs/msg/JointState", "bras_description/animation.py", 9)]
    assert [(t.period, t.line) for t in tutorial_run.timers] == [(0.05, 10)]


def test_tutorial_node_has_no_finding(tutorial_run, robot):
    assert run_findings(tutorial_run, robot, lang="en") == []


def test_recorded_states_match_the_formulas(tutorial_run):
    states = joint_states(tutorial_run)
    assert states.names == ["epaule", "coude"]
    t = states.times
    assert states.positions[:, 0] == pytest.approx(0.8 * __import__("numpy").sin(t), abs=1e-12)


def test_stand_in_never_reaches_the_parent_process(tutorial_run):
    assert "rclpy" not in sys.modules and "sensor_msgs" not in sys.modules
    assert importlib.util.find_spec("_bras_sim") is None  # the stand-in folder is not on sys.path


# What real rclpy (and the generated messages) do with each beginner node; the run must agree.
# (node, how it ends, failure class or None, run rule codes)
BEGINNER_NODES = [
    # rcl validates names only by syntax: 'joint_state' is a legal topic (rcl/validate_topic_name.c),
    # robot_state_publisher simply never hears it
    ("wrong_topic.py", "duration", None, ["BK644"]),
    # nothing in rclpy converts units: 45 and 90 are published as radians
    ("degrees.py", "duration", None, ["BK649", "BK649"]),
    # spin with no timer waits forever (rclpy/executors.py wait_for_ready_callbacks)
    ("no_timer.py", "duration", None, ["BK644"]),
    ("publish_forgotten.py", "duration", None, ["BK644"]),
    # an exception in a timer callback leaves rclpy.spin (rclpy/executors.py: handler() re-raises)
    ("raises_at_tick_3.py", "error", "IndexError", ["BK640"]),
    ("while_ok_sleep.py", "duration", None, []),
    # KeyboardInterrupt is what ros2 run's Ctrl-C raises in the node's Python code
    ("never_returns.py", "duration", None, ["BK644"]),
    ("ignores_ctrl_c.py", "stopped", None, ["BK644"]),
    # rosidl_generator_py (jazzy) resource/_msg.py.em:440, 604: no check unless
    # ROS_PYTHON_CHECK_FIELDS=1, array.array('d', [0, 1]) takes the integers
    ("integer_positions.py", "returned", None, ["BK650"]),
    # rclpy/node.py: raise NotInitializedException('cannot create node')
    ("node_before_init.py", "error", "NotInitializedException", ["BK640"]),
    # rclpy 7.1.6 executors.py:600-606: a destroyed node has no entities left; spin waits until
    # Ctrl-C (the real rclpy does so: tests/ros/test_rclpy_oracle.py)
    ("spin_destroyed.py", "duration", None, ["BK644"]),
    # rmw/src/validate_node_name.c: only alphanumerics and '_' (rclpy/validate_node_name.py raises)
    ("bad_node_name.py", "error", "InvalidNodeNameException", ["BK640"]),
    ("stamp_zero_wrong_names.py", "duration", None, ["BK646", "BK647", "BK650"]),
    # rcl/validate_topic_name.c: alphanumerics, '_', '~', '{', '}' and '/' only (rclpy/validate_topic_name.py raises)
    ("topic_with_space.py", "error", "InvalidTopicNameException", ["BK640"]),
    # rclpy/context.py Context.init: RuntimeError('Context.init() must only be called once')
    ("init_twice.py", "error", "RuntimeError", ["BK640"]),
    # rclpy/publisher.py Publisher.publish: raise TypeError('Expected {}, got {}')
    ("publishes_wrong_type.py", "error", "TypeError", ["BK640"]),
    # contained (bras_kit.trust.contain), a node writes only in the folder it runs in: /tmp is read-only
    ("logs_to_tmp.py", "error", "OSError", ["BK640", "BK659"]),
    # rclpy/timer.py Rate.sleep(): waits for a timer an executor must spin in another thread
    ("rate_loop.py", "duration", None, ["BK643"]),
    ("flood.py", "storm", None, ["BK642", "BK650"]),
    # the usual cure: rclpy.spin in a thread, so the rate's timer is spun (rclpy/timer.py Rate)
    ("spin_in_thread.py", "duration", None, []),
    # a thread that only sleeps: the main thread returns, Python waits for it (threading._shutdown)
    ("other_thread.py", "returned", None, ["BK644"]),
    ("uses_action.py", "not_simulated", "NotSimulated", ["BK641"]),
    ("twice_per_tick.py", "duration", None, ["BK651"]),
    ("nan_and_lengths.py", "duration", None, ["BK645", "BK648"]),
]


@pytest.mark.parametrize("node, ended, failure, codes", BEGINNER_NODES, ids=[row[0] for row in BEGINNER_NODES])
def test_beginner_node_behaves_as_with_real_rclpy(node, ended, failure, codes, robot):
    recording = run_node(str(NODES / node), duration=2.0)
    assert recording.ended == ended
    assert (recording.failure.kind if recording.failure else None) == failure
    assert sorted(f.code for f in run_findings(recording, robot, lang="en")) == codes


def test_exception_at_tick_3_shows_the_learners_line_and_the_simulated_time():
    recording = run_node(str(NODES / "raises_at_tick_3.py"), duration=2.0)
    assert recording.end == pytest.approx(0.15)  # third tick of a 0.05 s timer
    assert len(recording.messages) == 2
    frames = recording.failure.frames
    # main() -> rclpy.spin -> the timer callback: only the learner's two frames are kept
    assert [(f.path, f.function) for f in frames] == [("raises_at_tick_3.py", "main"), ("raises_at_tick_3.py", "tick")]
    source = (NODES / "raises_at_tick_3.py").read_text(encoding="utf-8").splitlines()
    assert "self.angles[self.ticks - 1]" in source[frames[-1].line - 1]


def test_topic_name_errors_read_as_rclpy_words_them():
    recording = run_node(str(NODES / "topic_with_space.py"), duration=1.0)
    assert recording.failure.detail.splitlines() == [
        "Invalid topic name: topic name must not contain characters other than alphanumerics, '_', '~', '{', or '}':",
        "  'joint states'", "        ^"]  # under the space (rclpy/exceptions.py NameValidationException)


def test_while_ok_loop_with_sleep_publishes_at_20_hz():
    recording = run_node(str(NODES / "while_ok_sleep.py"), duration=1.0)
    times = [m.time for m in recording.messages]
    assert times == pytest.approx([0.05 * k for k in range(21)], abs=1e-9)
    assert [m.fields["position"][0] for m in recording.messages] == pytest.approx(
        [0.5 * math.sin(0.05 * k) for k in range(21)], abs=1e-12)


def test_degrees_are_reported_with_joint_value_and_time(robot):
    recording = run_node(str(NODES / "degrees.py"), duration=2.0)
    coude = next(f for f in run_findings(recording, robot, lang="en") if f.data["joint"] == "coude")
    assert coude.data["value"] == 90.0 and coude.data["first"] == pytest.approx(0.05)
    assert "degrees" in coude.text("en") and "math.radians" in coude.hint_text("en")


def test_wrong_topic_says_where_the_messages_went(robot):
    recording = run_node(str(NODES / "wrong_topic.py"), duration=1.0)
    [finding] = run_findings(recording, robot, lang="fr")
    assert "'/joint_state'" in finding.text("en") and finding.line == 11
    assert finding.data["count"] == 20


def test_busy_loop_is_stopped_by_the_cpu_limit_with_a_clear_message():
    with pytest.raises(NodeRunError) as caught:
        run_node(str(NODES / "busy_loop.py"), duration=2.0, cpu_seconds=1)
    assert caught.value.kind == "cpu" and caught.value.time == 0.0
    assert "time.sleep()" in str(caught.value.hint)


def test_ten_simulated_seconds_take_well_under_a_second(tutorial_run):
    assert tutorial_run.wall_seconds < 1.0


def test_robot_of_a_package_is_its_urdf():
    robot = robot_of(str(TUTORIAL))
    assert [j.name for j in robot.movable_joints()] == ["epaule", "coude"]


def test_every_run_rule_is_triggered_by_a_beginner_node():
    from run_cases import (
        RECORD_RULES,  # BK657-BK658: nodes attacking their own record
        ROWS,  # BK652: the mistakes of the Jazzy table
    )

    from bras_kit.validate.package.run_rules import RUN_CHECKS

    jazzy = {code for *_, codes in ROWS for code, _line in codes}
    assert {code for *_, codes in BEGINNER_NODES for code in codes} | jazzy | set(RECORD_RULES) == set(RUN_CHECKS)


def test_subscriptions_hear_what_is_published_and_logs_carry_the_simulated_time():
    recording = run_node(str(NODES / "talker_listener.py"), duration=2.0)
    # it catches the end-of-run KeyboardInterrupt, then rclpy.shutdown() finds the context already
    # shut down by rclpy's SIGINT handler (signal_handler.cpp:143-144, context.cpp:161-164)
    assert recording.ended == "error" and recording.failure.kind == "RCLError"
    assert [m.fields["data"] for m in recording.on("/chatter")] == ["bonjour 1", "bonjour 2", "bonjour 3", "bonjour 4"]
    assert [(t, level, node, text) for t, level, node, text in recording.logs] == [
        (0.5 * k, "INFO", "talker_listener", f"heard: bonjour {k}") for k in range(1, 5)]
    assert [(s.node, s.topic, s.type) for s in recording.subscriptions] == [
        ("talker_listener", "/chatter", "std_msgs/msg/String")]


def test_a_polling_spin_once_loop_still_sees_its_timer_on_time():
    recording = run_node(str(NODES / "spin_once_poll.py"), duration=1.0)
    assert [m.time for m in recording.on("/angle")] == pytest.approx([0.1 * k for k in range(1, 11)], abs=1e-3)
    assert recording.ended == "duration"


def test_parameters_given_as_ros_args_reach_declare_parameter():
    from bras_kit.run import parse_parameters

    assert parse_parameters(["greeting:=salut", "rate:=20", "gain:=0.5", "on:=true"]) == {
        "greeting": "salut", "rate": 20, "gain": 0.5, "on": True}
    recording = run_node(str(NODES / "talker_listener.py"), duration=1.0, parameters={"greeting": "salut"})
    assert [m.fields["data"] for m in recording.on("/chatter")] == ["salut 1", "salut 2"]


def test_spin_in_a_thread_lets_the_main_loop_rate_sleep_at_its_rate():
    recording = run_node(str(NODES / "spin_in_thread.py"), duration=2.0)
    assert [m.time for m in recording.messages] == pytest.approx([0.1 * k for k in range(21)], abs=1e-9)
    assert recording.rate_sleeps == 0


def test_spin_until_future_complete_returns_when_the_future_is_done():
    recording = run_node(str(NODES / "future_and_time.py"), duration=5.0)
    assert recording.ended == "returned" and recording.end == pytest.approx(0.6)  # third tick of 0.2 s
    assert [m.fields["data"] for m in recording.on("/elapsed")] == pytest.approx([0.6, 500_000_000.0])
    assert [text for *_, text in recording.logs] == ["three ticks"]


# How a node sets the angles it publishes (bras-kit's run rules point BK649 at that line, where the
# value past the limit is written, not at create_publisher): (the lines of tick's body, the index of
# the line BK649 must name, counted from the first of them)
POSITION_WRITES = {
    "assigned": (["msg.position = [2.5 * math.sin(self.t), 0.0]"], 0),
    "appended": (["msg.position = []", "msg.position.append(2.5 * math.sin(self.t))", "msg.position.append(0.0)"],
                 2),
    "by_index": (["msg.position = [0.0, 0.0]", "msg.position[0] = 2.5 * math.sin(self.t)"], 1),
    "annotated_then_assigned": (["angles: list = [2.5 * math.sin(self.t), 0.0]", "msg.position = angles"], 1),
}


@pytest.mark.parametrize("case", list(POSITION_WRITES))
def test_bk649_names_the_line_that_sets_the_position(tmp_path, robot, case):
    body, index = POSITION_WRITES[case]
    head = ["import math", "import rclpy", "from rclpy.node import Node", "from sensor_msgs.msg import JointState", "",
            "", "class Animation(Node):", "    def __init__(self):", "        super().__init__('animation_bras')",
            "        self.pub = self.create_publisher(JointState, 'joint_states', 10)",
            "        self.timer = self.create_timer(0.05, self.tick)", "        self.t = 0.0", "",
            "    def tick(self):", "        self.t += 0.05", "        msg = JointState()",
            "        msg.header.stamp = self.get_clock().now().to_msg()", "        msg.name = ['epaule', 'coude']"]
    tail = ["        self.pub.publish(msg)", "", "", "def main():", "    rclpy.init()", "    rclpy.spin(Animation())", "",
            "", "if __name__ == '__main__':", "    main()"]
    node = tmp_path / "animation.py"
    node.write_text("\n".join(head + ["        " + line for line in body] + tail) + "\n", encoding="utf-8")
    recording = run_node(str(node), duration=2.0)
    found = [f for f in run_findings(recording, robot, lang="en", root=str(tmp_path)) if f.code == "BK649"]
    assert found and {f.line for f in found} == {len(head) + index + 1}, [(f.line, f.text("en")) for f in found]
    assert "create_publisher" not in node.read_text().splitlines()[found[0].line - 1]
