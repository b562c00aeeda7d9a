"""The package's nodes live beside the viewer (bras_kit.run.live): each JointState handed over
as the node publishes it, on the wall clock, nothing kept of it, stopped on request.

Oracles: the tutorial's own node (tests/data/launch/tutorial), whose k-th message carries
0.8 sin(0.05 k) and 1.2 sin(0.035 k) and is published 0.05 s after the one before; the
monotonic clock of this process; the files' stamps of the file system."""

from __future__ import annotations

import math
import os
import shutil
import time

import pytest
from paths import TESTS

from bras_kit.run import run_node
from bras_kit.run.live import LiveNodes, changed_files, package_stamps

TUTORIAL = TESTS / "data" / "launch" / "tutorial" / "bras_description"


def test_each_joint_state_arrives_as_it_is_published_on_the_wall_clock():
    got: list[tuple[float, list[str], list[float]]] = []
    nodes = LiveNodes(str(TUTORIAL), ["animation"],
                      lambda names, positions: got.append((time.monotonic(), list(names), list(positions))))
    nodes.start()
    time.sleep(3.0)
    nodes.stop()
    assert not nodes.running and nodes.errors == []
    count = len(got)
    time.sleep(0.5)
    assert len(got) == count, "states still arrive after stop()"
    assert count >= 20, count  # 3 s at 20 Hz, less the start-up
    for k, (_, names, positions) in enumerate(got, start=1):
        assert names == ["epaule", "coude"]
        assert positions == pytest.approx([0.8 * math.sin(0.05 * k), 1.2 * math.sin(0.035 * k)], abs=1e-9)
    # paced: once the node's start is caught up, the k-th is handed over at the node's start + 0.05 k
    # at the earliest, so the last 20 span 19 periods or more (all at once, they would span nothing);
    # a loaded machine only makes them later
    last = [arrived for arrived, _, _ in got[-20:]]
    assert last[-1] - last[0] >= 19 * 0.05 - 0.1, last


def test_a_live_run_that_keeps_nothing_holds_no_message_at_its_end():
    sent: list[object] = []
    kept = run_node(str(TUTORIAL), "animation", duration=1.0, live=True, on_joint_state=sent.append)
    assert len(kept.messages) == len(sent) >= 19
    sent.clear()
    streamed = run_node(str(TUTORIAL), "animation", duration=1.0, live=True, on_joint_state=sent.append, keep=False)
    assert len(sent) >= 19
    assert len(streamed.messages) <= 1  # at most the one of the last instant


def test_a_save_anywhere_in_the_package_is_seen_and_colcon_output_is_not(tmp_path):
    package = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL, package)
    before = package_stamps(str(package))
    assert str(package / "launch" / "affichage.launch.py") in before
    for folder in ("build", "install", "log", "bras_description.egg-info", ".git"):
        (package / folder).mkdir()
        (package / folder / "x").write_text("output")
    assert changed_files(before, package_stamps(str(package))) == []
    node = package / "bras_description" / "animation.py"
    node.write_text(node.read_text() + "\n# saved\n")
    os.utime(node, ns=(time.time_ns(), time.time_ns() + 10**9))
    (package / "urdf" / "new.urdf").write_text("<robot name='x'/>")
    assert changed_files(before, package_stamps(str(package))) == [
        str(node), str(package / "urdf" / "new.urdf")]


@pytest.mark.parametrize("later", ["now", "after_the_build"])
def test_a_second_save_in_the_same_clock_tick_is_seen(tmp_path, later):
    """Two saves of the same size within one tick of the file system's clock (a kernel before 6.13
    stamps a jiffy, 1 to 10 ms): same modification time, same size, other bytes. os.utime puts
    the first save's time back on the second, as such a clock does. Seen at the next look, and
    also when that look comes only after a build longer than the racy window (the look before the
    second save took the digest)."""
    package = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL, package)
    rviz = package / "urdf" / "bras.urdf"
    rviz.write_text(rviz.read_text().replace("base", "socl"))
    stamp = os.stat(rviz).st_mtime_ns
    before = package_stamps(str(package))
    rviz.write_text(rviz.read_text().replace("socl", "pied"))
    os.utime(rviz, ns=(stamp, stamp))
    if later == "after_the_build":
        from bras_kit.run import live

        old = live.RACY_NS
        live.RACY_NS = 0  # the look comes long after the save: the file is no longer recent
        try:
            after = package_stamps(str(package), before=before)
        finally:
            live.RACY_NS = old
    else:
        after = package_stamps(str(package), before=before)
    assert changed_files(before, after) == [str(rviz)]
    assert changed_files(after, package_stamps(str(package), before=after)) == []


@pytest.mark.slow
def test_a_live_run_beside_the_launch_says_when_the_angles_pass_the_limits(tmp_path):
    """bras-kit run beside bras-kit launch, its node sending 2.5 sin t to a joint limited to
    +-1.57: the terminal says so as soon as it happens (once per joint and side), and at Ctrl-C
    prints BK649 as a batch run does, at the line that sets msg.position. Oracle: the URDF's
    limit and the node's formula (2.5 sin t passes 1.57 at t = asin(1.57/2.5) = 0.68 s)."""
    import signal
    import subprocess
    import sys

    from pages import free_port, launch, launch_url
    from pages import wait as _wait

    package = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL, package)
    node = package / "bras_description" / "animation.py"
    text = node.read_text(encoding="utf-8")
    assert text.count("0.8 * math.sin") == 1
    node.write_text(text.replace("0.8 * math.sin", "2.5 * math.sin"), encoding="utf-8")
    position = next(k for k, line in enumerate(node.read_text().splitlines(), 1) if "msg.position" in line)
    env = {k: v for k, v in os.environ.items() if k not in ("DISPLAY", "WAYLAND_DISPLAY")}
    runtime = tmp_path / "runtime"
    runtime.mkdir(mode=0o700)
    env["XDG_RUNTIME_DIR"] = str(runtime)
    errors = tmp_path / "launch-stderr.txt"
    launched = launch([str(package), "--no-browser", "--port", str(free_port()), "--duration", "1"], env, errors)
    run_errors = tmp_path / "run-stderr.txt"
    try:
        launch_url(launched, errors)
        with open(run_errors, "w") as stderr:
            run = subprocess.Popen([sys.executable, "-m", "bras_kit", "run", str(package), "animation", "--quiet"],
                                   stdout=subprocess.PIPE, stderr=stderr, text=True, env=env)
        try:
            assert _wait(lambda: "joined the running bras-kit launch" in run_errors.read_text(), 60), \
                run_errors.read_text()
            assert _wait(lambda: "(BK649)" in run_errors.read_text(), 30), run_errors.read_text()
            time.sleep(1.0)
            run.send_signal(signal.SIGINT)
            out, _ = run.communicate(timeout=60)
        finally:
            if run.poll() is None:
                run.kill()
    finally:
        launched.send_signal(signal.SIGINT)
        launched.communicate(timeout=60)
    said = run_errors.read_text()
    assert said.count("(BK649)") == 1, said  # once: epaule's upper limit (its lower one comes at t = 3.8 s)
    assert "joint 'epaule' was sent" in said and "above its upper limit 1.57" in said
    assert "Traceback" not in said
    assert f"animation.py:{position}: BK649 error joint 'epaule'" in out, out
    assert run.returncode == 1
