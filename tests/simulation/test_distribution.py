"""The balance controller's force program: its wrench map, and its answers against cvxpy's on
instants captured from a closed-loop run (where the cones and the torque limits bind)."""

from __future__ import annotations

import dataclasses

import cvxpy as cp
import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.scenario.scenario import Scenario
from hexaleg.simulation import balance
from hexaleg.simulation.distribution import (
    REGULARISATION,
    TorqueBounds,
    distribute,
    inside_cones,
    wrench_map,
)
from hexaleg.simulation.run import Settings, simulate

TROT = '[gait]\npattern = "trot"\nperiod = 0.4\nstride_length = 0.12\nsamples = 200\n' \
       '[contact]\nmu = 1\n'
"""Solo-12's trot of #54 (fewer samples: the suite's time)."""


def reference(a, dw, f0, mu, spread, bounds, alpha=REGULARISATION):
    """The module's program written in cvxpy (its own modelling of the squares, the cones and
    the rows), solved to 1e-10."""
    n = len(f0)
    x = cp.Variable(3 * n)
    s = np.r_[np.ones(3), np.full(3, 1.0 / spread)]
    f = cp.reshape(x, (n, 3), order="C") + f0
    constraints = [cp.SOC(mu * f[i, 2], f[i, :2]) for i in range(n)]
    if bounds is not None:
        constraints += [bounds.t @ x <= bounds.high, bounds.t @ x >= bounds.low]
    objective = cp.sum_squares(cp.multiply(s, a @ x - dw)) + alpha * cp.sum_squares(x)
    cp.Problem(cp.Minimize(objective), constraints).solve(
        solver=cp.CLARABEL, tol_gap_abs=1e-11, tol_gap_rel=1e-11, tol_feas=1e-11)
    return np.asarray(x.value).reshape(n, 3)


def test_the_wrench_map_is_the_total_force_and_moment_about_the_centre():
    """``A f`` is (Σ f_i, Σ r_i × f_i) for random feet and forces (seeded)."""
    rng = np.random.default_rng(3)
    feet, com, f = rng.normal(size=(4, 3)), rng.normal(size=3), rng.normal(size=(4, 3))
    w = wrench_map(feet, com) @ f.ravel()
    assert np.allclose(w[:3], f.sum(axis=0), atol=1e-14)
    assert np.allclose(w[3:], np.cross(feet - com, f).sum(axis=0), atol=1e-14)


def test_no_wrench_change_keeps_the_plan_and_a_small_one_is_made():
    """ΔW = 0 gives Δf = 0; a small ΔW inside the cones is made to the regularisation's
    accuracy (four feet: the wrench map has full row rank)."""
    feet = np.array([[0.2, 0.15, 0], [0.2, -0.15, 0], [-0.2, 0.15, 0], [-0.2, -0.15, 0]])
    f0 = np.tile([0.0, 0.0, 6.0], (4, 1))
    a = wrench_map(feet, np.array([0, 0, 0.2]))
    df, bound = distribute(a, np.zeros(6), f0, 0.6, 0.25)
    assert not bound and np.all(df == 0)
    dw = np.array([0.3, -0.2, 1.0, 0.05, -0.04, 0.02])
    df, bound = distribute(a, dw, f0, 0.6, 0.25)
    assert not bound and inside_cones(f0 + df, 0.6)
    assert np.allclose(a @ df.ravel(), dw, rtol=1e-2, atol=1e-3)


def test_bad_values_are_named():
    a = wrench_map(np.zeros((2, 3)), np.zeros(3))
    with pytest.raises(InvalidParameterError, match="mu"):
        distribute(a, np.zeros(6), np.zeros((2, 3)), 0.0, 0.2)
    with pytest.raises(InvalidParameterError, match="shapes"):
        distribute(a, np.zeros(5), np.zeros((2, 3)), 0.6, 0.2)


@pytest.fixture(scope="module")
def captured(tmp_path_factory):
    """The force programs of every update of Solo-12's position-servo trot, closed loop (2
    cycles) on a floor of μ 0.4 (the plan's is 1: three quarters of the updates meet a cone;
    at μ 0.5 none does, the position servos getting the plan's torques as their reference):
    ``(a, dw, f0, mu, spread, bounds, answer, constrained)``."""
    config = tmp_path_factory.mktemp("trot") / "trot.toml"
    config.write_text(TROT)
    run = Scenario.load("solo12", config)
    prepared = run.prepare()
    seen = []
    original = balance.distribute

    def capture(a, dw, f0, mu, spread, bounds=None):
        answer, bound = original(a, dw, f0, mu, spread, bounds)
        seen.append((a, dw, f0, mu, spread, bounds, answer, bound))
        return answer, bound

    balance.distribute = capture
    try:
        simulate(prepared.robot, prepared.motion, prepared.motor, None,
                 Settings(controller="position", cycles=2, evaluate=1, force_samples=0,
                          feedback="on", mu=0.4), contact=prepared.contact,
                 prepared=prepared)
    finally:
        balance.distribute = original
    assert seen, "no update captured"
    return seen


def test_the_programs_answers_are_cvxpys_on_captured_instants(captured):
    """On 12 captured instants where a cone or a torque limit bound (Clarabel's path) and 6
    where none did (the normal equations), the correction is cvxpy's to 1e-5 of its size (a
    wrong sign, a dropped row or a cone about another axis is off by the correction's own size).
    1e-6 held on every instant of this fixture run alone; in the whole suite's order (two
    workers) the trot's run captured an instant 3.6e-6 of its size from cvxpy's, whose objective
    was 1.6e-7 of itself above cvxpy's: Clarabel's accuracy there ("Solved", 13 iterations), not
    the program's modelling. Why the run differs in that order is not traced."""
    bound = [c for c in captured if c[7]]
    free = [c for c in captured if not c[7]]
    assert len(bound) >= 12 and len(free) >= 6
    picks = [bound[i] for i in np.linspace(0, len(bound) - 1, 12).astype(int)] + \
        [free[i] for i in np.linspace(0, len(free) - 1, 6).astype(int)]
    for a, dw, f0, mu, spread, bounds, answer, _ in picks:
        expected = reference(a, dw, f0, mu, spread, bounds)
        scale = max(np.abs(expected).max(), np.abs(f0).max())
        assert np.abs(answer - expected).max() <= 1e-5 * scale
        assert inside_cones(f0 + answer, mu, slack=1e-7 * scale)
        assert bounds.holds(answer.ravel(), slack=1e-7 * scale)


def test_the_torque_rows_bind():
    """A wrench change far beyond the actuators: the correction stops at the torque bound."""
    feet = np.array([[0.2, 0.15, 0.0], [-0.2, -0.15, 0.0]])
    f0 = np.tile([0.0, 0.0, 10.0], (2, 1))
    a = wrench_map(feet, np.array([0, 0, 0.2]))
    t = -np.kron(np.eye(2), np.array([[0.0, 0.0, 0.2]]))  # one joint a foot: τ = −0.2 f_z
    bounds = TorqueBounds(t, np.full(2, -1.0), np.full(2, 1.0))
    df, bound = distribute(a, np.array([0, 0, 100.0, 0, 0, 0]), f0, 0.6, 0.25, bounds)
    assert bound and np.allclose(t @ df.ravel(), -1.0, atol=1e-7)
    assert np.allclose(df, reference(a, np.array([0, 0, 100.0, 0, 0, 0]), f0, 0.6, 0.25,
                                     bounds), atol=1e-6)


def test_an_80_kg_robots_program_is_solved_in_units_of_its_forces():
    """HyQ's (80 kg, example-robot-data) program at a stand on two feet of its position-servo
    trot (captured, rounded to 1e-3): a cone and the torque rows bind, offsets of hundreds of
    newtons. In newtons Clarabel's iterates cycled to its iteration limit and the run stopped
    ("Clarabel MaxIterations"); solved in units of the plan's largest force it is cvxpy's
    answer, inside the cones and the torque bounds."""
    feet = np.array([[0.572, -0.184, -0.542], [-0.383, 0.176, -0.537]])
    a = wrench_map(feet, np.zeros(3))
    dw = np.array([3801.37, -1303.18, -309.644, -183.793, 375.818, -463.445])
    f0 = np.array([[-64.352, 55.776, 384.094], [74.372, -88.01, 490.188]])
    t = np.array([[0, 0, 0, -0.323, 0.503, 0.12], [0, 0, 0, 0.455, 0.272, 0.078],
                  [0, 0, 0, 0.238, 0.199, -0.186], [0.325, -0.505, 0.114, 0, 0, 0],
                  [0.439, 0.3, 0.073, 0, 0, 0], [0.175, 0.175, 0.265, 0, 0, 0]])
    bounds = TorqueBounds(t, np.array([-150.919, -226.279, -79.458, -160.662, -147.87, -238.63]),
                          np.array([149.081, 73.721, 220.542, 139.338, 152.13, 61.37]))
    df, bound = distribute(a, dw, f0, 0.6, 0.57, bounds)
    expected = reference(a, dw, f0, 0.6, 0.57, bounds)
    assert bound and np.abs(df - expected).max() <= 1e-6 * np.abs(f0).max()
    assert inside_cones(f0 + df, 0.6, slack=1e-6) and bounds.holds(df.ravel(), slack=1e-6)


def test_dataclass_replace_keeps_settings_valid():
    """``feedback`` is a checked setting: an unknown value names the allowed ones."""
    from hexaleg.errors import UnknownNameError

    with pytest.raises(UnknownNameError, match="auto, off, on"):
        dataclasses.replace(Settings(), feedback="sometimes")


def test_a_sole_moves_its_centre_of_pressure_within_its_corners():
    """One 18 × 9 cm sole as its four corners (biped6's), carrying the weight of a 16.4 kg body
    0.45 m above it at its centre: a pitch moment a point foot cannot make is made by moving
    the centre of pressure forward, the corners' normal forces nonnegative; a moment beyond
    what the sole holds (the centre of pressure past the toe) stops at the edge — the cones
    bind, Clarabel's answer is cvxpy's, and no corner pulls."""
    from hexaleg.robot.soles import Sole

    corners = Sole(0.18, 0.09).corners()
    f0 = np.tile([0.0, 0.0, 16.4 * 9.81 / 4], (4, 1))
    a = wrench_map(corners, np.array([0.0, 0.0, 0.45]))
    dw = np.array([0.0, 0.0, 0.0, 0.0, -5.0, 0.0])  # N·m about y: −x f_z, the toe pressed
    df, bound = distribute(a, dw, f0, 0.6, 0.1)
    f = f0 + df
    cop = (f[:, 2] @ corners) / f[:, 2].sum()
    assert not bound and np.all(f[:, 2] > 0) and cop[0] > 0.02
    assert np.allclose(a @ df.ravel(), dw, atol=0.1)
    dw = np.array([0.0, 0.0, 0.0, 0.0, -40.0, 0.0])  # 40 N·m: 0.25 m of a 161 N load
    df, bound = distribute(a, dw, f0, 0.6, 0.1)
    f = f0 + df
    cop = (f[:, 2] @ corners) / f[:, 2].sum()
    assert bound and np.all(f[:, 2] > -1e-7) and cop[0] <= 0.09 + 1e-9
    assert np.allclose(df, reference(a, dw, f0, 0.6, 0.1, None), atol=1e-6)
