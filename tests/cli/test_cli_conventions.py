"""One rule per concept across commands: joint values, template parameters, --lang, '-' for
standard streams, files a command writes that another reads back."""

from __future__ import annotations

import json
import math
import subprocess
import sys

import numpy as np
import pytest

from bras_kit.model.expr import parse_joint_value


@pytest.mark.parametrize("text,radians", [
    ("0.5", 0.5), ("1,5", 1.5), ("-0,25", -0.25), ("pi/2", math.pi / 2), ("-0.5*pi", -math.pi / 2),
    ("90deg", math.pi / 2), ("-45 deg", -math.pi / 4), ("180°", math.pi), ("1e-3", 0.001),
])
def test_joint_values_accept_what_learners_type(text, radians):
    assert parse_joint_value(text) == pytest.approx(radians, abs=1e-15)


@pytest.mark.parametrize("text,words", [
    ("sin(t)", "depends on the time t"), ("nan", "not a finite number"), ("abc", "unknown name"),
    ("__import__('os')", "not allowed"),
])
def test_joint_values_refuse_what_is_not_one_number(text, words):
    from bras_kit.core.errors import BrasKitError

    with pytest.raises(BrasKitError, match=words):
        parse_joint_value(text)


def test_set_takes_degrees_and_decimal_comma_in_fk(run_cli):
    code, out, err = run_cli("fk", "--set", "epaule=90deg", "--set", "coude=0,5", "--format", "json")
    assert code == 0, err
    config = json.loads(out)["config"]
    assert config == {"epaule": pytest.approx(math.pi / 2), "coude": pytest.approx(0.5)}


def test_a_template_parameter_given_as_joint_points_to_param(run_cli, tmp_path):
    code, _, err = run_cli("render", "--set", "bras_length=0.8", "-o", str(tmp_path / "x.png"))
    assert code == 2
    assert "use --param bras_length=VALUE" in err
    assert not (tmp_path / "x.png").exists()


def test_the_wrist_joint_without_wrist_points_to_the_flag(run_cli):
    code, _, err = run_cli("fk", "--set", "poignet=0.3")
    assert code == 2
    assert "add --wrist" in err
    code, out, err = run_cli("fk", "--wrist", "--set", "poignet=0.3")
    assert code == 0, err


def test_a_value_that_reads_as_degrees_says_so(run_cli):
    code, _, err = run_cli("tree", "--set", "coude=90")
    assert code == 0
    assert "coude=90deg" in err
    code, _, err = run_cli("tree", "--set", "coude=2.5")  # past the limit, but not degrees
    assert "deg" not in err and "coude=2.5 is above its upper limit 2 by 0.5" in err


def test_validate_set_and_pose_are_one_option_and_keep_decimal_commas(run_cli):
    code, out, _ = run_cli("validate", "--set", "coude=1,5,epaule=0,2", "--format", "json")
    assert code == 0, out
    code, out, _ = run_cli("validate", "--pose", "coude=90", "--format", "json")
    finding = next(f for f in json.loads(out)["files"][0]["findings"] if f["code"] == "BK303")
    assert "90deg" in finding["hint"]


def test_formula_with_a_decimal_comma_is_explained(run_cli):
    code, _, err = run_cli("motion", "--motion", "coude=1,2*sin(t)")
    assert code == 2
    assert "decimal point" in err and "1.2" in err
    assert "tuples" not in err


@pytest.mark.parametrize("suffix", [".csv", ".json"])
def test_motion_output_reads_back_as_a_motion(run_cli, tmp_path, suffix):
    written = tmp_path / f"states{suffix}"
    code, _, err = run_cli("motion", "--duration", "2", "--rate", "10", "-o", str(written))
    assert code == 0, err
    again = tmp_path / f"again{suffix}"
    code, _, err = run_cli("motion", "--motion", str(written), "--duration", "2", "--rate", "10", "-o", str(again))
    assert code == 0, err
    from bras_kit.motion import read_states

    first, second = read_states(str(written)), read_states(str(again))
    assert first.names == second.names == ["epaule", "coude"]
    # the tutorial's formulas, by hand: epaule = 0.8 sin t, coude = 1.2 sin 0.7t
    t = second.times
    assert np.allclose(second.positions[:, 0], 0.8 * np.sin(t), atol=1e-9)
    assert np.allclose(second.positions[:, 1], 1.2 * np.sin(0.7 * t), atol=1e-9)


def test_a_recorded_joint_states_file_with_a_french_time_column(run_cli, tmp_path):
    recorded = tmp_path / "enregistrement.csv"
    recorded.write_text("temps,name,position,velocity\n"
                        "100.0,epaule,0.0,0.0\n100.0,coude,0.0,0.0\n"
                        "102.0,epaule,1.0,0.0\n102.0,coude,-1.0,0.0\n")
    out_file = tmp_path / "out.json"
    code, _, err = run_cli("motion", "--motion", str(recorded), "--duration", "2", "--rate", "2",
                           "-o", str(out_file))
    assert code == 0, err
    messages = json.loads(out_file.read_text())
    assert [m["time"] for m in messages] == [0.0, 0.5, 1.0, 1.5, 2.0]  # shifted to start at 0
    assert messages[2]["position"] == pytest.approx([0.5, -0.5])  # linear between the samples


def _bras_kit(*args: str, stdin: bytes | None = None) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "bras_kit", *args], input=stdin, capture_output=True, timeout=120)


def test_dash_reads_standard_input_and_writes_standard_output():
    urdf = _bras_kit("urdf", "--wrist")
    assert urdf.returncode == 0
    checked = _bras_kit("validate", "-", "--format", "json", stdin=urdf.stdout)
    assert checked.returncode == 0, checked.stderr
    assert json.loads(checked.stdout)["files"][0]["path"] == "-"
    tree = _bras_kit("tree", "-", stdin=urdf.stdout)
    assert b"poignet" in tree.stdout
    png = _bras_kit("render", "-", "-o", "-", "--size", "64x48", stdin=urdf.stdout)
    assert png.returncode == 0, png.stderr
    from io import BytesIO

    from PIL import Image

    assert Image.open(BytesIO(png.stdout)).size == (64, 48)


def test_lang_goes_before_or_after_the_command(run_cli):
    for argv in (("--lang", "fr", "explain", "BK301"), ("explain", "BK301", "--lang", "fr"),
                 ("explain", "--lang=fr", "BK301")):
        code, out, _ = run_cli(*argv)
        assert code == 0 and "articulation" in out, argv


def test_language_from_the_environment(monkeypatch, run_cli):
    monkeypatch.setenv("BRAS_KIT_LANG", "fr")
    code, out, _ = run_cli("explain", "BK301")
    assert "articulation" in out
    monkeypatch.setenv("BRAS_KIT_LANG", "en")
    monkeypatch.setenv("LANG", "fr_FR.UTF-8")
    code, out, _ = run_cli("explain", "BK301")
    assert "articulation" not in out  # BRAS_KIT_LANG wins over the locale
    monkeypatch.setenv("BRAS_KIT_LANG", "de")
    code, _, err = run_cli("explain", "BK301")
    assert code == 2 and "unknown language 'de'" in err


def test_an_unknown_option_prints_the_commands_own_usage(run_cli):
    code, _, err = run_cli("render", "--bogus")
    assert code == 2
    assert err.startswith("usage: bras-kit render ")
    assert "unrecognized arguments: --bogus" in err


def test_gif_name_and_fps_errors_name_their_option(run_cli, tmp_path):
    code, _, err = run_cli("render", "--gif", str(tmp_path / "a.png"))
    assert code == 2 and "--gif" in err and ".gif" in err
    assert not (tmp_path / "a.png").exists()
    code, _, err = run_cli("render", "--gif", str(tmp_path / "a.gif"), "--fps", "0")
    assert code == 2 and "between 1 and 120" in err


def test_reach_says_why_it_exits_1_when_the_target_is_reached(run_cli):
    code, out, err = run_cli("reach", "0.3", "0", "0.6", "--from", "coude=5")
    assert code == 1
    assert out.splitlines()[1].startswith("reached")
    assert "exit code 1: the move there leaves the joint limits" in err


def test_verbose_names_the_package_folder_taken_without_a_manifest(run_cli, tmp_path):
    (tmp_path / "pkgs" / "mesbras" / "urdf").mkdir(parents=True)
    (tmp_path / "pkgs" / "mesbras" / "urdf" / "a.xacro").write_text(
        '<robot name="a" xmlns:xacro="http://www.ros.org/wiki/xacro"><link name="base"/></robot>')
    top = tmp_path / "top.urdf.xacro"
    top.write_text('<robot name="t" xmlns:xacro="http://www.ros.org/wiki/xacro">'
                   '<xacro:include filename="$(find mesbras)/urdf/a.xacro"/></robot>')
    for command in ("xacro", "validate"):
        code, _, err = run_cli(command, str(top), "--package-path", str(tmp_path / "pkgs"), "--verbose")
        assert code == 0, err
        assert f"package 'mesbras': {tmp_path / 'pkgs' / 'mesbras'} (no package.xml" in err
