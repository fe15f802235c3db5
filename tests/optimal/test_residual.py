"""The Newton–Euler residual: zero on a trajectory made by Pinocchio's forward dynamics with
foot forces, and exactly the error of a wrong torque or a wrong force."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.optimal.residual import dynamics_residual


def _forward(robot, q0, v0, tau, forces, dt):
    """Semi-implicit Euler of ABA with each foot's world force at its foot frame: an
    independent maker of a trajectory (no Crocoddyl)."""
    model, data = robot.model, robot.data
    q, v = [q0], [v0]
    for k in range(len(tau)):
        pin.framesForwardKinematics(model, data, q[k])
        fext = [pin.Force.Zero() for _ in range(model.njoints)]
        for j, leg in enumerate(robot.legs):
            joint = model.frames[leg.foot_frame_id].parentJoint
            p = data.oMf[leg.foot_frame_id].translation
            world = pin.Force(forces[k, j], np.cross(p, forces[k, j]))
            fext[joint] += data.oMi[joint].actInv(world)
        full = np.concatenate([np.zeros(6), tau[k]])
        a = pin.aba(model, data, q[k], v[k], full, fext)
        v.append(v[k] + a * dt)
        q.append(pin.integrate(model, q[k], v[k + 1] * dt))
    return np.array(q), np.array(v)


@pytest.fixture(scope="module")
def made(robot):
    rng = np.random.default_rng(5)
    n, dt = 6, 0.01
    tau = rng.normal(size=(n, robot.nj)) * 0.2
    forces = rng.normal(size=(n, len(robot.legs), 3)) + np.array([0.0, 0.0, 2.0])
    q0 = robot.poses["standing"] if "standing" in robot.poses else pin.neutral(robot.model)
    v0 = rng.normal(size=robot.model.nv) * 0.1
    q, v = _forward(robot, q0, v0, tau, forces, dt)
    return q, v, dt, tau, forces


def test_a_forward_simulated_trajectory_has_no_residual(robot, made):
    q, v, dt, tau, forces = made
    assert np.abs(dynamics_residual(robot, q, v, dt, tau, forces)).max() < 1e-9


def test_a_wrong_torque_or_force_shows(robot, made):
    q, v, dt, tau, forces = made
    wrong = tau.copy()
    wrong[2, 4] += 0.1
    r = dynamics_residual(robot, q, v, dt, wrong, forces)
    assert r[2, 6 + 4] == pytest.approx(-0.1, abs=1e-9)
    moved = forces.copy()
    moved[3, 0, 2] += 1.0  # one more newton up under the first foot
    r = dynamics_residual(robot, q, v, dt, tau, moved)
    assert np.abs(r[3]).max() > 0.05 and np.abs(np.delete(r, 3, axis=0)).max() < 1e-9


def test_bad_shapes_are_named(robot, made):
    q, v, dt, tau, forces = made
    with pytest.raises(InvalidParameterError, match=r"forces\.shape"):
        dynamics_residual(robot, q, v, dt, tau, forces[:, :2])
    with pytest.raises(InvalidParameterError, match="trajectory shapes"):
        dynamics_residual(robot, q[:-1], v, dt, tau, forces)


def test_the_check_at_given_accelerations_shows_a_wrong_one(robot, made):
    """``rnea_residual`` at each knot's own acceleration (the forward model's ``Δv/dt`` here) is
    round-off; an acceleration wrong by ``δa`` at one knot leaves exactly ``M(q_k) δa`` there and
    nothing elsewhere. Catches a check that ignores the accelerations it is given (e.g. takes
    ``Δv/dt`` again)."""
    from hexaleg.optimal.residual import rnea_residual

    q, v, dt, tau, forces = made
    a = np.diff(v, axis=0) / dt
    assert np.abs(rnea_residual(robot, q[:-1], v[:-1], a, tau, forces)).max() < 1e-9
    wrong = a.copy()
    delta = np.zeros(robot.model.nv)
    delta[[2, 9]] = [0.5, -2.0]
    wrong[4] += delta
    r = rnea_residual(robot, q[:-1], v[:-1], wrong, tau, forces)
    mass = pin.crba(robot.model, robot.data, q[4])
    mass = np.triu(mass) + np.triu(mass, 1).T
    np.testing.assert_allclose(r[4], mass @ delta, atol=1e-9)
    assert np.abs(np.delete(r, 4, axis=0)).max() < 1e-9
    with pytest.raises(InvalidParameterError, match="knot shapes"):
        rnea_residual(robot, q, v[:-1], a, tau, forces)
