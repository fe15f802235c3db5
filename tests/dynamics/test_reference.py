"""Tests of hexaleg.dynamics.reference: the fast path against the cvxpy reference formulation."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import prepare
from hexaleg.dynamics.reference import solve_reference
from hexaleg.dynamics.solver import solve_fast
from hexaleg.robot.springs import DeadZoneSpring


def _springs(robot):
    return {leg.joint_names[1]: DeadZoneSpring(stiffness=1.5, theta_k=0.1, neutral=0.5)
            for leg in robot.legs}


@pytest.mark.parametrize(("mu", "cone", "binding"), [
    (0.6, "soc", False),      # default friction: no inequality binds, pure KKT path
    (0.3, "soc", True),       # low friction: the exact cone binds on many samples
    (0.25, "pyramid", True),  # the inscribed pyramid binds
])
def test_fast_path_equals_cvxpy_reference(robot, walk200, mu, cone, binding):
    """cvxpy solves every sample: the 200-sample gait."""
    prepared = prepare(robot, walk200, contact=ContactParams(mu=mu, cone=cone))
    tau_s = prepared.spring_torques(_springs(robot))
    w = prepared.weights("joule")
    f_fast, _, resolved = solve_fast(prepared.system, tau_s, "joule", w, prepared.contact)
    f_ref = solve_reference(prepared.system, tau_s, "joule", w, prepared.contact)
    assert resolved.any() == binding
    assert np.max(np.abs(f_fast - f_ref)) <= 1e-6


@pytest.mark.parametrize("objective", ["electrical", "positive_work"])
def test_non_smooth_objectives_match_the_reference_optimum(robot, walk200, objective):
    """Same optimal value to 1e-8 W; forces to 1e-6 N for positive work and 1e-5 N for electrical
    energy (measured 4e-8 and 4e-6 N): the regulariser ε = 1e-4 leaves the optimum only weakly
    curved, so solver tolerances of 1e-10 in value move the forces by microNewtons."""
    prepared = prepare(robot, walk200)
    tau_s = prepared.spring_torques(_springs(robot))
    w = prepared.weights(objective)
    eps = prepared.contact.regularization
    sys = prepared.system
    samples = np.arange(0, walk200.n_samples, 10)
    f_fast, _, _ = solve_fast(sys, tau_s, objective, w, prepared.contact)
    f_ref = solve_reference(sys, tau_s, objective, w, prepared.contact, samples=samples)

    def cost(f):  # the objectives as hexaleg.robot.motor defines them, independently of conic.py
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
