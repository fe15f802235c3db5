"""Tests of hexaleg.motion.gait: the tripod gait's kinematic consistency (Pinocchio FK, stance feet
at rest, finite differences), periodicity and static stability; the joint sinusoid (paper eq. 16,
25); the stand → sphere transform; parameters from TOML and the errors on bad input."""

from __future__ import annotations

import math
import re

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import (
    ConfigError,
    InvalidParameterError,
    UnknownNameError,
    UnreachableTargetError,
)
from hexaleg.motion.gait import (
    GaitParams,
    Sinusoid,
    gait_summary,
    joint_motion,
    nominal_footholds,
    sample_gait,
    smoothstep,
    swing_bump,
    swing_curve,
    transform_motion,
    tripod_gait,
)
from hexaleg.robot.model import LegSpec


@pytest.fixture(scope="module")
def turn(robot) -> hexaleg.motion.trajectory.Motion:
    """A turning gait with double support (β = 0.7) and a lower body."""
    return tripod_gait(robot, GaitParams(yaw_rate=0.4, duty_factor=0.7, body_height=0.08,
                                         stride_length=0.05, period=0.8, samples=400))


def _frame_kinematics(robot, motion):
    """World position, velocity and classical acceleration (LOCAL_WORLD_ALIGNED) of every foot."""
    data = robot.model.createData()
    shape = (motion.n_samples, len(robot.legs), 3)
    pos, vel, acc = np.empty(shape), np.empty(shape), np.empty(shape)
    for k in range(motion.n_samples):
        pin.forwardKinematics(robot.model, data, motion.q[k], motion.v[k], motion.a[k])
        pin.updateFramePlacements(robot.model, data)
        for i, leg in enumerate(robot.legs):
            fid = leg.foot_frame_id
            pos[k, i] = data.oMf[fid].translation
            vel[k, i] = pin.getFrameVelocity(robot.model, data, fid,
                                             pin.LOCAL_WORLD_ALIGNED).linear
            acc[k, i] = pin.getFrameClassicalAcceleration(robot.model, data, fid,
                                                          pin.LOCAL_WORLD_ALIGNED).linear
    return pos, vel, acc


# --------------------------------------------------------------------------- swing curves


def test_swing_profiles_start_and_stop_at_rest():
    ends = np.array([0.0, 1.0])
    for f in (smoothstep, swing_bump):
        _, d1, d2 = f(ends)
        assert np.allclose(d1, 0.0) and np.allclose(d2, 0.0)
    assert np.allclose(smoothstep(ends)[0], [0.0, 1.0])
    assert np.allclose(swing_bump(ends)[0], [0.0, 0.0])
    assert swing_bump(np.array([0.5]))[0][0] == pytest.approx(1.0)
    s = np.linspace(0.0, 1.0, 201)
    assert np.all(np.diff(smoothstep(s)[0]) >= 0)  # monotone ground track
    assert swing_bump(s)[0].max() == pytest.approx(1.0)


@pytest.mark.parametrize("f", [smoothstep, swing_bump])
def test_swing_profile_derivatives_equal_finite_differences(f):
    s, h = np.linspace(0.05, 0.95, 19), 1e-5
    _, d1, d2 = f(s)
    assert np.allclose((f(s + h)[0] - f(s - h)[0]) / (2 * h), d1, atol=1e-7)
    assert np.allclose((f(s + h)[1] - f(s - h)[1]) / (2 * h), d2, atol=1e-6)


def test_swing_curve_reaches_step_height_midway():
    p0, p1 = np.array([0.1, 0.2, 0.0]), np.array([0.16, 0.2, 0.0])
    p, dp, ddp = swing_curve(np.array([0.0, 0.5, 1.0]), p0, p1, 0.03)
    assert np.allclose(p, [p0, [0.13, 0.2, 0.03], p1])
    assert np.allclose(dp[[0, 2]], 0.0) and np.allclose(ddp[[0, 2]], 0.0)


# --------------------------------------------------------------------------- the tripod gait


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
def test_forward_kinematics_reproduces_every_foot_target(robot, which, request):
    motion = request.getfixturevalue(which)
    pos, _, _ = _frame_kinematics(robot, motion)
    assert np.abs(pos - motion.feet).max() <= 1e-9
    assert np.abs(motion.feet[..., 2][motion.stance]).max() <= 1e-12  # stance feet on the ground
    assert np.all(motion.feet[..., 2][~motion.stance] >= 0.0)  # 0 only at lift-off


@pytest.mark.parametrize("which", ["walk", "turn"])
def test_stance_feet_have_zero_velocity_and_acceleration(robot, which, request):
    """Pinocchio's frame velocity and classical acceleration of q, v, a: proves v, a match q."""
    motion = request.getfixturevalue(which)
    _, vel, acc = _frame_kinematics(robot, motion)
    assert np.abs(vel[motion.stance]).max() <= 1e-9
    assert np.abs(acc[motion.stance]).max() <= 1e-9
    # Swing feet really move (the check above is not vacuous).
    assert np.abs(vel[~motion.stance]).max() > 0.1


def test_swing_apex_is_the_step_height(walk):
    assert walk.feet[..., 2].max() == pytest.approx(0.03, abs=1e-9)


@pytest.mark.parametrize("gait", [GaitParams(samples=200),
                                  GaitParams(yaw_rate=0.4, duty_factor=0.7, samples=200)])
def test_velocity_and_acceleration_match_central_differences(robot, gait):
    """v ≈ pin.difference(q(t−h), q(t+h)) / 2h and a ≈ (v(t+h) − v(t−h)) / 2h, error ~h²."""
    t = np.arange(gait.samples) * gait.period / gait.samples
    motion = sample_gait(robot, gait, t)
    errors = []
    for h in (2e-3, 1e-3):
        plus, minus = sample_gait(robot, gait, t + h), sample_gait(robot, gait, t - h)
        dq = np.array([pin.difference(robot.model, qm, qp)
                       for qm, qp in zip(minus.q, plus.q, strict=True)]) / (2 * h)
        dv = (plus.v - minus.v) / (2 * h)
        errors.append((np.abs(dq - motion.v).max(), np.abs(dv - motion.a).max()))
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


def _inside_margin(points: np.ndarray, c: np.ndarray) -> float:
    """Signed distance of c inside the triangle ``points`` (3, 2) (independent check)."""
    a, b, d = points
    if (b[0] - a[0]) * (d[1] - a[1]) - (b[1] - a[1]) * (d[0] - a[0]) < 0:
        b, d = d, b
    out = []
    for p, q in ((a, b), (b, d), (d, a)):
        e = q - p
        out.append((e[0] * (c[1] - p[1]) - e[1] * (c[0] - p[0])) / np.linalg.norm(e))
    return min(out)


def test_com_stays_inside_each_tripod_and_margin_is_reported(robot, walk):
    data = robot.model.createData()
    margins = []
    for k in range(0, walk.n_samples, 10):
        com = pin.centerOfMass(robot.model, data, walk.q[k])
        margins.append(_inside_margin(walk.feet[k, walk.stance[k], :2], com[:2]))
    assert min(margins) > 0.05
    assert walk.info["static_margin"] == pytest.approx(min(margins), abs=1e-6)
    # The worst instant is a contact switch, the CoM β·stride/2 = 0.015 m from mid-stance: the
    # inradius R/2 of the equilateral tripod less 0.015·cos 30° towards a slanted edge.
    assert walk.info["static_margin_t"] in (0.0, 0.5)
    radius = walk.info["foot_radius"]
    assert walk.info["static_margin"] == pytest.approx(
        radius / 2 - 0.5 * 0.06 / 2 * math.cos(math.radians(30)), rel=1e-4)


def test_in_place_margin_is_the_inradius_of_the_tripod(robot):
    """Stride 0: the CoM stays on the axis of symmetry; an equilateral tripod of circumradius R
    has inradius R/2."""
    motion = tripod_gait(robot, GaitParams(stride_length=0.0, samples=100))
    assert motion.info["static_margin"] == pytest.approx(motion.info["foot_radius"] / 2, rel=1e-6)
    assert np.allclose(motion.q[:, :3], motion.q[0, :3])


def test_speed_wins_over_stride(robot):
    gait = GaitParams(period=0.5, stride_length=0.06, speed=0.1, samples=50)
    assert gait.stride == pytest.approx(0.05) and gait.velocity == pytest.approx(0.1)
    motion = tripod_gait(robot, gait)
    assert motion.distance == pytest.approx(0.05)
    assert np.allclose(motion.q[:, 0], 0.1 * motion.t)


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


@pytest.mark.parametrize(("kwargs", "name"), [
    ({"duty_factor": 0.4}, "duty_factor"),
    ({"duty_factor": 1.0}, "duty_factor"),
    ({"period": 0.0}, "period"),
    ({"period": -1.0}, "period"),
    ({"period": math.nan}, "period"),
    ({"step_height": 0.0}, "step_height"),
    ({"step_height": -0.01}, "step_height"),
    ({"samples": 5}, "samples"),
    ({"samples": 100.0}, "samples"),
    ({"stride_length": -0.1}, "stride_length"),
    ({"body_height": 0.0}, "body_height"),
    ({"groups": (("LF", "RM"), ("LF", "RH"))}, "groups"),
])
def test_bad_gait_parameters_are_rejected(kwargs, name):
    with pytest.raises(InvalidParameterError, match=rf"invalid {name} = .*allowed: ") as err:
        GaitParams(**kwargs)
    assert isinstance(err.value, hexaleg.HexalegError)


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


def test_gait_params_from_toml(tmp_path):
    path = tmp_path / "gait.toml"
    path.write_text('[gait]\nperiod = 2\nduty_factor = 0.75\nstep_height = 0.02\n'
                    'groups = [["LF"], ["RF"], ["LM"], ["RM"], ["LH"], ["RH"]]\n')
    gait = GaitParams.from_toml(path)
    assert gait.period == 2.0 and gait.duty_factor == 0.75 and gait.step_height == 0.02
    assert gait.groups[2] == ("LM",) and len(gait.groups) == 6
    assert GaitParams.from_toml({"speed": 0.05}).stride == pytest.approx(0.05)
    with pytest.raises(UnknownNameError, match=r"'stride'.*stride_length"):
        GaitParams.from_toml({"stride": 0.05})
    with pytest.raises(ConfigError, match="period"):
        GaitParams.from_toml({"period": "fast"})
    with pytest.raises(ConfigError, match="not found"):
        GaitParams.from_toml(tmp_path / "missing.toml")


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
    return hexaleg.load_robot(d / "quad.urdf", d / "quad.srdf", legs=specs)


def test_trot_on_a_quadruped_through_the_same_code(quadruped):
    gait = GaitParams(period=0.6, stride_length=0.1, step_height=0.04, samples=60,
                      groups=(("FL", "HR"), ("FR", "HL")))
    motion = tripod_gait(quadruped, gait)
    assert set(motion.info["ik"].values()) == {"newton"}
    assert motion.info["min_stance_feet"] == 2 and motion.info["static_margin"] is None
    pos, vel, acc = _frame_kinematics(quadruped, motion)
    assert np.abs(pos - motion.feet).max() <= 1e-9
    assert np.abs(vel[motion.stance]).max() <= 1e-9
    assert np.abs(acc[motion.stance]).max() <= 1e-9
    assert motion.info["body_height"] == pytest.approx(0.32 * math.cos(0.8), rel=1e-9)


def test_summary_reports_margin_and_joint_peaks(robot, walk):
    text = gait_summary(robot, walk)
    assert f"static margin {walk.info['static_margin']:.4f} m" in text
    row = next(line for line in text.splitlines() if line.startswith("LF_femur"))
    col = robot.column("LF_femur")
    assert f"{np.abs(walk.v[:, 6 + col]).max():.3f}" in row
    assert f"{math.degrees(walk.q[:, 7 + col].max()):.1f}" in row
    assert len(text.splitlines()) == 4 + robot.nj


# --------------------------------------------------------------------------- joint sinusoids


def test_joint_motion_embeds_the_papers_sinusoid(robot):
    """Paper eq. 25: f(t) = 0.3 sin(2t), with exact derivatives, other joints at stand."""
    motion = joint_motion(robot, {"LF_femur": Sinusoid(amplitude=0.3, omega=2.0)}, samples=400)
    col = robot.column("LF_femur")
    t = motion.t
    assert motion.period == pytest.approx(math.pi) and motion.periodic
    assert motion.fixed_base and not motion.stance.any() and motion.distance == 0.0
    assert np.allclose(motion.q[:, 7 + col], 0.3 * np.sin(2 * t))
    assert np.allclose(motion.v[:, 6 + col], 0.6 * np.cos(2 * t))
    assert np.allclose(motion.a[:, 6 + col], -1.2 * np.sin(2 * t))
    others = np.delete(np.arange(robot.nj), col)
    assert np.allclose(motion.q[:, 7 + others], robot.pose("stand")[7 + others])
    assert np.allclose(motion.v[:, 6 + others], 0) and np.allclose(motion.a[:, 6 + others], 0)
    assert np.allclose(motion.feet[7], robot.foot_positions(motion.q[7]))


def test_sinusoid_derivatives_equal_central_differences():
    f = Sinusoid(amplitude=0.4, omega=3.0, phase=0.5, offset=0.2)
    t, h = np.linspace(0.0, 2.0, 17), 1e-5
    value, d1, d2 = f(t)
    assert np.allclose((f(t + h)[0] - f(t - h)[0]) / (2 * h), d1, atol=1e-8)
    assert np.allclose((f(t + h)[1] - f(t - h)[1]) / (2 * h), d2, atol=1e-7)
    assert value[0] == pytest.approx(0.4 * math.sin(0.5) + 0.2)


def test_joint_motion_errors(robot):
    with pytest.raises(UnknownNameError, match=r"'LF_knee'.*LF_femur"):
        joint_motion(robot, {"LF_knee": Sinusoid(0.3, 2.0)})
    with pytest.raises(InvalidParameterError, match="period"):
        joint_motion(robot, {"LF_femur": Sinusoid(0.3, 2.0), "RF_femur": Sinusoid(0.3, 3.0)})
    with pytest.raises(InvalidParameterError, match="samples"):
        joint_motion(robot, {"LF_femur": Sinusoid(0.3, 2.0)}, samples=3)
    with pytest.raises(InvalidParameterError, match=r"LF_femur.*joint limits"):
        joint_motion(robot, {"LF_femur": Sinusoid(3.0, 2.0)})
    with pytest.raises(InvalidParameterError, match=r"Sinusoid\.omega"):
        Sinusoid(0.3, math.inf)
    two = joint_motion(robot, {"LF_femur": Sinusoid(0.3, 2.0), "RF_femur": Sinusoid(0.3, 3.0)},
                       period=2 * math.pi, samples=100)
    assert two.periodic
    assert not joint_motion(robot, {"LF_femur": Sinusoid(0.3, 2.0)}, period=1.0).periodic


# --------------------------------------------------------------------------- hexapod → sphere


@pytest.fixture(scope="module")
def fold(robot) -> hexaleg.motion.trajectory.Motion:
    return transform_motion(robot, duration=2.0, samples=401)


def test_transform_sits_down_on_its_feet_then_folds_resting_on_the_ground(robot, fold):
    sit = ~fold.supported
    n_sit = int(sit.sum())
    assert n_sit == 100 and sit[:n_sit].all()  # t < 0.25 · 2 s at dt = 5 ms
    # Starts standing: the stand pose with the feet on the ground; ends in the sphere pose.
    h0 = fold.info["stand_height"]
    assert h0 == pytest.approx(-robot.foot_positions(robot.pose("stand"))[:, 2].min(), abs=1e-15)
    assert np.allclose(fold.q[0, 7:], robot.pose("stand")[7:]) and fold.q[0, 2] == h0
    assert np.allclose(fold.q[-1, 7:], robot.pose("sphere")[7:])
    # The sphere rests on its lowest point, the lower body dome: in urdf/hexaleg.urdf a sphere
    # of radius 0.07 m centred 0.0135 m below the base.
    assert fold.info["rest_height"] == pytest.approx(0.0135 + 0.07, abs=1e-12)
    assert fold.info["clearance"] == pytest.approx(0.0, abs=1e-12)
    # Sitting: all six feet stand still on the ground and carry the body down vertically.
    assert fold.stance[:n_sit].all() and not fold.stance[n_sit:].any()
    pos, vel, acc = _frame_kinematics(robot, fold)
    assert np.abs(pos - fold.feet).max() <= 1e-9
    assert np.abs(pos[:n_sit] - pos[0]).max() <= 1e-9
    assert np.abs(pos[:n_sit, :, 2]).max() <= 1e-12
    assert np.abs(vel[:n_sit]).max() <= 1e-9 and np.abs(acc[:n_sit]).max() <= 1e-9
    assert np.abs(fold.q[:n_sit, [0, 1, 3, 4, 5]]).max() == 0.0  # straight down, no tilt
    assert np.all(np.diff(fold.q[:n_sit, 2]) <= 0.0)
    # Folding: the body rests (base still at the resting height), feet lift off and stay up.
    assert np.allclose(fold.q[n_sit:, :7], fold.q[-1, :7], atol=0.0)
    assert fold.q[-1, 2] == fold.info["rest_height"]
    assert np.abs(fold.v[n_sit:, :6]).max() == 0.0 and np.abs(fold.a[n_sit:, :6]).max() == 0.0
    assert np.all(fold.feet[n_sit + 1:, :, 2] > 0.0)
    assert np.abs(vel[n_sit:]).max() > 0.05  # the legs really move (feet at up to 0.077 m/s)


def test_transform_never_passes_below_the_ground(robot, fold):
    """Every geometry but the foot balls (the feet are their points) stays at z ≥ 0 all along,
    and the body touches the ground exactly while folding."""
    feet = [robot.model.frames[leg.foot_frame_id].name for leg in robot.legs]
    z, names = robot.lowest_points(fold.q, ignore=feet)
    assert z.min() >= -1e-12
    assert np.abs(z[fold.supported]).max() <= 1e-12
    assert set(np.asarray(names)[fold.supported]) == {"body_1"}
    assert fold.feet[..., 2].min() >= -1e-12


def test_transform_is_smooth_across_the_phase_switch(robot, fold):
    """Zero velocity and acceleration at both ends and at the switch; v and a are the time
    derivatives of q and v (central differences, interior samples, both phases)."""
    n_sit = int((~fold.supported).sum())
    assert fold.t[n_sit] == fold.info["sit_time"]  # the fold starts on a sample, at rest
    for k in (0, n_sit, fold.n_samples - 1):
        assert np.abs(fold.v[k]).max() == 0.0 and np.abs(fold.a[k]).max() == 0.0
    # ... and the sit ends at rest: one sample before the switch, v and a have almost vanished.
    assert np.abs(fold.v[n_sit - 1]).max() < 1e-3 * np.abs(fold.v).max()
    assert np.abs(fold.a[n_sit - 1]).max() < 3e-2 * np.abs(fold.a).max()
    assert fold.t[-1] == pytest.approx(2.0) and fold.period == 2.0 and not fold.periodic
    dt = fold.dt
    dq = np.array([pin.difference(robot.model, a, b)
                   for a, b in zip(fold.q[:-2], fold.q[2:], strict=True)]) / (2 * dt)
    assert np.abs(dq - fold.v[1:-1]).max() < 1e-3 * np.abs(fold.v).max()
    assert np.abs((fold.v[2:] - fold.v[:-2]) / (2 * dt) - fold.a[1:-1]).max() \
        < 1e-2 * np.abs(fold.a).max()


def test_transform_errors(robot):
    with pytest.raises(InvalidParameterError, match="duration"):
        transform_motion(robot, duration=0.0)
    with pytest.raises(UnknownNameError, match=r"'ball'.*sphere"):
        transform_motion(robot, end="ball")
    with pytest.raises(InvalidParameterError, match=r"rest_height.*\(0, 0\.0913\]"):
        transform_motion(robot, rest_height=-0.1)
    with pytest.raises(InvalidParameterError, match="cannot rise"):
        transform_motion(robot, rest_height=0.2)
    # Seated too low, the body dome would have to sink into the ground: named, with the depth.
    with pytest.raises(InvalidParameterError, match=r"body_1 reaches 33\.50 mm below"):
        transform_motion(robot, rest_height=0.05)
    with pytest.raises(InvalidParameterError, match="sit_fraction"):
        transform_motion(robot, sit_fraction=1.0)
    with pytest.raises(InvalidParameterError, match=r"two samples in each phase \(sit 1"):
        transform_motion(robot, samples=20, sit_fraction=0.01)


def test_supported_samples_are_checked_by_motion(robot, fold):
    fields = {f: getattr(fold, f) for f in ("t", "q", "v", "a", "stance", "feet", "period")}
    with pytest.raises(InvalidParameterError, match=r"Motion\.supported.*shape \(3,\)"):
        hexaleg.Motion(**fields, supported=np.ones(3, dtype=bool))
    with pytest.raises(InvalidParameterError, match=r"sample 0 .*feet are in stance"):
        hexaleg.Motion(**fields, supported=np.ones(fold.n_samples, dtype=bool))
    with pytest.raises(InvalidParameterError, match="fixed-base"):
        hexaleg.Motion(**{**fields, "stance": np.zeros_like(fold.stance)}, fixed_base=True,
                       supported=fold.supported)
    assert hexaleg.Motion(**{**fields, "stance": np.zeros_like(fold.stance)},
                          fixed_base=True).supported.all()


def test_updated_puts_a_tables_keys_over_a_gait():
    base = GaitParams(period=0.5, stride_length=0.08, samples=400)
    new = base.updated({"period": 2, "step_height": 0.02})
    assert (new.period, new.step_height) == (2.0, 0.02)
    assert (new.stride_length, new.samples) == (0.08, 400)  # untouched keys keep base's values
    with pytest.raises(UnknownNameError, match="'periode'"):
        base.updated({"periode": 1.0})
