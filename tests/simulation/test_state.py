"""Pinocchio ↔ MuJoCo vectors: round trips, the free flyer's velocity, acceleration and force
maps, continuous joints."""

from __future__ import annotations

import numpy as np
import pinocchio as pin
import pytest

from hexaleg.motion.recorded.base import rotation_from_quaternion
from hexaleg.simulation.model import build_model


@pytest.fixture(scope="module")
def joints(prepared):
    return build_model(prepared.robot, prepared.motion, prepared.motor).joints


def _states(robot, n, seed):
    rng = np.random.default_rng(seed)
    m = robot.model
    return [(pin.randomConfiguration(m, -np.ones(m.nq), np.ones(m.nq)), rng.normal(size=m.nv),
             rng.normal(size=m.nv)) for _ in range(n)]


def test_rotation_is_pinocchios():
    for q in np.random.default_rng(1).normal(size=(5, 4)):
        q /= np.linalg.norm(q)
        assert np.allclose(rotation_from_quaternion(q), pin.Quaternion(q).toRotationMatrix(),
                           atol=1e-14)


def test_maps_round_trip_also_in_batches(joints, robot):
    states = _states(robot, 4, seed=5)
    q = np.array([s[0] for s in states])
    v = np.array([s[1] for s in states])
    qpos, qvel = joints.to_mujoco(q, v)
    assert qpos.shape == (4, joints.nq_mj)
    q2, v2 = joints.to_pinocchio(qpos, qvel)
    assert np.allclose(q2, q, atol=1e-14) and np.allclose(v2, v, atol=1e-13)
    assert np.array_equal(joints.joints_mj(qpos), q[:, 7:])


def test_power_is_the_same_in_both_conventions(joints, robot):
    """τ·v is a power: the force map is the dual of the velocity map."""
    for q, v, tau in _states(robot, 3, seed=8):
        _, qvel = joints.to_mujoco(q, v)
        assert joints.force_to_mujoco(q, tau) @ qvel == pytest.approx(tau @ v, rel=1e-12)


def test_acceleration_is_the_derivative_of_the_mapped_velocity(joints, robot):
    """qacc = d(qvel)/dt along q(t) = q ⊕ v t + ½ a t², by central differences."""
    q, v, a = _states(robot, 1, seed=9)[0]
    h = 1e-6

    def qvel_at(t):
        qt = pin.integrate(robot.model, q, v * t + 0.5 * a * t * t)
        return joints.to_mujoco(qt, v + a * t)[1]

    numeric = (qvel_at(h) - qvel_at(-h)) / (2 * h)
    assert np.allclose(joints.acceleration_to_mujoco(q, v, a), numeric, atol=1e-6)
