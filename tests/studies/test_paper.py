"""Tests of hexaleg.studies.paper.model: the paper's single elastic joint (eq. 13–24, Table 6, eq.
25)."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest

from hexaleg.cli import main
from hexaleg.errors import HexalegError, InvalidParameterError
from hexaleg.studies.paper.model import (
    PaperJoint,
    k_E_readings,
    k_M_paper_number,
    metric,
    optimise,
    pinocchio_femur_torque,
)

J0 = PaperJoint()


def test_k_M_paper_number_within_table6_rounding():
    # Table 6 rounding: m = 3.611e-2 ± 5e-6 kg, l = 47.141 ± 5e-4 mm, I = 107.059 ± 5e-4 kg·mm².
    m, l_mm, i_mm = 3.611e-2, 47.141, 107.059
    tol = 4 / 1.05 * (5e-6 * l_mm**2 + 2 * m * l_mm * 5e-4 + 5e-4)
    assert abs(k_M_paper_number() - 713.547) <= tol
    assert k_M_paper_number() == pytest.approx(4 * (m * l_mm**2 + i_mm) / 1.05, rel=1e-12)


def test_k_M_SI_by_hand():
    # ω² (m l² + I)/α in SI, typed out: 4 (0.03611·0.047141² + 107.059e-6) / 1.05 N·m/rad.
    hand = 4 * (0.03611 * 0.047141**2 + 107.059e-6) / 1.05
    assert J0.k_M() == pytest.approx(hand, rel=1e-12)
    assert hand == pytest.approx(7.1354e-4, rel=1e-4)
    # ... which is 0.01245 N·mm/deg, not 713.5 N·mm/deg.
    assert hand * 1000 * math.pi / 180 == pytest.approx(0.012454, rel=1e-4)
    # The eq. 7 convention (κ = kα²) needs α times less stiffness for the same joint stiffness.
    assert PaperJoint(convention="eq7").k_M() == pytest.approx(hand / 1.05, rel=1e-12)


def test_k_M_makes_torque_constant_while_engaged():
    # Eq. 18–19: at k_M, dM/dt = 0 while the spring is engaged, M = −J ω² θ_k there (no gravity).
    t = J0.times(4096)
    th, _, _ = J0.trajectory(t)
    tau = J0.motor_torque(t, J0.k_M(), gravity=False)
    on = th > J0.theta_k
    np.testing.assert_allclose(tau[on], -J0.J * 4 * J0.theta_k, rtol=1e-12)


def test_int_sq_and_rms_and_joule_optimum_equal_closed_form():
    cf = J0.closed_form_int_sq()
    for name in ("int_sq", "rms", "joule"):
        opt = optimise(J0, name, gravity=False, n=8192, bounds=(0.5 * cf, 1.5 * cf), grid=61)
        assert opt.k == pytest.approx(cf, rel=1e-6), name


def test_mean_abs_optimum_equals_closed_form():
    cf = J0.closed_form_mean_abs()
    opt = optimise(J0, "mean_abs", gravity=False, n=32768, bounds=(0.8 * cf, 1.2 * cf), grid=41)
    assert opt.k == pytest.approx(cf, rel=1e-4)
    # It is neither eq. 19's k_M nor the peak-optimum interval's ends.
    assert cf > 1.5 * J0.k_M()


def test_work_optimum_equals_closed_form_and_is_not_k_E():
    cf = J0.closed_form_work()
    for name in ("positive_work", "absolute_work"):
        opt = optimise(J0, name, gravity=False, n=32768, bounds=(0.8 * cf, 1.2 * cf), grid=41)
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
    opt = optimise(J0, "peak", gravity=False)
    assert lo <= opt.k <= hi
    assert opt.saving == pytest.approx(J0.closed_form_peak_saving(), abs=1e-12)


def test_spring_is_conservative_over_a_period_and_eq21_has_no_minimum():
    # Eq. 20 over a whole period: zero net motor work for any stiffness, with or without gravity.
    e = J0.energy(np.array([0.0, J0.k_M(), 30.0]), 0.0, J0.period, gravity=True, n=40001)
    np.testing.assert_allclose(e, 0.0, atol=1e-9)
    # Eq. 21 from contact to the turning point is affine in k, slope ½ α (A − θ_k)² > 0.
    tk, tq = J0.contact_time(), math.pi / 4
    e0, e1 = J0.energy(np.array([0.0, 1.0]), tk, tq, gravity=False, n=200001)
    assert e1 - e0 == pytest.approx(0.5 * 1.05 * (0.3 - J0.theta_k) ** 2, rel=1e-6)
    assert k_E_readings()["eq21_time_tk_to_quarter"]["k_SI"] is None


def test_hanging_gravity_makes_spring_useless_upright_makes_it_useful():
    hang = optimise(J0, "int_sq", gravity=True)
    up = optimise(PaperJoint(posture="upright"), "int_sq", gravity=True)
    assert hang.k == 0.0 and hang.saving == 0.0
    assert up.k > 10 * J0.k_M() and up.saving > 0.5 and not up.on_bound


@pytest.mark.parametrize("posture", ["hanging", "upright"])
def test_pinocchio_femur_matches_eq13(posture):
    j = PaperJoint(posture=posture)
    t = j.times(64)
    for g in (False, True):
        ref = j.rigid_torque(t, gravity=g)
        tau = pinocchio_femur_torque(t, j, gravity=g)
        assert np.max(np.abs(tau - ref)) <= 1e-9 * np.max(np.abs(ref))


def test_bad_input():
    with pytest.raises(InvalidParameterError, match="never engages"):
        PaperJoint(amplitude=0.1)  # θ_k = 0.1278 rad
    with pytest.raises(InvalidParameterError, match="never engages"):
        PaperJoint(amplitude=J0.theta_k)
    with pytest.raises(InvalidParameterError, match="omega"):
        PaperJoint(omega=0.0)
    with pytest.raises(InvalidParameterError, match="omega"):
        PaperJoint(omega=-2.0)
    with pytest.raises(InvalidParameterError, match="alpha"):
        PaperJoint(alpha=0.0)
    with pytest.raises(InvalidParameterError, match="nan"):
        PaperJoint(mass=float("nan"))
    with pytest.raises(InvalidParameterError, match="posture"):
        PaperJoint(posture="sideways")
    with pytest.raises(InvalidParameterError, match="metric"):
        metric(J0, "speed", 1.0)
    with pytest.raises(InvalidParameterError, match="k"):
        J0.motor_torque(J0.times(16), -1.0)
    with pytest.raises(InvalidParameterError, match="t"):
        J0.trajectory(np.array([0.0, np.nan]))
    with pytest.raises(HexalegError):
        PaperJoint(offset=0.1).closed_form_int_sq()


def test_report_files_and_cli(tmp_path, capsys):
    assert main(["paper", "--out", str(tmp_path), "--samples", "512"]) == 0
    assert "713.544" in capsys.readouterr().out
    saved = json.loads((tmp_path / "paper.json").read_text())
    assert saved["k_M_paper_units"] == pytest.approx(713.544, abs=1e-3)
    assert saved["k_M_SI_Nm_per_rad"] == pytest.approx(J0.k_M())
    for key in ("k_M_paper_units", "k_M_SI_Nm_per_rad", "optima", "k_E", "saving_52_81",
                "pinocchio_check"):
        assert key in saved
    assert set(saved["optima"]) == {"no_gravity", "gravity_hanging", "gravity_upright"}
    assert "not reproduced" in saved["k_E"]["verdict"]
    pngs = sorted(p.name for p in tmp_path.glob("fig*.png"))
    assert [p[:5] for p in pngs] == [f"fig{i:02d}" for i in range(5, 14)]
    assert "713.5" in (tmp_path / "summary.md").read_text()
