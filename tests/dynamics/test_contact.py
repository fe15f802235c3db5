"""Tests of hexaleg.dynamics.contact: contact settings, objectives, the inequalities."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from hexaleg.dynamics.contact import ContactParams, check_objective, friction_usage, violations
from hexaleg.dynamics.prepare import prepare
from hexaleg.dynamics.solver import solve_fast
from hexaleg.errors import InfeasibleForcesError, InvalidParameterError


def test_pyramid_is_inside_the_cone(robot, walk200):
    prepared = prepare(robot, walk200, contact=ContactParams(mu=0.25, cone="pyramid"))
    f, _, _ = solve_fast(prepared.system, np.zeros_like(prepared.q), "joule",
                         prepared.weights("joule"), prepared.contact)
    f3 = f.reshape(walk200.n_samples, -1, 3)
    assert np.all(np.hypot(f3[..., 0], f3[..., 1]) <= 0.25 * f3[..., 2] + 1e-9)


def test_swing_feet_carry_nothing_and_stance_feet_push(robot, walk200):
    prepared = prepare(robot, walk200, contact=ContactParams(min_normal_force=0.5))
    analysis = prepared.evaluate()
    assert np.all(analysis.forces[~walk200.stance] == 0.0)
    assert np.all(analysis.forces[..., 2][walk200.stance] >= 0.5 - 1e-9)


def test_violations_flag_each_inequality(robot, walk200):
    """The default gait's optimal forces break nothing at μ = 0.6; a tiny μ, a normal force above
    any foot's load or a torque limit below the peak flag the samples that break it."""
    prepared = prepare(robot, walk200)
    sys = prepared.system
    f, tau, resolved = solve_fast(sys, np.zeros_like(prepared.q), "joule",
                                  prepared.weights("joule"), prepared.contact)
    assert not resolved.any()
    assert not violations(sys, f, tau, prepared.contact).any()
    loaded = sys.stance.any(axis=1)
    assert np.array_equal(violations(sys, f, tau, ContactParams(mu=1e-6)), loaded)
    assert np.array_equal(violations(sys, f, tau, ContactParams(min_normal_force=1e3)), loaded)
    peak = np.abs(tau).max(axis=1)  # per sample, over the joints
    limit = 0.5 * peak.max()
    tight = dataclasses.replace(sys, tau_max=np.full_like(sys.tau_max, limit))
    over = violations(tight, f, tau, prepared.contact)
    assert over.any() and np.array_equal(over, peak > limit + 1e-9)
    assert not violations(tight, f, tau, ContactParams(torque_limits=False)).any()


def test_bad_settings():
    with pytest.raises(InvalidParameterError, match="joule, torque_squared"):
        check_objective("fast")
    with pytest.raises(InvalidParameterError, match="mu"):
        ContactParams(mu=0.0)
    with pytest.raises(InvalidParameterError, match="soc or pyramid"):
        ContactParams(cone="square")
    with pytest.raises(InvalidParameterError, match="min_normal_force"):
        ContactParams(min_normal_force=-1.0)
    with pytest.raises(InvalidParameterError, match="finite"):
        ContactParams(mu=float("nan"))


def test_friction_usage_of_known_forces():
    f = np.array([[[3.0, 4.0, 10.0], [0.0, 0.0, 0.0], [1.0, 0.0, 5.0]]])
    stance = np.array([[True, True, False]])
    np.testing.assert_allclose(friction_usage(f, stance, 0.5), [[1.0, 0.0, 0.0]])


def test_contact_frame_turns_z_onto_the_normal_and_usage_is_about_it():
    from hexaleg.dynamics.contact import contact_frame

    assert np.array_equal(contact_frame(np.array([0.0, 0.0, 1.0])), np.eye(3))
    n = np.array([-0.3, 0.2, 1.0]) / np.linalg.norm([-0.3, 0.2, 1.0])
    r = contact_frame(n)
    assert np.allclose(r.T @ r, np.eye(3), atol=1e-15) and np.isclose(np.linalg.det(r), 1.0)
    assert np.allclose(r[:, 2], n, atol=1e-15)
    assert np.allclose(r @ np.cross([0.0, 0.0, 1.0], n), np.cross([0.0, 0.0, 1.0], n))  # axis
    # A force along n uses no friction; one at angle atan μ from n is on the cone.
    t = r[:, 0]
    f = np.array([[n * 10.0, (n + 0.5 * t) * 10.0]])
    assert np.allclose(friction_usage(f, np.ones((1, 2), bool), 0.5, n), [[0.0, 1.0]])
    assert friction_usage(f, np.ones((1, 2), bool), 0.5)[0, 0] > 0.5  # about z it is loaded


def test_ground_steeper_than_friction_is_refused_before_the_program():
    from hexaleg.dynamics.contact import check_ground_friction

    n = np.array([-np.sin(0.3), 0.0, np.cos(0.3)])
    check_ground_friction(None, ContactParams(mu=1e-3))
    check_ground_friction(n, ContactParams(mu=np.tan(0.3) + 1e-9))
    with pytest.raises(InfeasibleForcesError, match=r"γ = 17\.2°.*tan γ = 0\.3093 > μ = 0\.3"):
        check_ground_friction(n, ContactParams(mu=0.3))
