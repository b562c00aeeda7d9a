"""The stand-in against rclpy 7.1 (Jazzy) and rosidl_python (Jazzy): one small node per row.

Oracle: the source of ros2/rclpy (branch jazzy, 7.1.3) and ros2/rosidl_python (branch jazzy,
rosidl_generator_py 0.22), cited line by line for each row: what Jazzy does with the node,
not what the stand-in's code says.
"""

from __future__ import annotations

import pytest
from paths import TESTS
from run_cases import ROWS

from bras_kit.model.authoring import load
from bras_kit.run import run_node
from bras_kit.run.findings import run_findings

JAZZY = TESTS / "data" / "run" / "jazzy"
TUTORIAL = TESTS / "data" / "tutorial_package"



@pytest.fixture(scope="module")
def robot():
    return load(str(TUTORIAL / "urdf" / "bras.urdf"))


@pytest.mark.parametrize("node, ended, failure, codes", ROWS, ids=[row[0] for row in ROWS])
def test_node_behaves_as_on_jazzy(node, ended, failure, codes, robot):
    recording = run_node(str(JAZZY / node), duration=2.0)
    assert recording.ended == ended
    assert (recording.failure.kind if recording.failure else None) == failure
    found = sorted((f.code, f.line) for f in run_findings(recording, robot, lang="en"))
    assert found == sorted(codes, key=lambda c: (c[0], c[1] or 0))


def test_mixed_sequences_are_stored_as_doubles():
    recording = run_node(str(JAZZY / "positions_any_sequence.py"), duration=0.15)
    # k = 1, 2, 3: the tuple, the numpy array, the integer list (k % 3 picks), all doubles
    assert [m.fields["position"] for m in recording.messages] == [[0.1, 0.2], [0.3, 0.4], [0.0, 0.0]]


def test_worker_thread_publishes_at_its_rate_from_t0():
    recording = run_node(str(JAZZY / "worker_thread_rate.py"), duration=1.0)
    times = [m.time for m in recording.messages]
    assert times == pytest.approx([0.05 * k for k in range(21)], abs=1e-9)
    assert recording.rate_sleeps == 0  # rclpy.spin in the main thread runs the rate's timer


def test_multithreaded_executor_keeps_20_hz_while_a_reentrant_callback_sleeps():
    recording = run_node(str(JAZZY / "multithreaded_groups.py"), duration=2.0)
    ticks = [m.time for m in recording.on("/joint_states")]
    assert ticks == pytest.approx([0.05 * k for k in range(1, 41)], abs=1e-9)
    # think() at 0.5, 1.0, 1.5 sleeps 0.3 s each time: done at 0.8, 1.3, 1.8
    assert [m.time for m in recording.on("/slow")] == pytest.approx([0.8, 1.3, 1.8], abs=1e-9)


def test_multithreaded_run_is_the_same_every_time():
    first = run_node(str(JAZZY / "multithreaded_groups.py"), duration=1.0)
    second = run_node(str(JAZZY / "multithreaded_groups.py"), duration=1.0)
    assert [(m.time, m.topic) for m in first.messages] == [(m.time, m.topic) for m in second.messages]


def test_on_set_callback_refuses_and_accepts_and_p_overrides():
    recording = run_node(str(JAZZY / "parameters_callback.py"), duration=2.0)
    # tick 2 asks 5.0 (refused: SetParametersResult(successful=False)), tick 3 asks 1.2
    assert [m.fields["data"] for m in recording.on("/amplitude")] == [0.8, 0.8, 1.2, 1.2]
    overridden = run_node(str(JAZZY / "parameters_callback.py"), duration=0.5, parameters={"amplitude": 0.3})
    assert [m.fields["data"] for m in overridden.on("/amplitude")] == [0.3]


def test_override_of_another_type_is_refused_as_jazzy_does():
    # node.py:513-515 + 580-586 + 1228-1238: -p amplitude:=1 is an INTEGER for a DOUBLE parameter
    recording = run_node(str(JAZZY / "parameters_callback.py"), duration=0.5, parameters={"amplitude": 1})
    assert recording.failure.kind == "InvalidParameterTypeException"
    assert "expecting type 'DOUBLE'" in recording.failure.detail


def test_subscription_hears_its_own_joint_states_at_publish_time():
    recording = run_node(str(JAZZY / "subscribe_own_joint_states.py"), duration=1.0)
    assert [(t, text) for t, _level, _node, text in recording.logs] == [(0.5, "heard [0.1, 0.2]"),
                                                                        (1.0, "heard [0.1, 0.2]")]


def test_explanations_are_worded_in_french():
    recording = run_node(str(JAZZY / "tick_without_self.py"), duration=0.5)
    [finding] = [f for f in run_findings(recording, None, lang="fr") if f.code == "BK652"]
    assert "self" in finding.text() and finding.line == 12


@pytest.mark.parametrize("source, expected", [
    ("q1", None), ("epaule + 0.1", None),  # names the static reading cannot resolve (issue 33)
    ("0.8 * math.sin(self.t)", "0.8 * sin(t)"), ("2 * self.t", "2 * t"),  # a wave, a ramp of the time
])
def test_static_reading_judges_waves_of_time_never_unresolved_names(source, expected):
    import ast

    from bras_kit.ros.formulas import formula

    assert formula(ast.parse(source, mode="eval").body, {}) == expected


def test_tf2_buffer_answers_from_the_robot_joints_and_a_static_tool_frame(tmp_path):
    import math
    import shutil

    package = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL, package)
    shutil.copy(JAZZY / "tool_frame.py", package / "bras_description" / "tool_frame.py")
    recording = run_node(str(package / "bras_description" / "tool_frame.py"), duration=1.0)
    [said] = [m.fields["data"] for m in recording.on("/outil")]
    x, y, z = (float(v) for v in said.split())
    # the planar arm of the URDF: shoulder 0.05 above base, upper arm 0.6, tool 0.5 past the elbow,
    # both joints about y: x = 0.6 sin(q1) + 0.5 sin(q1 + q2), z = 0.05 + 0.6 cos(q1) + 0.5 cos(q1 + q2)
    assert (x, y, z) == pytest.approx((0.6 * math.sin(0.5) + 0.5 * math.sin(0.8), 0.0,
                                       0.05 + 0.6 * math.cos(0.5) + 0.5 * math.cos(0.8)), abs=1e-9)
    assert [m.topic for m in recording.messages if m.topic.startswith("/tf")] == ["/tf_static"]


def test_tf2_lookup_of_an_unknown_frame_says_so_as_tf2_does():
    recording = run_node(str(JAZZY / "tool_frame.py"), duration=1.0)  # a lone file: no robot, no 'base'
    [said] = [m.fields["data"] for m in recording.on("/outil")]
    assert said == 'no: "base" passed to lookupTransform argument target_frame does not exist. '


# What validate's static reading (BK627) sees in the same nodes, without running them: the same
# lines as the run's explanation (BK652); the nodes that work on Jazzy show nothing.
STATIC = [
    ("callback_called.py", [("callback_called", 10)]),
    ("now_without_to_msg.py", [("now_not_msg", 14)]),
    ("shutdown_after_ctrl_c.py", [("shutdown_twice", 13)]),
    ("stamp_whole_seconds.py", [("stamp_seconds", 16)]),
    ("super_forgotten.py", [("super_init", 7)]),
    ("tick_without_self.py", [("no_self", 12)]),
    ("timer_in_hertz.py", [("timer_period", 10)]),
    ("with_node.py", [("with_node", 12)]),
    ("time_step_off.py", [("time_step", 14)]),
    ("worker_thread_rate.py", []), ("multithreaded_groups.py", []), ("parameters_callback.py", []),
    ("positions_any_sequence.py", []), ("subscribe_own_joint_states.py", []), ("executor_with.py", []),
    ("tool_frame.py", []), ("../../tutorial_package/bras_description/animation.py", []),
]


@pytest.mark.parametrize("node, expected", STATIC, ids=[row[0] for row in STATIC])
def test_static_reading_sees_the_same_mistakes(node, expected):
    import ast

    from bras_kit.validate.package.node_mistakes import mistakes

    tree = ast.parse((JAZZY / node).read_text(encoding="utf-8"))
    assert [(variant, line) for variant, line, _ in mistakes(tree)] == expected


def test_time_step_off_runs_twice_as_fast_as_its_timer():
    import math

    recording = run_node(str(JAZZY / "time_step_off.py"), duration=0.5)
    # the node adds 0.1 per 0.05 s tick: at t it has written sin(2 t)
    assert [m.fields["position"][0] for m in recording.messages] == pytest.approx(
        [0.8 * math.sin(0.1 * k) for k in range(1, 11)], abs=1e-12)


def test_an_exception_in_a_worker_thread_is_the_nodes_failure_at_its_line():
    # Python prints it and the thread ends (threading.excepthook); the node is broken from then on
    recording = run_node(str(JAZZY / "worker_raises.py"), duration=1.0)
    assert [m.fields["data"] for m in recording.on("/value")] == [0.1, 0.2, 0.3]
    assert recording.failure.kind == "IndexError" and recording.failure.time == pytest.approx(0.3)
    assert recording.failure.context["thread"].startswith("Thread-")
    assert recording.failure.frames[-1].line == 19
    # threading.Timer waits on the simulated clock too
    assert [(t, text) for t, _level, _node, text in recording.logs] == [(0.25, "timer thread")]


def test_logging_filters_are_kept_per_call_site_on_the_node_clock():
    """rcutils_logger.py (7.1) 54-66: a filter's state belongs to the call site (CallerId), not to
    the text, so an f-string logged with once=True is said once; 122-148: throttle compares the
    clock (Clock(), the node's time) with the last time it logged; 172-176 + 325-327: throttle,
    then skip_first, then once, the first that says no stopping the others (skip_first + once:
    the second call alone)."""
    recording = run_node(str(JAZZY / "logging_filters.py"), duration=2.0)  # a lone file: no robot
    said = [(round(t, 9), level, text) for t, level, _node, text in recording.logs]
    missing = '"base" passed to lookupTransform argument target_frame does not exist. '
    assert said == [(0.05, "INFO", "tick 1"), (0.05, "INFO", "every second 1"), (0.05, "WARN", missing),
                    (0.1, "INFO", "after the first 2"),
                    (1.05, "INFO", "every second 21"), (1.05, "WARN", missing)]


def test_unknown_logging_option_is_rclpy_s_type_error(tmp_path):
    node = tmp_path / "typo.py"
    node.write_text((JAZZY / "logging_filters.py").read_text().replace("throttle_duration_sec=1.0)\n        log.info(f'after",
                                                                       "throttle_duration=1.0)\n        log.info(f'after"))
    recording = run_node(str(node), duration=0.5)
    assert recording.failure.kind == "TypeError"
    assert recording.failure.detail.startswith('parameter "throttle_duration" is not one of the recognized logging '
                                               'options')


def test_run_s_robot_is_the_one_tf2_answers_from():
    """bras-kit run checks a lone node against --urdf (else the built-in arm): its tf2 Buffer
    answers from that robot too, as robot_state_publisher would publish it."""
    import math
    import subprocess
    import sys

    for urdf in ([], ["--urdf", str(TUTORIAL / "urdf" / "bras.urdf")]):
        done = subprocess.run([sys.executable, "-m", "bras_kit", "run", str(JAZZY / "logging_filters.py"),
                               "--duration", "0.2", *urdf], capture_output=True, text=True, timeout=120)
        code, err = done.returncode, done.stderr
        assert code == 0, err
        # shoulder 0.05 above the base, the upper arm 0.6 long turned 0.5 rad about y: by hand
        assert f"avant_bras z={0.05 + 0.6 * math.cos(0.5):.6f}" in err
        assert "does not exist" not in err
