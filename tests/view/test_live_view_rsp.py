"""view --ros moves its arm only as robot_state_publisher 3.3.3 would move RViz's (issue 56): the
records are the probe's stream records; what the page is handed is checked against what
callbackJointState publishes (src/robot_state_publisher.cpp:300-363), worked by hand."""

from __future__ import annotations

import math

from bras_kit.model.authoring import arm_urdf
from bras_kit.model.robot import robot_from_xml
from bras_kit.model.xmlio import parse_xml
from bras_kit.view.live_ros import RosFeed

ROBOT = robot_from_xml(parse_xml(arm_urdf(), "a.urdf"), path="a.urdf", source_text=arm_urdf())


class Page:
    def __init__(self) -> None:
        self.shown: list[dict[str, float]] = []

    def show_joint_state(self, names, positions) -> None:
        self.shown.append(dict(zip(names, positions)))


def feed_with(records) -> list[dict[str, float]]:
    feed = RosFeed("python")
    feed.robot, page = ROBOT, Page()
    feed.viewer = page
    for stamp, names, positions in records:
        feed._take({"kind": "joint_state", "received": 1000.0 + stamp, "stamp": [int(stamp), round(stamp % 1 * 1e9)],
                    "name": list(names), "position": list(positions)})
    return page.shown


def test_the_tutorial_s_messages_move_the_page_each_time():
    shown = feed_with([(100 + 0.05 * i, ("epaule", "coude"), (0.01 * i, 0.0)) for i in range(1, 6)])
    assert [round(s["epaule"], 3) for s in shown] == [0.01, 0.02, 0.03, 0.04, 0.05]


def test_an_unchanging_stamp_moves_the_page_once():
    shown = feed_with([(100.0, ("epaule", "coude"), (0.1 * i, 0.0)) for i in range(1, 6)])
    assert shown == [{"epaule": 0.1, "coude": 0.0}]


def test_three_names_with_two_positions_do_not_move_the_page():
    assert feed_with([(100 + 0.1 * i, ("epaule", "coude", "poignet"), (0.1, 0.2)) for i in range(5)]) == []


def test_a_nan_leaves_that_joint_where_it_was():
    shown = feed_with([(100.0, ("epaule", "coude"), (0.1, 0.2)), (100.1, ("epaule", "coude"), (0.3, math.nan))])
    assert shown == [{"epaule": 0.1, "coude": 0.2}, {"epaule": 0.3}]


def test_an_empty_domain_names_where_the_nodes_are_as_doctor_ros_does(monkeypatch):
    import time

    from bras_kit.core.i18n import say
    from bras_kit.ros.graph import Elsewhere
    from bras_kit.view import live_ros

    searched = []

    def look_elsewhere(python, snapshot):
        searched.append(snapshot.domain)
        yield Elsewhere(42, "LOCALHOST", ("/robot_state_publisher", "/animation_bras"))

    monkeypatch.setattr(live_ros, "look_elsewhere", look_elsewhere)
    feed = RosFeed("python")
    feed._take({"kind": "hello", "domain": 0, "range": "LOCALHOST", "rmw": "rmw_fastrtps_cpp"})
    feed._take({"kind": "graph", "nodes": [], "topics": {}, "incompatible": [], "time": time.time()})
    for _ in range(100):
        if feed.elsewhere:
            break
        time.sleep(0.02)
    found = [f for r in feed.results() for f in r.findings if f.code == "BK800"]
    assert searched == [0] and len(found) == 1
    assert "export ROS_DOMAIN_ID=42" in say(found[0].hint, "en")
