"""Inputs that urdfdom and the validator accept but that used to crash a command (issue 26):
non-finite origins, very long chains, diverging simulations. Each gets a clear message and an
exit code, never an internal error, and nothing is written but the outputs asked for."""

from __future__ import annotations

import csv
from pathlib import Path

import pytest
from paths import TESTS

DATA = TESTS / "data" / "urdf"
CHAIN_LINK = ('<link name="l{i}"><inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" '
              'ixz="0" iyz="0"/></inertial><visual><geometry><box size="0.02 0.02 0.1"/></geometry></visual></link>')
CHAIN_JOINT = ('<joint name="j{i}" type="revolute"><parent link="l{parent}"/><child link="l{i}"/>'
               '<origin xyz="{origin}"/><axis xyz="0 1 0"/><limit lower="-1" upper="1" effort="10" velocity="1"/></joint>')


def chain(path: Path, links: int, first_origin: str = "0 0 0.1") -> Path:
    """A serial arm of ``links`` links, one revolute joint between each (the first at ``first_origin``)."""
    lines = ['<?xml version="1.0"?>', '<robot name="chain">']
    for i in range(links):
        lines.append(CHAIN_LINK.format(i=i))
        if i:
            lines.append(CHAIN_JOINT.format(i=i, parent=i - 1, origin=first_origin if i == 1 else "0 0 0.1"))
    path.write_text("\n".join([*lines, "</robot>"]) + "\n")
    return path


def test_render_refuses_an_origin_it_cannot_draw_naming_the_joint(run_cli, tmp_path):
    robot = chain(tmp_path / "arm.urdf", 3, "1e308 1e308 0")
    code, _, err = run_cli("render", str(robot), "-o", str(tmp_path / "arm.png"))
    assert code == 2 and "internal error" not in err
    assert "arm.urdf:5: joint 'j1' has the origin xyz=\"1e+308 1e+308 0\"" in err
    assert not (tmp_path / "arm.png").exists()


def test_render_refuses_a_nan_origin_with_the_validators_finding(run_cli, tmp_path):
    robot = chain(tmp_path / "arm.urdf", 3, "nan 0 0")
    code, _, err = run_cli("render", str(robot), "-o", str(tmp_path / "arm.png"))
    assert code == 1 and "internal error" not in err
    assert 'arm.urdf:5: BK207 error <joint name="j1"> <origin> xyz="nan 0 0" is not a finite number' in err
    assert not (tmp_path / "arm.png").exists()


def test_mjcf_of_a_chain_deeper_than_mujoco_reads_is_refused_up_front(run_cli, tmp_path):
    code, out, err = run_cli("mjcf", str(chain(tmp_path / "long.urdf", 1000)))
    assert code == 2 and out == "" and "internal error" not in err
    assert "link 'l496' is 497 links down its chain; MuJoCo reads at most 496 bodies" in err


def test_mjcf_of_a_long_chain_within_mujoco_limits_is_written(run_cli, tmp_path):
    code, out, err = run_cli("mjcf", str(chain(tmp_path / "long.urdf", 496)))
    assert code == 0, err
    assert out.count("<body ") == 496


def test_simulate_that_diverges_fails_with_the_time_and_joint_and_writes_nothing(run_cli, tmp_path, monkeypatch):
    monkeypatch.chdir(tmp_path)
    code, out, err = run_cli("simulate", str(DATA / "physics" / "tiny_inertia.urdf"), "--integrator", "Euler",
                             "--timestep", "0.01", "--duration", "2", "-o", "states.csv")
    assert code == 1
    assert "the simulation diverged at t = " in err and "joint 'j" in err
    assert "verdict" in out and "every motor kept up" not in out
    assert list(tmp_path.iterdir()) == []  # no states.csv from NaN, no MUJOCO_LOG.TXT
    assert "WARNING" not in err and "MUJOCO" not in err


def test_simulate_takes_set_like_every_other_command_and_start_still_works(run_cli, tmp_path):
    for flag in ("--set", "--start"):
        target = tmp_path / f"{flag[2:]}.csv"
        code, _, err = run_cli("simulate", "--inertials", "--control", "none", flag, "epaule=0.3", "--duration", "0",
                               "-o", str(target))
        assert code == 0, err
        rows = {row["name"]: float(row["position"]) for row in csv.DictReader(target.open())}
        assert rows["epaule"] == pytest.approx(0.3)


def test_frames_png_too_large_for_its_text_is_refused_with_a_vector_hint(run_cli, tmp_path):
    code, _, err = run_cli("frames", str(chain(tmp_path / "long.urdf", 1800)), "-o", str(tmp_path / "f.png"))
    assert code == 2 and "internal error" not in err
    assert "text would be smaller than a pixel" in err and ".svg or .pdf" in err
    assert [p.name for p in tmp_path.iterdir()] == ["long.urdf"]
