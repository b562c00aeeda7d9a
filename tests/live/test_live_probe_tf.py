"""The probe's reading of /tf and /tf_static (issue 56), with the real message types of Jazzy:
geometry_msgs/TransformStamped from the real wheels, in the TFMessage shape (tf2_msgs itself has
no wheel on PyPI, so the probe's subscriptions cannot be made here; its record of each transform
and the model's use of the records can)."""

from __future__ import annotations

import json

import pytest
from realros import new_domain, run_isolated

from bras_kit.live.watch import PROBE
from bras_kit.ros.graph import snapshot_from_json
from bras_kit.ros.rviz.frames import Tf, placed_links

pytestmark = pytest.mark.slow

SCRIPT = f"""
import importlib.util, json, math, sys, types
spec = importlib.util.spec_from_file_location("probe", {PROBE!r})
probe = importlib.util.module_from_spec(spec); spec.loader.exec_module(probe)
from geometry_msgs.msg import TransformStamped
def tf(parent, child, sec, x=0.0):
    t = TransformStamped(); t.header.frame_id = parent; t.child_frame_id = child
    t.header.stamp.sec = sec; t.transform.translation.x = x; t.transform.rotation.w = 1.0
    return t
holder = types.SimpleNamespace(transforms=[], lock=__import__("threading").Lock())
probe.Probe._on_tf(holder, types.SimpleNamespace(transforms=[tf("base", "bras", 5), tf("bras", "avant_bras", 5, math.nan)]), False)
probe.Probe._on_tf(holder, types.SimpleNamespace(transforms=[tf("world", "base", 1)]), True)
print(json.dumps(holder.transforms))
"""


def test_transforms_are_recorded_with_frames_stamps_static_and_nan_and_placed_as_tf2_would(real_rclpy, tmp_path):
    done = run_isolated([real_rclpy, "-c", SCRIPT], domain=new_domain(), timeout=60)
    assert done.returncode == 0, done.stderr
    records = json.loads(done.stdout.strip().splitlines()[-1])
    assert [(r["parent"], r["child"], r["stamp"], r["static"], r["nan"]) for r in records] == [
        ("base", "bras", [5, 0], False, False), ("bras", "avant_bras", [5, 0], False, True),
        ("world", "base", [1, 0], True, False)]
    seen = snapshot_from_json({"transforms": records}).transforms
    assert seen is not None and len(seen) == 3
    from live_states import URDF

    from bras_kit.model.robot import robot_from_xml
    from bras_kit.model.xmlio import parse_xml

    robot = robot_from_xml(parse_xml(URDF, "b.urdf"), path="b.urdf", source_text=URDF)
    placed = placed_links(robot, "base", [Tf(t.parent, t.child, t.stamp[0] * 10**9, t.static, nan=t.nan)
                                          for t in seen])
    # tf2 refuses the NaN (buffer_core.cpp:235-242): avant_bras has no transform, bras has one
    assert placed["bras"] is None and placed["base"] is None
    assert str(placed["avant_bras"]) == "No transform from [avant_bras] to [base]"
