"""bras-kit doctor --ros against real ROS 2 nodes: the real rclpy of Jazzy (its PyPI wheels), each
scenario in a loopback-only network namespace of its own (tests/realros.py), the nodes being
small real-rclpy stand-ins (tests/data/live/): robot_state_publisher 3.3's QoS, the slider
window, the tutorial's animation node and its broken variants.

The oracle of each scenario is the graph itself, set up broken in one known way: the finding
must name that breakage (code, the node or joint, in English and in French) and nothing else
may be an error; the healthy graph gives exit 0. Both doctors (JSON in English, text in French)
word the same look: the second reads what the first saved (``--save``, ``--from``).
"""

from __future__ import annotations

import concurrent.futures
import json
import subprocess
import sys

import pytest
from live_graphs import (  # noqa: F401
    ANIMATION,
    DATA,
    STATE_PUBLISHER,
    URDF,
    WATCH,
    _codes,
    _finding,
    _json,
    _run,
    _script,
)
from realros import graph_env, new_domain

pytestmark = pytest.mark.slow





SCENARIOS: dict[str, dict] = {}  # name -> how to run it (nodes, doctors), filled by @scenario
PARALLEL = 3  # scenarios at once: each mostly waits for discovery, a few rclpy starts share 2 cores


def scenario(name: str, nodes: list[list[str]], doctors: list[list[str]] | None = None, doctor_env: str = ""):
    """Declare the graph a test looks at; the module's scenarios selected for the session run
    concurrently (each in its own namespace and domain), each test reads its own."""
    SCENARIOS[name] = {"nodes": nodes, "doctors": doctors or [["--format", "json"], ["--lang", "fr"]],
                       "doctor_env": doctor_env}

    def mark(test):
        test.scenario = name
        return test

    return mark




@pytest.fixture(scope="module")
def graphs(request, real_rclpy):
    """name -> future (exit code, output) of each doctor, for the scenarios of the selected tests."""
    wanted = {getattr(item.function, "scenario", None) for item in request.session.items
              if item.module is request.module} - {None}
    # real_rclpy, the fixture: the venv is made once, before the threads want it
    with concurrent.futures.ThreadPoolExecutor(PARALLEL) as pool:
        yield {name: pool.submit(_run, **SCENARIOS[name]) for name in sorted(wanted)}


def run_scenario(graphs, name: str) -> list[tuple[int, str]]:
    """Each doctor's exit code and output; the nodes' last lines go to the test's captured output
    (pytest shows them when the test fails)."""
    out, nodes = graphs[name].result()
    print(nodes)
    return out








SLIDER = ["slider_window.py", URDF]
RVIZ = ["rviz_reader.py"]
JSON_ONLY = [["--format", "json"]]
THEIRS = new_domain()  # the domain of the other terminal, in the scenario "other-domain"


@scenario("tutorial", [STATE_PUBLISHER, ANIMATION, RVIZ])
def test_the_tutorial_graph_is_healthy_exit_0_no_error_in_both_languages(graphs):
    (code, out), (code_fr, out_fr) = run_scenario(graphs, "tutorial")
    document = _json(out)
    assert code == 0 and code_fr == 0, out + out_fr
    assert _codes(document, "error") == [] and _codes(document, "warning") == []
    assert set(document["nodes"]) == {"/robot_state_publisher", "/animation_bras", "/rviz2"}
    assert 17.0 <= document["joint_states_rate"] <= 22.0  # the tutorial's 20 Hz, measured
    assert "rien n'empêche RViz" in out_fr


@scenario("slider-left-open", [STATE_PUBLISHER, ANIMATION, SLIDER])
def test_the_slider_window_left_open_beside_the_node_is_named_with_the_tutorial_s_advice(graphs):
    (code, out), (_, out_fr) = run_scenario(graphs, "slider-left-open")
    document = _json(out)
    found = _finding(document, "BK811")
    assert found["severity"] == "warning" and code == 0  # the arm flickers, it is not still
    assert "/joint_state_publisher" in found["message"] and "/animation_bras" in found["message"]
    assert "close the slider window" in found["hint"]
    assert "BK811" in out_fr and "fermez la fenêtre à curseurs" in out_fr


@scenario("wrong-names", [STATE_PUBLISHER, ANIMATION + ["--names", "epaule,coudee"]])
def test_joint_names_that_are_not_the_urdf_s_are_named_with_the_nearest_one(graphs):
    (code, out), (code_fr, out_fr) = run_scenario(graphs, "wrong-names")
    document = _json(out)
    assert code == 1 and code_fr == 1
    unknown = _finding(document, "BK816")
    assert "'coudee'" in unknown["message"] and "'coude'" in unknown["message"]
    missing = _finding(document, "BK817")
    assert "'coude'" in missing["message"] and "'avant_bras'" in missing["message"]
    assert "BK816" in out_fr and "vouliez-vous dire 'coude'" in out_fr


@scenario("zero-stamps", [STATE_PUBLISHER, ANIMATION + ["--zero-stamps"]])
def test_zero_stamps_are_an_error_because_robot_state_publisher_publishes_nothing(graphs):
    (code, out), (_, out_fr) = run_scenario(graphs, "zero-stamps")
    document = _json(out)
    assert code == 1
    assert _codes(document, "error") == ["BK814"]
    assert "header.stamp = 0" in _finding(document, "BK814")["message"]
    assert "BK814" in out_fr and "horodat" in out_fr


@scenario("5-hz", [STATE_PUBLISHER, ANIMATION + ["--period", "0.2"]])
def test_a_5_hz_node_is_measured_and_compared_with_the_tutorial_s_20_hz(graphs):
    (code, out), (_, out_fr) = run_scenario(graphs, "5-hz")
    document = _json(out)
    assert code == 0 and _codes(document) == ["BK813"]
    assert 4.0 <= document["joint_states_rate"] <= 5.6
    assert "20 Hz" in _finding(document, "BK813")["message"]
    assert "BK813" in out_fr and "20 Hz" in out_fr


@scenario("past-limits", [STATE_PUBLISHER, ANIMATION + ["--scale", "3"]])
def test_positions_past_the_limits_are_named_per_joint(graphs):
    (code, out), (_, out_fr) = run_scenario(graphs, "past-limits")
    document = _json(out)
    messages = [f["message"] for f in document["findings"] if f["code"] == "BK818"]
    assert code == 0 and messages  # drawn anyway: a warning, the tutorial's "articulations dépassent"
    assert any("'epaule'" in m and "1.57" in m for m in messages)
    assert "BK818" in out_fr and "butée" in out_fr


@scenario("volatile-description", [STATE_PUBLISHER + ["--volatile"], ANIMATION, RVIZ])
def test_a_volatile_description_is_named_and_its_pair_with_the_transient_local_reader_too(graphs):
    (code, out), (_, out_fr) = run_scenario(graphs, "volatile-description")
    document = _json(out)
    assert code == 1
    assert "/robot_state_publisher" in _finding(document, "BK802")["message"]
    pair = _finding(document, "BK820")["message"]
    assert "/robot_state_publisher" in pair and "/rviz2" in pair and "volatile" in pair
    assert "BK802" in out_fr and "BK820" in out_fr


@scenario("path-as-description", [STATE_PUBLISHER + [
    "--text", "/home/eleve/ros2_ws/install/bras_description/share/bras_description/urdf/bras.urdf"], ANIMATION])
def test_a_file_path_given_as_the_description_is_named(graphs):
    (code, out), (_, out_fr) = run_scenario(graphs, "path-as-description")
    document = _json(out)
    assert code == 1 and "BK804" in _codes(document, "error")
    assert "file name" in _finding(document, "BK804")["message"]
    assert "open(urdf_path).read()" in _finding(document, "BK804")["hint"]
    assert "BK804" in out_fr and "nom de fichier" in out_fr


@scenario("coude-short", [["state_publisher.py", str(DATA / "bras_coude_court.urdf")], ANIMATION], JSON_ONLY)
def test_the_urdf_received_is_checked_by_the_validator_s_rules(graphs):
    (code, out), = run_scenario(graphs, "coude-short")
    document = _json(out)
    found = _finding(document, "BK301")
    assert found["place"] == "/robot_description" and found["line"] == 43 and found["name"] == "coude"
    assert code == 0  # a warning: the arm shows, misplaced


@scenario("sim-time-no-clock", [STATE_PUBLISHER, ANIMATION + ["--use-sim-time"]])
def test_use_sim_time_without_clock_is_named_and_the_silent_publisher_explained(graphs):
    (code, out), (_, out_fr) = run_scenario(graphs, "sim-time-no-clock")
    document = _json(out)
    assert code == 1
    assert _finding(document, "BK830")["place"] == "/animation_bras"
    # its timer runs on the ROS clock, which stays at zero: it never publishes (the real rclpy says so)
    assert "simulated time" in _finding(document, "BK812")["message"]
    assert "BK830" in out_fr and "/clock" in out_fr


@scenario("hand-made-messages", [STATE_PUBLISHER, ANIMATION + ["--stamp-offset", "-60", "--positions", "1"]])
def test_stamps_a_minute_behind_and_fewer_positions_than_names_are_both_named(graphs):
    (code, out), (_, out_fr) = run_scenario(graphs, "hand-made-messages")
    document = _json(out)
    assert code == 1  # robot_state_publisher ignores every message: the arm stays still
    far = _finding(document, "BK815")
    assert far["severity"] == "warning" and "before this computer's clock" in far["message"]
    assert 58 <= float(far["message"].split(" s before")[0].rsplit(" ", 1)[1]) <= 62
    lengths = _finding(document, "BK819")
    assert "2 names but 1 position:" in lengths["message"]
    assert "BK815" in out_fr and "BK819" in out_fr and "1 position :" in out_fr


@scenario("description-never-published", [STATE_PUBLISHER + ["--silent"], ANIMATION], JSON_ONLY)
def test_a_description_publisher_that_never_publishes_is_named(graphs):
    (code, out), = run_scenario(graphs, "description-never-published")
    document = _json(out)
    assert code == 1 and _codes(document, "error") == ["BK803"]
    assert "/robot_state_publisher" in _finding(document, "BK803")["message"]


@scenario("sim-time-with-clock", [STATE_PUBLISHER + ["--use-sim-time"], ["clock.py"], ANIMATION], JSON_ONLY)
def test_use_sim_time_with_a_clock_is_not_a_finding(graphs):
    (code, out), = run_scenario(graphs, "sim-time-with-clock")
    document = _json(out)
    assert "BK830" not in _codes(document) and "/horloge" in document["publishers"]["/clock"]


@scenario("no-joint-states", [STATE_PUBLISHER, RVIZ])
def test_nothing_publishing_joint_states_is_an_error_naming_the_link_rviz_cannot_place(graphs):
    (code, out), (_, out_fr) = run_scenario(graphs, "no-joint-states")
    document = _json(out)
    assert code == 1 and _codes(document, "error") == ["BK810"]
    assert 'No transform from [avant_bras] to [base]' in _finding(document, "BK810")["message"]
    assert "BK810" in out_fr


@scenario("no-description", [ANIMATION, RVIZ], JSON_ONLY)
def test_nothing_publishing_the_description_is_an_error(graphs):
    (code, out), = run_scenario(graphs, "no-description")
    document = _json(out)
    assert code == 1 and "BK801" in _codes(document, "error")
    assert "/rviz2" in _finding(document, "BK801")["message"]


@scenario("other-domain", [[f"ROS_DOMAIN_ID={THEIRS}", *STATE_PUBLISHER], [f"ROS_DOMAIN_ID={THEIRS}", *ANIMATION]])
def test_nodes_on_another_domain_are_found_and_the_line_to_type_given(graphs):
    (code, out), (code_fr, out_fr) = run_scenario(graphs, "other-domain")
    document = _json(out)
    assert code == 1 and code_fr == 1
    found = _finding(document, "BK800")
    assert f"export ROS_DOMAIN_ID={THEIRS}" in found["hint"] and "/animation_bras" in found["message"]
    assert document["elsewhere"][0]["domain"] == THEIRS
    assert f"tapez 'export ROS_DOMAIN_ID={THEIRS}'" in out_fr and "domaine" in out_fr


@scenario("range-off", [ANIMATION], doctor_env="ROS_AUTOMATIC_DISCOVERY_RANGE=OFF")
def test_a_terminal_with_discovery_off_is_told_the_range_that_finds_the_nodes(graphs):
    (code, out), (_, out_fr) = run_scenario(graphs, "range-off")
    document = _json(out)
    assert code == 1 and _codes(document) == ["BK800"]
    found = _finding(document, "BK800")
    assert "export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST" in found["hint"] and "/animation_bras" in found["message"]
    assert "tapez 'export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST'" in out_fr


@scenario("empty", [], JSON_ONLY)
def test_an_empty_graph_says_so_and_exits_1(graphs):
    (code, out), = run_scenario(graphs, "empty")
    document = _json(out)
    assert code == 1 and _codes(document) == ["BK800"] and document["elsewhere"] == []


@scenario("late-node", [ANIMATION + ["--late", "6"]], JSON_ONLY)
def test_a_node_that_shows_after_the_first_seconds_is_waited_for_not_called_absent(graphs):
    # its process is on the domain from the start (a participant, ports bound), the node itself
    # shows 6 s later: what a busy computer's discovery does to a node that was there all along
    (code, out), = run_scenario(graphs, "late-node")
    document = _json(out)
    assert "BK800" not in _codes(document) and document["nodes"] == ["/animation_bras"]
    # it waited past the 3.5 s floor for the node, then watched it publish (20 Hz: 30 messages are 1.5 s);
    # the node shows 6 s after its process starts, and the doctor starts 1-3 s after that process
    assert document["seconds"] > 4.5 and document["joint_states_received"] >= 30
    assert "BK801" in _codes(document, "error")  # what is really missing: no robot_state_publisher


@scenario("hidden-only", [ANIMATION + ["--late", "60"]], JSON_ONLY)
def test_a_domain_held_by_a_hidden_node_only_is_empty_after_the_longer_wait(graphs):
    # the ros2 daemon is such a node: the wait for a first node has an end
    (code, out), = run_scenario(graphs, "hidden-only")
    document = _json(out)
    assert code == 1 and _codes(document) == ["BK800"]
    assert 9.5 <= document["seconds"] < 15


def test_without_rclpy_one_line_says_how_to_get_it_and_exit_3(tmp_path):
    env = {k: v for k, v in graph_env(new_domain()).items() if k != "BRAS_KIT_ROS_PYTHON"}
    env["XDG_CACHE_HOME"] = str(tmp_path)  # no cached venv there
    done = subprocess.run([sys.executable, "-m", "bras_kit", "doctor", "--ros"], env=env, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 3, done.stderr
    assert "rclpy" in done.stderr and "ros-jazzy-rclpy[fastrtps]==7.1.6" in done.stderr and "Traceback" not in done.stderr
    assert done.stdout == ""


def test_a_file_that_is_not_a_saved_look_is_refused_in_one_line(tmp_path):
    not_a_look = tmp_path / "look.json"
    not_a_look.write_text('{"kind": "census", "nodes": []}', encoding="utf-8")
    done = subprocess.run([sys.executable, "-m", "bras_kit", "doctor", "--ros", "--from", str(not_a_look)],
                          capture_output=True, text=True, timeout=60)
    assert done.returncode == 2 and "is not a look saved by 'bras-kit doctor --ros --save'" in done.stderr
    assert "Traceback" not in done.stderr


def test_a_hostile_saved_look_is_read_field_by_field_without_a_traceback():
    """Wrong types, NaN, 1e400, names that are numbers: what does not fit is dropped, the rest judged."""
    done = subprocess.run([sys.executable, "-m", "bras_kit", "doctor", "--ros", "--format", "json", "--from",
                           str(DATA / "looks" / "hostile.json")], capture_output=True, text=True, timeout=60)
    document = json.loads(done.stdout)
    assert done.returncode == 1 and "Traceback" not in done.stderr
    assert document["nodes"] == ["/animation_bras"]
    assert {"BK802", "BK814", "BK112"} <= set(_codes(document))  # the description's own defects too



def test_a_flooding_publisher_is_judged_on_a_bounded_look(real_rclpy):
    """A stranger's publisher: 3,000 more names of 1,000 characters and one position fewer, 20
    times a second (60 MB a second on the bus). What the probe keeps is bounded (live/_probe.py's
    MAX_*), so the look bras-kit reads stays small, and the size check robot_state_publisher makes
    (robot_state_publisher.cpp:303, tag 3.3.3) answers on what is kept as on the message."""
    from live_graphs import run_with_look

    outs, _logs, look = run_with_look([STATE_PUBLISHER, ANIMATION + ["--flood", "3000", "--positions", "3001"]],
                                      JSON_ONLY)
    print(outs, _logs)
    (code, out), = outs
    assert look is not None and look["joint_states"], "the probe saw no joint state"
    for state in look["joint_states"]:
        assert len(state["name"]) == 1000 and len(state["position"]) == 999
        assert max(len(name) for name in state["name"]) <= 256
    assert len(json.dumps(look)) < 40 << 20
    assert code == 1 and "BK819" in _codes(_json(out))  # names and positions differ: rsp ignores each message
