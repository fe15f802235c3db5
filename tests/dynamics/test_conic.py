"""Tests of hexaleg.dynamics.conic: the exact per-sample Clarabel solve and its errors."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.dynamics.conic import solve_sample
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import InfeasibleForcesError, TorqueLimitError
from hexaleg.robot.catalogue import CATALOGUE


def test_conic_solve_equals_the_kkt_optimum_where_nothing_binds(robot, walk200):
    """At μ = 0.6 no inequality binds: the conic program's optimum is the KKT solution."""
    prepared = prepare(robot, walk200)
    sys, tau_s = prepared.system, np.zeros_like(prepared.q)
    f0 = prepared.gains("joule").f0
    for k in range(0, walk200.n_samples, 40):
        f = solve_sample(sys, k, tau_s, "joule", prepared.weights("joule"), prepared.contact)
        assert np.max(np.abs(f - f0[k])) <= 1e-6


def test_infeasible_friction_names_time_and_feet(robot, walk200):
    prepared = prepare(robot, walk200, contact=ContactParams(mu=0.01))
    with pytest.raises(InfeasibleForcesError, match=r"t = \d+\.\d+ s \(sample \d+\), stance feet"):
        prepared.evaluate()


def test_torque_limit_names_joint_time_and_torque(robot, walk200):
    weak = CATALOGUE["AX-18A"]
    weak = type(weak)(**{**weak.__dict__, "stall_torque": 0.05})
    prepared = prepare(robot, walk200, motor=weak)
    with pytest.raises(TorqueLimitError, match=r"joint \w+_\w+ needs .* N·m \(limit 0.0500 N·m\)"):
        prepared.evaluate()


def test_a_flight_phase_is_named_as_one(robot):
    """A gait whose legs all lift together (phases all 0, β = 0.6) used to be told "the stance
    feet (none) … the motion needs a body sway"."""
    import hexaleg

    motion = hexaleg.gait(robot, hexaleg.GaitParams(samples=100, phases=(0.0,) * 6,
                                                   duty_factor=0.6))
    with pytest.raises(InfeasibleForcesError, match=r"no foot is on the ground at t = 0\.6000 s "
                                                    r"\(sample 60\): every leg is in swing "
                                                    r"together for 40% of the samples \(a flight "
                                                    r"phase\).*raise duty_factor"):
        prepare(robot, motion).evaluate(None)


def test_a_biped_on_one_point_foot_is_pointed_at_the_zmp_pattern():
    """A two-legged robot on one point foot is refused by name, and the message points at the
    walking pattern hexaleg plans (``balance = 'zmp'``), not at a claim that it plans none."""
    from types import SimpleNamespace

    from hexaleg.dynamics.conic import raise_unreachable

    system = SimpleNamespace(leg_names=["L", "R"], stance=np.array([[True, False]]),
                             t=np.array([0.25]))
    with pytest.raises(InfeasibleForcesError, match=r"one point foot \(L\)") as err:
        raise_unreachable(system, 0, 1e-3)
    assert "balance = 'auto' or 'zmp'" in str(err.value)
    assert "do not plan" not in str(err.value)
