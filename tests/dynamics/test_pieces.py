"""Tests of hexaleg.dynamics.pieces: each objective as a per-joint cost equals its definition."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.dynamics.contact import OBJECTIVES
from hexaleg.dynamics.pieces import pieces
from hexaleg.robot.catalogue import motor


@pytest.mark.parametrize("objective", OBJECTIVES)
def test_per_joint_cost_is_the_objective(objective):
    m = motor()
    rng = np.random.default_rng(0)
    tau, qd = rng.normal(size=(4, 300)), rng.normal(size=(4, 300)) * 3
    c = np.full(tau.shape, m.joule_coefficient)
    eta = np.full(tau.shape, m.gearbox_efficiency)
    w = np.ones(tau.shape) if objective == "torque_squared" else c
    cost = pieces(objective, w, qd, eta, 1e-4).cost(tau)
    if objective == "joule":
        expected = c * tau**2
    elif objective == "torque_squared":
        expected = tau**2
    elif objective == "positive_work":
        expected = np.maximum(0.0, qd * tau) + 1e-4 * tau**2
    else:
        expected = m.electrical_power(tau, qd, regeneration=False) + 1e-4 * tau**2
    np.testing.assert_allclose(cost, expected, rtol=1e-12, atol=1e-15)


def test_every_piece_vanishes_at_zero_torque_and_slopes_are_derivatives():
    rng = np.random.default_rng(1)
    shape = (3, 10)
    p = pieces("electrical", np.full(shape, 2.0), rng.normal(size=shape),
               np.full(shape, 0.7), 1e-4)
    assert not p.values(np.zeros(shape)).any()
    tau, h = rng.normal(size=shape), 1e-6
    np.testing.assert_allclose(p.slopes(tau), (p.values(tau + h) - p.values(tau - h)) / (2 * h),
                               atol=1e-8)
    assert pieces("electrical", np.ones(shape), np.ones(shape), np.ones(shape), 1e-4).K == 2
