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
