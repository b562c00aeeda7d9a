"""Inverse kinematics, the Jacobian, reaching motions and the workspace, against values computed by hand."""

from __future__ import annotations

import math

import numpy as np
import pytest

from bras_kit.core.errors import ParameterError
from bras_kit.ik import (
    ik_2r,
    ik_2r_batch,
    jacobian,
    minimum_duration,
    motion_violations,
    planar_two_link,
    reach_motion,
    resolve_tip,
    serial_chain,
    solve_ik,
    tip_positions,
    workspace_figure,
    workspace_points,
)
from bras_kit.kinematics.frames import fk_batch, rpy_to_matrix, tf_tree
from bras_kit.model.authoring import arm
from bras_kit.model.robot import robot_from_xml
from bras_kit.model.xmlio import parse_xml

SHOULDER = np.array([0.0, 0.0, 0.05])  # epaule origin
UPPER, FOREARM = 0.6, 0.5  # coude origin z, forearm tip along avant_bras z

# A spatial arm: yaw, two pitches, a fixed joint with a turn, a roll, a prismatic slide,
# a roll, and a mimic joint following the last roll (so one column drives two joints).
SPATIAL_URDF = """<?xml version="1.0"?>
<robot name="spatial">
  <link name="base"/><link name="l1"/><link name="l2"/><link name="l3"/><link name="l3b"/>
  <link name="l4"/><link name="l5"/><link name="l6"/>
  <link name="pince"><visual><origin xyz="0 0 0.05"/><geometry><box size="0.02 0.02 0.1"/></geometry></visual></link>
  <joint name="j1" type="revolute"><parent link="base"/><child link="l1"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="1"/></joint>
  <joint name="j2" type="revolute"><parent link="l1"/><child link="l2"/>
    <origin xyz="0 0 0.2" rpy="0.1 0 0"/><axis xyz="0 1 0"/><limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
  <joint name="j3" type="revolute"><parent link="l2"/><child link="l3"/>
    <origin xyz="0 0.05 0.4"/><axis xyz="0 1 0"/><limit lower="-2.5" upper="2.5" effort="1" velocity="1"/></joint>
  <joint name="f" type="fixed"><parent link="l3"/><child link="l3b"/><origin xyz="0.02 0 0.1" rpy="0 0 0.3"/></joint>
  <joint name="j4" type="revolute"><parent link="l3b"/><child link="l4"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-3" upper="3" effort="1" velocity="2"/></joint>
  <joint name="j5" type="prismatic"><parent link="l4"/><child link="l5"/>
    <origin xyz="0 0 0.05"/><axis xyz="0 0 1"/><limit lower="0" upper="0.2" effort="1" velocity="0.5"/></joint>
  <joint name="j6" type="revolute"><parent link="l5"/><child link="l6"/>
    <origin xyz="0 0 0.08"/><axis xyz="1 0 0"/><limit lower="-2" upper="2" effort="1" velocity="2"/></joint>
  <joint name="j7" type="revolute"><parent link="l6"/><child link="pince"/>
    <origin xyz="0 0 0.06"/><axis xyz="0 1 0"/><limit lower="-3" upper="3" effort="1" velocity="2"/>
    <mimic joint="j6" multiplier="0.5" offset="0.1"/></joint>
</robot>
"""


# Two parallel joints in a tilted plane: a fixed mount turned about x, an elbow axis pointing the
# other way with a yaw in its origin, and a tool offset off the forearm's line.
TILTED_2R_URDF = """<?xml version="1.0"?>
<robot name="tilted">
  <link name="sol"/><link name="socle"/><link name="a"/><link name="b"/><link name="outil"/>
  <joint name="mount" type="fixed"><parent link="sol"/><child link="socle"/>
    <origin xyz="0.1 0.2 0.3" rpy="0.3 0 0"/></joint>
  <joint name="q1" type="revolute"><parent link="socle"/><child link="a"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-3.2" upper="3.2" effort="1" velocity="1"/></joint>
  <joint name="q2" type="revolute"><parent link="a"/><child link="b"/>
    <origin xyz="0.4 0.1 0.05" rpy="0 0 0.5"/><axis xyz="0 0 -1"/><limit lower="-3.2" upper="3.2" effort="1" velocity="1"/></joint>
  <joint name="tool" type="fixed"><parent link="b"/><child link="outil"/><origin xyz="0.3 -0.1 0.02"/></joint>
</robot>
"""


@pytest.fixture(scope="module")
def wrist_tree(wrist_robot):
    return tf_tree(wrist_robot)


@pytest.fixture(scope="module")
def spatial_tree():
    return tf_tree(robot_from_xml(parse_xml(SPATIAL_URDF, "spatial.urdf"), "spatial.urdf"))


def random_configs(tree, count: int, seed: int) -> np.ndarray:
    lower = np.array([j.bounds()[0] for j in tree.dof_joints()])
    upper = np.array([j.bounds()[1] for j in tree.dof_joints()])
    return np.random.default_rng(seed).uniform(lower, upper, size=(count, len(tree.dof)))


def tip_by_fk(tree, q: np.ndarray, link: str, offset) -> np.ndarray:
    """Tip position from the kinematics module's own forward kinematics (independent of ik.py)."""
    transforms = fk_batch(tree, np.atleast_2d(q))[:, tree.index(link)]
    return transforms[:, :3, :3] @ np.asarray(offset, dtype=float) + transforms[:, :3, 3]


def tutorial_tip(q1: float, q2: float) -> np.ndarray:
    """The tutorial arm's tip by hand: rotations about y turn z towards x."""
    return SHOULDER + np.array([UPPER * math.sin(q1) + FOREARM * math.sin(q1 + q2), 0.0,
                                UPPER * math.cos(q1) + FOREARM * math.cos(q1 + q2)])


# ---------------------------------------------------------------- the tip and the structure


def test_default_tip_is_the_far_end_of_the_forearm(tutorial_tree, wrist_tree):
    link, offset = resolve_tip(tutorial_tree)
    assert link == "avant_bras"
    np.testing.assert_allclose(offset, [0.0, 0.0, 0.5], atol=1e-15)
    link, offset = resolve_tip(wrist_tree)
    assert link == "main"
    np.testing.assert_allclose(offset, [0.0, 0.0, 0.15], atol=1e-15)


def test_tip_of_a_named_link_is_its_segment_end_and_the_offset_can_be_set(tutorial_tree):
    assert resolve_tip(tutorial_tree, "bras")[1][2] == pytest.approx(0.6)
    np.testing.assert_allclose(resolve_tip(tutorial_tree, "bras", (0.1, 0, -0.2))[1], [0.1, 0, -0.2])


def test_unknown_tip_link_names_the_valid_links(tutorial_tree):
    with pytest.raises(ParameterError, match="unknown link 'pince'") as err:
        solve_ik(tutorial_tree, (0.5, 0, 0.65), tip_link="pince")
    assert "avant_bras" in str(err.value.hint)


def test_two_link_structure_is_read_from_the_model(tutorial_tree):
    shape = planar_two_link(tutorial_tree)
    assert (shape.shoulder, shape.elbow) == ("epaule", "coude")
    assert shape.upper == pytest.approx(0.6) and shape.lower == pytest.approx(0.5)
    np.testing.assert_allclose(shape.origin, SHOULDER, atol=1e-15)
    assert abs(shape.normal[1]) == pytest.approx(1.0)
    assert shape.reach == pytest.approx((0.1, 1.1))


def test_two_link_structure_follows_changed_parameters():
    shape = planar_two_link(tf_tree(arm(params={"bras_length": 0.8, "avant_bras_length": 0.3, "base_length": 0.2})))
    assert shape.upper == pytest.approx(0.8) and shape.lower == pytest.approx(0.3)
    np.testing.assert_allclose(shape.origin, [0, 0, 0.1], atol=1e-15)


def test_two_link_structure_in_a_tilted_plane_round_trips():
    tree = tf_tree(robot_from_xml(parse_xml(TILTED_2R_URDF, "tilted.urdf"), "tilted.urdf"))
    shape = planar_two_link(tree)
    assert shape is not None and shape.sign == -1.0
    assert shape.upper == pytest.approx(math.hypot(0.4, 0.1))
    assert shape.lower == pytest.approx(math.hypot(0.3, 0.1))
    configs = random_configs(tree, 200, seed=4)
    targets = tip_by_fk(tree, configs, "outil", (0, 0, 0))
    for elbow in ("up", "down"):
        solved, ok = ik_2r_batch(shape, targets, elbow)
        assert ok.all()
        np.testing.assert_allclose(tip_by_fk(tree, solved, "outil", (0, 0, 0)), targets, atol=1e-9)
    result = ik_2r(tree, targets[0] + 0.05 * shape.normal)
    assert result.reason == "off_plane" and "0.05 m off" in str(result.message) and "the plane through" in str(result.message)


def test_chains_other_than_two_parallel_joints_are_not_two_link(wrist_tree, spatial_tree, tutorial_tree):
    assert planar_two_link(wrist_tree) is None
    assert planar_two_link(spatial_tree) is None
    assert planar_two_link(tutorial_tree, tip_link="bras") is None  # one joint


# ---------------------------------------------------------------- closed form


def test_ik_2r_gives_both_elbows_of_a_hand_solved_target(tutorial_tree):
    # epaule = 0, coude = pi/2 puts the tip at (0.5, 0, 0.65); the other elbow mirrors it about
    # the shoulder -> target line: epaule = 2 atan2(0.5, 0.6), coude = -pi/2.
    up = ik_2r(tutorial_tree, (0.5, 0.0, 0.65), elbow="up")
    down = ik_2r(tutorial_tree, (0.5, 0.0, 0.65), elbow="down")
    assert up.reachable and down.reachable and up.method == "analytic"
    assert up.joints["epaule"] == pytest.approx(0.0, abs=1e-12)
    assert up.joints["coude"] == pytest.approx(math.pi / 2, abs=1e-12)
    assert down.joints["epaule"] == pytest.approx(2 * math.atan2(0.5, 0.6), abs=1e-12)
    assert down.joints["coude"] == pytest.approx(-math.pi / 2, abs=1e-12)
    assert up.residual < 1e-12 and down.residual < 1e-12
    assert [s.elbow for s in up.solutions] == ["up", "down"]


def test_negative_x_target_mirrors_the_solution(tutorial_tree):
    result = ik_2r(tutorial_tree, (-0.5, 0.0, 0.65), elbow="up")
    assert result.joints["epaule"] == pytest.approx(0.0, abs=1e-12)
    assert result.joints["coude"] == pytest.approx(-math.pi / 2, abs=1e-12)


def test_ik_2r_without_elbow_picks_the_solution_closest_to_the_start(tutorial_tree):
    near_down = ik_2r(tutorial_tree, (0.5, 0.0, 0.65), start={"epaule": 1.3, "coude": -1.4})
    assert near_down.elbow == "down"
    assert ik_2r(tutorial_tree, (0.5, 0.0, 0.65)).elbow == "up"  # from the zero pose


def test_round_trip_of_random_targets_both_elbows(tutorial_tree):
    shape = planar_two_link(tutorial_tree)
    rng = np.random.default_rng(7)
    q = rng.uniform(-math.pi, math.pi, size=(500, 2))
    q = q[np.abs(np.sin(q[:, 1])) > 1e-3]  # keep clear of the boundary, where x -> acos is flat
    targets = np.array([tutorial_tip(a, b) for a, b in q])
    for elbow in ("up", "down"):
        solved, ok = ik_2r_batch(shape, targets, elbow)
        assert ok.all()
        np.testing.assert_allclose(tip_by_fk(tutorial_tree, solved, "avant_bras", (0, 0, 0.5)), targets, atol=1e-9)
    up, _ = ik_2r_batch(shape, targets, "up")
    down, _ = ik_2r_batch(shape, targets, "down")
    assert np.all(np.abs(up[:, 1] + down[:, 1]) < 1e-9)  # the two elbows bend opposite ways
    # one of the two is the configuration the target came from
    same = np.minimum(np.abs(np.remainder(up - q + math.pi, 2 * math.pi) - math.pi).max(axis=1),
                      np.abs(np.remainder(down - q + math.pi, 2 * math.pi) - math.pi).max(axis=1))
    assert same.max() < 1e-7


def test_round_trip_within_limits_through_ik_2r(tutorial_tree):
    for q1, q2 in random_configs(tutorial_tree, 150, seed=3):
        target = tutorial_tip(q1, q2)
        result = ik_2r(tutorial_tree, target)
        assert result.reachable, str(result.message)
        q = np.array([result.joints["epaule"], result.joints["coude"]])
        assert np.linalg.norm(tip_by_fk(tutorial_tree, q, "avant_bras", (0, 0, 0.5))[0] - target) < 1e-9
        assert abs(q[0]) <= 1.57 and abs(q[1]) <= 2.0
        for solution in result.solutions:  # both elbows land on the target, limits or not
            s = np.array([solution.joints["epaule"], solution.joints["coude"]])
            assert np.linalg.norm(tip_by_fk(tutorial_tree, s, "avant_bras", (0, 0, 0.5))[0] - target) < 1e-9


def test_too_far_is_reported_with_the_distance(tutorial_tree):
    result = ik_2r(tutorial_tree, (0.0, 0.0, 1.2))  # 1.15 m from the shoulder, reach 1.1 m
    assert not result.reachable and result.reason == "too_far"
    assert "0.05 m too far" in str(result.message)
    # the closest pose within limits is the stretched arm pointing at the target
    assert result.residual == pytest.approx(0.05, abs=1e-9)
    assert result.joints["epaule"] == pytest.approx(0.0, abs=1e-6)


def test_too_close_is_reported_with_the_distance(tutorial_tree):
    result = ik_2r(tutorial_tree, (0.0, 0.0, 0.1))  # 0.05 m from the shoulder, inner radius 0.1
    assert not result.reachable and result.reason == "too_close"
    assert "0.05 m too close" in str(result.message)


def test_target_off_the_arm_plane_is_unreachable(tutorial_tree):
    result = ik_2r(tutorial_tree, (0.5, 0.1, 0.65))
    assert not result.reachable and result.reason == "off_plane"
    assert "y = 0" in str(result.message) and "0.1 m off" in str(result.message)


def test_target_past_the_elbow_limit_names_the_joint_and_the_excess(tutorial_tree):
    # (0.5, 0, 0.3): 0.3125 = 0.61 + 0.6 cos(g): the elbow must bend acos(-0.4958) = 2.0896 > 2
    result = ik_2r(tutorial_tree, (0.5, 0.0, 0.3), elbow="up")
    assert not result.reachable and result.reason == "limits"
    excess = math.acos((0.3125 - 0.61) / 0.6) - 2.0
    assert [v.joint for v in result.violations] == ["coude"]
    assert result.violations[0].side == "upper"
    assert result.violations[0].excess == pytest.approx(excess, abs=1e-12)
    assert f"{excess:.4f} rad past its upper limit 2" in str(result.message)
    # the answer is still a pose within the limits, as close as they allow
    assert result.joints["coude"] <= 2.0 + 1e-12
    assert 0 < result.residual < 0.1


def test_target_past_the_shoulder_limit_names_the_shoulder(tutorial_tree):
    # (0.3, 0, -0.8) needs the upper arm pointing down: epaule = 2.2529 or -2.9315, past the 1.57 limits
    result = ik_2r(tutorial_tree, (0.3, 0.0, -0.8))
    assert result.reason == "limits"
    assert {v.joint for v in result.violations} == {"epaule"}
    rel = np.array([0.3, -0.85])
    gamma = math.acos((rel @ rel - 0.61) / 0.6)
    expected = math.atan2(0.3, -0.85) - math.atan2(0.5 * math.sin(gamma), 0.6 + 0.5 * math.cos(gamma))
    assert result.violations[0].value == pytest.approx(expected, abs=1e-12)
    assert result.violations[0].excess == pytest.approx(expected - 1.57, abs=1e-12)
    assert f"epaule would need {expected:.4f} rad, {expected - 1.57:.4f} rad past its upper limit 1.57" in str(result.message)


def test_other_elbow_is_suggested_when_it_is_within_limits(tutorial_tree):
    # elbow down for (0.6, 0, -0.2) needs epaule = 2.78; elbow up is fine
    result = ik_2r(tutorial_tree, (0.6, 0.0, -0.2), elbow="down")
    assert result.reason == "limits" and "elbow up is within the limits" in str(result.message)
    assert ik_2r(tutorial_tree, (0.6, 0.0, -0.2)).elbow == "up"


def test_stretched_arm_is_singular(tutorial_tree):
    result = ik_2r(tutorial_tree, (0.0, 0.0, 1.15))
    assert result.reachable and result.singular and result.reason == "singular"
    assert result.joints == {"epaule": 0.0, "coude": 0.0}
    assert "fully stretched" in str(result.message)


def test_target_on_the_shoulder_axis_is_singular():
    tree = tf_tree(arm(params={"bras_length": 0.5, "coude_lower": -3.2, "coude_upper": 3.2}))
    result = ik_2r(tree, (0.0, 0.0, 0.05), start={"epaule": 0.3})
    assert result.reachable and result.singular
    assert result.joints["epaule"] == pytest.approx(0.3)  # any shoulder angle works: keep the start's
    assert abs(result.joints["coude"]) == pytest.approx(math.pi)
    assert "shoulder axis" in str(result.message)


def test_ik_2r_refuses_other_chains(wrist_tree):
    with pytest.raises(ParameterError, match="not two revolute joints"):
        ik_2r(wrist_tree, (0.3, 0, 0.8))


@pytest.mark.parametrize("bad", [(math.nan, 0, 0.5), (0.3, math.inf, 0.5)])
def test_non_finite_targets_are_refused(tutorial_tree, wrist_tree, bad):
    with pytest.raises(ParameterError, match="not finite"):
        solve_ik(tutorial_tree, bad)
    with pytest.raises(ParameterError, match="not finite"):
        solve_ik(wrist_tree, bad)


# ---------------------------------------------------------------- numeric


def test_numeric_round_trip_for_the_wrist_arm(wrist_tree):
    lower, upper = np.array([-1.57, -2.0, -1.57]), np.array([1.57, 2.0, 1.57])
    configs = random_configs(wrist_tree, 200, seed=11)
    targets = tip_by_fk(wrist_tree, configs, "main", (0, 0, 0.15))
    for target in targets:
        result = solve_ik(wrist_tree, target)
        assert result.reachable and result.method == "numeric", str(result.message)
        q = np.array([result.joints[n] for n in wrist_tree.dof])
        assert np.all(q >= lower) and np.all(q <= upper)
        assert np.linalg.norm(tip_by_fk(wrist_tree, q, "main", (0, 0, 0.15))[0] - target) < 1e-9


def test_numeric_solver_starts_from_the_start_pose(wrist_tree):
    # the start already reaches the target: nothing to do
    start = {"epaule": 0.4, "coude": -0.7, "poignet": 0.2}
    target = tip_by_fk(wrist_tree, np.array([0.4, -0.7, 0.2]), "main", (0, 0, 0.15))[0]
    result = solve_ik(wrist_tree, target, start=start)
    assert result.iterations == 0 and result.joints == pytest.approx(start)


def test_numeric_solver_is_deterministic(wrist_tree):
    first = solve_ik(wrist_tree, (0.4, 0.0, 0.2))
    second = solve_ik(wrist_tree, (0.4, 0.0, 0.2))
    assert first.joints == second.joints and first.iterations == second.iterations


def test_numeric_position_and_orientation_for_the_wrist_arm(wrist_tree):
    # pitch 1.0 about y with the tip at (0.3, 0, 0.8): epaule + coude + poignet = 1.0
    result = solve_ik(wrist_tree, (0.3, 0.0, 0.8), rotation=rpy_to_matrix((0.0, 1.0, 0.0)))
    assert result.reachable and result.rotation_residual < 1e-9 and result.residual < 1e-9
    assert sum(result.joints.values()) == pytest.approx(1.0, abs=1e-9)


def test_numeric_out_of_reach_gives_the_closest_point(wrist_tree):
    result = solve_ik(wrist_tree, (0.0, 0.0, 1.5))  # straight up, reach 0.05 + 1.25 = 1.3
    assert not result.reachable and result.reason == "out_of_reach"
    assert result.residual == pytest.approx(0.2, abs=1e-6)
    assert "no closer than 0.2 m" in str(result.message)


def test_numeric_target_past_a_limit_names_the_joint(wrist_tree):
    result = solve_ik(wrist_tree, (0.0, 0.0, -1.0))  # straight down needs epaule near pi
    assert not result.reachable and result.reason == "limits"
    assert "epaule" in {v.joint for v in result.violations}
    assert "reachable only past the limits: epaule would need" in str(result.message)


def test_elbow_choice_is_refused_for_the_wrist_arm(wrist_tree):
    with pytest.raises(ParameterError, match="3 joints"):
        solve_ik(wrist_tree, (0.3, 0, 0.8), elbow="up")


def test_numeric_round_trip_of_a_spatial_arm_with_orientation(spatial_tree):
    chain = serial_chain(spatial_tree)
    assert chain.tip_link == "pince" and chain.joints == ("j1", "j2", "j3", "j4", "j5", "j6", "j7")
    configs = random_configs(spatial_tree, 40, seed=5)
    transforms = fk_batch(spatial_tree, configs)[:, spatial_tree.index("pince")]
    for pose in transforms:
        target = pose[:3, :3] @ np.array([0, 0, 0.1]) + pose[:3, 3]
        result = solve_ik(spatial_tree, target, rotation=pose[:3, :3])
        assert result.reachable, str(result.message)
        assert result.residual < 1e-9 and result.rotation_residual < 1e-9
        assert 0.0 <= result.joints["j5"] <= 0.2


def test_a_chain_without_movable_joints_cannot_be_solved(tutorial_tree):
    with pytest.raises(ParameterError, match="no movable joint"):
        solve_ik(tutorial_tree, (0, 0, 0.05), tip_link="base", method="numeric")


# ---------------------------------------------------------------- Jacobian


def _finite_difference_jacobian(tree, q, link, offset, step=1e-6):
    rows = []
    for i in range(len(q)):
        plus, minus = q.copy(), q.copy()
        plus[i] += step
        minus[i] -= step
        tp, tm = fk_batch(tree, np.stack([plus, minus]))[:, tree.index(link)]
        linear = ((tp[:3, :3] @ offset + tp[:3, 3]) - (tm[:3, :3] @ offset + tm[:3, 3])) / (2 * step)
        delta = tp[:3, :3] @ tm[:3, :3].T  # small rotation: its skew part / 2 step = angular velocity
        angular = np.array([delta[2, 1] - delta[1, 2], delta[0, 2] - delta[2, 0], delta[1, 0] - delta[0, 1]]) / (4 * step)
        rows.append(np.concatenate([linear, angular]))
    return np.array(rows).T


@pytest.mark.parametrize("which", ["tutorial", "wrist", "spatial"])
def test_jacobian_matches_finite_differences(which, tutorial_tree, wrist_tree, spatial_tree):
    tree = {"tutorial": tutorial_tree, "wrist": wrist_tree, "spatial": spatial_tree}[which]
    link, offset = resolve_tip(tree)
    for q in random_configs(tree, 10, seed=2):
        if which == "spatial":
            q[4] = min(max(q[4], 1e-3), 0.199)  # keep the slide inside its limits for the differences
        expected = _finite_difference_jacobian(tree, q, link, offset)
        np.testing.assert_allclose(jacobian(tree, q), expected, atol=1e-6)
        np.testing.assert_allclose(jacobian(tree, q, orientation=False), expected[:3], atol=1e-6)


def test_jacobian_of_the_tutorial_arm_by_hand(tutorial_tree):
    q1, q2 = 0.3, -0.8
    j = jacobian(tutorial_tree, {"epaule": q1, "coude": q2})
    # x = 0.6 sin q1 + 0.5 sin(q1 + q2), z = 0.05 + 0.6 cos q1 + 0.5 cos(q1 + q2); both joints turn about +y
    expected_linear = np.array([
        [0.6 * math.cos(q1) + 0.5 * math.cos(q1 + q2), 0.5 * math.cos(q1 + q2)],
        [0.0, 0.0],
        [-0.6 * math.sin(q1) - 0.5 * math.sin(q1 + q2), -0.5 * math.sin(q1 + q2)],
    ])
    np.testing.assert_allclose(j[:3], expected_linear, atol=1e-15)
    np.testing.assert_allclose(j[3:], [[0, 0], [1, 1], [0, 0]], atol=1e-15)


def test_jacobian_batches_and_zero_columns_off_the_chain(wrist_tree):
    q = random_configs(wrist_tree, 4, seed=1)
    batch = jacobian(wrist_tree, q)
    assert batch.shape == (4, 6, 3)
    np.testing.assert_allclose(batch[2], jacobian(wrist_tree, q[2]))
    to_elbow = jacobian(wrist_tree, q[0], "avant_bras", (0, 0, 0))
    np.testing.assert_array_equal(to_elbow[:, 2], 0.0)  # poignet does not move avant_bras


def test_chain_tip_matches_forward_kinematics(spatial_tree):
    q = random_configs(spatial_tree, 20, seed=9)
    np.testing.assert_allclose(tip_positions(spatial_tree, q), tip_by_fk(spatial_tree, q, "pince", (0, 0, 0.1)),
                               atol=1e-14)


# ---------------------------------------------------------------- reaching motion


def test_minimum_duration_by_hand(tutorial_tree):
    # quintic peak speed 15/8 |dq| / T: coude moves 1.6 rad at 1 rad/s -> T = 3 s
    start, goal = np.array([0.2, -0.8]), np.array([-0.4, 0.8])
    assert minimum_duration(tutorial_tree, start, goal) == pytest.approx(15 / 8 * 1.6)


def test_reaching_motion_stays_within_position_and_velocity_limits(wrist_tree):
    start = {"epaule": -1.5, "coude": 1.9, "poignet": -1.5}
    result = solve_ik(wrist_tree, (0.9, 0.0, 0.3), start=start)
    assert result.reachable
    motion = reach_motion(wrist_tree, start, result.joints)
    times = np.linspace(-0.5, motion.duration + 0.5, 20_001)
    positions = motion.positions(times)
    velocities = motion.velocities(times)
    limits = np.array([1.0, 1.0, 1.5])
    lower, upper = np.array([-1.57, -2.0, -1.57]), np.array([1.57, 2.0, 1.57])
    assert np.all(positions >= lower) and np.all(positions <= upper)
    assert np.all(np.abs(velocities) <= limits * (1 + 1e-12))
    numeric = np.diff(positions, axis=0) / np.diff(times)[:, None]
    assert np.all(np.abs(numeric) <= limits * (1 + 1e-6))
    # the slowest joint hits its limit exactly at mid-move; the move starts and ends at rest
    assert np.max(np.abs(velocities) / limits) == pytest.approx(1.0, abs=1e-6)
    np.testing.assert_allclose(motion.positions(0.0)[0], [-1.5, 1.9, -1.5])
    np.testing.assert_allclose(motion.positions(motion.duration)[0], [result.joints[n] for n in wrist_tree.dof])
    np.testing.assert_allclose(motion.velocities([0.0, motion.duration]), 0.0, atol=1e-15)
    assert motion_violations(wrist_tree, motion) == []


def test_too_short_a_move_is_refused_with_the_shortest_duration(tutorial_tree):
    with pytest.raises(ParameterError, match="coude would turn at") as err:
        reach_motion(tutorial_tree, None, {"epaule": 0.2, "coude": 1.6}, duration=1.0)
    assert "at least 3 s" in str(err.value.hint)
    assert reach_motion(tutorial_tree, None, {"epaule": 0.2, "coude": 1.6}, duration=4.0).duration == 4.0


def test_move_from_a_start_outside_the_limits_is_flagged(tutorial_tree):
    motion = reach_motion(tutorial_tree, {"coude": 2.5}, {"coude": 1.0})
    violations = motion_violations(tutorial_tree, motion)
    assert [(v.joint, v.side) for v in violations] == [("coude", "upper")]
    assert violations[0].excess == pytest.approx(0.5)


# ---------------------------------------------------------------- workspace


def test_workspace_points_respect_the_limits(tutorial_tree):
    bounded = workspace_points(tutorial_tree, 20_000)
    free = workspace_points(tutorial_tree, 20_000, limits=False)
    for points in (bounded, free):
        distance = np.linalg.norm(points - SHOULDER, axis=1)
        assert distance.max() <= 1.1 + 1e-12 and distance.min() >= 0.1 - 1e-12
        assert np.all(np.abs(points[:, 1]) < 1e-15)
    # lowest tip within limits: epaule = 1.57 with the forearm pointing down, z = 0.05 + 0.6 cos 1.57 - 0.5
    assert bounded[:, 2].min() >= 0.05 + 0.6 * math.cos(1.57) - 0.5 - 1e-12
    assert free[:, 2].min() < -1.0


def _pixel(figure, axes, x, z):
    figure.canvas.draw()
    image = np.asarray(figure.canvas.buffer_rgba())
    px, py = axes.transData.transform((x, z))
    return image[int(round(image.shape[0] - py)), int(round(px)), :3].astype(int)


def test_workspace_figure_shows_limits_solid_and_free_region_faint(tutorial_tree):
    figure, axes, summary = workspace_figure(tutorial_tree, 40_000)
    assert summary.axes == ("x", "z")
    solid = _pixel(figure, axes, 0.8, 0.3)  # reachable within the limits
    faint = _pixel(figure, axes, 0.05, -0.9)  # only with epaule near pi (off the grid lines)
    empty = _pixel(figure, axes, 0.9, -0.9)  # 1.31 m from the shoulder: never
    np.testing.assert_allclose(solid, [38, 89, 204], atol=3)
    np.testing.assert_allclose(faint, 255 * 0.65 + 0.35 * 255 * np.array([0.55, 0.65, 0.85]), atol=3)
    np.testing.assert_array_equal(empty, [255, 255, 255])
    # annulus areas: pi (1.1^2 - 0.1^2) without limits; cells are coarse, so within a few percent
    assert summary.area_without_limits == pytest.approx(math.pi * 1.2, rel=0.05)
    assert summary.area_within_limits < summary.area_without_limits
    assert summary.max_reach == pytest.approx(1.1, abs=1e-3)


def test_reaching_motion_samples_like_any_motion_and_passes_the_limit_check(wrist_robot, wrist_tree):
    from bras_kit.motion import check_limits, sample

    start = {"epaule": 0.3, "coude": -0.5}
    result = solve_ik(wrist_tree, (0.5, 0.0, 0.6), start=start)
    motion = reach_motion(wrist_tree, start, result.joints)
    states = sample(motion, motion.duration, 50.0)
    assert states.names == list(wrist_tree.dof)
    np.testing.assert_allclose(states.positions[0], [0.3, -0.5, 0.0], atol=1e-15)
    np.testing.assert_allclose(states.positions, motion.positions(states.times), atol=1e-15)
    np.testing.assert_allclose(states.velocities, motion.velocities(states.times), atol=1e-15)
    assert check_limits(wrist_robot, states) == []


def _reachable_by_hand(x: np.ndarray, z: np.ndarray, l1: float, l2: float, q1: float, q2: float) -> np.ndarray:
    """Points (shoulder frame) some pose with |epaule| <= q1, |coude| <= q2 reaches: law of cosines."""
    r2 = x * x + z * z
    c = (r2 - l1 * l1 - l2 * l2) / (2 * l1 * l2)
    ok = np.zeros_like(x, dtype=bool)
    inside = np.abs(c) <= 1
    for sign in (1, -1):
        elbow = sign * np.arccos(np.clip(c, -1, 1))
        shoulder = np.arctan2(x, z) - np.arctan2(l2 * np.sin(elbow), l1 + l2 * np.cos(elbow))
        shoulder = (shoulder + np.pi) % (2 * np.pi) - np.pi
        ok |= inside & (np.abs(elbow) <= q2) & (np.abs(shoulder) <= q1)
    return ok


def test_workspace_areas_agree_with_the_exact_regions(tutorial_tree):
    _, _, summary = workspace_figure(tutorial_tree, 100_000)
    assert summary.area_without_limits == pytest.approx(math.pi * (1.1 ** 2 - 0.1 ** 2), rel=0.015)
    grid = np.linspace(-1.1, 1.1, 2001)
    x, z = np.meshgrid(grid, grid)
    exact = _reachable_by_hand(x, z, 0.6, 0.5, 1.57, 2.0).mean() * 2.2 ** 2
    assert summary.area_within_limits == pytest.approx(exact, rel=0.02)
