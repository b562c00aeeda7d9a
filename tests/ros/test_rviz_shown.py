"""What RViz shows for the tutorial's arm (bras_kit.ros.rviz.config.shown), state by state.

Oracles: RViz jazzy's own words and rules (visualization_manager.cpp:431-451 for the Global Status,
tf_frame_transformer.cpp:213-219 "Frame [X] does not exist", ros_topic_display.hpp:197-202 "Error
subscribing: Empty topic name", tf_link_updater.cpp:68-75 "No transform from [X] to [Y]",
display.cpp:72-73 a display unchecked, display_group.cpp:123-132 an unknown class), and the
transforms robot_state_publisher 3.3.3 sends (bras_kit.ros.rviz.frames, tested on its own)."""

from __future__ import annotations

import pytest

from bras_kit.ros.rviz.config import (
    ERROR,
    OK,
    ROBOT_MODEL,
    TF,
    WARN,
    default_config,
    new_display,
    shown,
    with_display,
    with_fixed_frame,
    with_option,
)
from bras_kit.ros.rviz.started import launch_transforms

TOPICS = {"/robot_description"}


def _step_six(frame: str = "base", topic: str = "/robot_description"):
    config = with_display(with_fixed_frame(default_config(), frame), new_display(ROBOT_MODEL))
    config = with_option(config, 1, "Description Topic", topic)
    return with_display(config, new_display(TF))


def test_rviz_as_the_tutorials_launch_opens_it(tutorial_robot):
    seen = shown(default_config(), tutorial_robot, launch_transforms(tutorial_robot, True), TOPICS)
    assert (seen.global_status.level, seen.global_status.text) == (ERROR, "Frame [map] does not exist")
    assert not seen.arm_drawn
    assert seen.displays[0].drawn == ("Grid",)


def test_step_six_draws_the_arm(tutorial_robot):
    seen = shown(_step_six(), tutorial_robot, launch_transforms(tutorial_robot, True), TOPICS)
    assert (seen.global_status.level, seen.global_status.text) == (OK, "OK")
    assert seen.links == ("base", "bras", "avant_bras")
    model, tf = seen.displays[1], seen.displays[2]
    assert [s.text for s in model.statuses[:2]] == ["1 messages received", "URDF parsed OK"]
    assert sorted(tf.drawn) == ["avant_bras", "base", "bras"] and tf.level == OK


def test_a_robot_model_added_but_its_topic_left_empty(tutorial_robot):
    config = with_display(with_fixed_frame(default_config(), "base"), new_display(ROBOT_MODEL))
    seen = shown(config, tutorial_robot, launch_transforms(tutorial_robot, True), TOPICS)
    assert not seen.arm_drawn
    (status,) = seen.displays[1].statuses
    assert (status.level, status.name, status.text) == (ERROR, "Topic", "Error subscribing: Empty topic name")


@pytest.mark.parametrize("topic", ["/robot_descripton", "robot_description_", "/bras/robot_description"])
def test_a_topic_nothing_publishes_draws_nothing(tutorial_robot, topic):
    seen = shown(_step_six(topic=topic), tutorial_robot, launch_transforms(tutorial_robot, True), TOPICS)
    assert not seen.arm_drawn
    assert [(s.name, s.text) for s in seen.displays[1].statuses] == [("Topic", "OK")]  # subscribed, nothing heard


def test_without_joint_states_only_the_root_is_placed(tutorial_robot):
    seen = shown(_step_six(), tutorial_robot, launch_transforms(tutorial_robot, False), TOPICS)
    assert seen.links == ("base",)
    texts = {s.name: s.text for s in seen.displays[1].statuses}
    assert texts["avant_bras"] == "No transform from [avant_bras] to [base]"
    # nothing on tf at all: the Global Status warns of no tf data (visualization_manager.cpp:436-441)
    assert seen.global_status == type(seen.global_status)(WARN, "Fixed Frame",
                                                          "No tf data.  Actual error: Frame [base] does not exist")


# A learner's node alone (no slider window): robot_state_publisher publishes a transform for each
# joint a message names and the URDF knows, none for the others (robot_state_publisher.cpp,
# tag 3.3.3, 343-360 and publishTransforms), and RViz draws a link only where tf has a transform.
@pytest.mark.parametrize("sent, drawn, missing", [
    (("epaule", "coude"), ("base", "bras", "avant_bras"), None),
    (("epaule", "coud"), ("base", "bras"), "avant_bras"),  # the typo: the forearm has no transform
    (("coude",), ("base",), "bras"),  # the shoulder never sent: bras and what hangs on it are not placed
    (("shoulder", "elbow"), ("base",), "bras"),  # another robot's names
])
def test_a_node_alone_moves_only_the_joints_it_names(tutorial_robot, sent, drawn, missing):
    seen = shown(_step_six(), tutorial_robot, launch_transforms(tutorial_robot, True, names=sent), TOPICS)
    assert seen.links == drawn
    texts = {s.name: s.text for s in seen.displays[1].statuses}
    if missing is not None:
        assert texts[missing] == f"No transform from [{missing}] to [base]"


@pytest.mark.parametrize("frame", ["bras", "avant_bras"])
def test_a_fixed_frame_on_another_link_still_draws_every_link(tutorial_robot, frame):
    seen = shown(_step_six(frame), tutorial_robot, launch_transforms(tutorial_robot, True), TOPICS)
    assert seen.links == ("base", "bras", "avant_bras")


def test_a_wrong_fixed_frame_then_the_right_one(tutorial_robot):
    tfs = launch_transforms(tutorial_robot, True)
    wrong = shown(_step_six("monde"), tutorial_robot, tfs, TOPICS)
    assert wrong.global_status.text == "Frame [monde] does not exist" and not wrong.arm_drawn
    texts = {s.name: s.text for s in wrong.displays[1].statuses}
    assert texts["bras"] == "No transform from [bras] to [monde]"
    right = shown(with_fixed_frame(wrong.config, "/base"), tutorial_robot, tfs, TOPICS)
    assert right.arm_drawn


def test_a_robot_model_unchecked_or_unknown_draws_nothing(tutorial_robot):
    config = with_option(_step_six(), 1, "Enabled", False)
    seen = shown(config, tutorial_robot, launch_transforms(tutorial_robot, True), TOPICS)
    assert not seen.arm_drawn and seen.displays[1].statuses == ()
    odd = with_display(default_config(), new_display("rviz/RobotModel"))  # an RViz 1 class name
    seen = shown(odd, tutorial_robot, launch_transforms(tutorial_robot, True), TOPICS)
    assert seen.displays[1].level == ERROR and "could not be loaded" in seen.displays[1].statuses[0].text


def test_description_source_file(tutorial_robot):
    config = with_option(_step_six(), 1, "Description Source", "File")
    tfs = launch_transforms(tutorial_robot, True)
    assert shown(config, tutorial_robot, tfs, TOPICS).displays[1].statuses == ()  # no file: cleared
    config = with_option(config, 1, "Description File", "/tmp/bras.urdf")
    assert shown(config, tutorial_robot, tfs, TOPICS).displays[1].statuses[0].text == "URDF is empty"
    assert shown(config, tutorial_robot, tfs, TOPICS, files={"/tmp/bras.urdf": "<robot/>"}).arm_drawn
