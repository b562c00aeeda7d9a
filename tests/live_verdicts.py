"""The two verdicts on one recorded state: doctor --ros's (the look read as it saves it) and view
--ros's (the same records fed to its feed as the probe streams them)."""

from __future__ import annotations

import json

from bras_kit.core.i18n import say
from bras_kit.live.doctor import diagnose
from bras_kit.ros.graph import snapshot_from_json
from bras_kit.view.live_ros import RosFeed


def findings_of(results) -> list:
    return [f for r in results for f in r.findings]


def doctor_findings(data: dict) -> list:
    return findings_of(diagnose(snapshot_from_json(json.loads(json.dumps(data)))))


def view_findings(data: dict) -> list:
    """The page's checks for the same graph: hello, the descriptions, each joint state, then the
    graph record, as the probe's stream mode sends them (no viewer attached: its checks are these)."""
    feed = RosFeed("python")
    feed.started = data["started"]
    feed.find_rviz = lambda: list(data.get("rviz", []))  # the rviz2 the look saw, not this machine's now
    feed._take({"kind": "hello", **{k: data[k] for k in ("domain", "range", "rmw")}})
    for description in data.get("descriptions", []):
        feed._take({"kind": "description", **description})
    for sample in data.get("joint_states", []):
        feed._take({"kind": "joint_state", **sample})
    feed._take({"kind": "graph", **{k: v for k, v in data.items() if k not in (
        "kind", "descriptions", "joint_states", "started", "ended")}})
    return findings_of(feed.results())


def judge(state) -> list[str]:
    """What is wrong with the verdicts on ``state`` (empty: right)."""
    wrong = []
    for side, found in (("doctor", doctor_findings(state.data)), ("view", view_findings(state.data))):
        codes = sorted(f.code for f in found)
        errors = sorted(f.code for f in found if f.severity == "error")
        warnings = {f.code for f in found if f.severity == "warning"}
        verdict = state.verdict
        if errors != sorted(verdict.errors):
            wrong.append(f"{side}: errors {errors}, expected {sorted(verdict.errors)}")
        if not set(verdict.warnings) <= warnings:
            wrong.append(f"{side}: warnings {sorted(warnings)} lack {sorted(set(verdict.warnings) - warnings)}")
        if set(verdict.absent) & set(codes):
            wrong.append(f"{side}: {sorted(set(verdict.absent) & set(codes))} should not be there")
        for code, text in verdict.words:
            said = [say(f.message, "en") for f in found if f.code == code]
            if not any(text in s for s in said):
                wrong.append(f"{side}: {code} does not say {text!r}: {said}")
    return wrong


def shifted_to_now(data: dict) -> dict:
    """A saved look moved in time so that it ends now (view --ros judges the seconds before its
    clock): every reception, event and non-zero stamp by the same amount."""
    import copy
    import time

    delta = time.time() - data["ended"]
    out = copy.deepcopy(data)
    out["started"] += delta
    out["ended"] += delta
    for record in out.get("descriptions", []) + out.get("joint_states", []) + out.get("events", []):
        for key in ("received", "time"):
            if isinstance(record.get(key), (int, float)):
                record[key] += delta
        stamp = record.get("stamp")
        if isinstance(stamp, list) and stamp != [0, 0]:
            total = stamp[0] * 1_000_000_000 + stamp[1] + round(delta * 1e9)
            record["stamp"] = [total // 1_000_000_000, total % 1_000_000_000]
    return out
