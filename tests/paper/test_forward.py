"""Tests of hexaleg.paper.forward: the paper's Adams experiment forward beside the
analytic model (on the coarse grid of the ``forward`` fixture)."""

from __future__ import annotations

import math

import numpy as np
import pytest
from conftest import FORWARD_GRID

from hexaleg.errors import InvalidParameterError
from hexaleg.paper.forward import (
    COLUMNS,
    CURVES,
    MAX_GRID,
    NAMED,
    PAPER_EPS_MIN,
    PAPER_MEAN_MIN,
    TORQUE_METRICS,
    adams_model,
    forward_study,
    max_stiffness,
    parabola_vertex,
    stiffness_grid,
    without_friction,
)
from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.metrics import metric
from hexaleg.paper.readings import PAPER_K_E, PAPER_K_M, paper_number_to_si
from hexaleg.paper.simulated_joint import AdamsJoint, adams

J0 = PaperJoint()


def test_rigid_joint_forward_is_the_analytic_torque(forward):
    """Without a spring the forward run's torque is eq. 13's J θ̈ plus Table 5's secondary
    spring, which the analytic model leaves out: they differ by at most k₂A + c₂Aω = 3.06e-9 N·m
    (1.4e-5 of the peak); Table 2's friction adds a visible torque."""
    rigid = forward.torques[0]
    assert rigid.key == "rigid" and rigid.k == 0.0
    analytic, simulated, friction = rigid.torque
    np.testing.assert_array_equal(analytic, J0.motor_torque(rigid.t, 0.0, False))
    tables = forward.model.tables
    bound = (forward.model.stiffness_si(tables.secondary_stiffness) * J0.amplitude
             + forward.model.stiffness_si(tables.secondary_damping) * J0.amplitude * J0.omega)
    assert bound == pytest.approx(3.06e-9)
    assert np.abs(simulated - analytic).max() <= bound
    assert np.abs(friction - analytic).max() > 1e-3 * np.abs(analytic).max()


def test_the_forward_run_without_friction_finds_the_analytic_optima(forward):
    """The contact dynamics move neither optimum: the forward mean-|M| optimum lies within 3 % of
    the closed form (1350 vs 1320.1) and ε's within 1 % (1473 vs 1462.0)."""
    mean, eps = forward.optima["mean_abs"], forward.optima["epsilon"]
    assert mean.closed_form == pytest.approx(1320.1, abs=0.05)
    assert eps.closed_form == pytest.approx(1462.0, abs=0.05)
    assert mean.simulated == pytest.approx(mean.closed_form, rel=0.03)
    assert eps.simulated == pytest.approx(eps.closed_form, rel=0.01)
    assert mean.bracketed == (True, True) and eps.bracketed == (True, False)


def test_friction_moves_the_mean_torque_optimum_towards_the_papers_740(forward):
    mean, eps = forward.optima["mean_abs"], forward.optima["epsilon"]
    assert (mean.paper, mean.printed) == (PAPER_MEAN_MIN, PAPER_K_M)
    assert (eps.paper, eps.printed) == (PAPER_EPS_MIN, PAPER_K_E)
    assert 600 < mean.friction < 1000 < mean.simulated
    assert abs(mean.friction - 740) < abs(mean.simulated - 740) / 4
    assert eps.friction == FORWARD_GRID[0]  # below the grid: its end, flagged not bracketed
    assert mean.saving[2] < mean.saving[1] / 2 and eps.saving[2] < 0.02


def test_curves_optima_and_savings_are_the_runs(forward):
    """The curves are the analytic metric and the runs' (over the grid and at k = 0); the
    savings are at the grid's least value of each column."""
    np.testing.assert_array_equal(forward.grid, FORWARD_GRID)
    analytic = metric(J0, "mean_abs", paper_number_to_si(forward.grid), False,
                      forward.samples)
    np.testing.assert_allclose(forward.curves["mean_abs"][0], analytic, rtol=1e-15)
    for name in CURVES:
        values, zero = forward.curves[name], np.array(forward.baseline[name])
        assert values.shape == (len(COLUMNS), len(FORWARD_GRID))
        np.testing.assert_allclose(forward.optima[name].saving, 1 - values.min(axis=1) / zero,
                                   rtol=1e-12)
    k_m = next(r for r in forward.torques if r.key == "k_M")
    assert k_m.metrics["mean_abs"][2] == pytest.approx(
        adams(forward.model, PAPER_K_M, periods=1).mean_abs(), rel=1e-12)
    assert forward.period_check < 1e-6


def test_required_torques_at_the_named_stiffnesses(forward):
    assert [(r.key, r.label, r.k) for r in forward.torques] == list(NAMED)
    for r in forward.torques:
        assert r.torque.shape == (3, r.t.size) and tuple(r.metrics) == TORQUE_METRICS
        for name, (a, s, f) in r.metrics.items():
            assert a == pytest.approx(float(metric(J0, name, paper_number_to_si(r.k), False,
                                                   forward.samples)), rel=1e-12)
            assert s == pytest.approx(a, rel=0.08) if name == "mean_abs" else s > 0
            assert f > 0


def test_without_friction_is_the_run_with_friction_switched_off():
    """The lever is driven, so friction changes no state: the frictionless run is the run with
    friction less its friction torque."""
    with_, without = adams(AdamsJoint(), PAPER_K_M, 1), adams(AdamsJoint(friction=False),
                                                                PAPER_K_M, 1)
    derived = without_friction(with_)
    np.testing.assert_allclose(derived.torque, without.torque, rtol=0, atol=1e-18)
    np.testing.assert_array_equal(derived.arms, without.arms)
    assert not derived.friction.any() and with_.friction.any()


def test_parabola_vertex_on_a_parabola_and_at_the_grid_ends():
    ks = np.array([100.0, 300.0, 700.0, 900.0, 1500.0])
    assert parabola_vertex(ks, (ks - 750.0) ** 2) == (pytest.approx(750.0), True)
    assert parabola_vertex(ks, ks) == (100.0, False)
    assert parabola_vertex(ks, -ks) == (1500.0, False)
    # a tie: the first least value and its neighbours (100, 3), (300, 1), (700, 1)
    assert parabola_vertex(ks, np.array([3.0, 1.0, 1.0, 1.0, 3.0])) == (pytest.approx(500.0),
                                                                        True)


@pytest.mark.parametrize(("grid", "shown"), [
    ((0.0, 100.0, 200.0), "0.0"), ((100.0, -5.0, 200.0), "-5.0"),
    ((100.0, math.nan, 200.0), "nan"), ((100.0, 200.0), "[100.0, 200.0]"),
    ((100.0, 300.0, 200.0), "[100.0, 300.0, 200.0]"), ((100.0, "a", 200.0), "'a'")])
def test_a_bad_grid_is_named(grid, shown):
    with pytest.raises(InvalidParameterError, match="stiffness grid") as e:
        stiffness_grid(grid)
    assert shown in str(e.value) and ("> 0" in str(e.value) or "increasing" in str(e.value))


def test_a_grid_too_long_is_refused():
    stiffness_grid(np.arange(1.0, MAX_GRID + 1))
    with pytest.raises(InvalidParameterError, match=f"3 to {MAX_GRID}"):
        stiffness_grid(np.arange(1.0, MAX_GRID + 2))


def test_bad_samples_are_refused_before_any_run():
    with pytest.raises(InvalidParameterError, match=r"samples = 4\b"):
        forward_study(n=4)


def test_the_stiffest_grid_value_still_integrates():
    """max_stiffness keeps the forward run stable: at the bound its torques stay finite."""
    model = adams_model(PaperJoint())
    run = adams(model, max_stiffness(model), periods=1)
    assert np.all(np.isfinite(run.torque))
    with pytest.raises(InvalidParameterError, match=r"stiffness grid value = 1e\+100"):
        stiffness_grid([100.0, 200.0, 1e100])
