"""A generator of live states beyond the issue's 21 (issue 56): for each category of what a learner's
graph gets wrong, several states built as the probe records them, each with the verdict that
follows from the category (the flaw put in), worked from robot_state_publisher 3.3.3's
callbackJointState, tf2 and rviz2's sources, never from bras-kit's rules.

A state is (name, category, the probe's JSON object, the expected verdict): the exact error codes,
the warnings that must be there, the codes that must not. ``HELD_OUT`` names the states kept aside
while the rules were fixed, run last.
"""

from __future__ import annotations

import math
import time
from collections.abc import Iterator
from dataclasses import dataclass, field
from pathlib import Path
from typing import Any

URDF = (Path(__file__).parent / "data" / "live" / "bras.urdf").read_text()
WRIST = URDF.replace("</robot>", """  <link name="main"/>
  <joint name="poignet" type="revolute"><parent link="avant_bras"/><child link="main"/>
    <origin xyz="0 0 0.5"/><axis xyz="0 1 0"/><limit effort="5" lower="-1.5" upper="1.5" velocity="1"/></joint>
</robot>""")
# coude follows epaule (a belt): joint_state_publisher sends epaule only, rsp computes coude (lines 348-354)
MIMIC = URDF.replace('<joint name="coude" type="revolute">',
                     '<joint name="coude" type="revolute">\n    <mimic joint="epaule" multiplier="-1" offset="0"/>')
RSP = {"node": "/robot_state_publisher", "reliability": "reliable", "durability": "transient_local"}
RSP_READS = {**RSP, "reliability": "best_effort", "durability": "volatile"}
NODE = {"node": "/animation_bras", "reliability": "reliable", "durability": "volatile"}
JOINT_STATE, STRING = "sensor_msgs/msg/JointState", "std_msgs/msg/String"


@dataclass(frozen=True)
class Verdict:
    errors: tuple[str, ...] = ()  # exactly these error codes (sorted, repeats as found)
    warnings: tuple[str, ...] = ()  # at least these warning codes
    absent: tuple[str, ...] = ()  # none of these codes
    words: tuple[tuple[str, str], ...] = ()  # (code, text its English message holds)


@dataclass(frozen=True)
class State:
    name: str
    category: str
    data: dict[str, Any]
    verdict: Verdict
    extra: dict[str, Any] = field(default_factory=dict)


def _states(t0: float, at: list[float], stamp=None, names=("epaule", "coude"), positions=None) -> list[dict]:
    out = []
    for i, a in enumerate(at):
        s = t0 + a if stamp is None else stamp(i, a)
        values = positions(i, a) if positions else (0.8 * math.sin(a), 1.2 * math.sin(0.7 * a))
        sec = int(math.floor(s))
        out.append({"received": t0 + a, "stamp": [sec, min(999_999_999, round((s - sec) * 1e9))],
                    "name": list(names), "position": list(values)})
    return out


def _look(t0: float, joint_states: list[dict], *, publishers=(NODE,), topics=None, nodes=None, descriptions=None,
          seconds=3.0, **more: Any) -> dict[str, Any]:
    all_topics: dict[str, Any] = {
        "/robot_description": {"types": [STRING], "publishers": [RSP], "subscribers": []},
        "/joint_states": {"types": [JOINT_STATE], "publishers": list(publishers), "subscribers": [RSP_READS]}}
    all_topics.update(topics or {})
    return {"kind": "snapshot", "domain": 7, "range": "LOCALHOST", "rmw": "rmw_fastrtps_cpp",
            "started": t0, "ended": t0 + seconds,
            "nodes": nodes or ["/robot_state_publisher", "/animation_bras"],
            "topics": {k: v for k, v in all_topics.items() if v is not None},
            "descriptions": descriptions if descriptions is not None else [
                {"text": URDF, "received": t0 + 0.1, "length": len(URDF)}],
            "joint_states": joint_states, **more}


def _at(seconds: float = 3.0, period: float = 0.05, start: float = 0.05) -> list[float]:
    return [start + i * period for i in range(int((seconds - start) / period))]


def generate(t0: float | None = None) -> Iterator[State]:
    """Every state, its stamps around ``t0`` (now less a watch, by default: view --ros judges the
    last seconds before its clock)."""
    t0 = time.time() - 3.05 if t0 is None else t0
    at = _at()
    healthy = _states(t0, at)

    # names near the expected ones: a typo, another namespace, a remap: the graph shows where it went
    for topic in ("/joint_state", "/jointstates", "/arm/joint_states", "/bras/joint_states", "/joint_states_gui"):
        yield State(f"near-js{topic.replace('/', '-')}", "near names", _look(t0, [], publishers=(), topics={
            topic: {"types": [JOINT_STATE], "publishers": [NODE], "subscribers": []}}),
            Verdict(("BK810",), words=(("BK810", f"but {topic} is published by"),)))
    for topic in ("/arm/robot_description", "/robot_descriptions", "/bras/robot_description", "/robot_desc"):
        yield State(f"near-rd{topic.replace('/', '-')}", "near names", _look(
            t0, healthy, topics={"/robot_description": None, topic: {
                "types": [STRING], "publishers": [{**RSP, "node": "/arm/robot_state_publisher"}], "subscribers": []}},
            descriptions=[]), Verdict(("BK801",), words=(("BK801", topic),)))

    # the wrong type on the right name: what the graph says it carries
    for kind in ("std_msgs/msg/Float64MultiArray", "std_msgs/msg/String", "trajectory_msgs/msg/JointTrajectory"):
        yield State(f"type-{kind.rsplit('/', 1)[-1]}", "wrong types", _look(t0, [], topics={
            "/joint_states": {"types": [kind], "publishers": [NODE], "subscribers": [RSP_READS]}}),
            Verdict(("BK812",), words=(("BK812", kind),)))

    # several nodes of one name
    for count in (2, 3, 4):
        yield State(f"shared-name-{count}", "duplicate node names",
                    _look(t0, healthy, shared_names={"/animation_bras": count}),
                    Verdict((), ("BK844",), words=(("BK844", f"{count} nodes are named /animation_bras"),)))
    yield State("shared-rsp", "duplicate node names", _look(t0, healthy, shared_names={"/robot_state_publisher": 2}),
                Verdict((), ("BK844",)))

    # two description publishers: the same robot is one description; two robots are named
    old = {**RSP, "node": "/old/robot_state_publisher"}
    two = {"/robot_description": {"types": [STRING], "publishers": [RSP, old], "subscribers": []}}
    yield State("two-rsp-same-robot", "two description publishers", _look(
        t0, healthy, topics=two, descriptions=[{"text": URDF, "received": t0 + 0.1, "length": len(URDF)}] * 2),
        Verdict((), absent=("BK845",)))
    for first, second, differ in ((URDF, WRIST, "main, poignet"), (WRIST, URDF, "main, poignet")):
        yield State(f"two-rsp-{'wrist-last' if second is WRIST else 'wrist-first'}", "two description publishers",
                    _look(t0, healthy if second is URDF else _states(t0, at), topics=two, descriptions=[
                        {"text": first, "received": t0 + 0.1, "length": len(first)},
                        {"text": second, "received": t0 + 0.2, "length": len(second)}]),
                    Verdict(("BK845",) + (("BK817",) if second is WRIST else ()), words=(("BK845", differ),)))

    # NaN and inf: tf2 refuses the transform (buffer_core.cpp:235-242), RViz keeps the last valid one
    for joint, bad in (("epaule", math.nan), ("coude", math.inf), ("coude", -math.inf), ("epaule", math.inf)):
        index = ("epaule", "coude").index(joint)

        def values(i, a, index=index, bad=bad):
            v = [0.8 * math.sin(a), 1.2 * math.sin(0.7 * a)]
            v[index] = bad
            return v
        yield State(f"not-finite-{joint}-{bad}", "NaN/inf", _look(t0, _states(t0, at, positions=values)),
                    Verdict(("BK841",), absent=("BK840",), words=(("BK841", "TF_NAN_INPUT"),)))

    # degrees where radians are meant: every value fits the limits once read as degrees
    for scale in (0.5, 1.0):
        yield State(f"degrees-{scale}", "degrees", _look(t0, _states(t0, at, positions=lambda i, a, s=scale: (
            math.degrees(s * 0.8 * math.sin(a)), math.degrees(s * 1.2 * math.sin(0.7 * a)))), ),
            Verdict((), ("BK818",), words=(("BK818", "a number of degrees"),)))

    # stamps: frozen (the first message passes, then none: lines 325-340), whole seconds (one a
    # second), old or ahead but advancing (tf2 keeps the latest: drawn), and a clock at half speed
    yield State("stamp-frozen-late", "stamps", _look(t0, _states(t0, at, stamp=lambda i, a: t0 - 100.0)),
                Verdict(("BK840",), words=(("BK840", "do not advance"),)))
    yield State("stamp-frozen-now", "stamps", _look(t0, _states(t0, at, stamp=lambda i, a: t0 + 0.05)),
                Verdict(("BK840",)))
    yield State("stamp-whole-seconds", "stamps", _look(t0, _states(
        t0, at, stamp=lambda i, a: float(math.floor(t0 + a)))), Verdict((), ("BK843",), absent=("BK840",)))
    for offset in (-30.0, -120.0, 45.0):
        yield State(f"stamp-offset{offset:+.0f}", "stamps", _look(t0, _states(t0, at, stamp=lambda i, a, o=offset:
                                                                                 t0 + a + o)),
                    Verdict((), ("BK815",), absent=("BK840", "BK843")))
    yield State("stamp-half-speed", "stamps", _look(t0, _states(t0, at, stamp=lambda i, a: t0 + a / 2)),
                Verdict((), absent=("BK840",)))  # 25 ms between stamps: every other one clears 50 ms

    # nodes dying or stopping, joining late
    for stop in (0.8, 1.6, 1.9):
        cut = [s for s in healthy if s["received"] < t0 + stop]
        yield State(f"dies-{stop}", "nodes dying", _look(t0, cut, publishers=(), nodes=["/robot_state_publisher"],
                                                         events=[{"time": t0 + stop + 0.4, "kind": "left",
                                                                  "node": "/animation_bras"}]),
                    Verdict(("BK842",), words=(("BK842", "nothing publishes /joint_states any more"),)))
        yield State(f"stops-{stop}", "nodes dying", _look(t0, cut), Verdict(("BK842",)))
    late = [s for s in healthy if s["received"] >= t0 + 1.0]
    yield State("joins-late", "joining late", _look(t0, late, events=[
        {"time": t0 + 0.2, "kind": "joined", "node": "/robot_state_publisher"},
        {"time": t0 + 2.9, "kind": "joined", "node": "/animation_bras"}]), Verdict(absent=("BK842", "BK840")))

    yield State("description-late", "joining late", _look(t0, healthy, descriptions=[
        {"text": URDF, "received": t0 + 2.6, "length": len(URDF)}], events=[
        {"time": t0 + 0.3, "kind": "joined", "node": "/animation_bras"},
        {"time": t0 + 2.6, "kind": "joined", "node": "/robot_state_publisher"}]),
        Verdict(absent=("BK801", "BK803", "BK842")))

    # mimic joints: rsp computes the follower from the leader (lines 348-354)
    yield State("mimic-leader-only", "mimic joints", _look(t0, _states(t0, at, names=("epaule",), positions=lambda i, a: (
        0.8 * math.sin(a),)), descriptions=[{"text": MIMIC, "received": t0 + 0.1, "length": len(MIMIC)}]),
        Verdict(absent=("BK817", "BK840")))
    yield State("mimic-both-sent", "mimic joints", _look(t0, healthy, descriptions=[
        {"text": MIMIC, "received": t0 + 0.1, "length": len(MIMIC)}]), Verdict(absent=("BK817", "BK816")))

    # the old description still running: the new node's joint is unknown to it
    yield State("old-description", "old description still running", _look(t0, _states(
        t0, at, names=("epaule", "coude", "poignet"), positions=lambda i, a: (math.sin(a), 0.2, 0.3 * math.sin(a)))),
        Verdict(("BK816",), words=(("BK816", "poignet"),)))
    yield State("old-description-renamed", "old description still running", _look(t0, _states(
        t0, at, names=("shoulder", "elbow"))), Verdict(("BK816", "BK816", "BK817", "BK817")))


# kept aside while the rules were fixed, run last (tests/doctor/test_live_states_heldout.py)
HELD_OUT = ("near-js-joint_states_gui", "type-JointTrajectory", "stamp-offset+45", "mimic-both-sent", "dies-0.8",
            "not-finite-epaule-inf")
