"""Tests of hexaleg.paper.metrics: the costs of the paper's joint over a period, ε (eq.
24) and the numerically optimal stiffness against the closed forms."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.metrics import energy_ratio, metric, optimal_stiffness

J0 = PaperJoint()


def test_int_sq_and_rms_and_joule_optimum_equal_closed_form():
    cf = J0.closed_form_int_sq()
    for name in ("int_sq", "rms", "joule"):
        opt = optimal_stiffness(J0, name, gravity=False, n=8192, bounds=(0.5 * cf, 1.5 * cf),
                                grid=61)
        assert opt.k == pytest.approx(cf, rel=1e-6), name


def test_mean_abs_optimum_equals_closed_form():
    cf = J0.closed_form_mean_abs()
    opt = optimal_stiffness(J0, "mean_abs", gravity=False, n=32768,
                            bounds=(0.8 * cf, 1.2 * cf), grid=41)
    assert opt.k == pytest.approx(cf, rel=1e-4)
    # It is neither eq. 19's k_M nor the peak-optimum interval's ends.
    assert cf > 1.5 * J0.k_M()


def test_work_optimum_equals_closed_form_and_is_not_k_E():
    cf = J0.closed_form_work()
    for name in ("positive_work", "absolute_work"):
        opt = optimal_stiffness(J0, name, gravity=False, n=32768, bounds=(0.8 * cf, 1.2 * cf),
                                grid=41)
        assert opt.k == pytest.approx(cf, rel=2e-4), name
    assert cf * 1e6 == pytest.approx(1462.0, abs=0.5)  # eq. 19 units; the paper's k_E is 784.717


def test_peak_saving_in_flat_optimum_is_one_minus_thk_over_A():
    lo, hi = J0.closed_form_peak_interval()
    rigid = float(metric(J0, "peak", 0.0, gravity=False))
    assert rigid == pytest.approx(J0.J * 4 * 0.3, rel=1e-12)  # J A ω²
    for k in np.linspace(lo, hi, 7):
        peak = float(metric(J0, "peak", k, gravity=False))
        assert 1 - peak / rigid == pytest.approx(1 - J0.theta_k / 0.3, abs=1e-12)
    for k in (0.9 * lo, 1.1 * hi):  # outside the interval the peak is higher
        assert 1 - float(metric(J0, "peak", k, gravity=False)) / rigid < 1 - J0.theta_k / 0.3 - 1e-4
    opt = optimal_stiffness(J0, "peak", gravity=False)
    assert lo <= opt.k <= hi
    assert opt.saving == pytest.approx(J0.closed_form_peak_saving(), abs=1e-12)


def test_hanging_gravity_makes_spring_useless_upright_makes_it_useful():
    hang = optimal_stiffness(J0, "int_sq", gravity=True)
    up = optimal_stiffness(PaperJoint(posture="upright"), "int_sq", gravity=True)
    assert hang.k == 0.0 and hang.saving == 0.0
    assert up.k > 10 * J0.k_M() and up.saving > 0.5 and not up.on_bound


def test_energy_ratio_is_positive_work_over_J_and_swept_angle():
    # Rigid, no gravity: positive work J A² ω² per period, swept angle 4A: ε = A ω² / 4 (eq. 24).
    assert float(energy_ratio(J0, 0.0, gravity=False)) == pytest.approx(0.3 * 4 / 4, rel=1e-4)
    ks = np.array([0.0, J0.k_M()])
    np.testing.assert_array_equal(
        energy_ratio(J0, ks, gravity=True),
        metric(J0, "positive_work", ks, gravity=True) / (J0.J * 4 * J0.amplitude))


def test_bad_input():
    with pytest.raises(InvalidParameterError, match="metric"):
        metric(J0, "speed", 1.0)
    with pytest.raises(InvalidParameterError, match="bounds"):
        optimal_stiffness(J0, "rms", bounds=(1.0, 0.5))
