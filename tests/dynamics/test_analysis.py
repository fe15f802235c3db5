"""Tests of hexaleg.dynamics.analysis: an analysis' derived figures — the joint torque motor and
spring carry together, the motor's power, the springs' stored energy, computed when first asked
for (the invariants of the whole prepare → evaluate pipeline: test_prepare)."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.robot.springs import DeadZoneSpring, SpringSet


@pytest.fixture(scope="module")
def sprung(prepared):
    springs = SpringSet({leg.joint_names[1]: DeadZoneSpring(stiffness=1.5, theta_k=0.1,
                                                            neutral=0.5)
                         for leg in prepared.robot.legs})
    return prepared.evaluate(springs)


def test_the_total_torque_is_the_motors_and_the_springs(sprung):
    """A total of the motor's torque alone, or the motor less the spring, fails."""
    assert np.abs(sprung.tau_spring).max() > 0
    np.testing.assert_array_equal(sprung.tau_total, sprung.tau_motor + sprung.tau_spring)


def test_the_power_is_the_motors_alone(sprung):
    """The motor's power, not the joint's: a power of the total torque fails."""
    np.testing.assert_array_equal(sprung.power, sprung.tau_motor * sprung.qdot)


def test_the_stored_energy_is_the_springs_computed_when_asked(sprung, prepared):
    """Computed on first use (a sweep never asks), then kept; zero without springs."""
    assert "spring_energy" not in vars(sprung)
    stored = sprung.spring_energy
    np.testing.assert_array_equal(stored, sprung.springs.energies(sprung.robot, sprung.motion.q))
    assert stored is sprung.spring_energy and np.abs(stored).max() > 0
    rigid = prepared.evaluate(None)
    np.testing.assert_array_equal(rigid.spring_energy, np.zeros_like(rigid.q))
