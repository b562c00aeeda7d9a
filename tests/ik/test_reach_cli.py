"""bras-kit reach and bras-kit workspace: outputs, negative coordinates, exit codes, files."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from bras_kit.model.authoring import arm_urdf

ELBOW_X, ELBOW_Z = repr(0.6 * math.sin(1.2)), repr(0.05 + 0.6 * math.cos(1.2))  # elbow point at epaule = 1.2


def reach_json(run_cli, *argv):
    code, out, err = run_cli("reach", *argv, "--format", "json")
    return code, (json.loads(out) if out.strip() else None), err


# ---------------------------------------------------------------- reach: outputs


def test_text_output_lists_joints_tip_and_move(run_cli):
    code, out, err = run_cli("reach", "0.5", "0", "0.65", "--elbow", "up")
    assert code == 0, err
    assert "reached    (analytic, elbow up)" in out
    assert "epaule       +0.000000 rad" in out
    assert "coude        +1.570796 rad (  +90.00 deg)" in out
    assert "tip        x=0.5000 y=0.0000 z=0.6500 m" in out
    # the other elbow: epaule = 2 atan2(0.5, 0.6) = 1.3895, coude = -pi/2, within the limits
    assert "elbow down epaule=+1.3895, coude=-1.5708 (within the limits)" in out
    # quintic move from the zero pose: 15/8 * (pi/2) / 1 rad/s = 2.945 s
    assert "move       2.945 s from zero pose (quintic)" in out
    assert "within the position and velocity limits" in out


def test_json_output_has_the_documented_fields(run_cli):
    code, data, _ = reach_json(run_cli, "0.5", "0", "0.65", "--elbow", "down")
    assert code == 0
    assert {"reachable", "joints", "tip", "target", "residual", "message"} <= set(data)
    assert data["reachable"] is True
    assert data["joints"]["epaule"] == pytest.approx(2 * math.atan2(0.5, 0.6), abs=1e-12)
    assert data["joints"]["coude"] == pytest.approx(-math.pi / 2, abs=1e-12)
    assert data["target"] == [0.5, 0.0, 0.65]
    np.testing.assert_allclose(data["tip"], [0.5, 0.0, 0.65], atol=1e-12)
    assert data["residual"] < 1e-12
    assert data["tip_link"] == "avant_bras" and data["tip_offset"] == [0.0, 0.0, 0.5]
    assert data["motion"]["duration"] == pytest.approx(15 / 8 * math.pi / 2)
    assert data["motion"]["peak_velocity"]["coude"] == pytest.approx(1.0)


def test_wrist_arm_uses_the_numeric_solver(run_cli):
    code, data, _ = reach_json(run_cli, "--wrist", "0.3", "0", "0.8")
    assert code == 0 and data["method"] == "numeric"
    assert set(data["joints"]) == {"epaule", "coude", "poignet"}
    assert data["residual"] < 1e-9 and data["tip_link"] == "main"


def test_orientation_target_with_rpy(run_cli):
    code, data, _ = reach_json(run_cli, "--wrist", "0.3", "0", "0.8", "--rpy", "0", "1", "0")
    assert code == 0
    assert sum(data["joints"].values()) == pytest.approx(1.0, abs=1e-9)
    assert data["rotation_residual"] < 1e-9


def test_link_and_tip_offset_choose_the_point(run_cli):
    # the elbow point (bras + 0.6 z) at (0.6 sin 1.2, 0, 0.05 + 0.6 cos 1.2): epaule = 1.2
    code, data, _ = reach_json(run_cli, ELBOW_X, "0", ELBOW_Z, "--link", "bras")
    assert code == 0 and data["tip_link"] == "bras" and data["tip_offset"] == [0.0, 0.0, 0.6]
    assert data["method"] == "numeric" and data["joints"]["epaule"] == pytest.approx(1.2, abs=1e-9)
    code, data, _ = reach_json(run_cli, "0.5", "0", "0.65", "--tip-offset", "0", "0", "0.5", "--elbow", "up")
    assert data["joints"]["coude"] == pytest.approx(math.pi / 2, abs=1e-12)


def test_start_pose_picks_the_nearer_elbow(run_cli):
    code, data, _ = reach_json(run_cli, "0.5", "0", "0.65", "--from", "epaule=1.3", "--from", "coude=-1.4")
    assert code == 0 and data["elbow"] == "down"
    assert data["motion"]["from"] == {"epaule": 1.3, "coude": -1.4}


# ---------------------------------------------------------------- negative numbers


@pytest.mark.parametrize("argv", [
    ("-0.5", "0", "0.65"),
    ("-.5", "-0", "0.65"),
    ("-5e-1", "0", "6.5e-1"),
    ("--elbow", "up", "-0.5", "0", "0.65"),
])
def test_negative_coordinates_parse_as_positionals(run_cli, argv):
    code, data, err = reach_json(run_cli, *argv)
    assert code == 0, err
    assert data["target"][0] == -0.5
    if "--elbow" in argv:
        assert data["joints"]["epaule"] == pytest.approx(0.0, abs=1e-12)
        assert data["joints"]["coude"] == pytest.approx(-math.pi / 2, abs=1e-12)


def test_double_dash_before_negative_coordinates(run_cli):
    code, out, err = run_cli("reach", "--format", "json", "--", "-0.5", "0", "0.65")
    assert code == 0, err
    assert json.loads(out)["target"] == [-0.5, 0.0, 0.65]


def test_negative_coordinates_after_a_file(run_cli, tmp_path):
    path = tmp_path / "bras.urdf"
    path.write_text(arm_urdf(), encoding="utf-8")
    code, data, err = reach_json(run_cli, str(path), "-0.5", "0", "0.65", "--tip-offset", "-0.0", "0", "0.5",
                                 "--elbow", "up")
    assert code == 0, err
    assert data["joints"]["coude"] == pytest.approx(-math.pi / 2, abs=1e-12)
    code, data, err = reach_json(run_cli, str(path), "-" + ELBOW_X, "0", ELBOW_Z, "--link", "bras")
    assert code == 0, data["message"]
    assert data["joints"]["epaule"] == pytest.approx(-1.2, abs=1e-9)


# ---------------------------------------------------------------- exit codes


def test_out_of_reach_exits_1_with_a_valid_answer(run_cli):
    code, data, _ = reach_json(run_cli, "0", "0", "1.2")
    assert code == 1
    assert data["reachable"] is False and "0.05 m too far" in data["message"]
    assert data["residual"] == pytest.approx(0.05, abs=1e-9)
    assert set(data["joints"]) == {"epaule", "coude"} and "motion" not in data
    code, out, _ = run_cli("reach", "0", "0", "1.2")
    assert code == 1 and "NOT reached" in out and "closest pose within the limits" in out


def test_target_past_a_limit_exits_1_naming_the_joint(run_cli):
    code, data, _ = reach_json(run_cli, "0.5", "0", "0.3", "--elbow", "up")
    assert code == 1 and data["reason"] == "limits"
    assert data["violations"][0]["joint"] == "coude"
    assert data["violations"][0]["excess"] == pytest.approx(math.acos((0.3125 - 0.61) / 0.6) - 2.0)


def test_singular_target_exits_1(run_cli):
    code, data, _ = reach_json(run_cli, "0", "0", "1.15")
    assert code == 1 and data["reachable"] is True and data["singular"] is True
    assert "fully stretched" in data["message"]


@pytest.mark.parametrize("value", ["nan", "inf", "-inf", "abc"])
def test_bad_coordinates_exit_2(run_cli, value):
    code, out, err = run_cli("reach", "0.5", "0", value)
    assert code == 2 and out == ""
    assert "argument Z" in err and "Traceback" not in err
    assert ("not a finite number" in err) or ("not a number" in err)


def test_unknown_link_exits_2(run_cli):
    code, out, err = run_cli("reach", "0.5", "0", "0.65", "--link", "pince")
    assert code == 2 and "unknown link 'pince'" in err and "base, bras, avant_bras" in err


@pytest.mark.parametrize("argv, message", [
    (("--from", "genou=0.1"), "unknown joint 'genou'"),
    (("--from", "coude=abc"), "not a number"),
    (("--duration", "0.5"), "too fast: coude would turn at"),
    (("--wrist", "--elbow", "up"), "applies to two-joint planar arms"),
    (("--tip-offset", "0", "nan", "0"), "not a finite number"),
])
def test_bad_options_exit_2(run_cli, argv, message):
    code, _, err = run_cli("reach", "0.5", "0", "0.65", *argv)
    assert code == 2 and message in err and "Traceback" not in err


def test_start_outside_the_limits_is_flagged(run_cli):
    code, out, err = run_cli("reach", "0.5", "0", "0.65", "--from", "coude=2.5", "--elbow", "up")
    assert code == 1
    assert "coude=2.5, outside its limits -2..2" in err
    assert "leaves the limits: coude would need 2.5000 rad, 0.5000 rad past its upper limit 2" in out


# ---------------------------------------------------------------- GIF


def test_gif_of_the_move_and_no_overwrite_without_force(run_cli, tmp_path):
    from PIL import Image

    path = tmp_path / "reach.gif"
    # a 0.1 rad move of the elbow over 0.5 s: 11 frames of motion + 10 held
    argv = ("reach", "0.5", "0", "0.65", "--elbow", "up", "--from", "coude=1.4707963267948966",
            "--duration", "0.5", "--gif", str(path))
    code, out, err = run_cli(*argv)
    assert code == 0, err
    with Image.open(path) as image:
        assert image.n_frames == 21
    first = path.read_bytes()
    code, _, err = run_cli(*argv)
    assert code == 2 and "already exists" in err and path.read_bytes() == first
    code, _, err = run_cli(*argv, "--force")
    assert code == 0


# ---------------------------------------------------------------- workspace


def test_workspace_writes_a_picture_and_reports_areas(run_cli, tmp_path):
    from PIL import Image

    path = tmp_path / "ws.png"
    code, out, err = run_cli("workspace", "-o", str(path), "--samples", "20000")
    assert code == 0, err
    assert "tip region in the x-z plane" in out and "farthest tip 1.100 m" in out
    with Image.open(path) as image:
        assert image.size == (700, 600)
    code, _, err = run_cli("workspace", "-o", str(path), "--samples", "20000")
    assert code == 2 and "already exists" in err
    assert run_cli("workspace", "-o", str(path), "--samples", "20000", "--force")[0] == 0


def test_workspace_of_the_wrist_arm_reaches_further(run_cli, tmp_path):
    code, out, _ = run_cli("workspace", "--wrist", "-o", str(tmp_path / "w.svg"), "--samples", "20000")
    assert code == 0 and "farthest tip 1.250 m" in out
    assert (tmp_path / "w.svg").read_text(encoding="utf-8").lstrip().startswith("<?xml")


@pytest.mark.parametrize("argv, message", [
    (("-o", "ws.txt"), "unknown picture format"),
    (("--samples", "0"), "out of range"),
    (("--link", "pince"), "unknown link 'pince'"),
])
def test_workspace_bad_input_exits_2(run_cli, tmp_path, monkeypatch, argv, message):
    monkeypatch.chdir(tmp_path)
    code, _, err = run_cli("workspace", *argv)
    assert code == 2 and message in err


def test_reach_gif_marks_the_target(run_cli, tmp_path):
    from PIL import Image

    gif = tmp_path / "reach.gif"
    code, _, err = run_cli("reach", "0.5", "0", "0.6", "--gif", str(gif))
    assert code == 0, err
    with Image.open(gif) as animation:
        for index in (0, animation.n_frames - 1):
            animation.seek(index)
            rgb = np.asarray(animation.convert("RGB")).astype(int)
            magenta = (rgb[..., 0] > 170) & (rgb[..., 1] < 70) & (rgb[..., 2] > 100)  # 0.85 0.1 0.55
            assert magenta.sum() > 30, index
