"""bras-kit view --ros in a real browser (Debian's chromium, as tests/view/test_view.py drives it), on a
real ROS 2 graph (the real rclpy of Jazzy, tests/data/live/'s nodes), all in one loopback-only
network namespace: tests/live_view_driver.py plays the story and reports what the page showed.
The oracles are the page's pixels (the orange forearm drawn, and moved between screenshots)
and the findings the page lists as the graph changes under it."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import pytest
from paths import TESTS
from realros import graph_env, in_loopback_namespace, new_domain

pytestmark = pytest.mark.slow
HERE = TESTS


@pytest.fixture(scope="module")
def story(real_rclpy, chromium):  # the driver starts chromium in the namespace
    python = real_rclpy
    done = subprocess.run(in_loopback_namespace([sys.executable, str(HERE / "live_view_driver.py"), python]),
                          env=graph_env(new_domain(), BRAS_KIT_ROS_PYTHON=python), capture_output=True, text=True,
                          timeout=240, start_new_session=True)
    assert done.returncode == 0, done.stderr[-3000:] + done.stdout[-3000:]
    return json.loads(done.stdout.strip().splitlines()[-1])


def test_view_ros_prints_the_address_and_draws_the_live_arm(story):
    assert story["address_line"].startswith("bras-kit view: http://127.0.0.1:")
    assert story["drawn"]


def test_view_ros_moves_the_arm_with_the_node_s_joint_states(story):
    centroids = [c for c in story["centroids"] if c is not None]
    assert len(centroids) >= 3
    moved = max(math.dist(a, b) for a in centroids for b in centroids)
    assert moved > 5.0  # pixels: the tutorial's sines swing the forearm by tens of pixels


def test_view_ros_shows_the_doctor_s_findings_as_the_graph_changes(story):
    assert story["no_finding"]  # the tutorial's graph: nothing to say
    assert story["bk811"]  # the slider window joined: two publishers of /joint_states
    assert story["bk301"]  # the description replaced by one with coude short of the tip


def test_view_ros_survives_nodes_leaving_and_a_description_replaced(story):
    assert story["still_serving"]
    assert "Traceback" not in story["stderr"] and story["exit_code"] == 0, story["stderr"]
