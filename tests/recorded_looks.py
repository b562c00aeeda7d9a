"""Helpers shared by the tests (moved from test_live_rviz_verdicts.py, which still uses them)."""

from __future__ import annotations

import math
from pathlib import Path

from bras_kit.live.doctor import diagnose
from bras_kit.ros.graph import snapshot_from_json

URDF = (Path(__file__).parent / "data" / "live" / "bras.urdf").read_text()


T0 = 1_800_000_000.0  # the watch starts here (seconds, the probe's clock)


RSP = {"node": "/robot_state_publisher", "reliability": "reliable", "durability": "transient_local"}


NODE = {"node": "/animation_bras", "reliability": "reliable", "durability": "volatile"}


def look(messages, *, seconds=3.0, publishers=(NODE,), topics=None, nodes=None, descriptions=None):
    """A snapshot as the probe prints it: ``messages`` are (received offset, stamp s, names, positions)."""
    states = [{"received": T0 + at, "stamp": [int(stamp), round((stamp - int(stamp)) * 1e9)],
               "name": list(names), "position": list(positions)} for at, stamp, names, positions in messages]
    all_topics = {"/robot_description": {"types": ["std_msgs/msg/String"], "publishers": [RSP], "subscribers": []},
                  "/joint_states": {"types": ["sensor_msgs/msg/JointState"], "publishers": list(publishers),
                                    "subscribers": [{**RSP, "reliability": "best_effort",
                                                     "durability": "volatile"}]}}
    all_topics.update(topics or {})
    return snapshot_from_json({
        "kind": "snapshot", "domain": 7, "range": "LOCALHOST", "rmw": "rmw_fastrtps_cpp",
        "started": T0, "ended": T0 + seconds,
        "nodes": nodes or ["/robot_state_publisher", "/animation_bras"],
        "topics": {k: v for k, v in all_topics.items() if v is not None},
        "descriptions": descriptions if descriptions is not None else [
            {"text": URDF, "received": T0 + 0.1, "length": len(URDF)}],
        "joint_states": states})


def tutorial(at: float, stamp: float | None = None, *, t: float | None = None, names=("epaule", "coude")):
    angle = at if t is None else t
    return (at, T0 + at if stamp is None else stamp, names, (0.8 * math.sin(angle), 1.2 * math.sin(0.7 * angle)))


def codes(snapshot, severity=None):
    found = [f for r in diagnose(snapshot) for f in r.findings]
    return sorted(f.code for f in found if severity is None or f.severity == severity)


def message(snapshot, code) -> str:
    from bras_kit.core.i18n import say

    found = next(f for r in diagnose(snapshot) for f in r.findings if f.code == code)
    return say(found.message, "en")


def at_20_hz(seconds=3.0, start=0.05):
    return [start + i * 0.05 for i in range(int(seconds / 0.05) - 1)]
