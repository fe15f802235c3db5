"""Tests of hexaleg.motion.leg_ik (Newton inverse kinematics on a leg's chain, every sample at
once): Pinocchio is the independent reference, the sample-by-sample path (the branch carried
from sample to sample) is checked against the all-at-once one, a two-joint leg against its
plane, and a redundant (four-joint) leg against finite differences of its own position solution
and against a brute-force minimiser of the distance to the stand pose (SciPy's SLSQP)."""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np
import pinocchio as pin
import pytest
from scipy.optimize import minimize

import hexaleg
from hexaleg.motion import leg_ik
from hexaleg.motion.kinematics import analytic_geometry
from hexaleg.motion.leg_chain import leg_chain
from hexaleg.motion.leg_ik import NEWTON_JUMP, _newton, newton_leg_ik
from hexaleg.robot.model import Leg
from hexaleg.robot.registry import load

from .test_leg_chain import _pinocchio, _reference


def _walk(robot: hexaleg.Robot, leg: Leg, n: int, r: float = 0.03
          ) -> tuple[np.ndarray, ...]:
    """A foot circle of radius ``r`` in the sagittal plane around the stand foot, n samples, with
    its exact derivatives."""
    centre = leg_chain(robot, leg, _reference(robot)).frames(
        _reference(robot)[leg.q_index][None])[0][0]
    t = np.linspace(0.0, 1.0, n, endpoint=False)
    w = 2 * np.pi
    s, c = np.sin(w * t), np.cos(w * t)
    zero = np.zeros_like(t)
    return (centre + r * np.stack([c, zero, s], 1), r * w * np.stack([-s, zero, c], 1),
            -r * w * w * np.stack([c, zero, s], 1))


def test_newton_inverts_the_chain_with_exact_derivatives(a1):
    for leg in a1.legs:
        assert analytic_geometry(a1, leg) is None  # A1's legs go through Newton
        p, pd, pdd = _walk(a1, leg, 100)
        q, qd, qdd = newton_leg_ik(a1, leg, p, pd, pdd)
        for k in range(0, 100, 7):
            p_ref, jac, acc = _pinocchio(a1, leg, q[k], qd[k])
            assert np.abs(p_ref - p[k]).max() < 1e-12
            assert np.abs(jac @ qd[k] - pd[k]).max() < 1e-12
            assert np.abs(jac @ qdd[k] + acc - pdd[k]).max() < 1e-10


def test_coarse_samples_are_solved_each_from_the_one_before(a1):
    leg = a1.leg("LF")
    p, pd, pdd = _walk(a1, leg, 5, r=0.07)
    q = newton_leg_ik(a1, leg, p, pd, pdd)[0]
    assert np.abs(np.diff(q, axis=0)).max() > NEWTON_JUMP  # the sample-by-sample path ran
    carried = [_reference(a1)[leg.q_index]]
    for k in range(5):
        carried.append(newton_leg_ik(a1, leg, p[k:k + 1], pd[k:k + 1], pdd[k:k + 1],
                                     q0=carried[-1])[0][0])
    assert np.abs(q - np.array(carried[1:])).max() < 1e-12
    fine = newton_leg_ik(a1, leg, *_walk(a1, leg, 100, r=0.07))[0]
    assert np.abs(q - fine[::20]).max() < 1e-12  # the same branch as the continuous path


def test_a_jump_of_coarse_sampling_costs_one_sample_solve(a1, monkeypatch):
    """A path that jumps once (the foot's circle of 100 samples with 30 left out: the jump is
    the sampling's, not another branch) is solved again from its predecessor at the jump only:
    that sample lands on its all-at-once solution and the rest are kept. The whole path from the
    jump on was solved sample by sample before (30 solves)."""
    leg = a1.leg("LF")
    p, pd, pdd = (x[np.r_[0:40, 70:100]] for x in _walk(a1, leg, 100, r=0.07))
    singles = []

    def counted(chain, p, q, reference=None):
        singles.extend([len(p)] if len(p) == 1 else [])
        return _newton(chain, p, q, reference)

    monkeypatch.setattr(leg_ik, "_newton", counted)
    q = newton_leg_ik(a1, leg, p, pd, pdd)[0]
    assert np.abs(np.diff(q, axis=0)).max() > NEWTON_JUMP  # the jump is there
    assert len(singles) == 1
    carried = [_reference(a1)[leg.q_index]]
    for k in range(len(p)):
        carried.append(newton_leg_ik(a1, leg, p[k:k + 1], pd[k:k + 1], pdd[k:k + 1],
                                     q0=carried[-1])[0][0])
    assert np.abs(q - np.array(carried[1:])).max() < 1e-12  # the branch carried sample by sample


def test_a_target_that_is_not_a_number_is_named(a1):
    leg = a1.leg("LF")
    p, pd, pdd = _walk(a1, leg, 4)
    p[2, 0] = np.nan
    with pytest.raises(hexaleg.HexalegError, match=r"leg LF foot target p"):
        newton_leg_ik(a1, leg, p, pd, pdd)


def test_a_foot_frame_moved_in_place_is_read_again():
    robot = load("a1")
    leg = robot.leg("LF")
    p, pd, pdd = _walk(robot, leg, 8)
    q = newton_leg_ik(robot, leg, p, pd, pdd)[0]
    frame = robot.model.frames[leg.foot_frame_id]
    frame.placement = pin.SE3(np.eye(3), frame.placement.translation + np.array([0.0, 0.0, -0.02]))
    robot.model.frames[leg.foot_frame_id] = frame
    moved = newton_leg_ik(robot, leg, p, pd, pdd)[0]
    assert np.abs(moved - q).max() > 1e-3
    for k in range(8):
        assert np.abs(_pinocchio(robot, leg, moved[k], np.zeros(3))[0] - p[k]).max() < 1e-12


QUAD2DOF = Path(__file__).resolve().parents[1] / "data" / "quad2dof.toml"


def test_a_two_joint_leg_reaches_its_plane_and_names_a_target_off_it():
    """The planar hip–knee leg of the test quadruped: targets in its plane (the foot's forward
    kinematics at sampled angles) are inverted exactly, with q̇ and q̈ those of the motion; a
    target 5 mm to the side is named with its distance off the plane."""
    from hexaleg.errors import UnreachableTargetError

    robot = hexaleg.load(str(QUAD2DOF))
    leg = robot.leg("LF")
    reference = robot.pose("stand")
    chain = leg_chain(robot, leg, reference)
    assert chain.angular.shape == (2, 3)
    t = np.linspace(0.0, 1.0, 201)
    q_true = reference[leg.q_index] + 0.3 * np.stack([np.sin(2 * np.pi * t),
                                                     np.sin(2 * np.pi * t + 1.0)], axis=1)
    p = chain.frames(q_true)[0]
    pd = np.gradient(p, t, axis=0, edge_order=2)
    pdd = np.gradient(pd, t, axis=0, edge_order=2)
    q, qd, _ = newton_leg_ik(robot, leg, p, pd, pdd, t=t)
    np.testing.assert_allclose(q, q_true, atol=1e-9)
    np.testing.assert_allclose(qd[5:-5], np.gradient(q_true, t, axis=0)[5:-5], rtol=0, atol=2e-3)
    side = p.copy()
    side[:, 1] += 0.005
    with pytest.raises(UnreachableTargetError, match=r"0\.005 m off the plane its 2 joints"):
        newton_leg_ik(robot, leg, side, pd, pdd, t=t)


def test_planar_legs_walk_the_bound_by_default():
    from hexaleg.motion.scaling import robot_gait

    gait = robot_gait(str(QUAD2DOF), sized=False)
    assert gait.groups == (("LF", "RF"), ("LH", "RH"))


def _redundant_directions(robot: hexaleg.Robot, leg: Leg) -> np.ndarray:
    """The leg's redundant directions at the stand pose from Pinocchio's foot Jacobian: the
    right-singular vectors of its n − 3 smallest singular values, shape (n, n − 3)."""
    model, data = robot.model, robot.model.createData()
    jac = pin.computeFrameJacobian(model, data, _reference(robot), leg.foot_frame_id,
                                   pin.LOCAL_WORLD_ALIGNED)[:3, leg.v_index]
    return np.linalg.svd(jac)[2][3:].T


def test_a_redundant_leg_puts_its_foot_on_target_and_holds_its_redundant_directions(quad4dof):
    """Random reachable targets (the feet of random joint angles around the stand, up to 0.3 rad
    a joint) are reached to 1e-10 m by Pinocchio's forward kinematics, and the solution has the
    stand's component along the redundant directions (``N₀ᵀ (q − q_stand) = 0``, ``N₀`` from
    Pinocchio's Jacobian here), which the random angles themselves do not."""
    rng = np.random.default_rng(7)
    model, data = quad4dof.model, quad4dof.model.createData()
    for leg in quad4dof.legs:
        assert len(leg.joint_ids) == 4
        stand = _reference(quad4dof)[leg.q_index]
        null = _redundant_directions(quad4dof, leg)
        for _ in range(12):
            q_true = stand + rng.uniform(-0.3, 0.3, 4)
            target = _pinocchio(quad4dof, leg, q_true, np.zeros(4))[0]
            q = newton_leg_ik(quad4dof, leg, target[None], np.zeros((1, 3)),
                              np.zeros((1, 3)))[0][0]
            full = _reference(quad4dof)
            full[leg.q_index] = q
            pin.framesForwardKinematics(model, data, full)
            assert np.abs(data.oMf[leg.foot_frame_id].translation - target).max() < 1e-10
            assert np.abs(null.T @ (q - stand)).max() < 1e-10
            assert np.abs(null.T @ (q_true - stand)).max() > 1e-3  # not the given angles


def _foot_path(robot: hexaleg.Robot, leg: Leg, t: np.ndarray) -> tuple[np.ndarray, ...]:
    """A smooth closed foot path around the stand foot (3 cm forward–back and up–down, 1 cm
    sideways, period 1 s) with its exact derivatives."""
    centre = leg_chain(robot, leg, _reference(robot)).frames(
        _reference(robot)[leg.q_index][None])[0][0]
    w, a = 2 * np.pi, np.array([0.03, 0.01, 0.03])
    s, c, s2, c2 = np.sin(w * t), np.cos(w * t), np.sin(2 * w * t), np.cos(2 * w * t)
    p = centre + a * np.stack([s, s2, c - 1.0], 1)
    pd = a * w * np.stack([c, 2 * c2, -s], 1)
    pdd = -a * w * w * np.stack([s, 4 * s2, c], 1)
    return p, pd, pdd


def test_a_redundant_legs_rates_are_the_derivatives_of_its_positions(quad4dof):
    """``q̇`` and ``q̈`` of a four-joint leg are the time derivatives of its position solution:
    central differences (h = 10 µs) of the IK solved at t ± h agree to 1e-6 of their size. The
    pseudo-inverse rates ``J⁺ ṗ`` (another secondary objective's) do not."""
    leg = quad4dof.leg("RH")
    t = np.linspace(0.0, 1.0, 50, endpoint=False)
    h = 1e-5
    q, qd, qdd = newton_leg_ik(quad4dof, leg, *_foot_path(quad4dof, leg, t), t=t)
    q_plus, qd_plus, _ = newton_leg_ik(quad4dof, leg, *_foot_path(quad4dof, leg, t + h))
    q_minus, qd_minus, _ = newton_leg_ik(quad4dof, leg, *_foot_path(quad4dof, leg, t - h))
    fd_qd = (q_plus - q_minus) / (2 * h)
    fd_qdd = (qd_plus - qd_minus) / (2 * h)
    assert np.abs(qd - fd_qd).max() < 1e-6 * np.abs(qd).max()
    assert np.abs(qdd - fd_qdd).max() < 1e-6 * np.abs(qdd).max()
    assert np.abs((q_plus - 2 * q + q_minus) / h**2 - qdd).max() < 1e-3 * np.abs(qdd).max()
    jac = leg_chain(quad4dof, leg, _reference(quad4dof)).position_jacobian(q)[1]
    pinv = (np.linalg.pinv(jac) @ _foot_path(quad4dof, leg, t)[1][..., None])[..., 0]
    assert np.abs(pinv - fd_qd).max() > 1e-3 * np.abs(qd).max()


def _nearest_to_stand(robot: hexaleg.Robot, leg: Leg, target: np.ndarray) -> np.ndarray:
    """The leg's joint angles nearest the stand's, ``argmin ‖q − q_stand‖²``, with the foot on
    ``target`` (Pinocchio's forward kinematics and Jacobian), by SciPy's SLSQP."""
    stand = _reference(robot)[leg.q_index]

    def foot(q: np.ndarray) -> np.ndarray:
        return _pinocchio(robot, leg, q, np.zeros(len(q)))[0] - target

    def jac(q: np.ndarray) -> np.ndarray:
        return _pinocchio(robot, leg, q, np.zeros(len(q)))[1]

    res = minimize(lambda q: float((q - stand) @ (q - stand)), stand, jac=lambda q: 2 * (q - stand),
                   constraints=[{"type": "eq", "fun": foot, "jac": jac}], method="SLSQP",
                   options={"ftol": 1e-16, "maxiter": 500})
    assert res.success, res.message
    assert np.abs(foot(res.x)).max() < 1e-10
    return np.asarray(res.x)


def test_the_secondary_objective_is_the_nearest_configuration_to_first_order(quad4dof):
    """Holding the redundant directions at their stand values is, to first order in the foot's
    offset from its stand position, the configuration nearest the stand that reaches the target
    (the class docstring of LegChain): the distance to the brute-force minimiser shrinks like the
    offset squared (halving the offset quarters it) and stays far below the offset's own joint
    motion. Holding another direction instead (the ankle at its stand angle) is off to first
    order: its distance only halves."""
    leg = quad4dof.leg("LF")
    chain = leg_chain(quad4dof, leg, _reference(quad4dof))
    stand = chain.reference
    centre = chain.frames(stand[None])[0][0]
    direction = np.array([0.6, 0.3, -0.74]) / np.linalg.norm([0.6, 0.3, -0.74])
    ankle = dataclasses.replace(chain, redundant=np.array([[0.0], [0.0], [0.0], [1.0]]))
    ours, ankles = [], []
    for offset in (0.01, 0.005, 0.0025):
        target = centre + offset * direction
        q = newton_leg_ik(quad4dof, leg, target[None], np.zeros((1, 3)), np.zeros((1, 3)))[0][0]
        best = _nearest_to_stand(quad4dof, leg, target)
        assert np.linalg.norm(q - best) < 0.05 * np.linalg.norm(best - stand)
        ours.append(np.linalg.norm(q - best))
        held = _newton(ankle, target[None], stand[None])[0][0]
        ankles.append(np.linalg.norm(held - best))
    ratios = np.array(ours[:-1]) / np.array(ours[1:])
    assert np.all((ratios > 3.5) & (ratios < 4.5)), ratios  # second order
    ankle_ratios = np.array(ankles[:-1]) / np.array(ankles[1:])
    assert np.all((ankle_ratios > 1.7) & (ankle_ratios < 2.3)), ankle_ratios  # first order


def _biped6() -> hexaleg.Robot:
    from hexaleg.robot.description import read_description

    return read_description(Path(__file__).parents[1] / "data" / "biped6.toml").load()


def _yawing_walk(robot: hexaleg.Robot, leg: Leg, t: np.ndarray, amplitude: float = 0.2
                 ) -> tuple[tuple[np.ndarray, ...], tuple[np.ndarray, ...]]:
    """A sole's foot target moving fore and aft and up (base frame) under a body that yaws by
    ψ = A sin(2πt): the foot's turn in the base frame θ = (0, 0, −ψ) with its exact rates."""
    stand = robot.foot_positions(robot.pose("stand"))[robot.legs.index(leg)]
    w = 2 * np.pi
    s, c = np.sin(w * t), np.cos(w * t)
    p = stand + np.c_[0.05 * s, 0.0 * t, 0.03 * (1 - c)]
    pd = np.c_[0.05 * w * c, 0.0 * t, 0.03 * w * s]
    pdd = np.c_[-0.05 * w**2 * s, 0.0 * t, 0.03 * w**2 * c]
    zero = np.zeros_like(t)
    turn = (np.c_[zero, zero, -amplitude * s], np.c_[zero, zero, -amplitude * w * c],
            np.c_[zero, zero, amplitude * w**2 * s])
    return (p, pd, pdd), turn


def test_a_sole_leg_keeps_its_sole_flat_and_turns_it_against_the_body_exactly():
    """biped6's six-joint leg under a body that yaws: Pinocchio (independent of the chain)
    puts the foot on its targets and its orientation at Rz(−ψ) in the base frame — flat, and
    still in the world — to 1e-12; the rates equal central differences of the angles."""
    robot = _biped6()
    leg = robot.legs[0]
    t = np.linspace(0.0, 1.0, 401)
    (p, pd, pdd), turn = _yawing_walk(robot, leg, t)
    _assert_pose_and_rates(robot, leg, t, p, turn, newton_leg_ik(robot, leg, p, pd, pdd,
                                                                  turn=turn))


def _assert_pose_and_rates(robot: hexaleg.Robot, leg: Leg, t: np.ndarray, p: np.ndarray,
                           turn: tuple[np.ndarray, ...], solved: tuple[np.ndarray, ...]) -> None:
    """Pinocchio (independent of the chain) puts the foot on its targets and its orientation at
    exp(θ) in the base frame (the flat stand's is the identity) to 1e-12; the rates equal
    central differences of the angles."""
    q, qd, qdd = solved
    data = robot.model.createData()
    full = robot.pose("stand").copy()
    for k in range(0, len(t), 20):
        full[leg.q_index] = q[k]
        pin.framesForwardKinematics(robot.model, data, full)
        frame = data.oMf[leg.foot_frame_id]
        np.testing.assert_allclose(frame.translation, p[k], atol=1e-12)
        np.testing.assert_allclose(frame.rotation, pin.exp3(turn[0][k]), atol=1e-12)
    h = t[1] - t[0]
    np.testing.assert_allclose(qd[1:-1], (q[2:] - q[:-2]) / (2 * h), atol=2e-4)
    np.testing.assert_allclose(qdd[1:-1], (qd[2:] - qd[:-2]) / (2 * h), atol=2e-3)


def test_a_sole_leg_whose_rows_hold_the_foot_only_to_first_order_holds_it_by_newton(tmp_path):
    """An ankle that rolls before it pitches: the foot's orientation is no longer linear in the
    joints, so the rows that hold it at the stand would let it tilt (0.04 rad) as the foot moves;
    Newton on the whole pose holds it flat and turned against the body (Pinocchio's FK, 1e-12),
    its rates the central differences of its angles."""
    data = Path(__file__).parents[1] / "data"
    urdf = (data / "biped6.urdf").read_text()
    for side in ("L", "R"):  # swap the ankle's two axes
        ankle = f'<child link="{side}_ankle"/>\n    <origin xyz="0 0 -0.22" rpy="0 0 0"/>'
        foot = f'<child link="{side}_foot"/>\n    <origin xyz="0 0 0" rpy="0 0 0"/>'
        urdf = urdf.replace(ankle + '<axis xyz="0 1 0"/>', ankle + '<axis xyz="1 0 0"/>')
        urdf = urdf.replace(foot + '<axis xyz="1 0 0"/>', foot + '<axis xyz="0 1 0"/>')
    assert urdf.count('<child link="L_ankle"/>\n    <origin xyz="0 0 -0.22" rpy="0 0 0"/>'
                      '<axis xyz="1 0 0"/>') == 1  # swapped
    (tmp_path / "b.urdf").write_text(urdf)
    toml = (data / "biped6.toml").read_text().replace('urdf = "biped6.urdf"', 'urdf = "b.urdf"')
    (tmp_path / "b.toml").write_text(toml)
    from hexaleg.robot.description import read_description

    robot = read_description(tmp_path / "b.toml").load()
    leg = robot.legs[0]
    t = np.linspace(0.0, 1.0, 401)
    (p, pd, pdd), turn = _yawing_walk(robot, leg, t)
    _assert_pose_and_rates(robot, leg, t, p, turn, newton_leg_ik(robot, leg, p, pd, pdd,
                                                                  turn=turn))
