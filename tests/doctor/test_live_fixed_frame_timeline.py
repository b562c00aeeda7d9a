"""The live side's Fixed Frame, timeline, QoS words and /tf (issue 56), on recorded looks and on this
machine's own /proc.

The oracles: rviz2's option parsing and configuration order (ros2/rviz jazzy 591594e,
visualizer_app.cpp:95-103 and 165-169, visualization_frame.cpp:345-349 and 674-676), a real process
named rviz2 read through /proc, and the real rclpy's ``qos_check_compatible`` words.
"""

from __future__ import annotations

import os
import subprocess
import sys
import time

import pytest
from paths import DATA
from recorded_looks import NODE, RSP, T0, URDF, at_20_hz, codes, look, message, tutorial

from bras_kit.live.rviz_process import options, running_rviz
from bras_kit.ros.graph import snapshot_from_json
from bras_kit.ros.rviz.running import fixed_frame
from bras_kit.validate.live import LiveGraph, rclpy_policies, timeline

RVIZ_MAP = "Visualization Manager:\n  Global Options:\n    Fixed Frame: /map\n  Displays: []\n"
RVIZ_BASE = RVIZ_MAP.replace("/map", "base")


@pytest.mark.parametrize("argv, expected", [
    (["-d", "a.rviz"], ("a.rviz", "")),
    (["-da.rviz"], ("a.rviz", "")),
    (["--display-config", "a.rviz"], ("a.rviz", "")),
    (["--display-config=a.rviz", "-f", "base"], ("a.rviz", "base")),
    (["--fixed-frame=odom"], (None, "odom")),
    (["--ros-args", "-d", "x.rviz"], (None, "")),  # rcl's arguments, not rviz2's
    (["-d", "a.rviz", "--ros-args", "-r", "__node:=rviz2"], ("a.rviz", "")),
    ([], (None, "")),
])
def test_rviz2_options_are_read_as_its_qt_parser_reads_them(argv, expected):
    assert options(argv) == expected


def _rviz(**fields):
    record = {"pid": 4242, "argv": ["rviz2"], "config": "/home/eleve/.rviz2/default.rviz", "given": False,
              "text": None, "fixed_frame": ""}
    record.update(fields)
    return snapshot_from_json({"kind": "snapshot", "rviz": [record]}).rviz


def test_the_fixed_frame_follows_rviz2_s_order_f_then_d_then_saved_default_then_map():
    assert fixed_frame(_rviz(fixed_frame="/odom", given=True, text=RVIZ_BASE)).frame == "odom"  # -f wins
    d_file = fixed_frame(_rviz(given=True, config="/ws/bras.rviz", text=RVIZ_MAP))
    assert (d_file.frame, d_file.source, d_file.path) == ("map", "file", "/ws/bras.rviz")  # one '/' less
    assert fixed_frame(_rviz(given=True, text=None)).source == "missing"  # RViz's default then
    assert fixed_frame(_rviz(given=True, text=None)).frame == "map"
    assert (fixed_frame(_rviz(text=RVIZ_BASE)).frame, fixed_frame(_rviz(text=RVIZ_BASE)).source) == ("base", "home")
    assert (fixed_frame(_rviz()).frame, fixed_frame(_rviz()).source) == ("map", "default")
    # a .rviz that sets no Fixed Frame keeps the constructor's base_link (visualization_manager.cpp:185)
    assert fixed_frame(_rviz(given=True, text="Visualization Manager:\n  Displays: []\n")).frame == "base_link"
    assert fixed_frame(()).source == "not-seen"


def test_a_running_process_named_rviz2_is_found_with_its_d_file_on_its_domain_only(tmp_path):
    program = tmp_path / "rviz2"
    program.write_text("import time\ntime.sleep(30)\n")
    (tmp_path / "mine.rviz").write_text(RVIZ_BASE)
    env = {**os.environ, "ROS_DOMAIN_ID": "77"}
    child = subprocess.Popen([sys.executable, str(program), "-d", "mine.rviz"], cwd=tmp_path, env=env)
    try:
        for _ in range(100):  # its command line is there once exec is done
            found = [r for r in running_rviz({"ROS_DOMAIN_ID": "77"}) if r["pid"] == child.pid]
            if found:
                break
            time.sleep(0.05)
        assert found and found[0]["config"] == str(tmp_path / "mine.rviz") and found[0]["given"]
        assert found[0]["text"] == RVIZ_BASE
        assert not [r for r in running_rviz({"ROS_DOMAIN_ID": "78"}) if r["pid"] == child.pid]
    finally:
        child.kill()
        child.wait()


def _with_rviz(snapshot_messages, text, given=True, **kw):
    snapshot = look(snapshot_messages, **kw)
    data = {"kind": "snapshot", "domain": snapshot.domain, "started": snapshot.started, "ended": snapshot.ended,
            "nodes": list(snapshot.nodes), "rviz": [{"pid": 99, "argv": ["rviz2"], "config": "/ws/bras.rviz",
                                                     "given": given, "text": text, "fixed_frame": ""}]}
    from dataclasses import replace

    return replace(snapshot, rviz=snapshot_from_json(data).rviz)


def test_a_running_rviz2_whose_file_says_map_is_named_and_base_is_not():
    messages = [tutorial(at) for at in at_20_hz()]
    assert codes(_with_rviz(messages, RVIZ_MAP)) == ["BK846"]
    assert "Frame [map] does not exist" in message(_with_rviz(messages, RVIZ_MAP), "BK846")
    assert codes(_with_rviz(messages, RVIZ_BASE)) == []
    assert codes(look(messages)) == []  # no rviz2 seen: nothing said of its frame


def test_links_are_placed_in_the_fixed_frame_the_file_gives():
    # Fixed Frame bras: a NaN coude leaves avant_bras without a transform to bras either
    import math

    messages = [(at, T0 + at, ("epaule", "coude"), (0.1, math.nan)) for at in at_20_hz()]
    text = RVIZ_BASE.replace("base", "bras")
    assert "No transform from [avant_bras] to [bras]" in message(_with_rviz(messages, text), "BK841")


def _events(*events, descriptions=None, messages=None):
    snapshot = look(messages if messages is not None else [tutorial(at) for at in at_20_hz()],
                    descriptions=descriptions)
    from dataclasses import replace

    parsed = snapshot_from_json({"kind": "snapshot", "events": [
        {"time": T0 + at, "kind": kind, "node": node, "topic": topic} for at, kind, node, topic in events]})
    return replace(snapshot, events=parsed.events)


def test_the_timeline_says_who_joined_and_left_when_discovery_was_over():
    snapshot = _events((0.3, "joined", "/robot_state_publisher", ""), (1.1, "joined", "/animation_bras", ""),
                       (2.9, "joined", "/animation_poignet", ""), (3.5, "left", "/animation_bras", ""),
                       (3.5, "unpublishes", "/animation_bras", "/joint_states"))
    seen = [(round(at, 1), kind, what["node"]) for at, kind, what in timeline(LiveGraph(snapshot))]
    # nodes found in the first 2.5 s of discovery were there from the start
    assert seen == [(2.9, "joined", "/animation_poignet"), (3.5, "left", "/animation_bras"),
                    (3.5, "unpublishes", "/animation_bras")]
    from bras_kit.core.i18n import say
    from bras_kit.live.doctor import diagnose

    words = [say(f.message, "en") for r in diagnose(snapshot) for f in r.findings if f.code == "BK847"]
    assert "3.5 s: /animation_bras left the graph" in words and len(words) == 3


def test_the_timeline_says_when_the_description_was_replaced_and_the_joint_states_stopped():
    wrist = URDF.replace("</robot>", '<link name="main"/></robot>')
    descriptions = [{"text": URDF, "received": T0 + 0.1, "length": len(URDF)},
                    {"text": wrist, "received": T0 + 2.8, "length": len(wrist)}]
    snapshot = _events(descriptions=descriptions, messages=[tutorial(at) for at in at_20_hz() if at < 1.5])
    kinds = [(kind, round(at, 2)) for at, kind, _ in timeline(LiveGraph(snapshot))]
    assert kinds == [("silent", 1.45), ("replaced", 2.8)]
    from bras_kit.core.i18n import say
    from bras_kit.live.doctor import diagnose

    words = [say(f.message, "fr") for r in diagnose(snapshot) for f in r.findings if f.code == "BK847"]
    assert words == ["1.5 s : le dernier message /joint_states ; toujours publié par '/animation_bras', sans rien "
                     "envoyer", "2.8 s : une nouvelle description est arrivée sur /robot_description (texte 2) : "
                     "RViz la montre dès lors"]


def test_rclpy_s_reason_names_the_policies():
    reason = "ERROR: Best effort publisher and reliable subscription;ERROR: Volatile publisher and transient local " \
             "subscription;"
    assert rclpy_policies(reason) == ["reliability", "durability"]
    assert rclpy_policies("ERROR: Subscription deadline is less than publisher deadline;") == ["deadline"]
    assert rclpy_policies("WARNING: Publisher liveliness is system_default;") == []


def test_a_deadline_pair_is_worded_with_rclpy_s_reason_not_as_durability():
    topics = {"/robot_description": {"types": ["std_msgs/msg/String"], "publishers": [RSP], "subscribers": []}}
    snapshot = look([tutorial(at) for at in at_20_hz()], topics=topics)
    from dataclasses import replace

    pair = snapshot_from_json({"incompatible": [{
        "topic": "/joint_states", "publisher": NODE, "level": "error",
        "subscriber": {"node": "/rviz", "reliability": "reliable", "durability": "volatile"},
        "reason": "ERROR: Subscription deadline is less than publisher deadline;"}]}).mismatches
    text = message(replace(snapshot, mismatches=pair), "BK820")
    assert "policies deadline" in text and "rclpy: ERROR: Subscription deadline is less" in text


def test_transforms_not_read_are_said_inferred_and_read_ones_counted():
    from bras_kit.cli._doctor_ros import _text
    from bras_kit.live.doctor import diagnose

    snapshot = look([tutorial(at) for at in at_20_hz()])
    assert snapshot.transforms is None
    assert "/tf and /tf_static were not seen" in _text(snapshot, diagnose(snapshot), "en")
    from dataclasses import replace

    seen = snapshot_from_json({"transforms": [{"parent": "base", "child": "bras", "stamp": [1, 0], "static": False,
                                               "received": T0 + 1}]}).transforms
    read = replace(snapshot, transforms=seen)
    assert "1 transform seen on /tf and /tf_static" in _text(read, diagnose(read), "en")


@pytest.fixture(scope="module")
def workspace(tmp_path_factory):
    """A colcon workspace whose one launch file starts rviz2 -d its installed bras.rviz, built."""
    import shutil

    from bras_kit.ros.build import build_package

    root = tmp_path_factory.mktemp("ws")
    package = root / "src" / "bras_description"
    shutil.copytree(os.path.join(DATA, "launch", "fidelity", "bras_description"),
                    package)
    for launch in (package / "launch").iterdir():
        if launch.name != "ns_attribute_rviz_root.launch.py":
            launch.unlink()
    rviz = package / "rviz" / "bras.rviz"
    rviz.write_text(rviz.read_text().replace("Fixed Frame: base", "Fixed Frame: map"))
    assert build_package(str(package), str(root / "install")).failure is None
    return root


def test_without_a_running_rviz2_the_launch_file_s_rviz2_gives_the_frame(workspace):
    from bras_kit.live.rviz_process import launched_rviz

    record = launched_rviz(str(workspace / "src"))
    assert record is not None and record["given"] and record["launch"].endswith("ns_attribute_rviz_root.launch.py")
    assert record["config"].endswith("share/bras_description/rviz/bras.rviz") and "Fixed Frame: map" in record["text"]
    processes = snapshot_from_json({"rviz": [record]}).rviz
    frame = fixed_frame(processes)
    assert (frame.frame, frame.source, frame.launch) == ("map", "file", record["launch"])
    from dataclasses import replace

    snapshot = replace(look([tutorial(at) for at in at_20_hz()]), rviz=processes)
    assert codes(snapshot) == ["BK846"] and "would open with Fixed Frame map" in message(snapshot, "BK846")


def test_outside_a_workspace_no_launch_file_is_read(tmp_path):
    from bras_kit.live.rviz_process import launched_rviz

    assert launched_rviz(str(tmp_path)) is None
