"""The diagram commands: ``bras-kit tree``, ``bras-kit frames`` and ``bras-kit plot``."""

from __future__ import annotations

import io
import sys

import pytest

BRANCHING_URDF = """<?xml version="1.0"?>
<robot name="fourche">
  <link name="base"/><link name="gauche"/><link name="droite"/><link name="outil"/>
  <joint name="j_gauche" type="revolute">
    <parent link="base"/><child link="gauche"/><axis xyz="0 0 1"/>
    <limit lower="-1" upper="1" effort="1" velocity="1"/>
  </joint>
  <joint name="j_droite" type="continuous"><parent link="base"/><child link="droite"/></joint>
  <joint name="fixation_outil" type="fixed"><parent link="gauche"/><child link="outil"/></joint>
</robot>
"""

TWO_PARENTS_URDF = """<?xml version="1.0"?>
<robot name="boucle">
  <link name="a"/><link name="b"/><link name="c"/>
  <joint name="ab" type="fixed"><parent link="a"/><child link="b"/></joint>
  <joint name="cb" type="fixed"><parent link="c"/><child link="b"/></joint>
</robot>
"""


@pytest.fixture
def branching_file(tmp_path):
    path = tmp_path / "fourche.urdf"
    path.write_text(BRANCHING_URDF, encoding="utf-8")
    return str(path)


@pytest.fixture
def in_tmp(tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    return tmp_path


def _clean_error(code: int, err: str, *fragments: str) -> None:
    assert code == 2
    assert "Traceback" not in err
    for fragment in fragments:
        assert fragment in err


# ---------------------------------------------------------------- tree


def test_tree_prints_the_tutorial_arm(run_cli):
    code, out, err = run_cli("tree")
    assert code == 0 and err == ""
    assert out == (
        "base\n"
        "└─ epaule (revolute, axis 0 1 0, -1.57..1.57) → bras\n"
        "   └─ coude (revolute, axis 0 1 0, -2..2) → avant_bras\n"
    )


def test_tree_of_a_file_with_branches(run_cli, branching_file):
    code, out, _ = run_cli("tree", branching_file)
    assert code == 0
    assert out.splitlines() == [
        "base",
        "├─ j_gauche (revolute, axis 0 0 1, -1..1) → gauche",
        "│  └─ fixation_outil (fixed) → outil",
        "└─ j_droite (continuous, axis 1 0 0 (default)) → droite",
    ]


def test_tree_wrist_and_values_with_out_of_limits_warning(run_cli):
    code, out, err = run_cli("tree", "--wrist", "--set", "poignet=2", "--set", "coude=-0.5")
    assert code == 0
    assert out.splitlines()[2:] == [
        "   └─ coude (revolute, axis 0 1 0, -2..2) = -0.5 → avant_bras",
        "      └─ poignet (revolute, axis 0 1 0, -1.57..1.57) = 2 (out of limits) → main",
    ]
    assert "warning: poignet=2 is above its upper limit 1.57 by 0.43" in err


def test_tree_ascii_flag(run_cli):
    code, out, _ = run_cli("tree", "--ascii")
    assert code == 0
    assert out.splitlines()[2] == "   `- coude (revolute, axis 0 1 0, -2..2) -> avant_bras"


def test_tree_falls_back_to_ascii_when_stdout_cannot_print_box_characters(monkeypatch, capsys):
    from bras_kit.cli import main

    buffer = io.BytesIO()
    stream = io.TextIOWrapper(buffer, encoding="ascii")
    monkeypatch.setattr(sys, "stdout", stream)
    code = main(["tree"])
    stream.flush()
    assert code == 0
    assert buffer.getvalue().decode("ascii").splitlines() == [
        "base",
        "`- epaule (revolute, axis 0 1 0, -1.57..1.57) -> bras",
        "   `- coude (revolute, axis 0 1 0, -2..2) -> avant_bras",
    ]


def test_tree_unknown_joint_is_a_clean_error(run_cli):
    code, out, err = run_cli("tree", "--set", "genou=1")
    _clean_error(code, err, "unknown joint 'genou'", "movable joints: epaule, coude")
    assert out == ""


def test_tree_of_a_missing_file_is_a_clean_error(run_cli, tmp_path):
    code, _, err = run_cli("tree", str(tmp_path / "absent.urdf"))
    _clean_error(code, err, "no such file", "absent.urdf")


def test_tree_of_links_with_two_parents_is_a_clean_error(run_cli, tmp_path):
    path = tmp_path / "boucle.urdf"
    path.write_text(TWO_PARENTS_URDF, encoding="utf-8")
    code, out, err = run_cli("tree", str(path))
    _clean_error(code, err, "boucle.urdf:5", "link 'b' has two parents")
    assert out == ""


# ---------------------------------------------------------------- frames


def test_frames_writes_frames_pdf_like_view_frames_and_refuses_to_overwrite(run_cli, in_tmp):
    code, out, err = run_cli("frames")
    assert code == 0 and out == ""
    assert "wrote frames.pdf: 3 frames, 2 joints" in err
    first = (in_tmp / "frames.pdf").read_bytes()
    assert first.startswith(b"%PDF")
    (in_tmp / "frames.pdf").write_bytes(b"mine")
    code, _, err = run_cli("frames")
    _clean_error(code, err, "frames.pdf already exists", "--force")
    assert (in_tmp / "frames.pdf").read_bytes() == b"mine"
    code, _, _ = run_cli("frames", "--force")
    assert code == 0 and (in_tmp / "frames.pdf").read_bytes().startswith(b"%PDF")


def test_frames_dash_prints_dot_with_the_pose(run_cli):
    code, out, err = run_cli("frames", "-o", "-", "--set", "epaule=0.5")
    assert code == 0 and err == ""
    assert out.startswith('digraph "bras" {') and out.rstrip().endswith("}")
    assert '"base" -> "bras" [label="epaule\\nrevolute\\nxyz 0 0 0.05' in out
    assert "value 0.5 rad (28.65 deg)" in out


def test_frames_writes_dot_svg_and_png(run_cli, in_tmp, branching_file):
    for name in ("f.dot", "f.svg", "f.png"):
        code, _, err = run_cli("frames", branching_file, "-o", name)
        assert code == 0, err
    assert (in_tmp / "f.dot").read_text(encoding="utf-8").startswith('digraph "fourche"')
    svg = (in_tmp / "f.svg").read_text(encoding="utf-8")
    assert all(f">{name}</text>" in svg for name in ("base", "gauche", "droite", "outil"))
    assert (in_tmp / "f.png").read_bytes().startswith(b"\x89PNG")


def test_frames_dot_refuses_to_overwrite(run_cli, in_tmp):
    (in_tmp / "f.dot").write_text("mine", encoding="utf-8")
    code, _, err = run_cli("frames", "-o", "f.dot")
    _clean_error(code, err, "f.dot already exists")
    assert (in_tmp / "f.dot").read_text(encoding="utf-8") == "mine"


def test_frames_unknown_format_or_joint_writes_nothing(run_cli, in_tmp):
    code, _, err = run_cli("frames", "-o", "f.jpg")
    _clean_error(code, err, "unknown format '.jpg'", ".png, .svg, .pdf, .dot")
    code, _, err = run_cli("frames", "-o", "f.png", "--set", "genou=1")
    _clean_error(code, err, "unknown joint 'genou'")
    code, _, err = run_cli("frames", "-o", "f.png", "--set", "epaule=beaucoup")
    _clean_error(code, err, "not a number")
    assert list(in_tmp.iterdir()) == []


def test_frames_of_a_broken_tree_is_a_clean_error(run_cli, in_tmp):
    (in_tmp / "boucle.urdf").write_text(TWO_PARENTS_URDF, encoding="utf-8")
    code, _, err = run_cli("frames", "boucle.urdf", "-o", "f.png")
    _clean_error(code, err, "two parents")
    assert not (in_tmp / "f.png").exists()


# ---------------------------------------------------------------- plot


def test_plot_writes_plot_png_and_refuses_to_overwrite(run_cli, in_tmp):
    code, out, err = run_cli("plot", "--duration", "2")
    assert code == 0, err
    assert "wrote plot.png: 41 samples over 2 s; tip = 'avant_bras' + (0, 0, 0.5)" in err
    assert (in_tmp / "plot.png").read_bytes().startswith(b"\x89PNG")
    code, _, err = run_cli("plot")
    _clean_error(code, err, "plot.png already exists")
    code, _, err = run_cli("plot", "--force", "--rate", "10", "--duration", "1")
    assert code == 0 and "11 samples over 1 s" in err


def test_plot_warns_about_limits_the_motion_breaks(run_cli, in_tmp):
    code, _, err = run_cli("plot", "--motion", "coude=2.5*sin(t)", "--set", "epaule=0.3",
                           "--duration", "3", "-o", "p.svg")
    assert code == 0, err
    assert "warning: coude goes past its upper limit 2" in err
    assert "epaule" not in err.split("wrote")[1]
    assert (in_tmp / "p.svg").exists()


def test_plot_bad_input_is_a_clean_error(run_cli, in_tmp):
    code, _, err = run_cli("plot", "--motion", "danse")
    _clean_error(code, err, "'danse' is not a motion")
    code, _, err = run_cli("plot", "--set", "genou=1")
    _clean_error(code, err, "genou")
    code, _, err = run_cli("plot", "-o", "p.gif")
    _clean_error(code, err, "unknown format '.gif'")
    code, _, err = run_cli("plot", "--rate", "0")
    _clean_error(code, err, "rate")
    code, _, err = run_cli("plot", str(in_tmp / "absent.urdf"))
    _clean_error(code, err, "no such file")
    assert list(in_tmp.iterdir()) == []
