"""Tests of hexaleg.motion.recorded.integrator: a log's samples found to be the knots of a
semi-implicit Euler integration by their own numbers, and a log read back so marked."""

from __future__ import annotations

import dataclasses

import numpy as np
import pinocchio as pin
import pytest

import hexaleg
from hexaleg.motion.recorded.integrator import integrator_of, step_misses
from hexaleg.motion.recorded.write import write_motion_log
from hexaleg.motion.trajectory import SEMI_IMPLICIT, Motion
from hexaleg.optimal.motion_file import repeated


def knots(robot: hexaleg.Robot, motion: Motion, semi: bool = True) -> Motion:
    """``motion``'s cycle integrated again from its first configuration by the semi-implicit
    (else the explicit) Euler step, with its joint velocities made to close the cycle: a periodic
    motion whose samples are an integration's knots, built independently of the solver."""
    model, dt, n = robot.model, motion.dt, motion.n_samples
    v = motion.v.copy()
    v[:, 6:] -= v[:, 6:].mean(axis=0)  # the joints return to their start after a cycle
    phase = 2.0 * np.pi * np.arange(n) / n
    v[:, 0] += 0.02 * np.sin(phase)  # the base surges and bobs, m/s, as a whole robot's does
    v[:, 2] += 0.01 * np.cos(phase)
    ext = np.vstack([v, v[:1]])
    a = np.diff(ext, axis=0) / dt
    q = np.zeros((n + 1, model.nq))
    q[0] = motion.q[0]
    for k in range(n):
        q[k + 1] = pin.integrate(model, q[k], (ext[k + 1] if semi else ext[k]) * dt)
    start, end = pin.XYZQUATToSE3(q[0, :7]), pin.XYZQUATToSE3(q[n, :7])
    cycle = (end * start.inverse()).homogeneous
    return dataclasses.replace(
        motion, q=q[:n], v=v, a=a, distance=float(np.linalg.norm(cycle[:2, 3])),
        info={"cycle": cycle.tolist(), "integrator": SEMI_IMPLICIT} if semi else
        {"cycle": cycle.tolist()})


@pytest.fixture(scope="module")
def coarse(robot: hexaleg.Robot) -> Motion:
    """The default tripod at 50 samples a cycle (knots tens of milliseconds apart, as an
    optimal motion's)."""
    return hexaleg.gait(robot, hexaleg.GaitParams(samples=50))


def test_knots_are_told_from_samples(robot, coarse):
    """The knots of a semi-implicit integration are found; the knots of an explicit one, a
    parametric gait's samples and a motion with a missing value are not."""
    semi = knots(robot, coarse)
    misses = step_misses(robot.model, semi.q, semi.v, semi.a, semi.dt)
    assert misses[0] < 1e-12 < 1e-3 < misses[1]
    assert integrator_of(robot.model, semi.q, semi.v, semi.a, semi.dt) == SEMI_IMPLICIT
    explicit = knots(robot, coarse, semi=False)
    assert integrator_of(robot.model, explicit.q, explicit.v, explicit.a, explicit.dt) is None
    assert integrator_of(robot.model, coarse.q, coarse.v, coarse.a, coarse.dt) is None
    holed = semi.a.copy()
    holed[3, 7] = np.nan
    assert integrator_of(robot.model, semi.q, semi.v, holed, semi.dt) is None


def test_a_log_of_knots_reads_back_marked_and_closes_its_cycle(robot, coarse, tmp_path):
    """An optimal-like cycle written as a motion log (three cycles, by the writer of the optimal
    motion files) reads back through load_motion with ``info["integrator"]``, which the log has
    no column for, so balance feedback closes its cycle at the next cycle's first knot (the
    explicit step misses it by 50 µm here); a gait's log reads back without it."""
    from hexaleg.simulation.balance import cycle_end

    semi = knots(robot, coarse)
    written = repeated(semi, 3)
    path = write_motion_log(robot, written, tmp_path / "knots.csv")
    loaded = hexaleg.load_motion(robot, path)
    assert loaded.info.get("integrator") == SEMI_IMPLICIT
    step = written.q[semi.n_samples, :3] - written.q[0, :3]  # the cycle's own, to its next
    _, position = cycle_end(robot.model, loaded)  # (the reader sets the ground's height)
    _, explicit = cycle_end(robot.model, dataclasses.replace(loaded, info={}))
    assert np.abs(position - loaded.q[0, :3] - step).max() < 1e-9
    assert np.abs(explicit - loaded.q[0, :3] - step).max() > 1e-5
    gait = write_motion_log(robot, repeated(coarse, 3), tmp_path / "gait.csv")
    assert "integrator" not in hexaleg.load_motion(robot, gait).info
