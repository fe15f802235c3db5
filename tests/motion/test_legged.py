"""Tests of hexaleg.motion.legged: the tripod gait's kinematic consistency (Pinocchio FK, stance
feet at rest, finite differences), periodicity, footholds, other leg groups (a wave gait, a
quadruped's trot), the errors on bad input, the explained IK failures (parameter and a value
that works) and walking along the robot's heading."""

from __future__ import annotations

import dataclasses
import math
import re
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import (
    GaitReachError,
    InvalidParameterError,
    UnknownNameError,
    UnreachableTargetError,
)
from hexaleg.motion.legged import nominal_footholds, sample_gait, tripod_gait
from hexaleg.motion.params import GaitParams
from hexaleg.robot.model import LegSpec, load_robot


@pytest.fixture(scope="module")
def turn(robot) -> hexaleg.motion.trajectory.Motion:
    """A turning gait with double support (β = 0.7) and a lower body."""
    return tripod_gait(robot, GaitParams(yaw_rate=0.4, duty_factor=0.7, body_height=0.08,
                                         stride_length=0.05, period=0.8, samples=400))


def test_default_gait_shapes_and_fields(robot, walk):
    gait = GaitParams()
    T = gait.samples
    assert walk.t.shape == (T,) and walk.q.shape == (T, 25)
    assert walk.v.shape == walk.a.shape == (T, 24)
    assert walk.stance.shape == (T, 6) and walk.stance.dtype == bool
    assert walk.feet.shape == (T, 6, 3)
    assert np.allclose(walk.t, np.arange(T) * gait.period / T)
    assert walk.period == gait.period and walk.distance == pytest.approx(0.06)
    assert walk.periodic and not walk.fixed_base
    info = walk.info
    assert info["speed"] == pytest.approx(0.06)
    assert info["body_height"] == pytest.approx(0.0913, abs=1e-4)
    assert info["foot_radius"] == pytest.approx(0.1889, abs=1e-4)
    assert info["gait"]["groups"] == (("LF", "RM", "LH"), ("RF", "LM", "RH"))
    assert set(info["ik"].values()) == {"analytic"}
    # The base moves at constant forward speed at body height, level.
    assert np.allclose(walk.q[:, 0], 0.06 * walk.t) and np.allclose(walk.q[:, 1], 0.0)
    assert np.allclose(walk.q[:, 2], info["body_height"])
    assert np.allclose(walk.q[:, 3:7], [0.0, 0.0, 0.0, 1.0])
    assert np.allclose(walk.v[:, :6], [0.06, 0, 0, 0, 0, 0]) and np.allclose(walk.a[:, :6], 0)


@pytest.mark.parametrize("which", ["walk", "turn"])
def test_forward_kinematics_reproduces_every_foot_target(robot, which, request, frame_kinematics):
    motion = request.getfixturevalue(which)
    pos, _, _ = frame_kinematics(robot, motion)
    assert np.abs(pos - motion.feet).max() <= 1e-9
    assert np.abs(motion.feet[..., 2][motion.stance]).max() <= 1e-12  # stance feet on the ground
    assert np.all(motion.feet[..., 2][~motion.stance] >= 0.0)  # 0 only at lift-off


@pytest.mark.parametrize("which", ["walk", "turn"])
def test_stance_feet_have_zero_velocity_and_acceleration(robot, which, request,
                                                       frame_kinematics):
    """Pinocchio's frame velocity and classical acceleration of q, v, a: proves v, a match q."""
    motion = request.getfixturevalue(which)
    _, vel, acc = frame_kinematics(robot, motion)
    assert np.abs(vel[motion.stance]).max() <= 1e-9
    assert np.abs(acc[motion.stance]).max() <= 1e-9
    # Swing feet really move (the check above is not vacuous).
    assert np.abs(vel[~motion.stance]).max() > 0.1


def test_swing_apex_is_the_step_height(walk):
    assert walk.feet[..., 2].max() == pytest.approx(0.03, abs=1e-9)


@pytest.mark.parametrize("gait", [GaitParams(samples=200),
                                  GaitParams(yaw_rate=0.4, duty_factor=0.7, samples=200)])
def test_velocity_and_acceleration_match_central_differences(robot, gait, central_differences):
    """v ≈ pin.difference(q(t−h), q(t+h)) / 2h and a ≈ (v(t+h) − v(t−h)) / 2h, error ~h²."""
    t = np.arange(gait.samples) * gait.period / gait.samples
    motion, errors = central_differences(robot, gait, t)
    (ev1, ea1), (ev2, ea2) = errors
    assert ev1 < 1e-3 * np.abs(motion.v).max() and ea1 < 1e-2 * np.abs(motion.a).max()
    assert 3.5 < ev1 / ev2 < 4.5 and 3.5 < ea1 / ea2 < 4.5


def test_motion_is_periodic(robot, walk):
    """Sample T (t = period) equals sample 0 shifted by one stride."""
    end = sample_gait(robot, None, np.array([walk.period]))
    assert np.allclose(end.q[0, 7:], walk.q[0, 7:], atol=1e-12)
    assert np.allclose(end.q[0, :3], walk.q[0, :3] + [0.06, 0.0, 0.0], atol=1e-12)
    assert np.allclose(end.v[0], walk.v[0], atol=1e-12)
    assert np.allclose(end.a[0], walk.a[0], atol=1e-10)
    assert np.array_equal(end.stance[0], walk.stance[0])
    assert np.allclose(end.feet[0], walk.feet[0] + [0.06, 0.0, 0.0], atol=1e-12)


def test_turning_motion_is_periodic_up_to_a_rigid_motion(robot, turn):
    gait = GaitParams(**{**turn.info["gait"], "samples": 400})
    end = sample_gait(robot, gait, np.array([turn.period]))
    assert np.allclose(end.q[0, 7:], turn.q[0, 7:], atol=1e-12)
    m0 = pin.XYZQUATToSE3(turn.q[0, :7])
    m1 = pin.XYZQUATToSE3(end.q[0, :7])
    # One cycle of the constant twist: an arc of length stride, turned by yaw_rate · period.
    twist = pin.Motion(np.array([0.05 / 0.8, 0, 0]), np.array([0, 0, 0.4])) * 0.8
    assert np.allclose((m0 * pin.exp6(twist)).homogeneous, m1.homogeneous, atol=1e-12)
    assert turn.distance == pytest.approx(0.05)


def test_tripods_alternate_and_three_feet_always_stand(robot, walk):
    counts = walk.stance.sum(axis=1)
    assert counts.min() >= 3 and walk.info["min_stance_feet"] == 3
    names = robot.leg_names
    tripod_a = [names.index(n) for n in ("LF", "RM", "LH")]
    tripod_b = [names.index(n) for n in ("RF", "LM", "RH")]
    first = walk.t < 0.5
    assert walk.stance[first][:, tripod_a].all() and not walk.stance[first][:, tripod_b].any()
    assert walk.stance[~first][:, tripod_b].all() and not walk.stance[~first][:, tripod_a].any()
    assert _lift_offs(walk) == 2


def _lift_offs(motion) -> int:
    """Number of lift-offs of one leg per cycle."""
    s = motion.stance[:, 0].astype(int)
    return int(np.sum(np.abs(np.diff(np.r_[s, s[0]]))))


def test_foot_radius_and_body_height_set_the_footholds(robot):
    feet = nominal_footholds(robot, GaitParams(foot_radius=0.2, body_height=0.085))
    assert np.allclose(np.linalg.norm(feet[:, :2], axis=1), 0.2)
    assert np.allclose(feet[:, 2], -0.085)


def test_unreachable_foot_target_names_leg_time_and_distance(robot):
    gait = GaitParams(body_height=0.25, samples=40)
    with pytest.raises(UnreachableTargetError) as err:
        tripod_gait(robot, gait)
    msg = str(err.value)
    m = re.search(r"leg (\w+) at t = ([\d.e+-]+) s: .* ([\d.e+-]+) m out of reach", msg)
    assert m, msg
    assert m.group(1) in robot.leg_names and float(m.group(2)) >= 0.0
    # The femur axis is at the hip height, 0.25 m above the ground; the foot is 0.0789 m out
    # horizontally: distance √(0.0789² + 0.25²) beyond the 0.204 m reach (stance, mid-stride).
    assert 0.0 < float(m.group(3)) <= math.hypot(0.0789 + 0.02, 0.25) - 0.204 + 1e-3


def test_sample_times_must_be_finite(robot):
    with pytest.raises(InvalidParameterError, match="invalid t = "):
        sample_gait(robot, None, np.array([0.0, math.nan]))
    with pytest.raises(InvalidParameterError, match="invalid t = "):
        sample_gait(robot, None, np.array([]))
    assert not sample_gait(robot, None, np.array([0.1, 0.2])).periodic


def test_groups_must_name_every_leg_of_the_robot(robot):
    with pytest.raises(UnknownNameError, match=r"'XX'.*LF"):
        tripod_gait(robot, GaitParams(groups=(("LF", "RM", "LH"), ("RF", "LM", "XX")),
                                      samples=20))
    with pytest.raises(InvalidParameterError, match=r"missing \['RH'\]"):
        tripod_gait(robot, GaitParams(groups=(("LF", "RM", "LH"), ("RF", "LM")), samples=20))


def test_wave_gait_from_six_groups(robot):
    """One leg at a time (β = 5/6): five feet always on the ground."""
    motion = tripod_gait(robot, GaitParams(duty_factor=5 / 6, samples=120,
                                           groups=tuple((n,) for n in robot.leg_names)))
    assert motion.stance.sum(axis=1).min() == 5
    assert motion.info["static_margin"] > 0.05


QUAD_URDF = """<?xml version="1.0"?>
<robot name="quad">
  <link name="base"><inertial><origin xyz="0 0 0"/><mass value="1.5"/>
    <inertia ixx="0.01" iyy="0.03" izz="0.03" ixy="0" ixz="0" iyz="0"/></inertial></link>
{legs}
</robot>
"""
QUAD_LEG = """
  <joint name="{n}_HAA" type="revolute"><origin xyz="{x} {y} 0"/><parent link="base"/>
    <child link="{n}_hip"/><axis xyz="1 0 0"/>
    <limit lower="-3" upper="3" effort="3" velocity="20"/></joint>
  <link name="{n}_hip"><inertial><origin xyz="0 0 0"/><mass value="0.1"/>
    <inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="{n}_HFE" type="revolute"><origin xyz="0 {s} 0"/><parent link="{n}_hip"/>
    <child link="{n}_upper"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="3" velocity="20"/></joint>
  <link name="{n}_upper"><inertial><origin xyz="0 0 -0.08"/><mass value="0.15"/>
    <inertia ixx="3e-4" iyy="3e-4" izz="1e-5" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="{n}_KFE" type="revolute"><origin xyz="0 0 -0.16"/><parent link="{n}_upper"/>
    <child link="{n}_lower"/><axis xyz="0 1 0"/>
    <limit lower="-3" upper="3" effort="3" velocity="20"/></joint>
  <link name="{n}_lower"><inertial><origin xyz="0 0 -0.08"/><mass value="0.05"/>
    <inertia ixx="1e-4" iyy="1e-4" izz="1e-5" ixy="0" ixz="0" iyz="0"/></inertial></link>
  <joint name="{n}_foot_joint" type="fixed"><origin xyz="0 0 -0.16"/><parent link="{n}_lower"/>
    <child link="{n}_foot"/></joint>
  <link name="{n}_foot"/>
"""
QUAD = {"FL": (0.2, 0.1), "FR": (0.2, -0.1), "HL": (-0.2, 0.1), "HR": (-0.2, -0.1)}


@pytest.fixture(scope="module")
def quadruped(tmp_path_factory) -> hexaleg.Robot:
    """A Solo-like quadruped (HAA about x, HFE and KFE about y): not a hexaleg-type leg."""
    d = tmp_path_factory.mktemp("quad")
    legs = "".join(QUAD_LEG.format(n=n, x=x, y=y, s=0.05 * np.sign(y))
                   for n, (x, y) in QUAD.items())
    (d / "quad.urdf").write_text(QUAD_URDF.format(legs=legs))
    pose = "".join(f'<joint name="{n}_{j}" value="{v}"/>' for n in QUAD
                   for j, v in (("HAA", 0.0), ("HFE", 0.8), ("KFE", -1.6)))
    (d / "quad.srdf").write_text(f'<?xml version="1.0"?><robot name="quad">'
                                 f'<group_state name="stand" group="all">{pose}</group_state>'
                                 f'</robot>')
    specs = [LegSpec(n, (f"{n}_HAA", f"{n}_HFE", f"{n}_KFE"), f"{n}_foot") for n in QUAD]
    return load_robot(d / "quad.urdf", d / "quad.srdf", legs=specs)


def test_trot_on_a_quadruped_through_the_same_code(quadruped, frame_kinematics):
    gait = GaitParams(period=0.6, stride_length=0.1, step_height=0.04, samples=60,
                      groups=(("FL", "HR"), ("FR", "HL")))
    motion = tripod_gait(quadruped, gait)
    assert set(motion.info["ik"].values()) == {"newton"}
    assert motion.info["min_stance_feet"] == 2 and motion.info["static_margin"] is None
    pos, vel, acc = frame_kinematics(quadruped, motion)
    assert np.abs(pos - motion.feet).max() <= 1e-9
    assert np.abs(vel[motion.stance]).max() <= 1e-9
    assert np.abs(acc[motion.stance]).max() <= 1e-9
    assert motion.info["body_height"] == pytest.approx(0.32 * math.cos(0.8), rel=1e-9)


# --- IK failures name the leg, the time, the phase, the parameter and a value that works ---


def _reach_error(robot, gait) -> GaitReachError:
    with pytest.raises(GaitReachError) as err:
        tripod_gait(robot, gait)
    assert isinstance(err.value, UnreachableTargetError)  # old `except` clauses still catch it
    return err.value


def _suggested(message: str, name: str) -> float:
    m = re.search(rf"{name} = ([\d.e+-]+) m(/s)? would work", message)
    assert m, message
    return float(m.group(1))


def test_too_high_step_names_step_height_and_a_value_that_works(robot):
    gait = GaitParams(step_height=0.3)
    err = _reach_error(robot, gait)
    msg = str(err)
    m = re.match(r"leg (\w+) at t = ([\d.e+-]+) s: ", msg)
    assert m and m.group(1) == err.leg and m.group(1) in robot.leg_names, msg
    assert float(m.group(2)) == pytest.approx(err.t, abs=1e-5)
    assert "in swing" in msg and err.phase == "swing"
    assert "Most likely cause: step_height = 0.3 m" in msg and err.parameter == "step_height"
    assert err.value == 0.3 and err.distance > 0 and len(err.target) == 3
    value = _suggested(msg, "step_height")
    assert err.suggestion == {"step_height": value} and value == 0.27  # docs/gait.md quotes it
    # The swing's apex is what the leg cannot reach: the failing target is near its top.
    assert err.target[2] + 0.0913 > 0.5 * 0.3
    works = tripod_gait(robot, dataclasses.replace(gait, **err.suggestion))
    assert works.feet[..., 2].max() == pytest.approx(value, abs=1e-9)


def test_too_long_stride_names_stride_length_and_a_value_that_works(robot):
    gait = GaitParams(stride_length=0.6)
    err = _reach_error(robot, gait)
    msg = str(err)
    assert re.match(rf"leg {err.leg} at t = [\d.e+-]+ s: ", msg) and err.leg in robot.leg_names
    assert "stride_length = 0.6 m" in msg and err.parameter == "stride_length"
    assert err.phase in ("stance", "swing") and f"in {err.phase}" in msg
    value = _suggested(msg, "stride_length")
    assert err.suggestion == {"stride_length": value} and value == 0.34  # docs/gait.md
    assert tripod_gait(robot, dataclasses.replace(gait, **err.suggestion)).distance == value
    # Given as a speed, the speed is named (it wins over stride_length).
    fast = _reach_error(robot, GaitParams(speed=0.6))
    assert fast.parameter == "speed" and "speed = 0.6 m/s" in str(fast)
    assert fast.suggestion == {"speed": _suggested(str(fast), "speed")} == {"speed": 0.34}
    tripod_gait(robot, GaitParams(speed=fast.suggestion["speed"]))


@pytest.mark.parametrize(("name", "given", "word", "works"), [
    ("body_height", 0.25, "the body too high", 0.18),
    ("body_height", 0.01, "the body too low", 0.012),
    ("foot_radius", 0.35, "the footholds too far out", 0.27)])
def test_body_out_of_the_legs_range_names_the_size(robot, name, given, word, works):
    """The values docs/gait.md quotes."""
    gait = GaitParams(**{name: given})
    err = _reach_error(robot, gait)
    assert err.parameter == name and word in str(err)
    value = _suggested(str(err), name)
    assert err.suggestion == {name: value} and value == works
    tripod_gait(robot, dataclasses.replace(gait, **err.suggestion))


def test_stand_pose_with_straight_legs_is_named_with_a_bent_knee_stand(robot):
    straight = dataclasses.replace(robot, poses=dict(robot.poses))
    zero = robot.pose("zero")
    zero[:7] = [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 1.0]
    straight.poses["stand"] = zero
    err = _reach_error(straight, GaitParams())
    msg = str(err)
    assert err.parameter == "stand" and err.value is None
    assert "Cause: the stand pose: its legs are at the edge of their workspace" in msg
    assert "Bend the knees" in msg and "stand = {body_height = " in msg
    assert err.suggestion == {"body_height": 0.108, "foot_radius": 0.17}  # docs/gait.md
    walk = tripod_gait(straight, GaitParams(**err.suggestion))
    assert walk.info["body_height"] == err.suggestion["body_height"]
    # The suggested stand has the feet on the suggested footholds, knees bent.
    feet = straight.foot_positions(err.stand)
    assert np.allclose(feet, nominal_footholds(straight, GaitParams(**err.suggestion)),
                       atol=1e-9)
    assert np.all(np.abs(err.stand[9::3]) > 0.5)  # tibia angles


def test_without_a_stand_problem_straight_legs_are_not_blamed(robot):
    """A given body height and foot radius do not come from the stand: no stand diagnosis."""
    err = _reach_error(robot, GaitParams(step_height=0.3, body_height=0.09, foot_radius=0.19))
    assert err.parameter == "step_height"


@pytest.mark.parametrize("kind", ["step", "stand"])
def test_newton_legs_get_the_same_diagnosis(quadruped, kind):
    """A trot on the quadruped (Newton IK, balanced by a sway): the suggestion still works."""
    gait = GaitParams(period=0.6, stride_length=0.1, step_height=0.04, samples=60,
                      groups=(("FL", "HR"), ("FR", "HL")))
    robot = quadruped
    if kind == "step":
        gait = dataclasses.replace(gait, step_height=0.4)
    else:
        robot = dataclasses.replace(quadruped, poses=dict(quadruped.poses))
        robot.poses["stand"] = pin.neutral(quadruped.model)  # legs straight down
    err = _reach_error(robot, gait)
    assert err.parameter == ("step_height" if kind == "step" else "stand"), str(err)
    assert err.suggestion
    motion = tripod_gait(robot, dataclasses.replace(gait, **err.suggestion))
    assert motion.info["balance"]["mode"] == "sway"


# --- Gaits walk along the robot's heading ---


@pytest.mark.parametrize("which", ["walk", "turn"])
def test_a_robot_facing_another_way_walks_the_same_gait_along_its_heading(robot, which,
                                                                           request, rotated):
    motion = request.getfixturevalue(which)
    gait = GaitParams(**motion.info["gait"])
    turned = rotated(robot, math.pi / 2)
    assert np.allclose(turned.heading, [0.0, 1.0, 0.0])
    other = tripod_gait(turned, gait)
    rot = pin.rpy.rpyToMatrix(0.0, 0.0, math.pi / 2)
    assert np.abs(other.q[:, 7:] - motion.q[:, 7:]).max() < 1e-9  # the same joint motion
    assert np.abs(other.v[:, 6:] - motion.v[:, 6:]).max() < 1e-8
    assert np.abs(other.a[:, 6:] - motion.a[:, 6:]).max() < 1e-6
    assert np.allclose(other.q[:, :3], motion.q[:, :3] @ rot.T, atol=1e-12)  # turned path
    assert np.allclose(other.q[:, 3:7], motion.q[:, 3:7], atol=1e-15)  # same yaw
    assert np.allclose(other.v[:, :3], motion.v[:, :3] @ rot.T, atol=1e-12)
    assert np.allclose(other.feet, motion.feet @ rot.T, atol=1e-12)
    assert other.info["static_margin"] == pytest.approx(motion.info["static_margin"], abs=1e-9)


def test_heading_sideways_moves_the_base_along_it_with_feet_at_rest(robot, frame_kinematics):
    sideways = dataclasses.replace(robot, heading=np.array([0.0, 1.0, 0.0]))
    gait = GaitParams(samples=200)
    motion = tripod_gait(sideways, gait)
    end = sample_gait(sideways, gait, np.array([gait.period]))
    assert np.allclose(end.q[0, :3] - motion.q[0, :3], [0.0, 0.06, 0.0], atol=1e-12)
    assert np.allclose(motion.v[:, :6], [0.0, 0.06, 0.0, 0.0, 0.0, 0.0])
    pos, vel, acc = frame_kinematics(sideways, motion)
    assert np.abs(pos - motion.feet).max() <= 1e-9
    assert np.abs(vel[motion.stance]).max() <= 1e-9 and np.abs(acc[motion.stance]).max() <= 1e-9
    # LF stands on [0, T/2), swings, and touches down at t = T one stride further along +y.
    assert motion.stance[0, 0] and not motion.stance[-1, 0] and end.stance[0, 0]
    assert np.allclose(end.feet[0, 0] - motion.feet[0, 0], [0.0, 0.06, 0.0], atol=1e-12)
    limit = robot.model.velocityLimit[6:]
    assert np.all(np.abs(motion.v[:, 6:]) <= limit)
    # Not the forward gait: the legs move differently.
    assert np.abs(motion.q[:, 7:] - tripod_gait(robot, gait).q[:, 7:]).max() > 0.05


def test_a_bad_heading_is_refused(robot):
    upward = dataclasses.replace(robot)
    upward.heading = np.array([0.0, 0.0, 1.0])  # set after loading: not checked by Robot
    with pytest.raises(InvalidParameterError, match="invalid heading"):
        tripod_gait(upward, GaitParams(samples=20))


@pytest.mark.slow
def test_an_arm_given_a_motion_swings_through_the_gait_and_its_own_actuator_counts_it(
        tmp_path):
    """Issue #55's description key ``moves``: the wheeled test robot's arm pitch swings
    0.3 rad each cycle of its trot. Its torque in the analysis is Pinocchio's RNEA of the whole
    tree, and the analytic forearm: a leaf link (0.15 kg, centre 0.08 m out, I_yy 1.2e-4 kg·m²)
    pitching about a horizontal axis on a base that translates without turning,
    τ = I_o θ̈ + m (r_c × (a_pivot − g))_y, I_o = I_yy + m l² (parallel axes), r_c = l (cos θ,
    0, −sin θ); its own actuator draws energy for it, more than holding it still. ~3 s of CPU
    (two gaits of the wheeled robot)."""
    path = Path(__file__).resolve().parents[1] / "data" / "wheeled.toml"
    text = path.read_text().replace('urdf = "wheeled.urdf"',
                                    f'urdf = "{path.with_suffix(".urdf")}"')
    (tmp_path / "held.toml").write_text(text)
    (tmp_path / "w.toml").write_text(text.replace(
        "[robot]\n", "[robot]\nmoves = {arm_pitch = {amplitude = 0.3, phase = 0.5}}\n"))
    runs = {name: hexaleg.Scenario.load(str(tmp_path / f"{name}.toml")) for name in ("held", "w")}
    run = runs["w"]
    robot, motion = run.model, run.motion()
    analysis = run.prepare().evaluate(hexaleg.SpringSet(), "joule")
    model = robot.model
    joint = model.joints[model.getJointId("arm_pitch")]
    column = robot.joint_names.index("arm_pitch")
    theta, alpha = motion.q[:, joint.idx_q], motion.a[:, joint.idx_v]
    assert np.ptp(theta) == pytest.approx(0.6, rel=1e-3)
    data = model.createData()
    rnea = np.array([pin.rnea(model, data, q, v, a)[joint.idx_v]
                     for q, v, a in zip(motion.q, motion.v, motion.a, strict=True)])
    np.testing.assert_allclose(analysis.tau_motor[:, column], rnea, atol=1e-10)
    assert np.abs(motion.v[:, 3:6]).max() < 1e-12 and np.abs(motion.q[:, 3:6]).max() < 1e-12
    m, lever, i_yy, g = 0.15, 0.08, 1.2e-4, 9.81
    a_pivot = motion.a[:, :3]  # the base translates: its acceleration is the pivot's
    analytic = ((i_yy + m * lever ** 2) * alpha
                + m * (-lever * np.sin(theta) * a_pivot[:, 0]
                       - lever * np.cos(theta) * (a_pivot[:, 2] + g)))
    np.testing.assert_allclose(analysis.tau_motor[:, column], analytic, atol=1e-12)
    held = runs["held"].prepare().evaluate(hexaleg.SpringSet(), "joule")
    energy = analysis.metrics["joint"]["electrical"][column]
    assert energy > held.metrics["joint"]["electrical"][column] > 0
