"""From one snapshot of the graph to findings: the live rules (BK8xx) and, on the URDF received
on /robot_description, the validator's own rules (e.g. BK301: ``coude``'s origin not at the tip).

::

    from bras_kit.live.doctor import diagnose
    results = diagnose(snapshot)       # FileResult per topic or node, worded where shown
"""

from __future__ import annotations

from ..core.errors import BrasKitError
from ..findings.data import FileResult, finding, sort_key
from ..findings.registry import select_rules
from ..model.robot import Robot
from ..ros.graph import Snapshot
from ..ros.topics import DESCRIPTION
from ..validate import validate
from ..validate.live import LiveGraph, description_kind

# the validator's rules that need files or a package beside the URDF, which a live graph lacks
NOT_ON_LIVE_TEXT = ("BK6", "BK7", "BK8")


def robot_of(snapshot: Snapshot) -> tuple[Robot | None, FileResult | None]:
    """The robot of the last description received, and the URDF rules' findings on it (None, None
    when no URDF came; a text that is XML but cannot be read gives the loader's finding)."""
    if not snapshot.descriptions:
        return None, None
    text = snapshot.descriptions[-1].text
    if description_kind(text) != "urdf":
        return None, None
    from ..model.robot import robot_from_xml
    from ..model.xmlio import parse_xml
    from ..validate import _unreadable  # the same BK100-BK103 wording as 'bras-kit validate'

    try:
        robot = robot_from_xml(parse_xml(text, DESCRIPTION), path=DESCRIPTION, source_text=text)
    except BrasKitError as exc:
        return None, FileResult(DESCRIPTION, [_unreadable(DESCRIPTION, exc)])
    # infos (inertia for physics...) say nothing about RViz: only what is wrong with the arm shown
    findings = [f for f in validate(robot, ignore=NOT_ON_LIVE_TEXT) if f.severity != "info"]
    return robot, FileResult(DESCRIPTION, findings)


def diagnose(snapshot: Snapshot) -> list[FileResult]:
    """Every finding about the graph, grouped by the topic or node it is about (the description's
    URDF findings under /robot_description), causes first: the graph, then what it carries."""
    robot, urdf = robot_of(snapshot)
    graph = LiveGraph(snapshot, robot)
    by_place: dict[str, list] = {}
    for rule in select_rules(["BK8"]):
        if rule.check is None:
            continue
        for found in rule.check(graph):  # a live rule takes a LiveGraph
            by_place.setdefault(str(found.params.get("file", "")), []).append(finding(rule, found))
    results = [FileResult(place, sorted(found, key=sort_key)) for place, found in by_place.items()]
    if urdf is not None and urdf.findings:
        results.append(urdf)
    order = {DESCRIPTION: 1, "/joint_states": 2}
    return sorted(results, key=lambda r: (order.get(r.path, 0 if r.path.startswith("ROS_") else 3), r.path))
