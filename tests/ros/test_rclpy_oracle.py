"""The stand-in of rclpy against the REAL rclpy of Jazzy (7.1.6, the PyPI wheels): every node the
tests hold runs under both, and what each published and how each ended must agree, or the
difference is listed in docs/cli/run.md ("Where bras-kit run differs from ros2 run") with its
reason, and in KNOWN below.

The real side runs ``tests/oracle_harness.py`` with the oracle's interpreter
(``realros.oracle_python()``) in a loopback-only network namespace of its own
(``realros.run_isolated``): DDS never leaves the machine. The harness records inside the node's
own process (a DDS recorder joining late would miss the first messages). Both sides run the node
for RUN seconds of its own time, then Ctrl-C; the real one at wall-clock speed, so the real runs
go several at a time while the stand-in's run.

Compared, message by message in the node's own order: the topic, the names, the positions,
the lengths of velocity and effort, header.stamp against the node's clock when it published;
the rate in messages per second of node time; how the node ended (returned, Ctrl-C, hang, an
exception: its type, its words and the learner's line).
"""

from __future__ import annotations

import hashlib
import json
import math
import re
import subprocess
import sys
import tempfile
from dataclasses import dataclass, field
from pathlib import Path

import pytest
from paths import REPO, TESTS

sys.path.insert(0, str(TESTS))
import realros  # noqa: E402

pytestmark = pytest.mark.slow

DATA = TESTS / "data"
HARNESS = TESTS / "oracle_harness.py"
RUN = 2.0  # seconds of node time on each side
CPU_SECONDS = 4  # the stand-in's CPU limit here (a node that never lets time pass is stopped sooner)
AT_ONCE = 6  # real nodes at a time: they sleep between ticks, the two cores are not the limit
INTERNAL = ("/parameter_events", "/rosout")  # what rclpy itself publishes, not the node
POSITION_TOLERANCE = 1e-9
EPOCH_2001 = 978_307_200.0  # a stamp before it is not a clock's reading but a number the node chose
STAMP_TOLERANCE = 0.05  # s between a stamp and the node's clock when it published (real timing)
RATE_TOLERANCE = 0.25  # a real timer on a loaded machine; a period in Hz or two publishes per tick are far off


def corpus() -> list[Path]:
    """Every learner node under tests/data (a .py file that imports rclpy), one per content; not the
    attacks on the stand-in's own record (hostile_code/record/: they reach for bras-kit's _bras_sim,
    which a real ROS 2 has not; tests/trust/test_record_hostile.py runs them), nor the live tests'
    robot_state_publisher."""
    seen: dict[str, Path] = {}
    for path in sorted(DATA.rglob("*.py")):
        if path.is_relative_to(DATA / "hostile_code" / "record"):
            continue
        if path == DATA / "live" / "state_publisher.py":
            continue  # robot_state_publisher's counterpart, not a learner's node: started with its URDF by the
            # live tests, under the real rclpy only (tests/live/test_live_standins.py reads it on a real graph)
        text = path.read_text(encoding="utf-8", errors="replace")
        if not re.search(r"^\s*(import rclpy|from rclpy)", text, re.M):
            continue
        seen.setdefault(hashlib.sha256(text.encode()).hexdigest(), path)
    return sorted(seen.values())


# node (relative to tests/data) -> why the stand-in differs from rclpy 7.1.6 there; each is
# listed in docs/cli/run.md, and each must still differ (a fixed one leaves the list)
KNOWN: dict[str, str] = {
    "run/jazzy/logging_filters.py": "tf2_ros has no PyPI wheel of Jazzy: the oracle cannot import it",
    "run/jazzy/tool_frame.py": "tf2_ros has no PyPI wheel of Jazzy: the oracle cannot import it",
    "run/jazzy/now_without_to_msg.py": "the wheels are a release build: the C conversion's assert is compiled "
                                       "out and publish raises AttributeError at the same line",
    "run/jazzy/stamp_float_seconds.py": "the wheels are a release build: the C conversion's assert is compiled "
                                        "out and publish raises SystemError at the same line",
    "run/nodes/busy_loop.py": "a loop that never sleeps nor spins: the simulated clock cannot move, the CPU limit stops it",
    "run/nodes/flood.py": "10,000 messages without time passing: the stand-in stops the storm",
    "run/nodes/logs_to_tmp.py": "the walls: the node writes only in its run's folder",
    "run/nodes/uses_action.py": "rclpy.action is not simulated (BK641)",
}


@dataclass
class Sent:
    topic: str
    time: float  # node time, seconds
    names: list[str] | None
    positions: list[float] | None
    velocities: int | None
    efforts: int | None
    stamp_offset: float | None  # stamp minus the node's clock when published; None: no header
    stamp: float | None  # the stamp itself, seconds
    stamp_zero: bool
    whole_seconds: bool


@dataclass
class Outcome:
    ended: str  # returned, interrupted, hang, error, aborted, not_simulated, storm, exit
    error: tuple[str, str, int] | None = None  # type, words (without a file's place), learner's line
    sent: list[Sent] = field(default_factory=list)


def _sent(topic: str, time_s: float, published_ns: int, fields: dict) -> Sent:
    header = fields.get("header") if isinstance(fields, dict) else None
    offset, zero, whole, absolute = None, False, False, None
    if isinstance(header, dict):
        stamp = header.get("stamp") or {}
        sec, nanosec = int(stamp.get("sec", 0)), int(stamp.get("nanosec", 0))
        zero = sec == 0 and nanosec == 0
        whole = nanosec == 0 and not zero
        offset = (sec * 10**9 + nanosec - published_ns) / 1e9
        absolute = sec + nanosec * 1e-9
    names = fields.get("name") if isinstance(fields, dict) else None
    positions = fields.get("position") if isinstance(fields, dict) else None

    def length(key: str) -> int | None:
        value = fields.get(key) if isinstance(fields, dict) else None
        return len(value) if isinstance(value, list) else None

    return Sent(topic, time_s, list(names) if isinstance(names, list) else None,
                [float(p) for p in positions] if isinstance(positions, list) else None,
                length("velocity"), length("effort"), offset, absolute, zero, whole)


def _words(text: str) -> str:
    """An error's words without the place of a file (the oracle's venv, Jazzy's /opt/ros) nor
    rcl's source line (", at /project/src/rcl/init.c:333" in the wheels, "./src/..." in apt's)."""
    text = re.sub(r", at \S+:\d+$", "", text.strip())
    return re.sub(r" \((/|unknown location)[^)]*\)", "", text).strip()


def standin_outcome(path: Path) -> Outcome:
    from bras_kit.run import NodeRunError, run_node

    try:
        recording = run_node(str(path), duration=RUN, cpu_seconds=CPU_SECONDS)
    except NodeRunError as exc:
        return Outcome(f"limit:{exc.kind}")
    ended = {"duration": "interrupted", "stopped": "hang"}.get(recording.ended, recording.ended)
    error = None
    failure = recording.failure
    if failure is not None and failure.kind == "SystemExit":
        ended = f"exit:{failure.detail}"
    elif failure is not None:
        if failure.kind == "Aborted":
            ended = "aborted"
        line = failure.frames[-1].line if failure.frames else 0
        error = (failure.kind, _words(failure.detail), line)
    sent = [_sent(m.topic, m.time, recording.start_ns + int(round(m.time * 1e9)), m.fields)
            for m in recording.messages if m.topic not in INTERNAL]
    return Outcome(ended, error, sent)


def real_outcome(events: list[dict], returncode: int, stderr: str) -> Outcome:
    start = next((e["t_ns"] for e in events if e["event"] == "node"),
                 next((e["t_ns"] for e in events if e["event"] == "start"), 0))
    sent = [_sent(e["topic"], (e["t_ns"] - start) / 1e9, e["t_ns"], e["fields"])
            for e in events if e["event"] == "publish" and e["topic"] not in INTERNAL]
    end = next((e for e in events if e["event"] == "end"), None)
    if end is None:
        return Outcome("aborted" if returncode < 0 else f"died:{returncode}:{stderr[-300:]}", None, sent)
    ended = end["ended"] if end["ended"] != "exit" else f"exit:{end['code']}"
    error = (end["type"], _words(end["message"]), end["line"]) if ended == "error" else None
    if ended in ("interrupted", "returned", "hang"):
        thread = next((e for e in events if e["event"] == "thread_error"), None)
        if thread is not None and (thread["t_ns"] - start) / 1e9 < RUN:  # before Ctrl-C: the node's failure
            ended, error = "error", (thread["type"], _words(thread["message"]), thread["line"])
    return Outcome(ended, error, sent)


def run_real(paths: list[Path], folder: Path) -> dict[Path, Outcome]:
    python = realros.oracle_python()
    out: dict[Path, Outcome] = {}
    pending = list(paths)
    running: list[tuple[Path, Path, subprocess.Popen]] = []
    while pending or running:
        while pending and len(running) < AT_ONCE:
            path = pending.pop(0)
            events = folder / f"{len(pending)}-{path.stem}.jsonl"
            workdir = folder / f"{len(pending)}-{path.stem}.work"
            workdir.mkdir()
            argv = [python, str(HARNESS), str(path), "main", str(RUN), str(events)]
            env = realros.graph_env(realros.new_domain(), ORACLE_WORKDIR=str(workdir))
            running.append((path, events, subprocess.Popen(
                realros.in_loopback_namespace(argv), env=env, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE,
                text=True, start_new_session=True)))  # its own process group: no signal meant for others
        path, events, process = running.pop(0)
        try:
            _, stderr = process.communicate(timeout=RUN + 40)
        except subprocess.TimeoutExpired:
            process.kill()
            _, stderr = process.communicate()
        lines = events.read_text().splitlines() if events.exists() else []
        out[path] = real_outcome([json.loads(line) for line in lines if line.strip()], process.returncode, stderr)
    return out


@pytest.fixture(scope="module")
def outcomes(real_rclpy) -> dict[Path, tuple[Outcome, Outcome]]:
    import threading

    paths = corpus()
    real: dict[Path, Outcome] = {}
    with tempfile.TemporaryDirectory(prefix="bras-kit-oracle-") as folder:
        # the real nodes mostly sleep: they run in a thread (Popen and files only, no import:
        # a fork beside an importing thread would wait forever) while the stand-in's run here
        driver = threading.Thread(target=lambda: real.update(run_real(paths, Path(folder))), daemon=True)
        driver.start()
        standin = {path: standin_outcome(path) for path in paths}
        driver.join()
    assert set(real) == set(paths), "the real rclpy's runs did not all end"
    return {path: (standin[path], real[path]) for path in paths}


def differences(standin: Outcome, real: Outcome) -> list[str]:
    """What differs between the two runs of one node, in words (empty: they agree)."""
    out = []
    if standin.ended != real.ended:
        out.append(f"ended: stand-in {standin.ended}, rclpy {real.ended}")
    if (standin.error is None) != (real.error is None) or (
            standin.error and real.error and standin.error != real.error):
        out.append(f"error: stand-in {standin.error}, rclpy {real.error}")
    topics_s = [m.topic for m in standin.sent]
    topics_r = [m.topic for m in real.sent]
    if bool(topics_s) != bool(topics_r) or set(topics_s) != set(topics_r):
        out.append(f"topics: stand-in {sorted(set(topics_s))} ({len(topics_s)}), "
                   f"rclpy {sorted(set(topics_r))} ({len(topics_r)})")
    whole_s, whole_r = _whole_seconds(standin.sent), _whole_seconds(real.sent)
    if whole_s != whole_r:
        out.append(f"stamps in whole seconds: stand-in {whole_s}, rclpy {whole_r}")
    for topic in sorted(set(topics_s) & set(topics_r)):  # topic by topic: two timers' order is the OS's
        mine_all = [m for m in standin.sent if m.topic == topic]
        theirs_all = [m for m in real.sent if m.topic == topic]
        for k, (mine, theirs) in enumerate(zip(mine_all, theirs_all)):
            found = _message_differences(mine, theirs, whole_s and whole_r)
            if found:
                out.append(f"message {k} on {topic}: " + "; ".join(found))
                break
    for topic in set(topics_s) & set(topics_r):
        rate_s, rate_r = _rate(standin.sent, topic), _rate(real.sent, topic)
        if rate_s is not None and rate_r is not None and abs(rate_s - rate_r) > RATE_TOLERANCE * rate_r:
            out.append(f"rate on {topic}: stand-in {rate_s:.2f}/s, rclpy {rate_r:.2f}/s")
    return out


def _whole_seconds(sent: list[Sent]) -> bool:
    """Every stamp of the run counts whole seconds (a nanosec of 0 now and then is a tick that
    fell on the second, as the stand-in's exact clock does every twentieth tick)."""
    stamped = [m for m in sent if m.stamp_offset is not None and not m.stamp_zero]
    return len(stamped) >= 3 and all(m.whole_seconds for m in stamped)


def _message_differences(mine: Sent, theirs: Sent, whole: bool) -> list[str]:
    out = []
    if mine.topic != theirs.topic:
        out.append(f"topic {mine.topic} / {theirs.topic}")
    if mine.names != theirs.names:
        out.append(f"names {mine.names} / {theirs.names}")
    if (mine.positions is None) != (theirs.positions is None) or (
            mine.positions is not None and theirs.positions is not None and (
            len(mine.positions) != len(theirs.positions)
            or any(not (a == b or (math.isnan(a) and math.isnan(b)) or abs(a - b) <= POSITION_TOLERANCE)
                   for a, b in zip(mine.positions, theirs.positions)))):
        out.append(f"positions {mine.positions} / {theirs.positions}")
    if (mine.velocities, mine.efforts) != (theirs.velocities, theirs.efforts):
        out.append(f"velocity/effort lengths {(mine.velocities, mine.efforts)} / {(theirs.velocities, theirs.efforts)}")
    if mine.stamp_zero != theirs.stamp_zero:
        out.append(f"stamp zero {mine.stamp_zero} / {theirs.stamp_zero}")
    elif mine.stamp is not None and theirs.stamp is not None and max(mine.stamp, theirs.stamp) < EPOCH_2001:
        if abs(mine.stamp - theirs.stamp) > 1e-9:  # a stamp the node wrote by hand (sec = 1)
            out.append(f"stamp {mine.stamp} / {theirs.stamp}")
    elif mine.stamp_offset is not None and theirs.stamp_offset is not None and not mine.stamp_zero:
        limit = 1.0 + STAMP_TOLERANCE if whole else STAMP_TOLERANCE
        if abs(mine.stamp_offset - theirs.stamp_offset) > limit:
            out.append(f"stamp minus the node's clock {mine.stamp_offset:.3f} s / {theirs.stamp_offset:.3f} s")
    return out


def _rate(sent: list[Sent], topic: str) -> float | None:
    times = [m.time for m in sent if m.topic == topic]
    if len(times) < 5 or times[-1] <= times[0]:
        return None
    return (len(times) - 1) / (times[-1] - times[0])


def _name(path: Path) -> str:
    return str(path.relative_to(DATA))


@pytest.mark.parametrize("path", corpus(), ids=_name)
def test_node_runs_as_under_the_real_rclpy_of_jazzy(outcomes, path: Path) -> None:
    standin, real = outcomes[path]
    found = differences(standin, real)
    known = KNOWN.get(_name(path))
    if known is not None:
        assert found, f"{_name(path)} now runs as under rclpy 7.1.6: take it out of KNOWN and docs/cli/run.md"
        return
    assert not found, f"{_name(path)} differs from rclpy 7.1.6 (Jazzy):\n  " + "\n  ".join(found)


def test_every_known_difference_is_documented() -> None:
    page = (REPO / "docs" / "cli" / "run.md").read_text(encoding="utf-8")
    missing = [name for name in KNOWN if name not in page]
    assert not missing, f"docs/cli/run.md does not list: {missing}"


def test_the_corpus_holds_one_node_per_category_of_issue_44() -> None:
    names = {_name(p) for p in corpus()}
    for category in ("run/jazzy/init_args_remap.py", "run/jazzy/service_never_called.py",
                     "run/jazzy/wrong_import_type.py", "run/jazzy/names_as_one_string.py",
                     "run/jazzy/velocity_left_unset.py"):
        assert category in names
    assert len(names) >= 60
