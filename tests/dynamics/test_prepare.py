"""Tests of hexaleg.dynamics.prepare: whole-robot invariants of the prepare → evaluate pipeline."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.dynamics.prepare import analyze, prepare
from hexaleg.errors import InvalidParameterError, UnknownNameError
from hexaleg.motion.joint_motion import joint_motion
from hexaleg.motion.profiles import Sinusoid
from hexaleg.robot.springs import DeadZoneSpring


@pytest.fixture(scope="module")
def motion(walk):
    return walk


@pytest.fixture(scope="module")
def prepared(robot, motion):
    return prepare(robot, motion)


def femur_springs(robot, k=1.5, theta_k=0.1, neutral=0.5):
    return {leg.joint_names[1]: DeadZoneSpring(stiffness=k, theta_k=theta_k, neutral=neutral)
            for leg in robot.legs}


@pytest.fixture(scope="module")
def analysis(prepared, robot):
    return prepared.evaluate(femur_springs(robot))


def test_shapes(analysis, motion, robot):
    T = motion.n_samples
    assert analysis.forces.shape == (T, 6, 3)
    for name in ("tau_motor", "tau_spring", "power", "spring_energy", "q", "qdot"):
        assert getattr(analysis, name).shape == (T, robot.nj), name
    assert set(analysis.metrics["total"]) >= {"joule", "positive_work", "electrical"}


def test_newton_euler_balance_of_contact_forces(analysis, motion, robot):
    """Σ stance forces = m (a_com − g) at every sample (the whole robot's Newton equation)."""
    model, data = robot.model, robot.model.createData()
    rhs = np.empty((motion.n_samples, 3))
    for k in range(motion.n_samples):
        pin.centerOfMass(model, data, motion.q[k], motion.v[k], motion.a[k])
        rhs[k] = robot.mass * (data.acom[0] - model.gravity.linear)
    total = analysis.forces.sum(axis=1)
    assert np.max(np.abs(total - rhs)) <= 1e-8 * np.max(np.abs(rhs))


def test_base_rows_residual(prepared, analysis, motion):
    f = analysis.forces.reshape(motion.n_samples, -1)
    residual = np.einsum("tik,tk->ti", prepared.system.A, f) - prepared.system.b_base
    assert np.max(np.abs(residual)) <= 1e-9


def test_joint_rows_reassemble_rnea(prepared, analysis, motion, robot):
    """τ_motor + τ_spring + Σ J_jointᵀ f = (M a + h)_joints, checked with a fresh RNEA."""
    model, data = robot.model, robot.model.createData()
    for k in range(0, motion.n_samples, 97):
        b = pin.rnea(model, data, motion.q[k], motion.v[k], motion.a[k])
        pin.computeJointJacobians(model, data, motion.q[k])
        pin.updateFramePlacements(model, data)
        ext = np.zeros(model.nv)
        for i, leg in enumerate(robot.legs):
            J = pin.getFrameJacobian(model, data, leg.foot_frame_id,
                                     pin.ReferenceFrame.LOCAL_WORLD_ALIGNED)[:3]
            ext += J.T @ analysis.forces[k, i]
        assert np.allclose(b[:6], ext[:6], atol=1e-9)
        assert np.allclose(analysis.tau_motor[k] + analysis.tau_spring[k], b[6:] - ext[6:],
                           atol=1e-9)


def test_zero_signed_joint_work_over_the_periodic_gait(analysis, motion):
    """Stance feet do not move and the motion is periodic, so all joint torques do no net work."""
    p = analysis.tau_total * analysis.qdot
    assert abs(p.sum() * motion.dt) <= 1e-6 * np.abs(p).sum() * motion.dt
    # ... nor does any one spring (a conservative element on a closed path); the spring torque
    # has kinks at contact, so the periodic trapezoid rule is only O(dt²) here.
    ps = analysis.tau_spring * analysis.qdot
    assert np.all(np.abs(ps.sum(0)) <= 1e-4 * np.abs(ps).sum(0) + 1e-12)
    assert np.abs(ps).sum() > 0  # the springs do engage


def test_stored_energy_is_the_integral_of_spring_torque(analysis, motion):
    """U(t) − U(0) = −∫ τ_s q̇ dt (trapezoid; error O(dt²))."""
    ps = analysis.tau_spring * analysis.qdot
    work = np.concatenate([np.zeros((1, ps.shape[1])),
                           np.cumsum(0.5 * (ps[1:] + ps[:-1]) * motion.dt, axis=0)])
    du = analysis.spring_energy - analysis.spring_energy[0]
    assert np.max(np.abs(du + work)) <= 1e-3 * np.max(np.abs(analysis.spring_energy))


def test_no_springs_saves_nothing(prepared):
    rigid = prepared.evaluate(None)
    assert np.all(rigid.tau_spring == 0.0)
    assert rigid.savings["total"]["joule"] == 0.0
    assert rigid.metrics["total"]["joule"] == pytest.approx(rigid.baseline["total"]["joule"])


def test_two_stage_equals_one_shot(robot, motion, analysis):
    one = analyze(robot, motion, femur_springs(robot))
    assert np.array_equal(one.forces, analysis.forces)
    assert one.metrics["total"]["joule"] == analysis.metrics["total"]["joule"]


def test_saving_is_against_the_same_gait_without_springs(analysis):
    j, j0 = analysis.metrics["total"]["joule"], analysis.baseline["total"]["joule"]
    assert analysis.savings["total"]["joule"] == pytest.approx((j0 - j) / j0)


def test_single_joint_embedded_in_the_robot_is_eq14(robot):
    """One femur on eq. 16 (body fixed, gravity off): τ_motor = J_O f̈ − τ_spring(f) (eq. 14).

    J_O is computed by hand from the URDF parameters: the femur (Table 6: I + m l²) plus the
    tibia (uniform rod, 120 mm, 45 g, CoM 50 mm out) held at the stand pose's −110°.
    """
    free = hexaleg.load()
    free.model.gravity.linear[:] = 0.0
    femur_q = free.pose("stand")[free.leg("LF").q_index[1]]
    traj = Sinusoid(amplitude=0.3, omega=2.0, offset=femur_q)
    motion = joint_motion(free, {"LF_femur": traj}, samples=400)
    spring = DeadZoneSpring(stiffness=0.8, theta_k=0.1278, alpha=1.05, convention="eq14",
                            neutral=femur_q)
    an = analyze(free, motion, {"LF_femur": spring})
    m_f, l_f, i_f = 0.03611, 0.047141, 107.059e-6
    m_t, l_t, c_t = 0.045, 0.12, 0.05
    tib = np.array([0.084, 0.0]) + c_t * np.array([np.cos(np.radians(-110)),
                                                    np.sin(np.radians(-110))])
    j_o = i_f + m_f * l_f**2 + m_t * l_t**2 / 12 + m_t * tib @ tib
    f, _, fdd = traj(motion.t)
    expected = j_o * fdd - spring.torque(f)
    col = free.column("LF_femur")
    assert np.allclose(an.tau_motor[:, col], expected, rtol=1e-9, atol=1e-12)
    others = np.delete(np.arange(free.nj), [col, free.column("LF_tibia"), free.column("LF_coxa")])
    assert np.all(an.tau_motor[:, others] == 0.0)
    assert np.all(an.forces == 0.0)


def test_bad_input(prepared, robot):
    with pytest.raises(UnknownNameError, match="valid joints are: LF_coxa"):
        prepared.evaluate({"LF_knee": DeadZoneSpring(stiffness=1.0, theta_k=0.1)})
    with pytest.raises(InvalidParameterError, match="objective"):
        prepared.evaluate(None, objective="cheapest")
    with pytest.raises(hexaleg.HexalegError):
        DeadZoneSpring(stiffness=-1.0, theta_k=0.1)
    with pytest.raises(hexaleg.HexalegError):
        DeadZoneSpring(stiffness=float("nan"), theta_k=0.1)
    with pytest.raises(hexaleg.HexalegError):
        DeadZoneSpring(stiffness=1.0, theta_minus=0.2, theta_plus=0.1)
    with pytest.raises(hexaleg.HexalegError, match="motor"):
        prepare(robot, prepared.motion, motor="NoSuchServo")


def test_transform_feet_carry_the_sit_then_the_ground_carries_the_body(robot):
    """stand → sphere: while sitting, Newton–Euler over the six feet; while folding (the body on
    the ground, ``Motion.supported``) no foot is loaded, the motors drive the legs alone
    (τ_m + τ_s = RNEA joint rows) and the ground's reaction at rest is the robot's weight. Over
    the whole motion (at rest at both ends, the support does no work: the base does not move
    while it carries) the joints' work equals the rise of potential energy m g Δz_com."""
    from hexaleg.motion.transform import transform_motion

    motion = transform_motion(robot, samples=401)
    springs = {"LF_femur": DeadZoneSpring(stiffness=0.5, theta_k=0.1)}
    result = analyze(robot, motion, springs)
    data = robot.model.createData()
    sit, fold = ~motion.supported, motion.supported
    g = robot.model.gravity.linear
    for k in np.flatnonzero(sit):
        pin.centerOfMass(robot.model, data, motion.q[k], motion.v[k], motion.a[k])
        expected = robot.mass * (data.acom[0] - g)
        assert np.abs(result.forces[k].sum(axis=0) - expected).max() <= 1e-8 * robot.mass * 9.81
    assert result.forces[0, :, 2].sum() == pytest.approx(robot.mass * 9.81, rel=1e-12)
    assert np.abs(result.forces[fold]).max() == 0.0
    rnea = np.array([pin.rnea(robot.model, data, q, v, a)
                     for q, v, a in zip(motion.q, motion.v, motion.a, strict=True)])
    np.testing.assert_allclose((result.tau_motor + result.tau_spring)[fold], rnea[fold, 6:],
                               rtol=0, atol=1e-12)
    assert rnea[-1, :3] == pytest.approx([0.0, 0.0, robot.mass * 9.81], abs=1e-12)
    work = ((result.tau_motor + result.tau_spring) * result.qdot).sum() * motion.dt
    z = [pin.centerOfMass(robot.model, data, motion.q[k])[2] for k in (0, -1)]
    assert work == pytest.approx(robot.mass * 9.81 * (z[1] - z[0]), rel=1e-6)
    assert robot.mass * 9.81 * (z[1] - z[0]) > 0.05  # folding lifts the legs: not vacuous
    # The spring is conservative: its work is minus the change of its stored energy.
    spring_work = (result.tau_spring * result.qdot).sum() * motion.dt
    stored = result.spring_energy[-1].sum() - result.spring_energy[0].sum()
    assert spring_work == pytest.approx(-stored, rel=1e-6) and abs(stored) > 0.1


def test_epsilon_of_the_embedded_paper_joint_is_its_closed_form():
    """The paper's joint in the robot (LF femur on f = 0.3 sin 2t, body fixed), gravity off: the
    femur supplies the kinetic energy twice a cycle, E = J A² ω², over the path 4A, so eq. 24
    gives ε = A ω² / 4 = 0.3 s⁻² whatever the distal inertia J; the inertia is M[v, v] (CRBA);
    joints that do not move get ε = 0."""
    robot = hexaleg.load()
    robot.model.gravity.linear[:] = 0.0
    motion = joint_motion(robot, {"LF_femur": Sinusoid(0.3, 2.0)})
    prepared = prepare(robot, motion)
    eps = prepared.evaluate().metrics["epsilon"]
    j = robot.joint_names.index("LF_femur")
    assert eps["positive_work"][j] == pytest.approx(0.3 * 2.0**2 / 4, rel=1e-4)
    assert eps["angle"][j] == pytest.approx(4 * 0.3, rel=1e-4)
    M = pin.crba(robot.model, robot.model.createData(), motion.q[0])
    assert prepared.inertia[j] == pytest.approx(M[6 + j, 6 + j], rel=1e-12)
    assert np.count_nonzero(eps["positive_work"]) == 1


@pytest.mark.parametrize("stiffness", [1e300, 1e6])
def test_a_spring_in_the_wrong_unit_is_named_not_a_contact_force_error(robot, stiffness):
    """Issue #42: a femur stiffness of 1e300 ended in a contact-force error; a spring pushing
    over 1000 × its joint's stall torque is refused naming the joint, the spring and its
    torque (a 1e6 N·m/rad spring on a 1.8 N·m servo too)."""
    import hexaleg
    from hexaleg.errors import InvalidParameterError

    prepared = hexaleg.prepare(robot, hexaleg.gait(robot, hexaleg.GaitParams(samples=60)))
    with pytest.raises(InvalidParameterError, match=r"springs\['LF_femur'\].*1000 × the "
                       r"joint's stall torque \(1\.8 N·m\); it reaches"):
        prepared.evaluate({"LF_femur": hexaleg.LinearSpring(stiffness=stiffness)})
    assert prepared.evaluate({"LF_femur": hexaleg.LinearSpring(stiffness=0.1)})
