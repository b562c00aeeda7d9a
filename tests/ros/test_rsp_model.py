"""robot_state_publisher 3.3.3, tf2 and RViz's RobotModel lookup, case by case as their sources run.

Each expected value is worked out by hand from the cited lines (ros/robot_state_publisher tag 3.3.3
``src/robot_state_publisher.cpp``; ros2/geometry2 jazzy ``tf2/src/buffer_core.cpp``, ``cache.cpp``;
ros2/rviz jazzy ``tf_link_updater.cpp``), never from the module under test.
"""

from __future__ import annotations

import math

import pytest

from bras_kit.core.errors import ParameterError
from bras_kit.model.authoring import arm_urdf
from bras_kit.model.robot import robot_from_xml
from bras_kit.model.xmlio import parse_xml
from bras_kit.ros.rviz.frames import JointStateIn, RobotStatePublisher, Tf, placed_links

S = 1_000_000_000
MS = 1_000_000


def robot(text: str):
    return robot_from_xml(parse_xml(text, "t.urdf"), path="t.urdf", source_text=text)


ARM = robot(arm_urdf())
WRIST = robot(arm_urdf(wrist=True))


def msg(stamp_ns: int, names=("epaule", "coude"), positions=(0.1, 0.2), **kw) -> JointStateIn:
    return JointStateIn(stamp_ns, tuple(names), tuple(positions), **kw)


def children(received) -> list[str]:
    return [tf.child for tf in received.published]


# ---------------------------------------------------------------- the publish interval (lines 325-340)


def test_first_message_publishes_each_moving_joint_with_its_stamp():
    got = RobotStatePublisher(ARM).on_joint_state(msg(5 * S))
    assert [(t.parent, t.child, t.stamp_ns, t.static, t.joint) for t in got.published] == [
        ("bras", "avant_bras", 5 * S, False, "coude"), ("base", "bras", 5 * S, False, "epaule")]
    assert got.reason is None and got.ignored == ()


def test_equal_stamps_publish_once():
    rsp = RobotStatePublisher(ARM)
    results = [rsp.on_joint_state(msg(5 * S, positions=(0.1 * i, 0.0))) for i in range(20)]
    assert [len(r.published) for r in results] == [2] + [0] * 19
    assert "not 50 ms past 5.000 s" in str(results[1].reason)
    # RViz keeps the arm where the first message put it
    assert rsp.positions() == {"epaule": 0.0, "coude": 0.0}


@pytest.mark.parametrize(("gap_ms", "published"), [(1, False), (49, False), (50, True), (51, True)])
def test_a_stamp_publishes_only_50_ms_after_the_last_at_20_hz(gap_ms, published):
    rsp = RobotStatePublisher(ARM)
    rsp.on_joint_state(msg(5 * S))
    assert bool(rsp.on_joint_state(msg(5 * S + gap_ms * MS)).published) is published


def test_stamps_1_ms_apart_publish_every_50th():
    rsp = RobotStatePublisher(ARM)
    counts = [bool(rsp.on_joint_state(msg(5 * S + i * MS)).published) for i in range(201)]
    assert [i for i, done in enumerate(counts) if done] == [0, 50, 100, 150, 200]


def test_whole_second_stamps_sent_at_20_hz_move_the_arm_once_a_second():
    rsp = RobotStatePublisher(ARM)
    # a node at 20 Hz that writes only the seconds of its clock: 3 s of messages
    published = [rsp.on_joint_state(msg((100 + i // 20) * S, positions=(i / 100, 0.0))) for i in range(60)]
    assert [i for i, r in enumerate(published) if r.published] == [0, 20, 40]


def test_the_interval_is_cut_to_whole_milliseconds():
    rsp = RobotStatePublisher(ARM, publish_frequency=30.0)  # 1000/30 = 33.3 -> 33 ms (line 337)
    rsp.on_joint_state(msg(5 * S))
    assert not rsp.on_joint_state(msg(5 * S + 32 * MS)).published
    assert rsp.on_joint_state(msg(5 * S + 33 * MS)).published


def test_a_stamp_left_at_zero_is_never_published():
    rsp = RobotStatePublisher(ARM)
    assert [rsp.on_joint_state(msg(0)).published for _ in range(5)] == [()] * 5


def test_the_joint_published_longest_ago_decides():
    rsp = RobotStatePublisher(ARM)
    rsp.on_joint_state(msg(5 * S, names=["epaule"], positions=[0.1]))
    rsp.on_joint_state(msg(6 * S, names=["coude"], positions=[0.1]))
    # epaule last went out at 5 s, coude at 6 s: the older one (5 s) sets the bar, 5.05 s
    assert children(rsp.on_joint_state(msg(5 * S + 60 * MS))) == ["avant_bras", "bras"]


def test_ignore_timestamp_publishes_every_message():
    rsp = RobotStatePublisher(ARM, ignore_timestamp=True)
    assert all(rsp.on_joint_state(msg(5 * S)).published for _ in range(3))


def test_a_clock_gone_backwards_forgets_the_stamps():
    rsp = RobotStatePublisher(ARM)
    rsp.on_joint_state(msg(50 * S, received_ns=50 * S))
    assert not rsp.on_joint_state(msg(10 * S, received_ns=60 * S)).published  # older stamp: nothing
    back = rsp.on_joint_state(msg(10 * S, received_ns=10 * S))  # the clock went back: republished
    assert children(back) == ["avant_bras", "bras"]
    assert str(back.reason) == "Moved backwards in time, re-publishing joint transforms!"


def test_stamps_30_s_old_but_advancing_keep_the_arm_placed():
    rsp = RobotStatePublisher(ARM)
    sent: list[Tf] = list(rsp.static())
    for i in range(40):  # 2 s at 20 Hz, stamps 30 s behind rsp's clock
        got = rsp.on_joint_state(msg(70 * S + i * 50 * MS, positions=(i / 40, 0.0), received_ns=100 * S + i * 50 * MS))
        assert got.published
        sent += got.published
    assert set(placed_links(ARM, "base", sent).values()) == {None}


# ---------------------------------------------------------------- sizes, names, values (lines 303-312, 343-361)


def test_more_names_than_positions_is_ignored_with_its_error():
    got = RobotStatePublisher(WRIST).on_joint_state(msg(5 * S, names=("epaule", "coude", "poignet")))
    assert got.published == ()
    assert str(got.reason) == "Robot state publisher ignored an invalid JointState message"


def test_names_without_positions_is_ignored_with_the_first_name():
    got = RobotStatePublisher(ARM).on_joint_state(msg(5 * S, positions=()))
    assert got.published == ()
    assert str(got.reason) == ('Robot state publisher ignored a JointState message about joint(s) '
                               '"epaule"(,...) whose position member was empty.')


def test_a_message_ignored_for_its_sizes_does_not_count_as_published():
    rsp = RobotStatePublisher(ARM)
    rsp.on_joint_state(msg(5 * S, positions=(0.1,)))
    assert rsp.on_joint_state(msg(5 * S)).published  # the first valid one still goes out


def test_unknown_names_are_skipped_silently_and_the_rest_published():
    got = RobotStatePublisher(ARM).on_joint_state(
        msg(5 * S, names=("epaule", "coude", "poignet"), positions=(0.1, 0.2, 0.3)))
    assert children(got) == ["avant_bras", "bras"]
    assert got.reason is None and got.ignored == ("poignet",)


def test_only_unknown_names_publish_nothing():
    got = RobotStatePublisher(ARM).on_joint_state(msg(5 * S, names=("shoulder", "elbow")))
    assert got.published == () and got.ignored == ("shoulder", "elbow")
    assert "no name in the message is a moving joint" in str(got.reason)


def test_a_name_given_twice_keeps_its_first_position():
    got = RobotStatePublisher(ARM).on_joint_state(
        msg(5 * S, names=("epaule", "coude", "epaule"), positions=(0.1, 0.2, 0.9)))
    assert {t.joint: t.position for t in got.published} == {"epaule": 0.1, "coude": 0.2}


@pytest.mark.parametrize("bad", [math.nan, math.inf, -math.inf])
def test_a_revolute_joint_not_finite_goes_out_but_tf2_refuses_it(bad):
    rsp = RobotStatePublisher(ARM)
    first = rsp.on_joint_state(msg(5 * S, positions=(0.1, 0.2)))
    got = rsp.on_joint_state(msg(6 * S, positions=(0.3, bad)))
    assert [(t.child, t.nan) for t in got.published] == [("avant_bras", True), ("bras", False)]
    assert str(got.reason).startswith("TF_NAN_INPUT")
    assert rsp.positions() == {"epaule": 0.3, "coude": 0.2}  # tf2 keeps coude's last good value
    sent = rsp.static() + list(first.published) + list(got.published)
    assert set(placed_links(ARM, "base", sent).values()) == {None}


def test_nan_from_the_start_leaves_the_forearm_unplaced():
    rsp = RobotStatePublisher(ARM)
    sent = []
    for i in range(5):
        sent += rsp.on_joint_state(msg(5 * S + i * S, positions=(0.1, math.nan))).published
    placed = placed_links(ARM, "base", sent)
    assert placed["base"] is None and placed["bras"] is None
    assert str(placed["avant_bras"]) == "No transform from [avant_bras] to [base]"


PRISMATIC = """<robot name="p"><link name="a"/><link name="b"/>
<joint name="j" type="prismatic"><parent link="a"/><child link="b"/><axis xyz="{axis}"/>
<limit lower="0" upper="1" effort="1" velocity="1"/></joint></robot>"""


@pytest.mark.parametrize(("axis", "nan"), [("1 0 0", True), ("0.577350269 0.577350269 0.577350269", False)])
def test_a_prismatic_joint_at_infinity_is_nan_where_its_axis_has_a_zero(axis, nan):
    got = RobotStatePublisher(robot(PRISMATIC.format(axis=axis))).on_joint_state(msg(5 * S, ["j"], [math.inf]))
    assert [t.nan for t in got.published] == [nan]


# ---------------------------------------------------------------- joint types, mimic (lines 186-250, 348-354)

KINDS = """<robot name="k">
  <link name="base"/><link name="bras"/><link name="outil"/><link name="plateau"/><link name="drone"/>
  <link name="doigt"/><link name="doigt2"/>
  <joint name="epaule" type="revolute"><parent link="base"/><child link="bras"/><axis xyz="0 1 0"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  <joint name="fixe" type="fixed"><parent link="bras"/><child link="outil"/></joint>
  <joint name="glisse" type="planar"><parent link="base"/><child link="plateau"/></joint>
  <joint name="libre" type="floating"><parent link="base"/><child link="drone"/></joint>
  <joint name="pince" type="prismatic"><parent link="outil"/><child link="doigt"/><axis xyz="1 0 0"/>
    <mimic joint="epaule" multiplier="2" offset="0.1"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
  <joint name="pince2" type="prismatic"><parent link="outil"/><child link="doigt2"/><axis xyz="1 0 0"/>
    <mimic joint="pince" multiplier="1" offset="0"/><limit lower="0" upper="1" effort="1" velocity="1"/></joint>
</robot>"""


def test_fixed_and_planar_joints_go_out_once_on_tf_static_and_floating_not_at_all():
    rsp = RobotStatePublisher(robot(KINDS), start_ns=7 * S)
    assert [(t.parent, t.child, t.stamp_ns, t.static) for t in rsp.static()] == [
        ("bras", "outil", 7 * S, True), ("base", "plateau", 7 * S, True)]


def test_a_mimic_joint_follows_its_leader_and_a_mimic_of_a_mimic_follows_by_name_order():
    rsp = RobotStatePublisher(robot(KINDS))
    got = rsp.on_joint_state(msg(5 * S, ["epaule"], [0.2]))
    # std::map order: pince (leader epaule, known) then pince2 (leader pince, now known)
    assert {t.joint: round(t.position, 9) for t in got.published} == {"epaule": 0.2, "pince": 0.5, "pince2": 0.5}


def test_a_mimic_joint_in_the_message_keeps_the_message_value():
    got = RobotStatePublisher(robot(KINDS)).on_joint_state(msg(5 * S, ["epaule", "pince"], [0.2, 0.9]))
    assert {t.joint: t.position for t in got.published}["pince"] == 0.9


def test_names_of_fixed_and_floating_joints_are_skipped():
    got = RobotStatePublisher(robot(KINDS)).on_joint_state(msg(5 * S, ["epaule", "fixe", "libre"], [0.1, 0.0, 0.0]))
    assert got.ignored == ("fixe", "libre") and got.reason is None


def test_what_rviz_places_for_each_joint_type():
    model = robot(KINDS)
    rsp = RobotStatePublisher(model)
    sent = rsp.static() + list(rsp.on_joint_state(msg(5 * S, ["epaule"], [0.2])).published)
    placed = placed_links(model, "base", sent)
    assert [link for link, why in placed.items() if why is not None] == ["drone"]
    assert str(placed["drone"]) == "No transform from [drone] to [base]"


# ---------------------------------------------------------------- RViz's lookup (tf2 at time zero)


def test_a_link_whose_joint_never_gets_a_position_is_not_placed_nor_what_hangs_from_it():
    rsp = RobotStatePublisher(WRIST)
    sent = list(rsp.on_joint_state(msg(5 * S, ["epaule", "poignet"], [0.1, 0.2])).published)
    placed = placed_links(WRIST, "base", sent)
    assert {k: v is None for k, v in placed.items()} == {"base": True, "bras": True, "avant_bras": False,
                                                         "main": False}
    assert str(placed["main"]) == "No transform from [main] to [base]"


def test_nothing_received_places_only_the_fixed_frame_itself():
    placed = placed_links(ARM, "base", [])
    assert placed["base"] is None and placed["bras"] is not None


def test_the_default_fixed_frame_map_places_nothing():
    rsp = RobotStatePublisher(ARM)
    sent = list(rsp.on_joint_state(msg(5 * S)).published)
    assert [str(v) for v in placed_links(ARM, "map", sent).values()] == [
        "No transform from [base] to [map]", "No transform from [bras] to [map]",
        "No transform from [avant_bras] to [map]"]


def test_an_empty_fixed_frame_places_nothing_not_even_itself():
    rsp = RobotStatePublisher(ARM)
    sent = list(rsp.on_joint_state(msg(5 * S)).published)
    assert str(placed_links(ARM, "", sent)["base"]) == "No transform from [base] to []"


def test_a_fixed_frame_down_the_arm_places_the_links_above_it_too():
    rsp = RobotStatePublisher(ARM)
    sent = list(rsp.on_joint_state(msg(5 * S)).published)
    assert set(placed_links(ARM, "avant_bras", sent).values()) == {None}


def test_a_second_node_animating_the_wrist_30_s_behind_unplaces_only_the_hand():
    rsp = RobotStatePublisher(WRIST)
    sent: list[Tf] = []
    for i in range(20):
        t = 100 * S + i * 100 * MS
        sent += rsp.on_joint_state(msg(t)).published
        sent += rsp.on_joint_state(msg(t - 30 * S, ["poignet"], [0.1])).published
    placed = placed_links(WRIST, "base", sent)
    # base->main's latest common time is the wrist's, 30 s before epaule's: past tf2's 10 s history
    assert {k: v is None for k, v in placed.items()} == {"base": True, "bras": True, "avant_bras": True,
                                                         "main": False}


def test_a_second_node_animating_the_wrist_in_step_places_the_whole_arm():
    rsp = RobotStatePublisher(WRIST)
    sent: list[Tf] = []
    for i in range(20):
        t = 100 * S + i * 50 * MS
        sent += rsp.on_joint_state(msg(t)).published
        sent += rsp.on_joint_state(msg(t + 10 * MS, ["poignet"], [0.1])).published
    assert set(placed_links(WRIST, "base", sent).values()) == {None}


def test_one_transform_each_at_different_stamps_cannot_be_chained():
    # a TimeCache with one entry answers only its own stamp (cache.cpp:137-146)
    sent = [Tf("base", "bras", 5 * S, False), Tf("bras", "avant_bras", 6 * S, False)]
    placed = placed_links(ARM, "base", sent)
    assert placed["bras"] is None and placed["avant_bras"] is not None


def test_static_transforms_never_age():
    sent = [Tf("base", "bras", 1 * S, True), Tf("bras", "avant_bras", 500 * S, False)]
    assert set(placed_links(ARM, "base", sent).values()) == {None}


def test_publish_frequency_out_of_bounds_is_refused():
    for bad in (0.0, -1.0, 1000.5):
        with pytest.raises(ParameterError):
            RobotStatePublisher(ARM, publish_frequency=bad)


def test_a_message_with_no_names_publishes_nothing():
    got = RobotStatePublisher(ARM).on_joint_state(msg(5 * S, names=(), positions=()))
    assert got.published == () and "names no joint" in str(got.reason)


def test_an_older_stamp_without_a_clock_gone_back_publishes_nothing():
    rsp = RobotStatePublisher(ARM)
    rsp.on_joint_state(msg(50 * S, received_ns=50 * S))
    assert rsp.on_joint_state(msg(10 * S, received_ns=50 * S + 50 * MS)).published == ()
    assert rsp.on_joint_state(msg(10 * S)).published == ()
