"""Tests of hexaleg.dynamics.forces: the energy-optimal force distribution, fast path vs cvxpy
reference."""

from __future__ import annotations

import numpy as np
import pytest

import hexaleg
from hexaleg.dynamics.forces import (
    ContactParams,
    check_objective,
    quadratic_gains,
    solve_fast,
    solve_reference,
)
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import InfeasibleForcesError, InvalidParameterError, TorqueLimitError
from hexaleg.robot.motor import CATALOGUE
from hexaleg.robot.springs import DeadZoneSpring


@pytest.fixture(scope="module")
def motion(walk200):
    """cvxpy solves every sample: the 200-sample gait."""
    return walk200


def _springs(robot):
    return {leg.joint_names[1]: DeadZoneSpring(stiffness=1.5, theta_k=0.1, neutral=0.5)
            for leg in robot.legs}


@pytest.mark.parametrize(("mu", "cone", "binding"), [
    (0.6, "soc", False),      # default friction: no inequality binds, pure KKT path
    (0.3, "soc", True),       # low friction: the exact cone binds on many samples
    (0.25, "pyramid", True),  # the inscribed pyramid binds
])
def test_fast_path_equals_cvxpy_reference(robot, motion, mu, cone, binding):
    prepared = prepare(robot, motion, contact=ContactParams(mu=mu, cone=cone))
    tau_s = prepared.spring_torques(_springs(robot))
    w = prepared.weights("joule")
    f_fast, _, resolved = solve_fast(prepared.system, tau_s, "joule", w, prepared.contact)
    f_ref = solve_reference(prepared.system, tau_s, "joule", w, prepared.contact)
    assert resolved.any() == binding
    assert np.max(np.abs(f_fast - f_ref)) <= 1e-6


@pytest.mark.parametrize("objective", ["electrical", "positive_work"])
def test_non_smooth_objectives_match_the_reference_optimum(robot, motion, objective):
    """Same optimal value to 1e-8 W; forces to 1e-6 N for positive work and 1e-5 N for electrical
    energy (measured 4e-8 and 4e-6 N): the regulariser ε = 1e-4 leaves the optimum only weakly
    curved, so solver tolerances of 1e-10 in value move the forces by microNewtons."""
    prepared = prepare(robot, motion)
    tau_s = prepared.spring_torques(_springs(robot))
    w = prepared.weights(objective)
    eps = prepared.contact.regularization
    sys = prepared.system
    samples = np.arange(0, motion.n_samples, 10)
    f_fast, _, _ = solve_fast(sys, tau_s, objective, w, prepared.contact)
    f_ref = solve_reference(sys, tau_s, objective, w, prepared.contact, samples=samples)

    def cost(f):  # the objectives as hexaleg.robot.motor defines them, independently of forces.py
        tau = sys.torques(f, tau_s)[samples]
        qd = sys.qdot[samples]
        if objective == "electrical":
            power = prepared.motor.electrical_power(tau, qd, regeneration=False)
        else:
            power = np.maximum(0, qd * tau)
        return power.sum(1) + eps * (tau**2).sum(1)

    assert np.allclose(cost(f_fast), cost(f_ref), atol=1e-8)
    tol = 1e-6 if objective == "positive_work" else 1e-5
    assert np.max(np.abs(f_fast[samples] - f_ref[samples])) <= tol


def test_quadratic_gains_give_the_constrained_optimum(robot, motion):
    """KKT: base rows hold and no direction in their null space lowers Σ w τ²."""
    prepared = prepare(robot, motion)
    sys = prepared.system
    w = prepared.weights("joule")
    gains = quadratic_gains(sys, w)
    f = gains.f0
    assert np.max(np.abs(np.einsum("tik,tk->ti", sys.A, f) - sys.b_base)) <= 1e-9
    rng = np.random.default_rng(0)
    for k in rng.choice(motion.n_samples, 10, replace=False):
        cols = np.flatnonzero(np.repeat(sys.stance[k], 3))
        A = sys.A[k][:, cols]
        null = np.linalg.svd(A)[2][6:].T  # basis of A's null space
        tau = sys.b_joint[k] - sys.D[k] @ f[k]
        grad = -2 * sys.D[k][:, cols].T @ (w * tau)
        assert np.max(np.abs(null.T @ grad)) <= 1e-9 * np.max(np.abs(grad))


def test_pyramid_is_inside_the_cone(robot, motion):
    prepared = prepare(robot, motion, contact=ContactParams(mu=0.25, cone="pyramid"))
    f, _, _ = solve_fast(prepared.system, np.zeros_like(prepared.q), "joule",
                      prepared.weights("joule"), prepared.contact)
    f3 = f.reshape(motion.n_samples, -1, 3)
    assert np.all(np.hypot(f3[..., 0], f3[..., 1]) <= 0.25 * f3[..., 2] + 1e-9)


def test_swing_feet_carry_nothing_and_stance_feet_push(robot, motion):
    prepared = prepare(robot, motion, contact=ContactParams(min_normal_force=0.5))
    analysis = prepared.evaluate()
    assert np.all(analysis.forces[~motion.stance] == 0.0)
    assert np.all(analysis.forces[..., 2][motion.stance] >= 0.5 - 1e-9)


def test_infeasible_friction_names_time_and_feet(robot, motion):
    prepared = prepare(robot, motion, contact=ContactParams(mu=0.01))
    with pytest.raises(InfeasibleForcesError, match=r"t = \d+\.\d+ s \(sample \d+\), stance feet"):
        prepared.evaluate()


def test_torque_limit_names_joint_time_and_torque(robot, motion):
    weak = CATALOGUE["AX-18A"]
    weak = type(weak)(**{**weak.__dict__, "stall_torque": 0.05})
    prepared = prepare(robot, motion, motor=weak)
    with pytest.raises(TorqueLimitError, match=r"joint \w+_\w+ needs .* N·m \(limit 0.0500 N·m\)"):
        prepared.evaluate()


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


@pytest.mark.parametrize("objective", ["joule", "positive_work"])
def test_unreachable_wrench_is_caught_on_every_path(robot, motion, objective):
    """LF and LM alone: gravity has a moment about the line through them that no foot force can
    balance (the KKT system is singular). Both the KKT path and the conic path (which drops
    redundant base rows) say so with the time and the feet, not a numpy traceback."""
    stance = motion.stance.copy()
    stance[5] = False
    stance[5, [0, 1]] = True  # LF, LM
    two = hexaleg.Motion(t=motion.t, q=motion.q, v=motion.v, a=motion.a, stance=stance,
                         feet=motion.feet, period=motion.period, distance=motion.distance)
    expected = r"feet LF, LM cannot .*\(sample 5\).*miss the base rows"
    with pytest.raises(InfeasibleForcesError, match=expected):
        prepare(robot, two).evaluate(objective=objective)
