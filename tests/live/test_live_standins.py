"""The stand-ins of robot_state_publisher 3.3.3 and rviz2 (tests/data/live/) look on the graph as
the real nodes do (issue 56): read with the real rclpy's graph API and parameter service, judged
against their sources (ros/robot_state_publisher 3.3.3 src/robot_state_publisher.cpp; ros2/rviz
jazzy visualizer_app.cpp and robot_model_display.cpp), in a loopback-only namespace of its own."""

from __future__ import annotations

import json
import shlex
import subprocess

import pytest
from live_graphs import DATA, URDF
from realros import graph_env, new_domain, shell_in_loopback_namespace

pytestmark = pytest.mark.slow

CHECKER = """
import json, time, rclpy
from rcl_interfaces.srv import ListParameters
rclpy.init()
node = rclpy.create_node("_checker")
def qos(i):
    q = i.qos_profile
    # (the depth is not in what Fast DDS announces of a remote endpoint: the graph says 0)
    return [i.node_namespace.rstrip("/") + "/" + i.node_name, q.reliability.name.lower(), q.durability.name.lower()]
end = time.monotonic() + 20
while time.monotonic() < end:
    rclpy.spin_once(node, timeout_sec=0.1)
    names = {n for n, _ in node.get_node_names_and_namespaces()}
    if {"robot_state_publisher", "rviz"} <= names and node.get_subscriptions_info_by_topic("/robot_description") \\
            and node.get_subscriptions_info_by_topic("/joint_states"):
        break
client = node.create_client(ListParameters, "/robot_state_publisher/list_parameters")
client.wait_for_service(timeout_sec=10)
future = client.call_async(ListParameters.Request())
rclpy.spin_until_future_complete(node, future, timeout_sec=10)
print(json.dumps({
    "nodes": sorted(n for n, _ in node.get_node_names_and_namespaces() if not n.startswith("_")),
    "description_publishers": [qos(i) for i in node.get_publishers_info_by_topic("/robot_description")],
    "description_readers": [qos(i) for i in node.get_subscriptions_info_by_topic("/robot_description")],
    "joint_states_readers": [qos(i) for i in node.get_subscriptions_info_by_topic("/joint_states")],
    "parameter_events_readers": sorted({qos(i)[0] for i in node.get_subscriptions_info_by_topic("/parameter_events")}),
    "parameters": sorted(future.result().result.names) if future.result() else None,
}))
"""


def test_the_stand_ins_show_the_topics_qos_and_parameters_of_their_sources(real_rclpy):
    python = shlex.quote(real_rclpy)
    script = "\n".join([
        "T=$(mktemp -d)",
        f"{python} state_publisher.py {shlex.quote(URDF)} > $T/rsp 2>&1 & a=$!",
        f"{python} rviz2 -d bras.rviz > $T/rviz 2>&1 & b=$!",
        f"{python} -c {shlex.quote(CHECKER)}",
        "kill $a $b; wait; rm -rf $T",
    ])
    done = subprocess.run(shell_in_loopback_namespace(script), cwd=DATA, env=graph_env(new_domain()),
                          capture_output=True, text=True, timeout=120)
    seen = json.loads(done.stdout.strip().splitlines()[-1])
    # rsp: node robot_state_publisher (line 77); rviz2: node rviz (visualizer_app.cpp:150)
    assert seen["nodes"] == ["robot_state_publisher", "rviz"]
    # rclcpp::QoS(1).transient_local(), reliable (lines 132-135)
    assert seen["description_publishers"] == [["/robot_state_publisher", "reliable", "transient_local"]]
    # RobotModel's topic: KeepLast(1) transient_local (robot_model_display.cpp:138), reliable
    assert seen["description_readers"] == [["/rviz", "reliable", "transient_local"]]
    # SensorDataQoS: best effort, volatile (lines 143-147)
    assert seen["joint_states_readers"] == [["/robot_state_publisher", "best_effort", "volatile"]]
    assert "/robot_state_publisher" in seen["parameter_events_readers"]  # on_parameter_event (156-158)
    parameters = set(seen["parameters"])
    assert {"robot_description", "publish_frequency", "frame_prefix", "ignore_timestamp", "use_sim_time"} <= parameters
    # QosOverridingOptions::with_default_policies() (lines 139-141): history, depth, reliability
    assert {"qos_overrides./joint_states.subscription.history", "qos_overrides./joint_states.subscription.depth",
            "qos_overrides./joint_states.subscription.reliability"} <= parameters
