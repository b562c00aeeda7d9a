"""The tool tip shared by IK, plots and the workspace."""

from __future__ import annotations

import numpy as np

from bras_kit.kinematics.frames import tf_tree
from bras_kit.kinematics.tip import end_link, tool_tip
from bras_kit.model.robot import robot_from_xml
from bras_kit.model.xmlio import parse_xml


def test_tutorial_tip_is_the_far_end_of_the_forearm(tutorial_tree, wrist_robot):
    link, offset = tool_tip(tutorial_tree)
    assert link == "avant_bras"
    np.testing.assert_allclose(offset, [0, 0, 0.5], atol=1e-15)
    link, offset = tool_tip(tf_tree(wrist_robot))
    assert link == "main"
    np.testing.assert_allclose(offset, [0, 0, 0.15], atol=1e-15)


def test_a_slightly_tilted_segment_ends_at_its_face_centre_not_a_corner():
    text = """<robot name="t"><link name="a"/>
      <link name="b"><visual><origin xyz="0 0 0.2"/><geometry><box size="0.04 0.06 0.4"/></geometry></visual></link>
      <joint name="j" type="revolute"><parent link="a"/><child link="b"/><origin xyz="0 0 0.1" rpy="0 0.1 0"/>
        <axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>"""
    link, offset = tool_tip(tf_tree(robot_from_xml(parse_xml(text))))
    assert link == "b"
    np.testing.assert_allclose(offset, [0, 0, 0.4], atol=1e-15)


def test_end_link_is_the_deepest_leaf_and_a_tie_goes_to_the_farthest():
    text = """<robot name="y"><link name="root"/><link name="short"/><link name="long"/>
      <joint name="s" type="fixed"><parent link="root"/><child link="short"/><origin xyz="0.1 0 0"/></joint>
      <joint name="l" type="fixed"><parent link="root"/><child link="long"/><origin xyz="0 0.3 0"/></joint></robot>"""
    assert end_link(tf_tree(robot_from_xml(parse_xml(text)))) == "long"
