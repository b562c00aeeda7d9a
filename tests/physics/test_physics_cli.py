"""bras-kit simulate and bras-kit mjcf end to end, and real robots from example-robot-data in MuJoCo."""

from __future__ import annotations

import site
import subprocess
import sys
import xml.etree.ElementTree as ET
from pathlib import Path

import numpy as np
import pytest

from bras_kit.model.authoring import load
from bras_kit.motion import read_states
from bras_kit.physics import build_mjcf, simulate

ROBOTS = next((Path(folder) / "cmeel.prefix" / "share" / "example-robot-data" / "robots"
               for folder in site.getsitepackages()
               if (Path(folder) / "cmeel.prefix" / "share" / "example-robot-data" / "robots").is_dir()),
              Path(sys.prefix) / "missing")
if not ROBOTS.is_dir():  # a non-standard layout: ask the package where it lives
    import example_robot_data  # type: ignore[import-not-found]

    ROBOTS = Path(example_robot_data.getModelPath("panda_description/urdf/panda.urdf")) / "example-robot-data" / "robots"
PACKAGES = str(ROBOTS.parent)
REAL = {
    "panda": ROBOTS / "panda_description" / "urdf" / "panda.urdf",
    "ur5": ROBOTS / "ur_description" / "urdf" / "ur5_robot.urdf",
}


def _file_facts(path: Path) -> tuple[list[tuple[str, float]], set[str]]:
    """Straight from the URDF text: (driven joint, effort) and the distinct mesh file names."""
    root = ET.parse(path).getroot()
    driven = []
    for joint in root.findall("joint"):
        if joint.get("type") in ("revolute", "continuous", "prismatic") and joint.find("mimic") is None:
            limit = joint.find("limit")
            driven.append((joint.get("name") or "", float(limit.get("effort")) if limit is not None else np.inf))
    meshes = {m.get("filename") or "" for m in root.iter("mesh")}
    return driven, meshes


def _dae_pieces(path: Path) -> int:
    """From the COLLADA text: the triangle sets of every geometry the scene instances."""
    ns = "{http://www.collada.org/2005/11/COLLADASchema}"
    root = ET.parse(path).getroot()
    geometries = {g.get("id"): g for g in root.iter(ns + "geometry")}
    sets = 0
    for instance in root.iter(ns + "instance_geometry"):
        geometry = geometries[(instance.get("url") or "#").lstrip("#")]
        sets += sum(1 for e in geometry.iter() if e.tag in (ns + "triangles", ns + "polylist", ns + "polygons"))
    return sets


@pytest.mark.parametrize("name", REAL)
def test_real_robot_loads_in_mujoco_with_its_meshes_and_efforts(name):
    import mujoco

    path = REAL[name]
    robot = load(path, package_paths=[PACKAGES])
    built = build_mjcf(robot, package_paths=[PACKAGES])
    model = built.compile()
    driven, meshes = _file_facts(path)
    assert [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_ACTUATOR, a) for a in range(model.nu)] == [n for n, _ in driven]
    assert list(model.actuator_forcerange[:, 1]) == pytest.approx([e for _, e in driven])
    # a STL is one mesh; a DAE visual one mesh per material piece (each geom with its colour)
    files = {name: Path(PACKAGES).parent / name[len("package://"):] for name in meshes}
    assert model.nmesh == len(built.assets) == sum(_dae_pieces(f) if f.suffix == ".dae" else 1 for f in files.values())
    assert {Path(asset.source).name for asset in built.assets.values()} == {Path(m).name for m in meshes}
    assert any(source.endswith(".dae") for source in built.converted)  # both robots draw with DAE visuals
    assert all(model.mesh_vertnum[m] > 0 for m in range(model.nmesh))


def test_seven_joint_panda_holds_a_pose_with_gravity_compensation():
    robot = load(REAL["panda"], package_paths=[PACKAGES])
    ready = ["panda_joint2=-0.785", "panda_joint4=-2.356", "panda_joint6=1.571", "panda_joint7=0.785"]  # its usual pose
    states = simulate(robot, ready, control="pd+gravity", duration=1.0, package_paths=[PACKAGES])
    assert len([n for n in states.names if n.startswith("panda_joint")]) == 7
    assert np.max(np.abs(states.positions[-1] - states.targets[-1])) < 1e-3
    assert np.all(np.abs(states.efforts) <= states.effort_limits * (1 + 1e-9))


def test_simulate_prints_the_weak_shoulder_in_french(run_cli):
    code, out, err = run_cli("simulate", "--inertials", "--param", "epaule_effort=2", "--lang", "fr", "--duration", "6")
    assert code == 0, err
    assert "epaule : le moteur est trop faible" in out
    assert "coude" in out and "Traceback" not in err
    code, _, _ = run_cli("simulate", "--inertials", "--param", "epaule_effort=2", "--duration", "6", "--strict")
    assert code == 1


def test_simulate_without_inertials_says_to_add_them(run_cli):
    code, out, err = run_cli("simulate")
    assert code == 2 and out == ""
    assert "no <inertial>" in err and "--inertials" in err and "Traceback" not in err


def test_simulate_writes_states_with_efforts_and_refuses_to_overwrite(run_cli, tmp_path):
    target = tmp_path / "states.csv"
    code, _, err = run_cli("simulate", "--inertials", "--duration", "2", "-o", str(target))
    assert code == 0, err
    header = target.read_text().splitlines()[0]
    assert header == "time,name,position,velocity,effort"
    states = read_states(str(target))
    assert len(states) == 41 and states.names == ["epaule", "coude"]
    rows = [line.split(",") for line in target.read_text().splitlines()[1:]]
    assert max(abs(float(r[4])) for r in rows) <= 10.0
    code, _, err = run_cli("simulate", "--inertials", "--duration", "2", "-o", str(target))
    assert code == 2 and "already exists" in err


def test_collisions_without_inertials_warn_about_water_density(run_cli):
    code, _, err = run_cli("simulate", "--collisions", "--duration", "1", "--control", "pd+gravity")
    assert code == 0, err
    assert "1000 kg/m³" in err and "'bras'" in err


def test_mjcf_file_opens_in_mujoco_with_its_meshes(run_cli, tmp_path):
    import mujoco

    target = tmp_path / "ur5.xml"
    code, _, err = run_cli("mjcf", str(REAL["ur5"]), "--package-path", PACKAGES, "-o", str(target))
    assert code == 0, err
    model = mujoco.MjModel.from_xml_path(str(target))  # MuJoCo reads the file and its mesh folder itself
    assert model.nu == 6 and model.nmesh == len(list((tmp_path / "ur5_meshes").iterdir()))


def test_mjcf_prints_the_tutorial_arm_with_motors_at_effort(run_cli):
    code, out, err = run_cli("mjcf", "--inertials", "--param", "coude_effort=3")
    assert code == 0, err
    root = ET.fromstring(out)
    ranges = {a.get("joint"): a.get("forcerange") for a in root.iter("general")}
    assert ranges == {"epaule": "-10 10", "coude": "-3 3"}
    assert {(e.get("body1"), e.get("body2")) for e in root.iter("exclude")} == {("base", "bras"), ("bras", "avant_bras")}


@pytest.mark.slow
def test_simulate_gif_is_drawn_by_the_bras_kit_renderer_from_the_simulated_states(tmp_path):
    from PIL import Image

    gif, plot = tmp_path / "fall.gif", tmp_path / "torques.png"
    result = subprocess.run([sys.executable, "-m", "bras_kit", "simulate", "--inertials", "--control", "none",
                             "--duration", "3", "--gif", str(gif), "--plot", str(plot)],
                            capture_output=True, text=True, timeout=300, env={**__import__("os").environ,
                                                                             "PYOPENGL_PLATFORM": "egl",
                                                                             "MPLBACKEND": "Agg"})
    assert result.returncode == 0, result.stderr
    with Image.open(gif) as image:
        assert image.n_frames == 61  # 3 s at 20 Hz, both ends
        image.seek(0)
        first = np.asarray(image.convert("RGB"), dtype=int)
        image.seek(image.n_frames - 1)
        last = np.asarray(image.convert("RGB"), dtype=int)
    assert np.mean(np.any(first != last, axis=2)) > 0.01  # the arm moved: the pictures differ
    with Image.open(plot) as picture:
        pixels = np.asarray(picture.convert("RGB"), dtype=int)
    band = np.all(np.abs(pixels - (246, 204, 204)) <= 2, axis=2)  # the effort-limit bands' pink
    assert band.mean() > 0.01


def test_mjcf_of_a_real_robot_reports_package_names_and_converted_meshes_in_french(run_cli):
    code, _, err = run_cli("mjcf", str(REAL["panda"]), "--package-path", PACKAGES, "--lang", "fr")
    assert code == 0, err
    assert "maillages nommés package://… trouvés par bras-kit" in err
    assert "convertis en STL avec trimesh" in err and "link0.dae" in err
    assert "panda_link8" not in err  # a frame-only link (mass 0, fixed) is not a physics problem


def test_simulate_json_messages_carry_the_measured_effort(run_cli, tmp_path):
    import json

    target = tmp_path / "states.json"
    code, _, err = run_cli("simulate", "--inertials", "--duration", "1", "--control", "pd+gravity", "-o", str(target))
    assert code == 0, err
    messages = json.loads(target.read_text())
    assert len(messages) == 21 and messages[0]["name"] == ["epaule", "coude"]
    assert all(len(m["effort"]) == 2 and max(abs(e) for e in m["effort"]) <= 10.0 for m in messages)
    assert read_states(str(target)).names == ["epaule", "coude"]
