"""Tests of hexaleg.motion.kinematics: the analytic leg IK against Pinocchio, its exact derivatives,
the Newton fallback, and the unreachable-target errors."""

from __future__ import annotations

import math
import re

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.errors import UnreachableTargetError
from hexaleg.motion.kinematics import (
    LegGeometry,
    analytic_geometry,
    analytic_leg_ik,
    leg_ik,
)
from hexaleg.motion.leg_ik import newton_leg_ik
from hexaleg.robot.builder import load_params
from hexaleg.robot.model import HEXALEG_LEGS, LegSpec, load_robot


def _trajectory(t: np.ndarray, centre: np.ndarray) -> tuple[np.ndarray, ...]:
    """A smooth foot path (an ellipse tilted out of the ground plane) and its exact derivatives."""
    w = 2.0 * math.pi
    amp = np.array([0.02, 0.015, 0.01])
    ph = np.array([0.0, 0.7, 1.9])
    arg = w * t[:, None] + ph
    return (centre + amp * np.sin(arg), amp * w * np.cos(arg), -amp * w**2 * np.sin(arg))


def test_geometry_read_from_the_model_matches_the_parameter_file(robot):
    params = load_params()
    for leg in robot.legs:
        geom = analytic_geometry(robot, leg)
        assert geom is not None
        yaw = math.radians(params["hip_yaw_deg"][params.legs.index(leg.name)])
        assert geom.yaw == pytest.approx(yaw, abs=1e-9)
        assert math.hypot(geom.hip[0], geom.hip[1]) == pytest.approx(
            params["body"]["hip_radius"], abs=1e-9)
        assert geom.coxa == pytest.approx(params["coxa"]["length"])
        assert geom.femur == pytest.approx(params["femur"]["length_mm"] * 1e-3)
        assert geom.tibia == pytest.approx(params["tibia"]["length"])
        assert geom.reach == pytest.approx((0.036, 0.204))


def test_closed_form_forward_kinematics_equals_pinocchio(robot):
    rng = np.random.default_rng(1)
    data = robot.model.createData()
    for leg in robot.legs:
        geom = analytic_geometry(robot, leg)
        for _ in range(20):
            q = robot.pose("zero")
            q_leg = rng.uniform(-2.5, 2.5, 3)
            q[leg.q_index] = q_leg
            pin.framesForwardKinematics(robot.model, data, q)
            assert np.linalg.norm(data.oMf[leg.foot_frame_id].translation
                                  - geom.forward(q_leg)) < 1e-14


def test_jacobian_equals_central_differences_of_forward(robot):
    geom = analytic_geometry(robot, robot.legs[2])
    q = np.array([0.3, 0.4, -1.7])
    h = 1e-6
    fd = np.column_stack([(geom.forward(q + h * e) - geom.forward(q - h * e)) / (2 * h)
                          for e in np.eye(3)])
    assert np.allclose(geom.jacobian(q), fd, atol=1e-9)


def test_ik_inverts_forward_kinematics_on_the_knee_up_branch(robot):
    rng = np.random.default_rng(2)
    for leg in robot.legs:
        geom = analytic_geometry(robot, leg)
        q = np.column_stack([rng.uniform(-1.2, 1.2, 200), rng.uniform(-1.0, 1.3, 200),
                             rng.uniform(-2.8, -0.2, 200)])
        # The closed form's domain: the foot outward of the coxa axis (no reach over the back).
        q = q[geom.coxa + geom.femur * np.cos(q[:, 1])
              + geom.tibia * np.cos(q[:, 1] + q[:, 2]) > 0.01]
        p = geom.forward(q)
        q_ik, _, _ = analytic_leg_ik(geom, p, np.zeros_like(p), np.zeros_like(p))
        assert np.abs(q_ik - q).max() < 1e-9
        assert np.all(q_ik[:, 2] <= 0.0)


def test_stand_pose_is_recovered_from_its_feet(robot):
    q = robot.pose("stand")
    feet = robot.foot_positions(q)
    for i, leg in enumerate(robot.legs):
        q_ik, _, _ = analytic_leg_ik(analytic_geometry(robot, leg), feet[i:i + 1],
                                     np.zeros((1, 3)), np.zeros((1, 3)))
        assert np.allclose(q_ik[0], q[leg.q_index], atol=1e-12)
        assert np.allclose(np.degrees(q_ik[0]), [0.0, 20.0, -110.0], atol=1e-9)


def test_velocity_and_acceleration_are_exact(robot):
    """q̇ = J⁻¹ṗ; q̈ from Pinocchio's foot acceleration; and central differences converge ~h²."""
    leg = robot.leg("RM")
    geom = analytic_geometry(robot, leg)
    centre = robot.foot_positions(robot.pose("stand"))[4] + [0.0, 0.0, 0.02]
    t = np.linspace(0.0, 1.0, 41)
    q, qd, qdd = analytic_leg_ik(geom, *_trajectory(t, centre))
    _, pd, pdd = _trajectory(t, centre)
    assert np.allclose(np.einsum("nij,nj->ni", geom.jacobian(q), qd), pd, atol=1e-13)
    data = robot.model.createData()
    for k in range(len(t)):
        qf, vf, af = robot.pose("zero"), np.zeros(robot.model.nv), np.zeros(robot.model.nv)
        qf[leg.q_index], vf[leg.v_index], af[leg.v_index] = q[k], qd[k], qdd[k]
        pin.forwardKinematics(robot.model, data, qf, vf, af)
        acc = pin.getFrameClassicalAcceleration(robot.model, data, leg.foot_frame_id,
                                                pin.LOCAL_WORLD_ALIGNED).linear
        assert np.allclose(acc, pdd[k], atol=1e-11)
    errors = []
    for h in (1e-3, 5e-4):
        qp, qdp, _ = analytic_leg_ik(geom, *_trajectory(t + h, centre))
        qm, qdm, _ = analytic_leg_ik(geom, *_trajectory(t - h, centre))
        errors.append((np.abs((qp - qm) / (2 * h) - qd).max(),
                       np.abs((qdp - qdm) / (2 * h) - qdd).max()))
    for coarse, fine in zip(errors[0], errors[1], strict=True):
        assert 3.5 < coarse / fine < 4.5  # second order: halving h quarters the error


def test_newton_agrees_with_the_closed_form(robot):
    leg = robot.leg("LH")
    centre = robot.foot_positions(robot.pose("stand"))[2]
    t = np.linspace(0.0, 1.0, 25)
    traj = _trajectory(t, centre)
    q_a, qd_a, qdd_a = analytic_leg_ik(analytic_geometry(robot, leg), *traj)
    q_n, qd_n, qdd_n = newton_leg_ik(robot, leg, *traj)
    assert np.abs(q_n - q_a).max() < 1e-10
    assert np.abs(qd_n - qd_a).max() < 1e-9
    assert np.abs(qdd_n - qdd_a).max() < 1e-8


def test_legs_that_do_not_fit_the_closed_form_use_newton():
    # Foot frame at the knee: the tibia has no length, so the closed form must refuse this leg.
    legs = [LegSpec(s.name, s.joints, f"{s.name}_tibia_link") for s in HEXALEG_LEGS]
    odd = load_robot(legs=legs)
    assert all(analytic_geometry(odd, leg) is None for leg in odd.legs)


def _out_of_reach(message: str) -> tuple[str, float, float]:
    m = re.search(r"leg (\w+) at t = ([\d.e+-]+) s: .* ([\d.e+-]+) m out of reach", message)
    assert m, message
    return m.group(1), float(m.group(2)), float(m.group(3))


def test_unreachable_target_names_leg_time_and_distance(robot):
    leg = robot.leg("LM")
    geom = analytic_geometry(robot, leg)
    t = np.array([0.0, 0.1, 0.2])
    femur_axis = np.array([0.0, 0.08 + 0.03, 0.0])
    p = femur_axis + np.array([[0.0, 0.1, -0.1], [0.0, 0.2, -0.1], [0.0, 0.25, -0.1]])
    with pytest.raises(UnreachableTargetError) as err:
        leg_ik(robot, leg, p, np.zeros_like(p), np.zeros_like(p), t=t)
    name, when, dist = _out_of_reach(str(err.value))
    assert (name, when) == ("LM", 0.1)
    assert dist == pytest.approx(math.hypot(0.2, 0.1) - (geom.femur + geom.tibia), rel=1e-5)
    # The error carries its data: leg, time, sample, target (base frame) and distance.
    e = err.value
    assert (e.leg, e.t, e.index) == ("LM", 0.1, 1) and np.allclose(e.target, p[1])
    assert e.distance == pytest.approx(math.hypot(0.2, 0.1) - (geom.femur + geom.tibia))
    too_close = femur_axis + np.array([[0.0, 0.01, -0.01]])
    with pytest.raises(UnreachableTargetError, match=r"leg LM at t = 0 s"):
        leg_ik(robot, leg, too_close, np.zeros((1, 3)), np.zeros((1, 3)))


def test_joint_limits_are_enforced(robot):
    leg = robot.leg("RF")
    geom = analytic_geometry(robot, leg)
    # A reachable point that needs the coxa beyond ±150°: behind the hip.
    p = geom.forward(np.array([[math.radians(170.0), 0.3, -1.5]]))
    with pytest.raises(UnreachableTargetError, match=r"RF_coxa .*outside its limits") as err:
        leg_ik(robot, leg, p, np.zeros((1, 3)), np.zeros((1, 3)))
    assert (err.value.leg, err.value.index, err.value.distance) == ("RF", 0, None)
    assert np.allclose(err.value.target, p[0])


def test_newton_reports_unreachable_targets(robot):
    leg = robot.leg("RH")
    p = np.array([[-0.5, -0.5, 0.0]])
    with pytest.raises(UnreachableTargetError, match=r"leg RH at t = 0 s: .*out of reach") as err:
        newton_leg_ik(robot, leg, p, np.zeros((1, 3)), np.zeros((1, 3)))
    # Newton's remaining distance is the data the gait's diagnosis reads.
    assert (err.value.leg, err.value.t, err.value.index) == ("RH", 0.0, 0)
    assert err.value.target == (-0.5, -0.5, 0.0) and err.value.distance > 0.1


def test_leg_geometry_rejects_bad_lengths():
    with pytest.raises(hexaleg.HexalegError, match="femur"):
        LegGeometry(hip=(0.0, 0.0, 0.0), yaw=0.0, coxa=0.03, femur=0.0, tibia=0.1)


def test_a_redundant_leg_keeps_its_swing_within_the_limits_by_its_spare_direction(
        quad4dof, monkeypatch):
    """Issue #55 (Centauro's swing took a hip 0.1° past its limit though its leg had spare
    directions): a four-joint leg whose ankle would leave its tightened limit by 2° sets its
    self-motion off the stand's by a constant and stays within, its foot on every target (the
    forward kinematics, independent of the solver) and its redundant coordinate constant over
    the cycle; the same targets without the shift are refused naming the ankle, and a limit
    on the hip's abduction (no spare direction moves it) is still refused by name."""
    from hexaleg.motion import kinematics
    from hexaleg.motion.leg_chain import leg_chain

    robot, leg = quad4dof, quad4dof.leg("LF")
    ref = robot.pose("stand")
    ref[:7] = pin.neutral(robot.model)[:7]
    chain = leg_chain(robot, leg, ref)
    (p0,), _ = chain.position_jacobian(chain.reference[None])
    s = np.linspace(0.0, 1.0, 100, endpoint=False)
    p = p0 + np.c_[0.04 * np.cos(2 * np.pi * s), 0 * s, 0.03 * np.maximum(np.sin(2 * np.pi * s), 0)]
    zero = np.zeros_like(p)
    free, *_ = leg_ik(robot, leg, p, zero, zero)
    afe = leg.joint_names.index("LF_AFE")
    upper = robot.model.upperPositionLimit.copy()
    tight = upper.copy()
    tight[leg.q_index[afe]] = free[:, afe].max() - math.radians(2.0)
    try:
        robot.model.upperPositionLimit = tight
        q, *_ = leg_ik(robot, leg, p, zero, zero)
        assert (q[:, afe] <= tight[leg.q_index[afe]]).all()
        reached, _ = chain.position_jacobian(q)
        np.testing.assert_allclose(reached, p, atol=1e-10)
        self_motion = (q - chain.reference) @ chain.redundant
        assert np.ptp(self_motion) < 1e-9 and abs(self_motion[0, 0]) > math.radians(1.0)
        monkeypatch.setattr(kinematics, "_within_limits",
                            lambda robot, leg, p, pd, pdd, t, q, qd, qdd: (q, qd, qdd))
        with pytest.raises(UnreachableTargetError, match=r"LF_AFE .*outside its limits"):
            leg_ik(robot, leg, p, zero, zero)
        monkeypatch.undo()
        haa = leg.joint_names.index("LF_HAA")
        tight = upper.copy()
        tight[leg.q_index[haa]] = free[:, haa].max() - math.radians(0.5)
        robot.model.upperPositionLimit = tight
        with pytest.raises(UnreachableTargetError, match=r"LF_HAA .*outside its limits"):
            leg_ik(robot, leg, p, zero, zero)
    finally:
        robot.model.upperPositionLimit = upper
