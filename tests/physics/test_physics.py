"""Physics with MuJoCo, checked against physics worked out by hand (not against the code under test).

Integrators and time steps used: the pendulum period with bras-kit's default (implicitfast,
2 ms); the energy balance with RK4 at 1 ms (implicitfast damps, by design, and would lose energy);
everything else with the defaults.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from paths import TESTS

from bras_kit.core.errors import ModelError
from bras_kit.model.authoring import arm
from bras_kit.model.robot import robot_from_xml
from bras_kit.model.xmlio import parse_xml
from bras_kit.motion import pose_motion
from bras_kit.physics import build_mjcf, simulate

G = 9.81  # MuJoCo's default gravity, m/s^2
# the tutorial arm's defaults (bras_kit/templates/robot/bras.urdf.xacro): masses, lengths, efforts
M1, L1, M2, L2 = 1.0, 0.6, 0.5, 0.5
EFFORT = 10.0

# --- a single pendulum --------------------------------------------------------------------------------------------
MASS, D, SIDE, LENGTH = 2.0, 0.3, 0.05, 0.6  # kg, pivot -> centre of mass (m), box section and length (m)
I_COM = MASS / 12 * (SIDE ** 2 + LENGTH ** 2)  # solid box about its centre, axis across the long side
I_PIVOT = I_COM + MASS * D ** 2  # parallel axes
PERIOD = 2 * math.pi * math.sqrt(I_PIVOT / (MASS * G * D))
THETA0 = 0.05  # rad: small enough that the period grows by only theta0^2/16 = 0.016 %


def _pendulum(dynamics: str = ""):
    text = f"""<robot name="pendule">
  <link name="support"/>
  <link name="tige">
    <inertial><origin xyz="0 0 {-D}"/><mass value="{MASS}"/>
      <inertia ixx="{I_COM}" ixy="0" ixz="0" iyy="{I_COM}" iyz="0" izz="{MASS / 6 * SIDE ** 2}"/></inertial>
    <visual><origin xyz="0 0 {-D}"/><geometry><box size="{SIDE} {SIDE} {LENGTH}"/></geometry></visual>
  </link>
  <joint name="pivot" type="continuous"><parent link="support"/><child link="tige"/>
    <origin xyz="0 0 1"/><axis xyz="0 1 0"/>{dynamics}</joint>
</robot>"""
    return robot_from_xml(parse_xml(text, "pendule.urdf"), "pendule.urdf", text)


def _crossings(times: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Times where ``values`` goes from negative to positive, linearly interpolated."""
    k = np.nonzero((values[:-1] < 0) & (values[1:] >= 0))[0]
    return times[k] - values[k] * (times[k + 1] - times[k]) / (values[k + 1] - values[k])


def test_pendulum_period_matches_the_compound_pendulum_formula():
    states = simulate(_pendulum(), pose_motion(_pendulum()), control="none", start={"pivot": THETA0},
                      duration=10 * PERIOD, rate=1000, damping=0)
    assert states.integrator == "implicitfast" and states.timestep == 0.002
    up = _crossings(states.times, states.positions[:, 0])
    measured = float(np.mean(np.diff(up)))
    expected = PERIOD * (1 + THETA0 ** 2 / 16)
    assert len(up) >= 9
    assert measured == pytest.approx(expected, rel=0.005)


def test_pendulum_energy_is_conserved_over_ten_periods():
    states = simulate(_pendulum(), pose_motion(_pendulum()), control="none", start={"pivot": THETA0},
                      duration=10 * PERIOD, rate=200, damping=0, integrator="RK4", timestep=0.001)
    theta, omega = states.positions[:, 0], states.velocities[:, 0]
    energy = 0.5 * I_PIVOT * omega ** 2 + MASS * G * D * (1 - np.cos(theta))
    e0 = MASS * G * D * (1 - math.cos(THETA0))
    assert np.max(np.abs(energy - e0)) / e0 < 1e-3
    assert np.max(np.abs(theta)) == pytest.approx(THETA0, rel=1e-3)  # it swings back to where it started


def _peaks(values: np.ndarray) -> np.ndarray:
    """Indices of the local maxima of ``values``."""
    return np.nonzero((values[1:-1] > values[:-2]) & (values[1:-1] >= values[2:]))[0] + 1


def test_pendulum_without_dynamics_keeps_its_swing_with_the_defaults():
    """No <dynamics>: no damping (as in Gazebo). Issue 19: 0.05 N.m.s/rad made it lose 70 % in 8 s."""
    robot = _pendulum()
    states = simulate(robot, pose_motion(robot), control="none", start={"pivot": THETA0}, duration=8.0, rate=500)
    assert states.model is not None and states.model.dynamics == {"pivot": (0.0, 0.0)}
    assert 'damping="' not in states.model.xml and "frictionloss" not in states.model.xml
    theta = states.positions[:, 0]
    last_period = states.times >= states.times[-1] - PERIOD
    assert np.max(theta[last_period]) == pytest.approx(THETA0, rel=0.01)


DAMPING = 0.02  # N.m.s/rad: light, so the swing is the textbook underdamped oscillator


def test_declared_damping_decays_the_swing_like_the_damped_oscillator():
    """I theta'' + b theta' + m g d theta = 0: the amplitude decays as exp(-b t / (2 I))."""
    robot = _pendulum(f'<dynamics damping="{DAMPING}" friction="0"/>')
    states = simulate(robot, pose_motion(robot), control="none", start={"pivot": THETA0}, duration=6 * PERIOD,
                      rate=1000, integrator="RK4", timestep=0.001)
    assert states.model is not None and states.model.dynamics == {"pivot": (DAMPING, 0.0)}
    theta = states.positions[:, 0]
    peaks = _peaks(theta)
    assert len(peaks) >= 4
    expected = THETA0 * np.exp(-DAMPING * states.times[peaks] / (2 * I_PIVOT))
    np.testing.assert_allclose(theta[peaks], expected, rtol=0.01)


def test_damping_argument_replaces_the_declared_damping_on_every_joint():
    robot = _pendulum('<dynamics damping="0.5" friction="0.1"/>')
    built = build_mjcf(robot, damping=0.0, control="none")
    assert built.dynamics == {"pivot": (0.0, 0.1)} and built.damping_given
    assert 'frictionloss="0.1"' in built.xml and 'damping="' not in built.xml


TINY = (TESTS / "data" / "urdf" / "physics" / "tiny_inertia.urdf")


def test_a_diverging_run_stops_where_it_went_nan_and_names_the_joint(tmp_path, monkeypatch):
    from bras_kit.model.authoring import load

    monkeypatch.chdir(tmp_path)  # MuJoCo would write MUJOCO_LOG.TXT here
    robot = load(str(TINY))
    states = simulate(robot, integrator="Euler", timestep=0.01, duration=2.0)
    assert states.diverged is not None
    assert states.diverged.joint in {"j1", "j2", "j3"}
    assert 0 < states.diverged.time <= 2.0
    assert np.all(np.isfinite(states.positions))
    assert list(tmp_path.iterdir()) == []


def test_too_weak_only_when_the_motion_needs_more_than_the_effort():
    """Stiff gains and Euler make the motors chatter at their limit: that is not weakness."""
    states = simulate(arm(inertials=True), kd=1e6, integrator="Euler", duration=2.0)
    for report in states.report:
        assert report.weak == (report.needed_peak > report.effort), report
    assert any(report.saturated for report in states.report)


# --- the tutorial arm held by its motors ---------------------------------------------------------------------------

def _holding_torques(q1: float, q2: float) -> tuple[float, float]:
    """Torque the motors must give to hold the arm: minus the sum over child bodies of m g x lever arm.

    Axes are y; a positive angle tilts a segment towards +x, where gravity pulls it further.
    """
    elbow_x = L1 * math.sin(q1)
    forearm_x = elbow_x + L2 / 2 * math.sin(q1 + q2)
    shoulder = M1 * G * (L1 / 2) * math.sin(q1) + M2 * G * forearm_x
    elbow = M2 * G * (L2 / 2) * math.sin(q1 + q2)
    return -shoulder, -elbow


POSES = [(0.5, 0.3), (-1.0, 1.2), (1.2, -0.8), (0.0, 1.5), (-0.4, -1.1)]


@pytest.mark.parametrize("pose", POSES, ids=[f"{a}_{b}" for a, b in POSES])
def test_gravity_compensation_holds_the_arm_with_the_hand_computed_torques(pose):
    robot = arm(inertials=True)
    config = {"epaule": pose[0], "coude": pose[1]}
    states = simulate(robot, pose_motion(robot, config), control="pd+gravity", duration=2.0)
    assert np.max(np.abs(states.positions - np.array(pose))) < 1e-6
    expected = _holding_torques(*pose)
    assert states.efforts[-1] == pytest.approx(expected, abs=1e-6)


def test_plain_pd_sags_under_gravity_by_torque_over_stiffness():
    robot = arm(inertials=True)
    states = simulate(robot, pose_motion(robot, {"epaule": 0.0, "coude": 0.6}), control="pd", duration=4.0)
    # at rest the motor torque kp * error balances gravity: error = holding torque / kp (small-angle check)
    hold = np.array(_holding_torques(*states.positions[-1]))
    error = np.array([0.0, 0.6]) - states.positions[-1]
    assert error * 100.0 == pytest.approx(hold, abs=1e-4)
    assert np.all(np.abs(error) > 1e-3)


@pytest.mark.parametrize("params", [{}, {"epaule_effort": 2}, {"coude_effort": 0.5}])
@pytest.mark.parametrize("control", ["pd", "pd+gravity"])
def test_motor_torques_never_exceed_effort(control, params):
    robot = arm(inertials=True, params=params)
    states = simulate(robot, control=control, duration=6.0)
    limits = np.array([params.get("epaule_effort", EFFORT), params.get("coude_effort", EFFORT)])
    assert np.all(np.abs(states.efforts) <= limits * (1 + 1e-9))


# MuJoCo's joint limits are soft (default solref: 0.02 s time constant, critically damped), so a joint
# hitting its stop goes past it by about speed x time constant before it is pushed back. Bound stated:
# 0.02 s x the fastest speed reached, plus 0.005 rad for the weight resting on the stop.
LIMIT_SOFTNESS_S, LIMIT_REST = 0.02, 0.005


def test_dropped_arm_comes_to_rest_on_its_shoulder_limit_within_the_softness_bound():
    robot = arm(params={"coude_lower": -0.01, "coude_upper": 0.01, "bras_mass": 1.0}, inertials=True)
    states = simulate(robot, pose_motion(robot), control="none", start={"epaule": 0.3}, duration=6.0, rate=500)
    upper = 1.57
    speed = float(np.max(np.abs(states.velocities[:, 0])))
    past = float(np.max(states.positions[:, 0] - upper))
    assert past <= LIMIT_SOFTNESS_S * speed + LIMIT_REST
    assert states.positions[-1, 0] == pytest.approx(upper, abs=LIMIT_REST)
    assert abs(states.velocities[-1, 0]) < 1e-3
    assert states.joint_report("epaule").final_position == pytest.approx(upper, abs=LIMIT_REST)


def test_weak_shoulder_is_reported_and_strong_elbow_is_not():
    robot = arm(inertials=True, params={"epaule_effort": 2})
    states = simulate(robot, control="pd", duration=10.0)
    shoulder, elbow = states.joint_report("epaule"), states.joint_report("coude")
    # holding the arm straight out at the sine's peak (0.8 rad) needs more than 2 N.m
    assert -_holding_torques(0.8, 0.0)[0] > 2.0
    assert shoulder.weak and shoulder.needed_peak > 2.0 and shoulder.share_at_limit > 0.5
    assert not elbow.weak
    assert states.weak_joints == ["epaule"]


def test_strong_motors_track_the_sine_closely_with_gravity_compensation():
    states = simulate(arm(inertials=True), control="pd+gravity", duration=10.0)
    assert not states.weak_joints
    assert all(r.error_max < 0.05 and r.share_at_limit == 0 for r in states.report)


# --- building the model ----------------------------------------------------------------------------------------------

VARIANTS = {
    "inertials": {"inertials": True},
    "wrist-inertials": {"wrist": True, "inertials": True},
    "long-bras": {"inertials": True, "params": {"bras_length": 0.8, "bras_mass": 3}},
    "narrow-limits": {"wrist": True, "inertials": True, "params": {"coude_lower": -0.5, "coude_upper": 0.5}},
}


@pytest.mark.parametrize("options", VARIANTS.values(), ids=VARIANTS.keys())
def test_every_variant_builds_with_one_body_per_link_and_one_motor_per_joint(options):
    import mujoco

    robot = arm(**options)
    model = build_mjcf(robot).compile()
    links = [link.name for link in robot.links]
    assert [mujoco.mj_id2name(model, mujoco.mjtObj.mjOBJ_BODY, b) for b in range(1, model.nbody)] == links
    assert model.nu == len(links) - 1
    masses = {"base": 2.0, "bras": 1.0, "avant_bras": 0.5, "main": 0.2}
    masses.update({k.removesuffix("_mass"): float(v) for k, v in options.get("params", {}).items() if k.endswith("_mass")})
    assert list(model.body_mass[1:]) == pytest.approx([masses[n] for n in links])
    assert model.actuator_forcerange[:, 1] == pytest.approx([EFFORT, EFFORT, 5.0][:model.nu])


def test_arm_without_inertials_is_refused_with_a_hint():
    with pytest.raises(ModelError) as info:
        build_mjcf(arm())
    assert "bras" in str(info.value.message) and "--inertials" in str(info.value.hint)


def test_collision_only_link_weighs_as_water():
    import mujoco

    model = build_mjcf(arm(collisions=True)).compile()
    bras = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "bras")
    assert model.body_mass[bras] == pytest.approx(1000 * 0.08 * 0.08 * 0.6)  # box volume x 1000 kg/m^3


def test_floor_is_under_the_base_and_touching_segments_are_excluded():
    built = build_mjcf(arm(inertials=True))
    assert built.floor_z == pytest.approx(-0.05)  # half the base cylinder's 0.1 m height
    assert 'type="plane"' in built.xml and 'pos="0 0 -0.05"' in built.xml
    assert [(p, c) for p, c, _ in built.excluded] == [("base", "bras"), ("bras", "avant_bras")]
    assert '<exclude body1="base" body2="bras"/>' in built.xml


def test_collisions_match_the_visuals_in_the_template():
    robot = arm(collisions=True, wrist=True)
    for link in robot.links:
        assert len(link.collisions) == len(link.visuals) == 1
        assert link.collisions[0].geometry == link.visuals[0].geometry.__class__(
            **{**link.visuals[0].geometry.__dict__, "line": link.collisions[0].geometry.line})
        assert link.collisions[0].origin.xyz == link.visuals[0].origin.xyz
    assert all(link.collisions for link in arm(inertials=True).links)


@pytest.mark.parametrize("options", [{"collisions": True}, {"collisions": True, "wrist": True},
                                     {"inertials": True, "wrist": True}], ids=["collisions", "wrist", "inertials"])
def test_urdf_with_collisions_passes_check_urdf(tmp_path, options):
    import shutil
    import subprocess

    from bras_kit.model.authoring import arm_urdf

    program = shutil.which("check_urdf")
    assert program, "check_urdf (liburdfdom-tools) is missing"
    path = tmp_path / "bras.urdf"
    path.write_text(arm_urdf(**options))
    result = subprocess.run([program, str(path)], capture_output=True, text=True, timeout=60)
    assert result.returncode == 0 and "Successfully Parsed XML" in result.stdout, result.stdout + result.stderr
    assert path.read_text().count("<collision>") == (4 if options.get("wrist") else 3)


def test_missing_inertials_are_explained_in_french():
    from bras_kit.core.i18n import say_error
    from bras_kit.physics.diagnostics import check_physics_ready

    with pytest.raises(ModelError) as info:
        check_physics_ready(arm())
    assert "links bougent mais n'ont pas d'<inertial> : 'bras', 'avant_bras'" in say_error(info.value, "fr")
    assert "--inertials" in str(info.value.hint)
    check_physics_ready(arm(inertials=True), "fr")  # nothing to say


def test_an_inertia_given_in_a_turned_frame_reaches_mujoco_turned_into_the_link_frame():
    import mujoco

    from bras_kit.model.authoring import load

    robot = load(str(TESTS / "data" / "urdf" / "physics" / "rotated_inertia.urdf"))
    model = build_mjcf(robot).compile()  # MuJoCo refused fullinertia beside an orientation
    body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "bloc")
    rotation = np.zeros(9)
    mujoco.mju_quat2Mat(rotation, model.body_iquat[body])
    rotation = rotation.reshape(3, 3)
    tensor = rotation @ np.diag(model.body_inertia[body]) @ rotation.T  # MuJoCo's tensor, in the link's frame
    # a quarter turn about z swaps the x and y moments: diag(1, 2, 3) seen from the link is diag(2, 1, 3)
    np.testing.assert_allclose(tensor, np.diag([2.0, 1.0, 3.0]), atol=1e-9)
    np.testing.assert_allclose(model.body_ipos[body], [0.1, 0.0, 0.0], atol=1e-12)
    assert model.body_mass[body] == pytest.approx(2.0)


def test_a_point_mass_without_inertia_on_a_fixed_frame_is_accepted_with_its_mass():
    import mujoco

    from bras_kit.model.authoring import load

    robot = load(str(TESTS / "data" / "urdf" / "physics" / "rotated_inertia.urdf"))
    model = build_mjcf(robot).compile()  # MuJoCo refused a zero fullinertia (eigenvalues must be > 0)
    frame = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, "repere")
    assert model.body_mass[frame] == pytest.approx(0.01)
    np.testing.assert_allclose(model.body_inertia[frame], 0.0, atol=1e-12)


def test_a_scaled_mesh_is_scaled_by_its_mujoco_asset():
    import mujoco

    from bras_kit.model.authoring import load

    robot = load(str(TESTS / "data" / "urdf" / "physics" / "scaled_mesh.urdf"))
    model = build_mjcf(robot).compile()  # MuJoCo refused scale= on a <geom>
    radius = {}
    for name in ("simple", "double"):
        body = mujoco.mj_name2id(model, mujoco.mjtObj.mjOBJ_BODY, name)
        geoms = [g for g in range(model.ngeom) if model.geom_bodyid[g] == body and model.geom_type[g] == mujoco.mjtGeom.mjGEOM_MESH]
        assert len(geoms) == 1
        radius[name] = model.geom_rbound[geoms[0]]
    assert radius["double"] == pytest.approx(2 * radius["simple"], rel=1e-6)
