"""bras-kit validate and bras-kit explain: output, exit codes, JSON, languages, folders."""

from __future__ import annotations

import json

import pytest
from paths import TESTS

DATA = TESTS / "data" / "urdf"
GOOD, BROKEN = DATA / "good", DATA / "broken"

ELBOW_TOO_LOW = (
    f"{BROKEN / 'coude_trop_bas.urdf'}:31: BK301 warning <joint name=\"coude\"> joint 'coude' is at z=0.5, "
    "but the <box> of link 'bras' runs z 0..0.6: the child hangs 0.1 m short of the segment's end\n"
    "  hint: put the joint at the end of 'bras': <origin xyz=\"0 0 0.6\"/>\n"
)


@pytest.fixture(autouse=True)
def english_locale(monkeypatch):
    for var in ("LC_ALL", "LC_MESSAGES"):
        monkeypatch.delenv(var, raising=False)
    monkeypatch.setenv("LANG", "C.UTF-8")


def test_no_file_checks_the_tutorial_arm(run_cli):
    code, out, err = run_cli("validate")
    assert code == 0, err
    assert out == (
        "<bras-kit tutorial arm>:19: BK505 info <link name=\"bras\"> 2 moving links have no <inertial> "
        "('bras', 'avant_bras'): fine for RViz, needed for physics simulation\n"
        "  hint: add <inertial> with <mass> and <inertia> (try bras-kit urdf --inertials for the tutorial arm)\n"
        "\n"
        "1 file checked: 0 errors, 0 warnings, 1 info.\n"
    )


def test_built_in_arm_variants(run_cli):
    code, out, _ = run_cli("validate", "--wrist", "--inertials")
    assert code == 0
    assert out.endswith("1 file checked: no problems found.\n")
    # issue 52: the base is anchored to a massless world root, as `new --inertials` does, so KDL's
    # root-inertia note (BK506) is gone; the generated file holds nothing bras-kit itself flags
    assert "BK506" not in out
    code, out, _ = run_cli("validate", "--param", "bras_length=0.8", "--ignore", "BK505")
    assert (code, out) == (0, "1 file checked: no problems found.\n")


def test_the_tutorials_pitfall_is_a_warning_with_file_line_and_hint(run_cli):
    # BK301 is the tutorial's heuristic: a warning (exit 0), an error only under --strict
    code, out, err = run_cli("validate", str(BROKEN / "coude_trop_bas.urdf"), "--ignore", "BK505")
    assert code == 0
    assert out == ELBOW_TOO_LOW + "\n1 file checked: 0 errors, 1 warning.\n"
    assert err == ""
    assert run_cli("validate", "--strict", str(BROKEN / "coude_trop_bas.urdf"), "--ignore", "BK505")[0] == 1


def test_error_exits_1_with_file_line_and_hint(run_cli, tmp_path):
    path = tmp_path / "limits.urdf"
    path.write_text((GOOD / "bras.urdf").read_text(encoding="utf-8").replace(
        '<limit lower="-2.0" upper="2.0"', '<limit lower="2.0" upper="-2.0"', 1), encoding="utf-8")
    code, out, err = run_cli("validate", str(path), "--select", "BK202")
    assert code == 1
    assert f"{path}:" in out and " BK202 error " in out and "  hint: " in out
    assert out.endswith("1 file checked: 1 error, 0 warnings.\n")
    assert err == ""


def test_warnings_pass_unless_strict(run_cli):
    path = str(BROKEN / "avant_bras_decale.urdf")
    code, out, _ = run_cli("validate", path)
    assert code == 0
    assert out.endswith("1 file checked: 0 errors, 1 warning, 1 info.\n")
    assert run_cli("validate", "--strict", path)[0] == 1
    assert run_cli("validate", "--strict", "--ignore", "BK302", path)[0] == 0


def test_infos_never_fail_even_strict(run_cli):
    assert run_cli("validate", "--strict", str(GOOD / "bras.urdf"))[0] == 0


def test_unreadable_file_exits_2_and_still_reports_the_others(run_cli):
    code, out, _ = run_cli("validate", str(BROKEN / "mal_forme.urdf"), str(BROKEN / "coude_trop_bas.urdf"),
                           "--ignore", "BK505")
    assert code == 2
    assert out.startswith(
        f"{BROKEN / 'mal_forme.urdf'}:5: BK100 error not well-formed XML: the tag <cylinder> opened on line 5 is never closed: the reader met </geometry> on line 5 while <cylinder> was still open\n"
        "  hint: look at this line: a tag left open, a missing '/>' or a stray quote are the usual causes\n"
        + ELBOW_TOO_LOW)
    assert out.endswith("2 files checked (1 could not be read): 1 error, 1 warning.\n")


def test_missing_file_exits_2(run_cli, tmp_path):
    code, out, _ = run_cli("validate", str(tmp_path / "absent.urdf"))
    assert code == 2
    assert out.startswith(f"{tmp_path / 'absent.urdf'}: BK103 error no such file: {tmp_path / 'absent.urdf'}\n")


@pytest.mark.parametrize("argv, message", [
    (["--pose", "coude"], "'coude' is not NAME=VALUE"),
    (["--pose", "coude=beaucoup"], "the joint value is not a number"),
    (["--pose", "poignet=0.3"], "--pose names joint 'poignet', which this robot does not have"),
    (["--select", "BK9"], "no rule code starts with 'BK9'"),
    (["--duration", "-1", "--motion", "tutorial"], "--duration -1: must be a positive number of seconds"),
    (["--motion", "coude=sin("], "coude"),
    (["--wrist", str(GOOD / "bras.urdf")], "--wrist, --inertials and --param apply to the built-in arm only"),
])
def test_bad_usage_exits_2_with_a_message(run_cli, argv, message):
    code, out, err = run_cli("validate", *argv)
    assert code == 2
    assert out == ""
    assert err.startswith("bras-kit validate: error: ") and message in err
    assert "Traceback" not in err


def test_bad_option_value_exits_2(run_cli):
    code, _, err = run_cli("validate", "--format", "xml")
    assert code == 2
    assert "invalid choice: 'xml'" in err


def test_folder_without_robot_files_is_a_usage_error(run_cli, tmp_path):
    code, _, err = run_cli("validate", str(tmp_path))
    assert code == 2
    assert f"no .urdf or .xacro file found in {tmp_path}" in err


def test_several_files_and_a_folder(run_cli):
    code, out, _ = run_cli("validate", str(GOOD), str(BROKEN / "coude_trop_bas.urdf"))
    assert code == 0
    files = [line.split(":")[0] for line in out.splitlines() if line.startswith(str(DATA))]
    assert sorted(set(files)) == sorted({
        str(GOOD / "bras.urdf"), str(GOOD / "xacro" / "bras.urdf.xacro"), str(GOOD / "xacro" / "segments.xacro"),
        str(BROKEN / "coude_trop_bas.urdf")})
    assert out.endswith("4 files checked: 0 errors, 1 warning, 4 info.\n")


def test_json_output(run_cli):
    code, out, _ = run_cli("validate", "--format", "json", str(BROKEN / "coude_trop_bas.urdf"),
                           str(BROKEN / "avant_bras_decale.urdf"), str(BROKEN / "mal_forme.urdf"))
    assert code == 2
    document = json.loads(out)
    assert set(document) == {"files", "summary"}
    assert document["summary"] == {"files": 3, "unreadable": 1, "errors": 1, "warnings": 2, "infos": 2}
    assert [(f["path"], f["ok"]) for f in document["files"]] == [
        (str(BROKEN / "coude_trop_bas.urdf"), True),  # a warning only
        (str(BROKEN / "avant_bras_decale.urdf"), True),
        (str(BROKEN / "mal_forme.urdf"), False),
    ]
    for entry in document["files"]:
        assert set(entry) == {"path", "ok", "findings"}
        for finding in entry["findings"]:
            assert set(finding) == {"code", "severity", "message", "element", "name", "line", "hint"}
    elbow = [f for f in document["files"][0]["findings"] if f["code"] == "BK301"]
    assert elbow == [{
        "code": "BK301", "severity": "warning",
        "message": "joint 'coude' is at z=0.5, but the <box> of link 'bras' runs z 0..0.6: "
                   "the child hangs 0.1 m short of the segment's end",
        "element": "joint", "name": "coude", "line": 31,
        "hint": "put the joint at the end of 'bras': <origin xyz=\"0 0 0.6\"/>",
    }]
    assert document["files"][2]["findings"][0] == {
        "code": "BK100", "severity": "error", "message": "not well-formed XML: the tag <cylinder> opened on line 5 is never closed: the reader met </geometry> on line 5 while <cylinder> was still open",
        "element": "file", "name": None, "line": 5,
        "hint": "look at this line: a tag left open, a missing '/>' or a stray quote are the usual causes",
    }


def test_json_ok_follows_strict(run_cli):
    path = str(BROKEN / "avant_bras_decale.urdf")
    assert json.loads(run_cli("validate", "--format", "json", path)[1])["files"][0]["ok"] is True
    code, out, _ = run_cli("validate", "--format", "json", "--strict", path)
    assert code == 1
    assert json.loads(out)["files"][0]["ok"] is False


def test_french_output(run_cli):
    code, out, _ = run_cli("validate", "--lang", "fr", "--ignore", "BK505", str(BROKEN / "coude_trop_bas.urdf"))
    assert code == 0
    assert out == (
        f"{BROKEN / 'coude_trop_bas.urdf'}:31: BK301 avertissement <joint name=\"coude\"> l'articulation 'coude' est en "
        "z=0.5, mais le <box> du link 'bras' occupe z 0..0.6 : l'enfant est accroché 0.1 m avant le bout du segment\n"
        "  correctif : placez l'articulation au bout de 'bras' : <origin xyz=\"0 0 0.6\"/>\n"
        "\n"
        "1 fichier vérifié : 0 erreur, 1 avertissement.\n"
    )


def test_language_follows_the_locale(run_cli, monkeypatch):
    monkeypatch.setenv("LANG", "fr_FR.UTF-8")
    assert run_cli("validate", "--ignore", "BK505")[1] == "1 fichier vérifié : aucun problème.\n"
    monkeypatch.setenv("LC_ALL", "en_GB.UTF-8")  # LC_ALL wins over LANG
    assert run_cli("validate", "--ignore", "BK505")[1] == "1 file checked: no problems found.\n"
    assert run_cli("validate", "--ignore", "BK505", "--lang", "fr")[1] == "1 fichier vérifié : aucun problème.\n"


def test_pose_outside_limits_on_the_command_line(run_cli):
    code, out, _ = run_cli("validate", "--pose", "coude=2.5", "--pose", "epaule=0.3", "--select", "BK3")
    assert code == 1
    assert run_cli("validate", "--pose", "coude=2.5,epaule=0.3", "--select", "BK3")[1] == out
    assert out == (
        "<bras-kit tutorial arm>:53: BK303 error <joint name=\"coude\"> joint 'coude' = 2.5 rad is 0.5 rad "
        "above its upper limit 2\n"
        "  hint: stay within -2..2 rad, or widen the <limit> if the mechanism allows it\n"
        "\n1 file checked: 1 error, 0 warnings.\n"
    )


def test_motion_on_the_command_line(run_cli):
    code, out, _ = run_cli("validate", "--motion", "coude=2.4*sin(t)", "--duration", "2", "--select", "BK304")
    assert code == 1
    assert "BK304 error <joint name=\"coude\"> joint 'coude' goes past its upper limit 2 rad at t=1 s" in out
    assert run_cli("validate", "--motion", "tutorial", "--select", "BK3")[0] == 0


def test_xacro_file_with_arguments_and_source_lines(run_cli, tmp_path):
    xacro = tmp_path / "bras.urdf.xacro"
    text = (GOOD / "xacro" / "bras.urdf.xacro").read_text(encoding="utf-8")
    xacro.write_text(text.replace('<xacro:property name="bras_length" value="0.6"/>',
                                  '<xacro:arg name="coude_z" default="0.6"/>\n'
                                  '  <xacro:property name="bras_length" value="0.6"/>')
                     .replace('<origin xyz="0 0 ${bras_length}"/>', '<origin xyz="0 0 $(arg coude_z)"/>'),
                     encoding="utf-8")
    (tmp_path / "segments.xacro").write_text((GOOD / "xacro" / "segments.xacro").read_text(encoding="utf-8"))
    assert run_cli("validate", str(xacro), "--select", "BK3")[0] == 0
    code, out, _ = run_cli("validate", str(xacro), "--xacro-arg", "coude_z:=0.5", "--select", "BK3")
    assert code == 0
    # the line of <joint name="coude"> in the xacro source, not in the expanded text
    assert out.startswith(f"{xacro}:25: BK301 warning <joint name=\"coude\">")


def test_explain_prints_the_rule(run_cli):
    code, out, _ = run_cli("explain", "BK301")
    assert code == 0
    assert out.startswith("BK301 joint-not-at-segment-end (warning)\nA joint is not at the end of its parent segment.\n\n")
    assert "the tutorial's elbow coude is at z = 0.6" in out
    assert out.endswith("Family: the tutorial's pitfalls\nSkip it with: bras-kit validate --ignore BK301\n")


def test_explain_in_french_and_by_name(run_cli):
    code, out, _ = run_cli("explain", "visual-not-at-joint", "--lang", "fr")
    assert code == 0
    assert out.startswith("BK302 visual-not-at-joint (avertissement)\n"
                          "Le visuel d'un segment ne part pas de son articulation.\n")
    assert run_cli("explain", "bk302")[1].startswith("BK302 visual-not-at-joint (warning)\n")


def test_explain_unknown_code_exits_2(run_cli):
    code, out, err = run_cli("explain", "BK999")
    assert (code, out) == (2, "")
    assert err == ("bras-kit explain: error: unknown rule 'BK999'\n"
                   "  hint: run 'bras-kit explain' with no code to list every rule\n")
    code, _, err = run_cli("explain", "joint-not-at-segment-en")
    assert code == 2
    assert "did you mean BK301 (joint-not-at-segment-end)?" in err


def test_explain_without_code_lists_every_rule(run_cli):
    from bras_kit.validate import RULES

    code, out, _ = run_cli("explain")
    assert code == 0
    listed = [line.split()[0] for line in out.splitlines() if line.startswith("  BK")]
    assert listed == sorted(RULES)
    assert "  BK301  warning       joint-not-at-segment-end         a joint is not at the end of its parent segment" in out

