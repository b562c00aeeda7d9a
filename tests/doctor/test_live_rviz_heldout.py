"""States kept aside while the model's verdicts were written (issue 56), run last: each expected
verdict worked by hand from robot_state_publisher 3.3.3's callbackJointState and tf2's cache."""

from __future__ import annotations

import math

from recorded_looks import T0, at_20_hz, codes, look, message, tutorial


def test_stamps_30_s_ahead_but_advancing_still_move_the_arm():
    # rsp's bar is min(its clock, last stamps) + 50 ms (lines 325-338): every stamp 30 s ahead clears it
    snapshot = look([tutorial(at, T0 + at + 30) for at in at_20_hz()])
    assert codes(snapshot) == ["BK815"]
    assert "after this computer's clock" in message(snapshot, "BK815")


def test_a_joint_never_sent_is_named_and_the_arm_is_not_called_still():
    snapshot = look([(at, T0 + at, ("epaule",), (0.5 * math.sin(at),)) for at in at_20_hz()])
    assert codes(snapshot, "error") == ["BK817"]


def test_a_bag_replayed_in_a_loop_stops_the_arm_after_its_first_pass():
    # stamps run over 1 s then start again: rsp's last stamp is the loop's end, every later one is older
    messages = [(at, T0 + (at % 1.0), ("epaule", "coude"), (math.sin(at), 0.1)) for at in at_20_hz()]
    snapshot = look(messages)
    assert codes(snapshot, "error") == ["BK840"]
    assert "stops" in message(snapshot, "BK840")


def test_positions_swapped_in_order_of_names_are_fine():
    snapshot = look([(at, T0 + at, ("coude", "epaule"), (0.1, 0.5 * math.sin(at))) for at in at_20_hz()])
    assert codes(snapshot) == []
