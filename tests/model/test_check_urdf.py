"""Every URDF bras-kit writes is accepted by urdfdom's check_urdf, the parser ROS itself uses."""

from __future__ import annotations

import pytest
from paths import TESTS
from urdfdom_oracle import check_urdf

from bras_kit.model.authoring import arm_urdf
from bras_kit.validate import validate_path

VARIANTS = {
    "default": {},
    "wrist": {"wrist": True},
    "inertials": {"inertials": True},
    "wrist-inertials": {"wrist": True, "inertials": True},
    "long-bras": {"params": {"bras_length": 0.8}},
    "short-forearm-wrist": {"wrist": True, "params": {"avant_bras_length": 0.3}},
    "narrow-limits": {"wrist": True, "params": {"coude_lower": -0.5, "coude_upper": 0.5,
                                                "poignet_lower": 0.1, "poignet_upper": 0.6}},
    "everything-changed": {"wrist": True, "inertials": True,
                           "params": {"base_radius": 0.2, "bras_width": 0.1, "bras_mass": 3,
                                      "poignet_color": "1 1 0 0.5", "epaule_effort": 25}},
}


@pytest.mark.parametrize("options", VARIANTS.values(), ids=VARIANTS.keys())
def test_generated_urdf_passes_check_urdf(tmp_path, options):
    path = tmp_path / "bras.urdf"
    path.write_text(arm_urdf(**options))
    result = check_urdf(path)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "Successfully Parsed XML" in result.stdout
    assert "robot name is: bras" in result.stdout
    assert "root Link: base has 1 child(ren)" in result.stdout
    chain = ["bras", "avant_bras"] + (["main"] if options.get("wrist") else [])
    children = [line.split()[-1] for line in result.stdout.splitlines() if "child(1):" in line]
    assert children == chain


def test_cli_written_urdf_passes_check_urdf(run_cli, tmp_path):
    path = tmp_path / "cli.urdf"
    code, _, err = run_cli("urdf", "--wrist", "--inertials", "-o", str(path))
    assert code == 0, err
    assert check_urdf(path).returncode == 0


def test_check_urdf_rejects_a_joint_to_a_missing_link(tmp_path):
    """The same check fails on a broken file, so the tests above can fail too."""
    path = tmp_path / "broken.urdf"
    path.write_text(arm_urdf().replace('<child link="avant_bras"/>', '<child link="nulle_part"/>'))
    result = check_urdf(path)
    assert result.returncode != 0
    assert "nulle_part" in result.stdout + result.stderr


def test_check_urdf_rejects_a_second_root(tmp_path):
    path = tmp_path / "two_roots.urdf"
    path.write_text(arm_urdf().replace("</robot>", '<link name="orphelin"/></robot>'))
    assert check_urdf(path).returncode != 0


@pytest.mark.parametrize("wrist", [False, True], ids=["default", "wrist"])
def test_scaffolded_package_urdf_passes_check_urdf(tmp_path, wrist):
    from bras_kit.scaffold.package import render_package

    path = tmp_path / "bras.urdf"
    path.write_text(render_package(wrist=wrist, params={"bras_length": 0.7})["urdf/bras.urdf"])
    result = check_urdf(path)
    assert result.returncode == 0, result.stdout + result.stderr
    assert ("child(1):  main" in result.stdout) == wrist


REFUSED_BY_URDFDOM = {
    "safety-controller-none": ('<limit lower="-1.57"', '<safety_controller soft_upper_limit="None" k_velocity="1"/>'
                                                        '<limit lower="-1.57"', "BK230"),
    "arabic-indic-digit": ('upper="1.57"', 'upper="\u0661"', "BK123"),
    "full-width-digit": ('upper="1.57"', 'upper="\uff11"', "BK123"),
    "underscore-in-number": ('upper="1.57"', 'upper="1_0"', "BK123"),
}


@pytest.mark.parametrize("old,new,code", REFUSED_BY_URDFDOM.values(), ids=REFUSED_BY_URDFDOM.keys())
def test_validator_errors_where_urdfdom_refuses_the_file(tmp_path, old, new, code):
    text = (TESTS / "data" / "urdf" / "good" / "bras.urdf").read_text(encoding="utf-8")
    assert old in text
    path = tmp_path / "robot.urdf"
    path.write_text(text.replace(old, new, 1), encoding="utf-8")
    assert check_urdf(path).returncode != 0
    assert code in [f.code for f in validate_path(str(path)) if f.severity == "error"]
