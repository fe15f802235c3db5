"""The measures of a walk: energy through the energy module, foot forces, the plan's samples."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.dynamics import energy


def test_energy_is_the_energy_module_of_the_simulated_torques(feedforward):
    """Each evaluated cycle's metrics are :func:`hexaleg.dynamics.energy.metrics` of the recorded
    motor torques and joint speeds; the electrical energy is Σ P_e dt of the motor model."""
    run = feedforward.with_springs
    traj, sim = run.trajectory, run.sim
    steps = round(feedforward.motion.period / sim.timestep)
    window = slice(traj.n - steps, traj.n)
    qdot = traj.qvel[window][:, sim.joints.dof]
    expected = energy.metrics(traj.tau_motor[window], qdot, sim.timestep,
                              feedforward.analysis.motor)
    assert run.metrics["electrical"] == pytest.approx(expected["total"]["electrical"], rel=1e-12)
    power = feedforward.analysis.motor.electrical_power(traj.tau_motor[window], qdot)
    assert run.metrics["electrical"] == pytest.approx(power.sum() * sim.timestep, rel=1e-12)


def test_planned_index_wraps_the_period(walk):
    from hexaleg.simulation.measures import planned_index

    h = walk.dt
    t = np.array([0.0, h, 2.5 * h, walk.period - h / 2, walk.period, 3 * walk.period + h])
    assert list(planned_index(walk, t)) == [0, 1, 2, walk.n_samples - 1, 0, 1]


def test_feet_carry_the_weight_as_predicted(feedforward):
    """Three stance feet: their mean normal force is a third of the weight, as in the analysis."""
    forces = feedforward.baseline.forces
    assert 3 * forces["normal_mean_sim"] == pytest.approx(forces["weight"], rel=0.03)
    assert forces["normal_mean_sim"] == pytest.approx(forces["normal_mean_predicted"], rel=0.03)
