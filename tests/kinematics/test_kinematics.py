"""Forward kinematics and the TF tree, against values computed by hand."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from bras_kit.core.errors import ModelError, ParameterError
from bras_kit.kinematics.frames import (
    fk,
    fk_batch,
    matrix_to_quat_xyzw,
    matrix_to_rpy,
    relative_transform,
    rpy_to_matrix,
    tf_tree,
)
from bras_kit.model.robot import robot_from_xml
from bras_kit.model.xmlio import parse_xml


def robot_from(text: str):
    return robot_from_xml(parse_xml(text, "test.urdf"), "test.urdf")


def rot_y(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, 0, s], [0, 1, 0], [-s, 0, c]])


def rot_x(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[1, 0, 0], [0, c, -s], [0, s, c]])


def rot_z(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0], [s, c, 0], [0, 0, 1]])


POSES = [(0.0, 0.0), (0.5, -0.7), (0.8, 1.2), (-1.57, 2.0), (1.0, -2.0)]


@pytest.mark.parametrize("shoulder,elbow", POSES)
def test_forearm_frame_matches_hand_computation(tutorial_tree, shoulder, elbow):
    transforms = fk(tutorial_tree, {"epaule": shoulder, "coude": elbow})
    forearm = transforms["avant_bras"]
    expected_origin = [0.6 * math.sin(shoulder), 0.0, 0.05 + 0.6 * math.cos(shoulder)]
    np.testing.assert_allclose(forearm[:3, 3], expected_origin, atol=1e-12)
    np.testing.assert_allclose(forearm[:3, :3], rot_y(shoulder + elbow), atol=1e-12)
    upper = transforms["bras"]
    np.testing.assert_allclose(upper[:3, 3], [0.0, 0.0, 0.05], atol=1e-12)
    np.testing.assert_allclose(upper[:3, :3], rot_y(shoulder), atol=1e-12)


def test_zero_pose_stacks_segments_vertically(tutorial_tree):
    transforms = fk(tutorial_tree)
    np.testing.assert_allclose(transforms["avant_bras"][:3, 3], [0, 0, 0.65], atol=1e-12)
    np.testing.assert_allclose(transforms["base"], np.eye(4), atol=0)


def test_wrist_joint_sits_at_forearm_tip(wrist_robot):
    tree = tf_tree(wrist_robot)
    a, b, c = 0.3, -0.4, 0.9
    wrist = fk(tree, {"epaule": a, "coude": b, "poignet": c})["main"]
    expected = [0.6 * math.sin(a) + 0.5 * math.sin(a + b), 0.0,
                0.05 + 0.6 * math.cos(a) + 0.5 * math.cos(a + b)]
    np.testing.assert_allclose(wrist[:3, 3], expected, atol=1e-12)
    np.testing.assert_allclose(wrist[:3, :3], rot_y(a + b + c), atol=1e-12)


def test_batched_fk_equals_single_fk(wrist_robot):
    tree = tf_tree(wrist_robot)
    rng = np.random.default_rng(7)
    q = rng.uniform(-1.5, 1.5, size=(50, len(tree.dof)))
    batch = fk_batch(tree, q)
    assert batch.shape == (50, len(tree.links), 4, 4)
    for k in range(50):
        single = fk(tree, dict(zip(tree.dof, q[k])))
        for i, name in enumerate(tree.links):
            np.testing.assert_allclose(batch[k, i], single[name], atol=1e-14)


PRISMATIC_CHAIN = """<robot name="gantry">
  <link name="world"/><link name="carriage"/><link name="arm"/>
  <joint name="slide" type="prismatic">
    <parent link="world"/><child link="carriage"/>
    <origin xyz="0.1 0 0.2"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="1" effort="5" velocity="0.5"/>
  </joint>
  <joint name="turn" type="revolute">
    <parent link="carriage"/><child link="arm"/>
    <origin xyz="0 0 0.3"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" effort="5" velocity="1"/>
  </joint>
</robot>"""


def test_prismatic_then_revolute_chain():
    tree = tf_tree(robot_from(PRISMATIC_CHAIN))
    transforms = fk(tree, {"slide": 0.4, "turn": 0.25})
    np.testing.assert_allclose(transforms["carriage"][:3, 3], [0.5, 0, 0.2], atol=1e-12)
    np.testing.assert_allclose(transforms["arm"][:3, 3], [0.5, 0, 0.5], atol=1e-12)
    np.testing.assert_allclose(transforms["arm"][:3, :3], rot_z(0.25), atol=1e-12)


BRANCHING = """<robot name="fork">
  <link name="base"/><link name="left"/><link name="right"/><link name="tool"/>
  <joint name="j_left" type="continuous">
    <parent link="base"/><child link="left"/><origin xyz="0 0.2 0"/><axis xyz="0 0 1"/>
  </joint>
  <joint name="j_right" type="revolute">
    <parent link="base"/><child link="right"/><origin xyz="0 -0.2 0" rpy="0 0 1.5707963267948966"/>
    <axis xyz="1 0 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="tool_mount" type="fixed">
    <parent link="left"/><child link="tool"/><origin xyz="0.3 0 0.1" rpy="0.1 0.2 0.3"/>
  </joint>
</robot>"""


def test_branching_tree_with_fixed_tool_frame():
    tree = tf_tree(robot_from(BRANCHING))
    assert tree.root == "base"
    assert set(tree.children("base")) == {"left", "right"}
    assert tree.dof == ("j_left", "j_right")
    q = 0.7
    transforms = fk(tree, {"j_left": q, "j_right": 0.4})
    tool_rot = rot_z(q) @ (rot_z(0.3) @ rot_y(0.2) @ rot_x(0.1))
    tool_pos = np.array([0, 0.2, 0]) + rot_z(q) @ np.array([0.3, 0, 0.1])
    np.testing.assert_allclose(transforms["tool"][:3, :3], tool_rot, atol=1e-12)
    np.testing.assert_allclose(transforms["tool"][:3, 3], tool_pos, atol=1e-12)
    right_rot = rot_z(math.pi / 2) @ rot_x(0.4)
    np.testing.assert_allclose(transforms["right"][:3, :3], right_rot, atol=1e-12)


def test_relative_transform_is_pose_of_target_in_source(tutorial_tree):
    relative = relative_transform(tutorial_tree, {"epaule": 0.9, "coude": 0.3}, "bras", "avant_bras")
    np.testing.assert_allclose(relative[:3, 3], [0, 0, 0.6], atol=1e-12)
    np.testing.assert_allclose(relative[:3, :3], rot_y(0.3), atol=1e-12)


def test_mimic_joint_follows_its_leader():
    text = """<robot name="gripper">
      <link name="palm"/><link name="f1"/><link name="f2"/>
      <joint name="finger" type="prismatic"><parent link="palm"/><child link="f1"/>
        <axis xyz="0 1 0"/><limit lower="0" upper="0.04" effort="1" velocity="0.1"/></joint>
      <joint name="finger_mirror" type="prismatic"><parent link="palm"/><child link="f2"/>
        <axis xyz="0 1 0"/><limit lower="-0.04" upper="0" effort="1" velocity="0.1"/>
        <mimic joint="finger" multiplier="-1" offset="0.001"/></joint>
    </robot>"""
    tree = tf_tree(robot_from(text))
    assert tree.dof == ("finger",)
    transforms = fk(tree, {"finger": 0.03})
    np.testing.assert_allclose(transforms["f2"][:3, 3], [0, -0.029, 0], atol=1e-12)


def test_ten_thousand_link_chain_needs_no_recursion():
    count = 10_000
    parts = ['<robot name="long">'] + [f'<link name="l{i}"/>' for i in range(count)]
    parts += [f'<joint name="j{i}" type="revolute"><parent link="l{i}"/><child link="l{i + 1}"/>'
              f'<origin xyz="0 0 0.01"/><axis xyz="0 1 0"/>'
              f'<limit lower="-1" upper="1" effort="1" velocity="1"/></joint>' for i in range(count - 1)]
    tree = tf_tree(robot_from("".join(parts) + "</robot>"))
    transforms = fk_batch(tree, np.zeros(len(tree.dof)))
    np.testing.assert_allclose(transforms[-1, :3, 3], [0, 0, 0.01 * (count - 1)], atol=1e-9)
    assert tree.depth(f"l{count - 1}") == count - 1


def test_floating_joint_is_reported_not_moved():
    text = """<robot name="f"><link name="a"/><link name="b"/>
      <joint name="free" type="floating"><parent link="a"/><child link="b"/><origin xyz="1 2 3"/></joint></robot>"""
    tree = tf_tree(robot_from(text))
    assert tree.unsupported_joints == ["free"]
    assert tree.dof == ()
    np.testing.assert_allclose(fk(tree)["b"][:3, 3], [1, 2, 3])


@pytest.mark.parametrize("rpy", [(0.1, 0.2, 0.3), (-2.0, 1.0, 3.0), (0.0, -1.2, 0.0)])
def test_rpy_is_fixed_axis_roll_pitch_yaw_and_round_trips(rpy):
    matrix = rpy_to_matrix(rpy)
    np.testing.assert_allclose(matrix, rot_z(rpy[2]) @ rot_y(rpy[1]) @ rot_x(rpy[0]), atol=1e-12)
    np.testing.assert_allclose(matrix_to_rpy(matrix), rpy, atol=1e-12)


def test_quaternion_of_rotation_about_y():
    x, y, z, w = matrix_to_quat_xyzw(rot_y(0.6))
    np.testing.assert_allclose([x, y, z, w], [0, math.sin(0.3), 0, math.cos(0.3)], atol=1e-12)


@pytest.mark.parametrize("body,expected", [
    ('<joint name="a" type="fixed"><parent link="base"/><child link="ghost"/></joint>', "ghost"),
    ('<joint name="a" type="fixed"><parent link="base"/><child link="x"/></joint>'
     '<joint name="b" type="fixed"><parent link="base"/><child link="x"/></joint>', "two parents"),
    ('<joint name="a" type="fixed"><parent link="x"/><child link="y"/></joint>'
     '<joint name="b" type="fixed"><parent link="y"/><child link="x"/></joint>', "loop"),
    ("", "several root links: base, x, y"),
])
def test_tree_errors_name_the_culprits(body, expected):
    text = f'<robot name="r"><link name="base"/><link name="x"/><link name="y"/>{body}</robot>'
    with pytest.raises(ModelError, match=expected):
        tf_tree(robot_from(text))


def test_unknown_joint_in_configuration_lists_movable_joints(tutorial_tree):
    with pytest.raises(ParameterError) as info:
        tutorial_tree.config_vector({"genou": 1.0})
    assert "genou" in str(info.value) and "epaule, coude" in str(info.value)


def test_fk_cli_json_schema_and_values(run_cli):
    code, out, _ = run_cli("fk", "--set", "epaule=0.5", "--set", "coude=-0.7", "--format", "json")
    assert code == 0
    data = json.loads(out)
    assert data["root"] == "base"
    assert data["config"] == {"epaule": 0.5, "coude": -0.7}
    forearm = data["links"]["avant_bras"]
    np.testing.assert_allclose(forearm["xyz"], [0.6 * math.sin(0.5), 0, 0.05 + 0.6 * math.cos(0.5)], atol=1e-12)
    np.testing.assert_allclose(forearm["quat_xyzw"], [0, math.sin(-0.1), 0, math.cos(-0.1)], atol=1e-12)
    np.testing.assert_allclose(forearm["rpy"], [0, -0.2, 0], atol=1e-12)
    assert set(data["links"]) == {"base", "bras", "avant_bras"}


def test_fk_cli_text_like_tf2_echo(run_cli):
    code, out, _ = run_cli("fk", "--from", "bras", "--to", "avant_bras", "--set", "coude=0.3")
    assert code == 0
    assert "At bras -> avant_bras" in out
    assert "Translation: [0.000000, 0.000000, 0.600000]" in out


def test_fk_cli_warns_outside_limits(run_cli):
    code, _, err = run_cli("fk", "--set", "coude=2.5")
    assert code == 0
    assert "coude=2.5 is above its upper limit 2 by 0.5" in err


@pytest.mark.parametrize("argv,needle", [
    (("fk", "--set", "genou=1"), "unknown joint 'genou'"),
    (("fk", "--set", "coude=abc"), "not a number"),
    (("fk", "--link", "main"), "unknown link 'main'"),
    (("fk", "--from", "bras"), "--from and --to go together"),
    (("fk", "missing.urdf"), "no such file"),
])
def test_fk_cli_bad_input_is_a_clean_error(run_cli, argv, needle):
    code, _, err = run_cli(*argv)
    assert code == 2
    assert needle in err
    assert "Traceback" not in err


def test_prismatic_joint_under_a_moving_parent_slides_along_the_rotated_axis():
    text = """<robot name="boom"><link name="base"/><link name="mast"/><link name="slider"/>
      <joint name="yaw" type="continuous"><parent link="base"/><child link="mast"/>
        <origin xyz="0 0 1"/><axis xyz="0 0 1"/></joint>
      <joint name="extend" type="prismatic"><parent link="mast"/><child link="slider"/>
        <origin xyz="0.2 0 0" rpy="0 0 0.5"/><axis xyz="1 0 0"/>
        <limit lower="0" upper="2" effort="1" velocity="1"/></joint></robot>"""
    tree = tf_tree(robot_from(text))
    q = np.array([[0.3, 0.7], [-1.0, 1.5]])
    batch = fk_batch(tree, q)
    for k, (yaw, extend) in enumerate(q):
        expected_rot = rot_z(yaw + 0.5)
        expected_pos = np.array([0, 0, 1]) + rot_z(yaw) @ np.array([0.2, 0, 0]) + expected_rot @ [extend, 0, 0]
        np.testing.assert_allclose(batch[k, 2, :3, :3], expected_rot, atol=1e-12)
        np.testing.assert_allclose(batch[k, 2, :3, 3], expected_pos, atol=1e-12)


def test_mimic_multiplier_of_zero_holds_the_follower_still():
    text = """<robot name="m"><link name="a"/><link name="b"/><link name="c"/>
      <joint name="lead" type="continuous"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/></joint>
      <joint name="follow" type="continuous"><parent link="a"/><child link="c"/><axis xyz="0 0 1"/>
        <mimic joint="lead" multiplier="0" offset="0.25"/></joint></robot>"""
    transforms = fk(tf_tree(robot_from(text)), {"lead": 1.0})
    np.testing.assert_allclose(transforms["c"][:3, :3], rot_z(0.25), atol=1e-12)
