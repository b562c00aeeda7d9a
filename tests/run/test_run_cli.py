"""bras-kit run on the command line: the tutorial's node and the scaffolded ones, -o, --gif."""

from __future__ import annotations

import importlib.util
import math

import numpy as np
import pytest
from paths import TESTS

from bras_kit.motion.states_io import read_states
from bras_kit.run import run_node
from bras_kit.run.findings import run_findings
from bras_kit.run.node import robot_of
from bras_kit.scaffold.package import scaffold_package

TUTORIAL = TESTS / "data" / "tutorial_package"
ORANGE_HUE = 28.2  # the forearm's material (0.95 0.5 0.1)
GREY = 0.08  # saturation under which a pixel is the grey base


def test_run_writes_the_joint_states_as_csv_that_read_back(run_cli, tmp_path):
    out = tmp_path / "states.csv"
    code, _, err = run_cli("run", str(TUTORIAL), "animation", "--duration", "1", "--quiet", "-o", str(out),
                           "--lang", "en")
    assert code == 0, err
    assert "/joint_states: 20 messages at 20 Hz" in err
    states = read_states(str(out))
    k = np.arange(1, 21)
    assert states.names == ["epaule", "coude"]
    assert states.times == pytest.approx(0.05 * k)
    assert states.positions[:, 1] == pytest.approx(1.2 * np.sin(0.7 * 0.05 * k), abs=1e-12)


def test_run_refuses_to_overwrite_without_force(run_cli, tmp_path):
    out = tmp_path / "states.csv"
    out.write_text("mine\n", encoding="utf-8")
    code, _, err = run_cli("run", str(TUTORIAL), "--duration", "1", "-o", str(out), "--lang", "en")
    assert code == 2 and "--force" in err and out.read_text(encoding="utf-8") == "mine\n"


def test_run_exits_1_with_the_finding_of_a_broken_node(run_cli, tmp_path):
    node = TESTS / "data" / "run" / "nodes" / "wrong_topic.py"
    code, out, err = run_cli("run", str(node), "--urdf", str(TUTORIAL / "urdf" / "bras.urdf"), "--duration", "1",
                             "--quiet", "--lang", "fr")
    assert code == 1
    assert "wrong_topic.py:11: BK644 erreur rien n'a été publié sur /joint_states" in out
    assert "Traceback" not in err


def test_unknown_executable_lists_the_ones_there_are(run_cli):
    code, _, err = run_cli("run", str(TUTORIAL), "animaton", "--lang", "en")
    assert code == 2
    assert "no executable 'animaton' in console_scripts" in err and "'animation'" in err


def _hue_mask(image: np.ndarray, hue: float) -> np.ndarray:
    rgb = image.astype(float) / 255.0
    high, low = rgb.max(axis=2), rgb.min(axis=2)
    span = np.where(high > low, high - low, 1.0)
    r, g, b = rgb[..., 0], rgb[..., 1], rgb[..., 2]
    h = np.where(high == r, ((g - b) / span) % 6, np.where(high == g, (b - r) / span + 2, (r - g) / span + 4)) * 60
    s = np.where(high > 0, (high - low) / np.where(high > 0, high, 1), 0)
    return (np.abs((h - hue + 180) % 360 - 180) < 12) & (s > 0.4) & (high > 0.25)


def _base_mask(image: np.ndarray) -> np.ndarray:
    rgb = image.astype(float) / 255.0
    high, low = rgb.max(axis=2), rgb.min(axis=2)
    return (high - low < GREY) & (high < 0.6) & (high > 0.25)


def test_gif_forearm_leans_the_way_the_sines_say(run_cli, tmp_path):
    from PIL import Image

    gif = tmp_path / "arm.gif"
    code, _, err = run_cli("run", str(TUTORIAL), "--duration", "6", "--quiet", "--gif", str(gif), "--lang", "en")
    assert code == 0, err
    image = Image.open(gif)
    assert image.n_frames == 120
    leans = {}
    for t in (2.0, 5.0):  # frame k shows tick k + 1, t = 0.05 (k + 1)
        image.seek(round(t / 0.05) - 1)
        frame = np.asarray(image.convert("RGB"))
        forearm, base = _hue_mask(frame, ORANGE_HUE), _base_mask(frame)
        assert forearm.sum() > 200 and base.sum() > 200
        leans[t] = np.nonzero(forearm)[1].mean() - np.nonzero(base)[1].mean()
    # the forearm points at epaule + coude from the vertical, towards +x (right) when positive
    assert 0.8 * math.sin(2.0) + 1.2 * math.sin(1.4) > 0 and leans[2.0] > 50
    assert 0.8 * math.sin(5.0) + 1.2 * math.sin(3.5) < 0 and leans[5.0] < -50


@pytest.mark.parametrize("lang", ["en", "fr"])
@pytest.mark.parametrize("wrist", [False, True])
def test_scaffolded_node_publishes_its_own_motion_with_no_finding(tmp_path, lang, wrist):
    package = tmp_path / "bras_description"
    scaffold_package(package, wrist=wrist, lang=lang)
    recording = run_node(str(package), "animation", duration=2.0)
    spec = importlib.util.spec_from_file_location("scaffolded_motion", package / "bras_description" / "motion.py")
    motion = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(motion)  # plain maths, no ROS: the scaffold's own oracle
    messages = recording.joint_state_messages()
    assert len(messages) == 40
    expected_names = ["epaule", "coude"] + (["poignet"] if wrist else [])
    for k, message in enumerate(messages, start=1):
        assert message.fields["name"] == expected_names
        assert message.fields["position"] == pytest.approx(motion.joint_positions(0.05 * k), abs=1e-12)
        assert message.fields["velocity"] == pytest.approx(motion.joint_velocities(0.05 * k), abs=1e-12)
    assert run_findings(recording, robot_of(str(package)), lang=lang) == []


def test_motion_node_samples_what_the_node_published(run_cli, tmp_path):
    out = tmp_path / "states.csv"
    code, _, err = run_cli("motion", "--node", f"{TUTORIAL}:animation", "--duration", "2", "-o", str(out),
                           "--lang", "en")
    assert code == 0, err
    states = read_states(str(out))
    # the motion starts with the node's first message, sent at t = 0.05 s on the node's clock
    t = states.times + 0.05
    assert states.positions[:40, 0] == pytest.approx(0.8 * np.sin(t[:40]), abs=1e-12)
    assert states.positions[:40, 1] == pytest.approx(1.2 * np.sin(0.7 * t[:40]), abs=1e-12)


def test_motion_node_checks_the_limits_with_the_motion_checks(run_cli):
    node = TESTS / "data" / "run" / "nodes" / "degrees.py"
    code, out, err = run_cli("motion", str(TUTORIAL / "urdf" / "bras.urdf"), "--node", str(node), "--duration", "1",
                             "--strict", "--lang", "en")
    assert code == 1
    assert "coude goes past its upper limit 2 by 88 rad" in err


def test_render_node_and_view_export_use_the_same_recording(run_cli, tmp_path):
    gif, page = tmp_path / "arm.gif", tmp_path / "arm.html"
    code, _, err = run_cli("render", "--node", str(TUTORIAL), "--duration", "1", "--gif", str(gif), "--lang", "en")
    assert code == 0, err
    assert "20 frames at 20 fps" in err
    code, _, err = run_cli("view", "--node", str(TUTORIAL), "--duration", "1", "--export", str(page), "--lang", "en")
    assert code == 0, err
    assert "21 frames of animation.py" in err  # what the node published, taken directly (no CSV)


def test_validate_run_adds_what_the_node_did_to_the_static_findings(run_cli, tmp_path):
    import shutil

    package = tmp_path / "bras_description"
    shutil.copytree(TUTORIAL, package)
    node = package / "bras_description" / "animation.py"
    node.write_text(node.read_text(encoding="utf-8").replace("'joint_states', 10", "'joint_state', 10"),
                    encoding="utf-8")
    code, out, _ = run_cli("validate", str(package), "--lang", "en")
    assert "BK644" not in out  # the static rules see a publisher: they cannot tell the topic is wrong
    code, out, _ = run_cli("validate", str(package), "--run", "--duration", "1", "--lang", "en")
    assert code == 1
    assert f"{node}:9: BK644 error nothing was published on /joint_states" in out


def test_grade_runs_nodes_only_when_asked(tmp_path):
    import shutil

    from bras_kit.grade import Options, load_rubric
    from bras_kit.grade.submissions import Submission
    from bras_kit.grade.worker import grade

    package = tmp_path / "alice" / "bras_description"
    shutil.copytree(TUTORIAL, package)
    node = package / "bras_description" / "animation.py"
    node.write_text(node.read_text(encoding="utf-8").replace("'joint_states', 10", "'joint_state', 10"),
                    encoding="utf-8")
    submission = Submission("alice", str(tmp_path / "alice"), "folder")
    rubric = load_rubric(None)
    quiet = grade(submission, rubric, Options(lang="en"))
    assert not any(f["code"].startswith("BK64") for f in quiet["findings"])
    ran = grade(submission, rubric, Options(lang="en", run_nodes=True))
    [finding] = [f for f in ran["findings"] if f["code"].startswith("BK64")]
    assert finding["code"] == "BK644" and finding["file"].endswith("bras_description/animation.py")


@pytest.mark.parametrize("lang", ["en", "fr"])
def test_scaffold_readme_run_commands_work_as_written(run_cli, tmp_path, monkeypatch, lang):
    import shlex

    scaffold_package(tmp_path / "bras_description", lang=lang)
    readme = (tmp_path / "bras_description" / "README.md").read_text(encoding="utf-8")
    commands = [line.split("#")[0].strip() for line in readme.splitlines() if line.startswith("bras-kit run ")]
    assert len(commands) == 2
    monkeypatch.chdir(tmp_path)  # where bras-kit new made the package, as the README assumes
    for command in commands:
        code, _, err = run_cli(*shlex.split(command)[1:], "--duration", "1", "--quiet")
        assert code == 0, (command, err)
    assert (tmp_path / "states.csv").is_file() and (tmp_path / "arm.gif").is_file()


def test_run_records_a_ros2_bag_that_foxglove_reads(run_cli, tmp_path):
    from mcap.reader import make_reader
    from mcap_ros2.decoder import DecoderFactory

    code, _, err = run_cli("run", str(TUTORIAL), "--duration", "1", "--quiet", "-o", str(tmp_path / "node.mcap"),
                           "--lang", "en")
    assert code == 0, err
    with open(tmp_path / "node" / "node.mcap", "rb") as handle:
        reader = make_reader(handle, decoder_factories=[DecoderFactory()])
        states = [decoded for _, channel, _, decoded in reader.iter_decoded_messages()
                  if channel.topic == "/joint_states"]
    assert len(states) == 20
    for k, state in enumerate(states, start=1):
        assert list(state.name) == ["epaule", "coude"]
        assert list(state.position) == pytest.approx([0.8 * math.sin(0.05 * k), 1.2 * math.sin(0.035 * k)], abs=1e-12)
