"""Motion programs, waypoint files, sampling, limit checks and `bras-kit motion`."""

from __future__ import annotations

import json
import math
import os

import numpy as np
import pytest
from paths import DATA as DATA_DIR

from bras_kit.core.errors import ParameterError, UnsafeExpressionError
from bras_kit.motion import (
    DEFAULT_DURATION,
    DEFAULT_RATE,
    JointStates,
    check_limits,
    clamp,
    describe_segment,
    describe_violation,
    formula_motion,
    motion_from_specs,
    pose_motion,
    read_states,
    read_waypoints,
    sample,
    states_to_csv,
    states_to_json,
    tutorial_motion,
    waypoint_motion,
    waypoint_speeds,
)

DATA = os.path.join(DATA_DIR, "motion")


def read(path) -> str:
    with open(path, encoding="utf-8") as handle:
        return handle.read()


def data(name: str) -> str:
    return os.path.join(DATA, name)


def write(folder, name: str, text: str) -> str:
    path = folder / name
    path.write_text(text, encoding="utf-8")
    return str(path)


EXTRA_URDF = """<?xml version="1.0"?>
<robot name="extra">
  <link name="base"/><link name="a"/><link name="b"/><link name="c"/><link name="d"/><link name="e"/>
  <joint name="socle" type="fixed"><parent link="base"/><child link="a"/></joint>
  <joint name="glissiere" type="prismatic"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
    <limit lower="0" upper="0.2" effort="50" velocity="0.05"/></joint>
  <joint name="tourelle" type="continuous"><parent link="b"/><child link="c"/><axis xyz="0 0 1"/>
    <limit effort="5" velocity="0.3"/></joint>
  <joint name="pince" type="revolute"><parent link="c"/><child link="d"/><axis xyz="1 0 0"/>
    <limit lower="0.5" upper="1.0" effort="1" velocity="2"/></joint>
  <joint name="copie" type="revolute"><parent link="d"/><child link="e"/><axis xyz="1 0 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="2"/><mimic joint="pince" multiplier="-1"/></joint>
</robot>
"""


@pytest.fixture(scope="module")
def extra_robot(tmp_path_factory):
    from bras_kit.model.authoring import load

    path = tmp_path_factory.mktemp("robots") / "extra.urdf"
    path.write_text(EXTRA_URDF, encoding="utf-8")
    return load(str(path))


# ---------------------------------------------------------------- the tutorial's motion


def test_tutorial_motion_matches_the_node_at_each_tick(tutorial_robot):
    states = sample(tutorial_motion(tutorial_robot))
    k = np.arange(201)
    assert states.names == ["epaule", "coude"]
    assert np.allclose(states.times, 0.05 * k, rtol=0, atol=1e-12)
    assert np.max(np.abs(states.positions[:, 0] - 0.8 * np.sin(0.05 * k))) < 1e-12
    assert np.max(np.abs(states.positions[:, 1] - 1.2 * np.sin(0.05 * k * 0.7))) < 1e-12


def test_tutorial_motion_at_the_first_ticks_by_hand(tutorial_robot):
    positions = tutorial_motion(tutorial_robot).positions(np.array([0.05, 0.1]))
    assert positions[0] == pytest.approx([0.8 * math.sin(0.05), 1.2 * math.sin(0.035)], abs=1e-15)
    assert positions[1] == pytest.approx([0.8 * math.sin(0.1), 1.2 * math.sin(0.07)], abs=1e-15)


def test_tutorial_velocities_are_the_exact_derivatives(tutorial_robot):
    states = sample(tutorial_motion(tutorial_robot))
    t = states.times
    assert np.max(np.abs(states.velocities[:, 0] - 0.8 * np.cos(t))) < 1e-15
    assert np.max(np.abs(states.velocities[:, 1] - 0.84 * np.cos(0.7 * t))) < 1e-15


def test_velocities_agree_with_finite_differences_of_positions(tutorial_robot):
    states = sample(formula_motion(tutorial_robot, ["epaule=0.3*sin(2*t)*exp(-0.1*t)", "coude=t**2/50"]),
                    duration=5, rate=1000)
    slope = np.gradient(states.positions, states.times, axis=0)
    assert np.max(np.abs(slope[1:-1] - states.velocities[1:-1])) < 1e-5


def test_tutorial_motion_stays_within_the_tutorial_limits(tutorial_robot, wrist_robot):
    assert check_limits(tutorial_robot, sample(tutorial_motion(tutorial_robot), duration=30)) == []
    assert check_limits(wrist_robot, sample(tutorial_motion(wrist_robot), duration=30)) == []


def test_wrist_follows_its_own_pace(wrist_robot):
    motion = tutorial_motion(wrist_robot)
    assert motion.names == ["epaule", "coude", "poignet"]
    t = np.array([0.0, 0.5, 1.0])
    assert motion.positions(t)[:, 2] == pytest.approx(1.0 * np.sin(1.3 * t), abs=1e-15)
    assert motion.sources()["poignet"] == "1*sin(1.3*t)"


def test_wrist_amplitude_shrinks_to_fit_narrow_limits():
    from bras_kit.model.authoring import arm

    robot = arm(wrist=True, params={"poignet_lower": -0.5, "poignet_upper": 0.5})
    states = sample(tutorial_motion(robot), duration=20)
    assert check_limits(robot, states) == []
    assert states.positions[:, 2].max() == pytest.approx(0.4, abs=1e-3)  # 0.8 x 0.5


def test_other_joints_of_any_robot_move_gently_inside_their_limits(extra_robot):
    motion = tutorial_motion(extra_robot)
    assert motion.names == ["glissiere", "tourelle", "pince"]  # no fixed, no mimic joint
    states = sample(motion, duration=60)
    assert check_limits(extra_robot, states) == []
    assert np.all(np.ptp(states.positions, axis=0) > 0)  # every joint moves
    assert states.positions[:, 0].min() >= 0 and states.positions[:, 0].max() <= 0.2
    assert states.positions[:, 2].min() >= 0.5 and states.positions[:, 2].max() <= 1.0


# ---------------------------------------------------------------- formulas and poses


def test_formula_drives_its_joint_and_others_stay_at_zero(tutorial_robot):
    motion = formula_motion(tutorial_robot, ["epaule=0.8*sin(t)"])
    positions = motion.positions(np.array([1.0, 2.0]))
    assert positions[:, 0].tolist() == [0.8 * math.sin(1.0), 0.8 * math.sin(2.0)]
    assert positions[:, 1].tolist() == [0.0, 0.0]
    assert motion.duration is None


def test_formula_joints_not_given_keep_their_base_value(tutorial_robot):
    motion = formula_motion(tutorial_robot, ["epaule = t / 10"], base={"coude": 0.3})
    assert motion.positions(np.array([2.0])).tolist() == [[0.2, 0.3]]


def test_formula_on_an_unknown_joint_lists_the_movable_ones(tutorial_robot):
    with pytest.raises(ParameterError) as caught:
        formula_motion(tutorial_robot, ["genou=sin(t)"])
    assert "unknown joint 'genou'" in str(caught.value.message)
    assert str(caught.value.hint) == "movable joints: epaule, coude"


def test_formula_on_fixed_and_mimic_joints_is_refused(extra_robot):
    with pytest.raises(ParameterError, match="fixed and cannot move"):
        formula_motion(extra_robot, ["socle=t"])
    with pytest.raises(ParameterError, match="mimics 'pince'"):
        formula_motion(extra_robot, ["copie=t"])


def test_unsafe_formula_caret_includes_the_joint_name(tutorial_robot):
    with pytest.raises(UnsafeExpressionError) as caught:
        formula_motion(tutorial_robot, ["coude=t.real"])
    assert str(caught.value.message).splitlines()[1:] == ["    coude=t.real", "           ^"]


def test_two_formulas_for_one_joint_are_refused(tutorial_robot):
    with pytest.raises(ParameterError, match="two formulas for joint 'coude'"):
        formula_motion(tutorial_robot, ["coude=t", "coude=2*t"])


def test_spec_without_equals_sign_is_explained(tutorial_robot):
    with pytest.raises(ParameterError, match="is not a motion"):
        motion_from_specs(tutorial_robot, ["sin(t)"])


def test_pose_motion_holds_still(tutorial_robot):
    states = sample(pose_motion(tutorial_robot, {"coude": -0.7}), duration=1)
    assert len(states) == 21
    assert np.all(states.positions == [0.0, -0.7])
    assert np.all(states.velocities == 0.0)


# ---------------------------------------------------------------- combining specs


def test_no_specs_is_the_tutorial_motion(tutorial_robot):
    motion = motion_from_specs(tutorial_robot, [])
    assert motion.sources() == {"epaule": "0.8*sin(t)", "coude": "1.2*sin(0.7*t)"}


def test_only_set_values_is_a_fixed_pose(tutorial_robot):
    motion = motion_from_specs(tutorial_robot, [], {"epaule": 0.4})
    assert motion.positions(np.array([0.0, 3.0])).tolist() == [[0.4, 0.0], [0.4, 0.0]]


def test_set_value_holds_a_joint_while_the_tutorial_moves_the_rest(wrist_robot):
    motion = motion_from_specs(wrist_robot, ["tutorial"], {"poignet": 0.5})
    positions = motion.positions(np.array([1.0]))[0]
    assert positions.tolist() == [0.8 * math.sin(1.0), 1.2 * math.sin(0.7), 0.5]


def test_formula_overrides_the_tutorial_for_its_joint(tutorial_robot):
    motion = motion_from_specs(tutorial_robot, ["tutorial", "coude=0.5"])
    assert motion.positions(np.array([1.0])).tolist() == [[0.8 * math.sin(1.0), 0.5]]


def test_a_joint_driven_twice_is_refused(tutorial_robot):
    with pytest.raises(ParameterError, match="driven twice"):
        motion_from_specs(tutorial_robot, ["coude=t"], {"coude": 0.2})
    with pytest.raises(ParameterError, match="driven twice"):
        motion_from_specs(tutorial_robot, [data("arc.csv"), "coude=t"])


def test_waypoint_file_and_formula_on_different_joints(tutorial_robot, tmp_path):
    path = write(tmp_path, "e.csv", "time,epaule\n0,0\n2,1\n")
    motion = motion_from_specs(tutorial_robot, [path, "coude=-t/4"])
    assert motion.duration == 2.0
    assert motion.positions(np.array([1.0])).tolist() == [[0.5, -0.25]]


# ---------------------------------------------------------------- sampling


@pytest.mark.parametrize("duration, rate, count", [
    (10, 20, 201), (4, 20, 81), (1.03, 20, 21), (0, 20, 1), (2, 0.5, 2), (3, 10, 31),
])
def test_sample_count_includes_both_ends(tutorial_robot, duration, rate, count):
    states = sample(tutorial_motion(tutorial_robot), duration, rate)
    assert len(states) == count
    assert states.times[-1] == (count - 1) / rate


def test_default_duration_and_rate(tutorial_robot):
    states = sample(tutorial_motion(tutorial_robot))
    assert (DEFAULT_DURATION, DEFAULT_RATE) == (10.0, 20.0)
    assert len(states) == 201 and states.times[1] == 0.05


def test_default_duration_of_waypoints_is_the_last_time(tutorial_robot):
    assert len(sample(waypoint_motion(tutorial_robot, data("arc.csv")))) == 81


@pytest.mark.parametrize("duration, rate, words", [
    (-1, 20, "not a time"), (math.inf, 20, "not a time"), (1, 0, "not a rate"), (1, math.nan, "not a rate"),
    (1e9, 1e3, "too many"),
])
def test_bad_duration_or_rate(tutorial_robot, duration, rate, words):
    with pytest.raises(ParameterError, match=words):
        sample(tutorial_motion(tutorial_robot), duration, rate)


def test_a_formula_undefined_at_a_sample_names_the_joint_and_time(tutorial_robot):
    with pytest.raises(ParameterError) as caught:
        sample(formula_motion(tutorial_robot, ["coude=log(t - 1)"]))
    assert str(caught.value.message) == "the motion of coude (log(t - 1)) is not a number at t=0 s"


def test_an_infinite_slope_falls_back_on_finite_differences(tutorial_robot):
    states = sample(formula_motion(tutorial_robot, ["coude=sqrt(t)/10"]), duration=1, rate=4)
    assert np.all(np.isfinite(states.velocities))
    assert states.velocities[0, 1] == pytest.approx(math.sqrt(0.25) / 10 / 0.25)  # forward difference
    assert states.velocities[1, 1] == pytest.approx(0.05 / math.sqrt(0.25))  # exact elsewhere


# ---------------------------------------------------------------- limits


def test_brief_example_goes_past_the_elbow_limit_first_just_after_asin_08(tutorial_robot):
    states = sample(formula_motion(tutorial_robot, ["coude=2.5*sin(t)"]))
    upper = [v for v in check_limits(tutorial_robot, states) if v.kind == "position" and v.side == "upper"]
    assert len(upper) == 1
    v = upper[0]
    assert v.joint == "coude" and v.bound == 2.0
    assert math.asin(0.8) <= v.time < math.asin(0.8) + 0.05
    assert v.excess == pytest.approx(0.5, abs=2.5 * (1 - math.cos(0.025)))


def test_violation_fields_exact_when_the_peak_falls_on_a_sample(tutorial_robot):
    # 2.5 sin(pi t / 2) peaks at t = 1, 5, 9; it is above 2 for (2/pi) asin(0.8) = 0.59 < t < 1.41
    states = sample(formula_motion(tutorial_robot, ["coude=2.5*sin(pi*t/2)"]))
    violations = check_limits(tutorial_robot, states)
    upper = next(v for v in violations if v.side == "upper")
    assert (upper.joint, upper.kind, upper.time, upper.value, upper.bound) == ("coude", "position", 0.6, 2.5, 2.0)
    assert (upper.excess, upper.peak_time, upper.samples) == (0.5, 1.0, 51)
    assert str(describe_violation(upper)) == (
        "coude goes past its upper limit 2 by 0.5 rad at t=1 s (first at t=0.6 s, 51 samples)")
    lower = next(v for v in violations if v.side == "lower")
    assert (lower.time, lower.value, lower.bound, lower.excess, lower.peak_time) == (2.6, -2.5, -2.0, 0.5, 3.0)


def test_velocity_violation_names_joint_speed_and_time(tutorial_robot):
    states = sample(formula_motion(tutorial_robot, ["coude=2.5*sin(pi*t/2)"]))
    speed = next(v for v in check_limits(tutorial_robot, states) if v.kind == "velocity")
    assert speed.joint == "coude" and speed.bound == 1.0 and speed.time == 0.0
    assert speed.value == pytest.approx(2.5 * math.pi / 2)
    assert speed.excess == pytest.approx(2.5 * math.pi / 2 - 1.0)
    assert str(describe_violation(speed)).startswith("coude moves at 3.927 rad/s at t=0 s, 2.93 rad/s over its "
                                                "velocity limit 1 rad/s")


def test_motion_exactly_at_the_limit_is_not_a_violation(tutorial_robot):
    states = sample(formula_motion(tutorial_robot, ["coude=2*sin(pi*t/2)/3*3"]), duration=4)
    assert [v for v in check_limits(tutorial_robot, states) if v.kind == "position"] == []


def test_clamp_keeps_positions_inside_and_stops_there(tutorial_robot):
    states = sample(formula_motion(tutorial_robot, ["coude=2.5*sin(pi*t/2)"]))
    clamped = clamp(tutorial_robot, states)
    assert clamped.positions[:, 1].max() == 2.0 and clamped.positions[:, 1].min() == -2.0
    assert clamped.positions[20, 1] == 2.0 and clamped.velocities[20, 1] == 0.0  # t = 1
    inside = np.abs(states.positions[:, 1]) <= 2.0
    assert np.array_equal(clamped.positions[inside], states.positions[inside])
    assert np.array_equal(clamped.velocities[inside], states.velocities[inside])
    assert [v.kind for v in check_limits(tutorial_robot, clamped)] == ["velocity"]
    assert states.positions[20, 1] == 2.5  # the input is left alone


# ---------------------------------------------------------------- waypoints


ARC_TIMES = [0.0, 1.0, 2.5, 4.0]
ARC_VALUES = [[0.0, 0.0], [0.5, -0.4], [0.2, 0.6], [0.0, 0.0]]


@pytest.mark.parametrize("name", ["arc.csv", "arc.json", "arc.yaml", "arc_list.json", "arc_columns.yaml",
                                  "arc_semicolon.csv"])
def test_waypoint_formats_read_the_same_arc(tutorial_robot, name):
    points = read_waypoints(data(name), tutorial_robot)
    assert points.times.tolist() == ARC_TIMES
    assert points.joints == ["epaule", "coude"]
    assert points.values.tolist() == ARC_VALUES


def test_waypoint_formats_give_identical_motions(tutorial_robot):
    t = np.linspace(-1, 5, 241)
    reference = waypoint_motion(tutorial_robot, data("arc.csv")).evaluate(t)
    for name in ["arc.json", "arc.yaml", "arc_list.json", "arc_semicolon.csv"]:
        other = waypoint_motion(tutorial_robot, data(name)).evaluate(t)
        assert np.array_equal(other[0], reference[0]) and np.array_equal(other[1], reference[1])
    cubic = waypoint_motion(tutorial_robot, data("arc.csv"), "cubic").evaluate(t)
    written = waypoint_motion(tutorial_robot, data("arc_columns.yaml")).evaluate(t)
    assert np.array_equal(cubic[0], written[0])


def test_interpolation_comes_from_the_file_unless_overridden(tutorial_robot):
    assert read_waypoints(data("arc_columns.yaml"), tutorial_robot).interpolation == "cubic"
    assert read_waypoints(data("arc_columns.yaml"), tutorial_robot, "linear").interpolation == "linear"
    assert read_waypoints(data("arc.csv"), tutorial_robot).interpolation == "linear"


@pytest.mark.parametrize("interpolation", ["linear", "cubic"])
def test_interpolation_is_exact_at_the_waypoints(tutorial_robot, interpolation):
    states = sample(waypoint_motion(tutorial_robot, data("arc.csv"), interpolation))
    assert states.positions[[0, 20, 50, 80]].tolist() == ARC_VALUES  # t = 0, 1, 2.5, 4


def test_linear_interpolation_between_waypoints(tutorial_robot):
    motion = waypoint_motion(tutorial_robot, data("arc.csv"))
    positions, velocities = motion.evaluate(np.array([0.5, 1.75]))
    assert positions[0].tolist() == [0.25, -0.2]
    assert positions[1] == pytest.approx([0.35, 0.1], abs=1e-15)
    assert velocities[0].tolist() == [0.5, -0.4]
    assert velocities[1] == pytest.approx([-0.2, 2 / 3])


def test_cubic_values_and_knot_velocity_by_hand(tutorial_robot, tmp_path):
    # knots (0, 0), (1, 1), (3, 2): slopes 1 and 0.5; weights 2*2+1 = 5 and 2+2*1 = 4,
    # so the middle velocity is 9 / (5/1 + 4/0.5) = 9/13 and at t = 0.5 the value is
    # 1/2 (h01) - 1/8 * 9/13 (h11) = 43/104.
    path = write(tmp_path, "c.csv", "time,epaule\n0,0\n1,1\n3,2\n")
    positions, velocities = waypoint_motion(tutorial_robot, path, "cubic").evaluate(np.array([0, 0.5, 1, 3]))
    assert positions[:, 0] == pytest.approx([0, 43 / 104, 1, 2], abs=1e-15)
    assert velocities[:, 0] == pytest.approx([0, velocities[1, 0], 9 / 13, 0], abs=1e-15)


def test_cubic_never_overshoots_a_waypoint(tutorial_robot):
    motion = waypoint_motion(tutorial_robot, data("fast.csv"), "cubic")
    positions, velocities = motion.evaluate(np.linspace(0, 2.5, 25001))
    assert positions[:, 0].max() == 1.0 and positions[:, 0].min() == 0.0
    assert velocities[0, 0] == 0.0 and velocities[-1, 0] == 0.0


def test_cubic_velocity_is_continuous_at_the_waypoints(tutorial_robot):
    motion = waypoint_motion(tutorial_robot, data("arc.csv"), "cubic")
    knots = np.array([1.0, 2.5])
    left, right = motion.velocities(knots - 1e-9), motion.velocities(knots + 1e-9)
    assert np.max(np.abs(left - right)) < 1e-7
    assert np.max(np.abs(motion.velocities(np.array([0.0, 4.0])))) == 0.0  # starts and ends at rest


def test_joints_hold_still_before_the_first_and_after_the_last_waypoint(tutorial_robot, tmp_path):
    path = write(tmp_path, "late.csv", "time,coude\n1,0.5\n2,1.0\n")
    positions, velocities = waypoint_motion(tutorial_robot, path).evaluate(np.array([0.0, 0.5, 3.0]))
    assert positions[:, 1].tolist() == [0.5, 0.5, 1.0]
    assert velocities[:, 1].tolist() == [0.0, 0.0, 0.0]
    assert positions[:, 0].tolist() == [0.0, 0.0, 0.0]  # epaule is not in the file


def test_single_waypoint_is_a_pose(tutorial_robot, tmp_path):
    path = write(tmp_path, "one.yaml", "- {time: 0.5, positions: {coude: 1e-1}}\n")
    motion = waypoint_motion(tutorial_robot, path)
    assert motion.duration == 0.5 and motion.positions(np.array([0.0, 9.0]))[:, 1].tolist() == [0.1, 0.1]


def test_too_fast_linear_segment_is_reported(tutorial_robot):
    segments = waypoint_speeds(tutorial_robot, waypoint_motion(tutorial_robot, data("fast.csv")))
    assert len(segments) == 1
    s = segments[0]
    assert (s.joint, s.start, s.end, s.speed, s.limit, s.lines) == ("epaule", 0.0, 0.5, 2.0, 1.0, (3, 4))
    assert str(describe_segment(s)) == (
        "fast.csv lines 3-4: epaule needs 2 rad/s between t=0 s and t=0.5 s (linear), above its velocity "
        "limit 1 rad/s; space these waypoints about 1 s apart")


def test_too_fast_cubic_segment_reports_its_peak_speed(tutorial_robot):
    # from rest to rest over 1 rad in 0.5 s: the cubic peaks at 1.5 x 2 rad/s in the middle
    segments = waypoint_speeds(tutorial_robot, waypoint_motion(tutorial_robot, data("fast.csv"), "cubic"))
    assert [(s.joint, s.start, s.end) for s in segments] == [("epaule", 0.0, 0.5)]
    assert segments[0].speed == pytest.approx(3.0, abs=1e-12)


def test_slow_waypoints_report_nothing(tutorial_robot):
    motion = waypoint_motion(tutorial_robot, data("arc.csv"), "cubic")
    assert waypoint_speeds(tutorial_robot, motion) == []
    assert check_limits(tutorial_robot, sample(motion)) == []


# ---------------------------------------------------------------- bad waypoint files


@pytest.mark.parametrize("name, line, words", [
    ("bad_order.csv", 4, "waypoint time 1.5 does not come after the previous one (2)"),
    ("bad_number.csv", 3, "coude: 'abc' is not a number"),
    ("bad_joint.csv", 1, "unknown joint 'genou'"),
    ("bad_missing.json", 4, "waypoint 2 has no value for coude"),
    ("bad_indent.yaml", 4, "not valid YAML"),
])
def test_bad_fixture_file_names_file_line_and_problem(tutorial_robot, name, line, words):
    with pytest.raises(ParameterError) as caught:
        waypoint_motion(tutorial_robot, data(name))
    error = caught.value
    assert error.path == data(name) and error.line == line
    assert words in str(error.message)
    assert str(error.hint)


def test_unknown_joint_in_a_file_lists_the_movable_ones(tutorial_robot):
    with pytest.raises(ParameterError) as caught:
        read_waypoints(data("bad_joint.csv"), tutorial_robot)
    assert str(caught.value.hint) == "movable joints: epaule, coude"


@pytest.mark.parametrize("name, text, line, words", [
    ("empty.csv", "# nothing\n\n", None, "empty"),
    ("header.csv", "time,epaule\n", None, "no waypoints after the header"),
    ("first.csv", "t,epaule\n0,0\n", 1, "first column is 't', not 'time'"),
    ("alone.csv", "time\n0\n", 1, "names no joint"),
    ("twice.csv", "time,epaule,epaule\n0,0,0\n", 1, "'epaule' appears twice"),
    ("short.csv", "time,epaule,coude\n0,0,0\n\n1,0.5\n", 4, "row has 2 values, the header has 3"),
    ("negative.csv", "time,epaule\n-1,0\n0,1\n", 2, "negative"),
    ("same.csv", "time,epaule\n0,0\n0,1\n", 3, "does not come after"),
    ("inf.csv", "time,epaule\n0,inf\n", 2, "'inf' is not a number"),
    ("broken.json", '{"waypoints": [\n  {"time": 0,, }\n]}', 2, "not valid JSON"),
    ("key.json", '{"interpolaton": "cubic", "waypoints": []}', None, "unknown key 'interpolaton'"),
    ("interp.json", '{"interpolation": "spline", "waypoints": [{"time": 0, "positions": {"epaule": 0}}]}',
     None, "unknown interpolation 'spline'"),
    ("none.json", '{"joints": ["epaule"]}', None, "no 'waypoints'"),
    ("emptylist.json", "[]", None, "non-empty list"),
    ("list.json", '[{"time": 0, "positions": [0, 0]}]', 1, "positions is a list but the file has no 'joints'"),
    ("count.yaml", "joints: [epaule, coude]\nwaypoints:\n  - {time: 0, positions: [0]}\n", 3,
     "1 positions for 2 joints"),
    ("scalar.yaml", "waypoints:\n  - 3\n", 2, "waypoint 1 is not a mapping"),
    ("bool.yaml", "- time: 0\n  positions: {epaule: yes}\n", 1, "epaule = True is not a number"),
    ("notime.yaml", "- positions: {epaule: 0}\n", 1, "waypoint 1: no 'time'"),
    ("extra.yaml", "- {time: 0, velocity: 1, positions: {epaule: 0}}\n", 1, "unknown key 'velocity'"),
    ("textime.yaml", "- {time: soon, positions: {epaule: 0}}\n", 1, "time 'soon' is not a number"),
    ("fixed.yaml", "- {time: 0, positions: {genou: 0}}\n", 1, "unknown joint 'genou'"),
])
def test_bad_waypoint_file(tutorial_robot, tmp_path, name, text, line, words):
    path = write(tmp_path, name, text)
    with pytest.raises(ParameterError) as caught:
        read_waypoints(path, tutorial_robot)
    assert words in str(caught.value.message)
    assert caught.value.path == path and caught.value.line == line


def test_missing_waypoint_file(tutorial_robot, tmp_path):
    with pytest.raises(ParameterError, match="no such waypoint file"):
        read_waypoints(str(tmp_path / "absent.csv"), tutorial_robot)


def test_waypoint_file_with_another_extension_is_refused(tutorial_robot, tmp_path):
    with pytest.raises(ParameterError, match="not a waypoint file"):
        read_waypoints(write(tmp_path, "w.txt", "time,epaule\n0,0\n"), tutorial_robot)


# ---------------------------------------------------------------- joint-state files


def test_csv_long_form_has_one_row_per_joint_per_sample(tutorial_robot):
    states = sample(tutorial_motion(tutorial_robot))
    lines = states_to_csv(states).splitlines()
    assert len(lines) == 1 + 201 * 2
    assert lines[0] == "time,name,position,velocity"
    assert lines[1] == "0.0,epaule,0.0,0.8"
    assert lines[3].startswith("0.05,epaule,") and lines[4].startswith("0.05,coude,")


def test_states_round_trip_through_csv_and_json_exactly(tutorial_robot, tmp_path):
    states = sample(tutorial_motion(tutorial_robot), duration=2)
    for name, text in (("s.csv", states_to_csv(states)), ("s.json", states_to_json(states))):
        back = read_states(write(tmp_path, name, text))
        assert back.names == states.names
        assert np.array_equal(back.times, states.times)
        assert np.array_equal(back.positions, states.positions)
        assert np.array_equal(back.velocities, states.velocities)


def test_json_messages_look_like_joint_state(tutorial_robot):
    messages = json.loads(states_to_json(sample(tutorial_motion(tutorial_robot), duration=1)))
    assert len(messages) == 21
    assert messages[20]["time"] == 1.0
    assert messages[20]["name"] == ["epaule", "coude"]
    assert messages[20]["position"] == [0.8 * math.sin(1.0), 1.2 * math.sin(0.7)]


def test_read_states_refuses_a_file_out_of_order(tmp_path):
    path = write(tmp_path, "s.csv", "time,name,position,velocity\n0,a,0,0\n0,b,0,0\n0.1,b,0,0\n0.1,a,0,0\n")
    with pytest.raises(ParameterError, match="out of order"):
        read_states(path)


def test_joint_states_config_by_name(tutorial_robot):
    states = JointStates(np.array([0.0]), ["epaule", "coude"], np.array([[0.1, 0.2]]), np.zeros((1, 2)))
    assert states.config(0) == {"epaule": 0.1, "coude": 0.2}
    assert states.column("coude") == 1


# ---------------------------------------------------------------- the command


def test_cli_summary_without_output(run_cli):
    code, out, err = run_cli("motion")
    assert code == 0 and err == ""
    lines = out.splitlines()
    assert lines[0] == "motion: tutorial; 10 s at 20 Hz, 201 samples x 2 joints"
    assert lines[2].split() == ["epaule", "-0.800", "0.800", "-1.57", "1.57", "0.800", "1", "rad/s", "ok",
                                "0.8*sin(t)"]
    assert lines[-1] == "all within limits"


def test_cli_writes_csv_with_one_row_per_joint_per_sample(run_cli, tmp_path):
    path = str(tmp_path / "states.csv")
    code, out, err = run_cli("motion", "-o", path)
    assert code == 0 and f"wrote {path}" in err
    lines = read(path).splitlines()
    assert len(lines) == 1 + 201 * 2
    assert lines[-1].startswith("10.0,coude,")


def test_cli_writes_json_messages(run_cli, tmp_path):
    path = str(tmp_path / "states.json")
    code, _, _ = run_cli("motion", "--wrist", "--duration", "2", "--rate", "10", "-o", path)
    messages = json.loads(read(path))
    assert code == 0 and len(messages) == 21
    assert messages[0]["name"] == ["epaule", "coude", "poignet"]


def test_cli_refuses_to_overwrite_without_force(run_cli, tmp_path):
    path = tmp_path / "states.csv"
    path.write_text("mine\n", encoding="utf-8")
    code, _, err = run_cli("motion", "-o", str(path))
    assert code == 2 and "already exists" in err and "--force" in err
    assert path.read_text(encoding="utf-8") == "mine\n"
    code, _, _ = run_cli("motion", "-o", str(path), "--force")
    assert code == 0 and path.read_text(encoding="utf-8").startswith("time,name,position,velocity\n")


def test_cli_bad_formula_exits_2_with_a_caret_and_no_traceback(run_cli):
    code, out, err = run_cli("motion", "--motion", "coude=__import__('os')")
    assert code == 2 and out == ""
    assert "Traceback" not in err
    lines = err.splitlines()
    assert lines[0] == "bras-kit motion: error: '__import__' is not allowed in a formula"
    assert lines[1:3] == ["    coude=__import__('os')", "          ^"]


def test_cli_unknown_joint_lists_the_movable_ones(run_cli):
    code, _, err = run_cli("motion", "--set", "genou=1")
    assert code == 2 and "unknown joint 'genou'" in err and "movable joints: epaule, coude" in err


def test_cli_warns_about_limits_and_clamps_on_request(run_cli, tmp_path):
    code, out, err = run_cli("motion", "-m", "coude=2.5*sin(pi*t/2)")
    assert code == 0
    assert "warning: coude goes past its upper limit 2 by 0.5 rad at t=1 s (first at t=0.6 s, 51 samples)" in err
    assert "--clamp" in err
    assert "past upper, past lower, too fast" in out
    path = str(tmp_path / "clamped.json")
    code, _, err = run_cli("motion", "-m", "coude=2.5*sin(pi*t/2)", "--clamp", "-o", path)
    coude = np.array([m["position"][1] for m in json.loads(read(path))])
    assert code == 0 and coude.max() == 2.0 and coude.min() == -2.0
    assert "warning: clamped: coude goes past its upper limit" in err


def test_cli_strict_exits_1_on_violations(run_cli):
    assert run_cli("motion", "-m", "coude=2.5*sin(t)", "--strict")[0] == 1
    assert run_cli("motion", "--strict")[0] == 0


def test_cli_waypoints_report_the_too_fast_segment(run_cli, tmp_path):
    path = str(tmp_path / "fast.csv")
    code, out, err = run_cli("motion", "-m", data("fast.csv"), "-o", path)
    assert code == 0
    assert "fast.csv lines 3-4: epaule needs 2 rad/s between t=0 s and t=0.5 s" in err
    assert len(read(path).splitlines()) == 1 + 51 * 2  # 2.5 s at 20 Hz


def test_cli_interpolation_and_duration(run_cli, tmp_path):
    path = str(tmp_path / "arc.csv")
    code, _, _ = run_cli("motion", "-m", data("arc.csv"), "--interpolation", "cubic", "--duration", "5",
                         "--rate", "2", "-o", path)
    rows = read(path).splitlines()
    assert code == 0 and len(rows) == 1 + 11 * 2
    assert rows[3] == "0.5,epaule,0.25,0.75"  # cubic from rest: 0.5 at u = 0.5 times 0.5; speed 1.5 x 0.5


def test_cli_waypoint_file_given_as_the_robot_is_explained(run_cli):
    code, _, err = run_cli("motion", data("arc.csv"))
    assert code == 2 and "looks like a waypoint file" in err and "--motion" in err


def test_cli_unknown_output_extension(run_cli, tmp_path):
    code, _, err = run_cli("motion", "-o", str(tmp_path / "states.txt"))
    assert code == 2 and "cannot tell the format" in err


def test_cli_csv_to_stdout(run_cli):
    code, out, _ = run_cli("motion", "--duration", "1", "-o", "-")
    assert code == 0 and len(out.splitlines()) == 1 + 21 * 2


@pytest.mark.parametrize("formula", ["1/0", "t % 0", "1/(t-1)", "0**-1"])
def test_division_by_zero_is_a_clean_error_not_an_exception(run_cli, formula):
    code, _, err = run_cli("motion", "--motion", f"coude={formula}", "--duration", "2")
    assert code == 2
    assert "is not a number at t=" in err
    assert "Traceback" not in err
