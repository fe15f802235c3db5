"""Tests of hexaleg.motion.leg_chain (a leg's forward kinematics over a stack of samples):
Pinocchio is the independent reference, for legs of three joints (one prismatic), and four (a
redundant leg); the bias acceleration is also checked by central differences. The inverse
kinematics on the chain is tests/motion/test_leg_ik.py's."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import RobotModelError
from hexaleg.motion.leg_chain import leg_chain
from hexaleg.robot.model import Leg, LegSpec, load_robot

_INERTIAL = ('<inertial><mass value="0.1"/><inertia ixx="1e-4" iyy="1e-4" izz="1e-4" ixy="0" '
             'ixz="0" iyz="0"/></inertial>')
POGO = f"""<robot name="pogo">
<link name="base">{_INERTIAL}</link><link name="hip">{_INERTIAL}</link>
<link name="thigh">{_INERTIAL}</link><link name="shank">{_INERTIAL}</link><link name="foot"/>
<joint name="abad" type="revolute"><parent link="base"/><child link="hip"/>
 <origin xyz="0.1 0.05 0" rpy="0 0 0.3"/><axis xyz="1 0 0"/>
 <limit lower="-1" upper="1" effort="10" velocity="10"/></joint>
<joint name="flex" type="revolute"><parent link="hip"/><child link="thigh"/>
 <origin xyz="0 0.03 0" rpy="0.1 0 0"/><axis xyz="0 1 0"/>
 <limit lower="-2" upper="2" effort="10" velocity="10"/></joint>
<joint name="slide" type="prismatic"><parent link="thigh"/><child link="shank"/>
 <origin xyz="0 0 -0.15" rpy="0 0.2 0"/><axis xyz="0 0 -1"/>
 <limit lower="0" upper="0.1" effort="10" velocity="1"/></joint>
<joint name="ankle" type="fixed"><parent link="shank"/><child link="foot"/>
 <origin xyz="0.01 0 -0.05"/></joint>
</robot>"""
"""One leg with a telescopic shank: abduction, flexion and a prismatic joint (the chain's
linear axes), every placement turned."""


@pytest.fixture(scope="module")
def pogo(tmp_path_factory: pytest.TempPathFactory) -> hexaleg.Robot:
    path = Path(tmp_path_factory.mktemp("pogo")) / "pogo.urdf"
    path.write_text(POGO)
    return load_robot(path, legs=[LegSpec("LF", ("abad", "flex", "slide"), "foot")],
                              joint_kinds=("abad", "flex", "slide"))


def _reference(robot: hexaleg.Robot) -> np.ndarray:
    q = robot.pose("stand") if "stand" in robot.poses else pin.neutral(robot.model)
    q[:7] = pin.neutral(robot.model)[:7]
    return q


def _pinocchio(robot: hexaleg.Robot, leg: Leg, q_leg: np.ndarray,
               qd_leg: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The foot's position, translation Jacobian and classical acceleration at zero joint
    acceleration, from Pinocchio, every other joint at the reference pose."""
    model, data = robot.model, robot.model.createData()
    q, v = _reference(robot), np.zeros(model.nv)
    q[leg.q_index], v[leg.v_index] = q_leg, qd_leg
    pin.forwardKinematics(model, data, q, v, np.zeros(model.nv))
    pin.updateFramePlacements(model, data)
    fid = leg.foot_frame_id
    acc = pin.getFrameClassicalAcceleration(model, data, fid, pin.LOCAL_WORLD_ALIGNED).linear
    jac = pin.computeFrameJacobian(model, data, q, fid, pin.LOCAL_WORLD_ALIGNED)[:3, leg.v_index]
    return data.oMf[fid].translation.copy(), jac, acc


@pytest.mark.parametrize("which", ["a1", "pogo", "quad4dof"])
def test_chain_equals_pinocchio(which, request):
    robot = request.getfixturevalue(which)
    rng = np.random.default_rng(3)
    for leg in robot.legs:
        chain = leg_chain(robot, leg, _reference(robot))
        n = len(leg.joint_ids)
        q = _reference(robot)[leg.q_index] + rng.uniform(-0.05, 0.05, (20, n))
        qd = rng.normal(size=(20, n))
        p, jac = chain.position_jacobian(q)
        bias = chain.bias(q, qd)
        for k in range(20):
            p_ref, jac_ref, acc_ref = _pinocchio(robot, leg, q[k], qd[k])
            assert np.abs(p[k] - p_ref).max() < 1e-14
            assert np.abs(jac[k] - jac_ref).max() < 1e-14
            assert np.abs(bias[k] - acc_ref).max() < 1e-13


def test_bias_is_the_derivative_of_the_jacobian_along_the_motion(pogo):
    leg = pogo.legs[0]
    chain = leg_chain(pogo, leg, _reference(pogo))
    q, qd, h = np.array([[0.2, -0.4, 0.05]]), np.array([[1.3, -0.7, 0.4]]), 1e-6
    fd = (chain.position_jacobian(q + h * qd)[1] - chain.position_jacobian(q - h * qd)[1]) / (2 * h)
    assert np.allclose(chain.bias(q, qd), (fd @ qd[..., None])[..., 0], atol=1e-8)
    wrong = chain.bias(q, qd) - (fd @ qd[..., None])[..., 0]
    assert np.abs(wrong).max() < 1e-8  # the check has teeth: J̇q̇ is ~1 m/s² here
    assert np.abs(chain.bias(q, qd)).max() > 0.1


def test_a_leg_that_is_not_one_chain_is_named(a1):
    leg = a1.leg("LF")
    joints = ("FL_hip_joint", "FR_thigh_joint", "FL_calf_joint")
    crossed = dataclasses.replace(leg, joint_names=joints,
                                  joint_ids=tuple(a1.model.getJointId(j) for j in joints))
    with pytest.raises(RobotModelError,
                       match="FR_thigh_joint does not hang below joint FL_hip_joint"):
        leg_chain(a1, crossed, _reference(a1))


def test_a_joint_newton_cannot_move_is_named(tmp_path):
    path = tmp_path / "wheel.urdf"
    path.write_text(POGO.replace('type="prismatic"', 'type="continuous"'))
    robot = load_robot(path, legs=[LegSpec("LF", ("abad", "flex", "slide"), "foot")],
                               joint_kinds=("abad", "flex", "slide"))
    with pytest.raises(RobotModelError, match=r"joint slide is a JointModelRevoluteUnbounded"
                                              r".*\(2 configuration values, 1 velocities\)"):
        leg_chain(robot, robot.legs[0], _reference(robot))


def test_a_redundant_leg_stretched_at_its_stand_is_named(quad4dof):
    """At the zero configuration the four-joint leg hangs straight: the foot Jacobian loses rank
    and the redundant directions are not defined; the chain says so instead of solving."""
    q = pin.neutral(quad4dof.model)
    with pytest.raises(RobotModelError, match=r"leg LF: at the stand pose .* stretched or folded"):
        leg_chain(quad4dof, quad4dof.leg("LF"), q)


def test_a_sole_leg_holds_its_foots_orientation_and_a_three_joint_one_cannot():
    """biped6's leg: the rows span the foot's angular Jacobian (Pinocchio's, at the stand) and
    turn it by θ through S⁻¹Uᵀ; the point-foot biped's three joints given a sole are named."""
    from hexaleg.robot.description import read_description
    from hexaleg.robot.soles import Sole

    data = Path(__file__).parents[1] / "data"
    robot = read_description(data / "biped6.toml").load()
    leg = robot.legs[1]
    stand = robot.pose("stand")
    chain = leg_chain(robot, leg, stand)
    assert chain.sole and chain.redundant.shape == (6, 3)
    pdata = robot.model.createData()
    pin.computeJointJacobians(robot.model, pdata, stand)
    pin.updateFramePlacements(robot.model, pdata)
    omega = pin.getFrameJacobian(robot.model, pdata, leg.foot_frame_id,
                                 pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)[3:, leg.v_index]
    theta = np.array([0.01, -0.02, 0.03])
    dq = chain.redundant @ (chain.turn_rows @ theta)  # in the rows' space: J_ω dq = θ
    np.testing.assert_allclose(omega @ dq, theta, atol=1e-14)
    biped = read_description(data / "biped.toml").load()
    biped.soles = {"L1": Sole(0.06, 0.03)}
    with pytest.raises(RobotModelError, match="leg L1 has a sole and 3 joints"):
        leg_chain(biped, biped.legs[0], biped.pose("stand"))


def test_talos_walks_its_sized_gait_on_flat_soles():
    """Data we did not make (example-robot-data's URDF): Talos' legs (hip yaw, roll, pitch,
    knee, ankle pitch, roll) keep both soles flat over its sized ZMP walk (period 2.86 s,
    stride 0.49 m)."""
    from hexaleg.motion.scaling import robot_gait
    from hexaleg.robot.description import read_description

    desc = read_description(Path(__file__).parents[1] / "data" / "talos.toml")
    robot = desc.load()
    gait = dataclasses.replace(robot_gait(desc), samples=50)
    assert gait.period == pytest.approx(2.8632, abs=1e-4)
    assert gait.stride_length == pytest.approx(0.4919, abs=1e-4)
    motion = hexaleg.gait(robot, gait)
    pdata = robot.model.createData()
    for k in range(motion.n_samples):
        pin.framesForwardKinematics(robot.model, pdata, motion.q[k])
        for leg in robot.legs:
            rotation = pdata.oMf[leg.foot_frame_id].rotation
            assert abs(rotation[2, 0]) < 1e-9 and abs(rotation[2, 1]) < 1e-9  # flat


def test_g1s_hip_turning_pitch_roll_yaw_walks_its_soles_flat(tmp_path):
    """Unitree G1 (example-robot-data) on the sole its foot's four contact spheres span: its hip
    turns pitch, roll, then yaw, so its redundant rows hold the foot only to first order (0.04
    rad off flat, refused until Newton held the whole pose); its walk now keeps both soles flat
    (Pinocchio's FK, independent of the chain) at every sample."""
    from hexaleg.motion.scaling import robot_gait
    from hexaleg.robot.description import read_description

    legs = "\n".join(
        f'[[robot.legs]]\nname = "{name}"\njoints = ['
        + ", ".join(f'"{side}_{j}_joint"' for j in ("hip_pitch", "hip_roll", "hip_yaw", "knee",
                                                     "ankle_pitch", "ankle_roll"))
        + f']\nfoot = {{link = "{side}_ankle_roll_link", point = [0.035, 0.0, -0.035]}}'
        for name, side in (("L1", "left"), ("R1", "right")))
    (tmp_path / "g1.toml").write_text(
        '[robot]\nname = "g1"\nsource = "example-robot-data"\n'
        'urdf = "g1_description/urdf/g1_29dof_rev_1_0.urdf"\n'
        'stand = {body_height = 0.68}\ngait = {duty_factor = 0.6}\nsole = [0.17, 0.05]\n'
        + legs + "\n")
    g1 = read_description(tmp_path / "g1.toml")
    robot = g1.load()
    walk = hexaleg.gait(robot, dataclasses.replace(robot_gait(g1), stride_length=0.2,
                                                   step_height=0.05, samples=50))
    data = robot.model.createData()
    for q in walk.q:
        pin.framesForwardKinematics(robot.model, data, q)
        for leg in robot.legs:
            z = data.oMf[leg.foot_frame_id].rotation[2]
            np.testing.assert_allclose(z, [0.0, 0.0, 1.0], atol=1e-12)  # flat
