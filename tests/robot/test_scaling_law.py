"""Tests of hexaleg.robot.scaling_law: the Joule scaling law P_peak = a τ_peak^β fitted on the
catalogue — its fit recovers a known law, its residuals are the catalogue's own, a law fitted
without an actuator family brackets that family (leave-one-out), and every actuator it gives is
labelled assumed."""

from __future__ import annotations

import numpy as np
import pytest

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.catalogue import CATALOGUE
from hexaleg.robot.motor import Motor
from hexaleg.robot.scaling_law import (
    ENDS,
    LAW_MARK,
    catalogue_law,
    family,
    fit,
)


def _actuator(name: str, torque: float, c: float, eta: float = 0.8) -> Motor:
    return Motor(name=name, gear_ratio=1.0, torque_constant=1.0, resistance=c,
                 gearbox_efficiency=eta, regeneration=False, stall_torque=torque,
                 no_load_speed=10.0, voltage=24.0, source="test")


def test_the_fit_recovers_a_known_law():
    """Actuators made exactly on P = 7 τ^0.8 give a = 7, β = 0.8 and no spread."""
    motors = {f"m{i}": _actuator(f"m{i}", t, 7.0 * t**0.8 / t**2)
              for i, t in enumerate((0.5, 2.0, 30.0, 300.0))}
    law = fit(motors)
    assert law.coefficient == pytest.approx(7.0, rel=1e-12)
    assert law.exponent == pytest.approx(0.8, rel=1e-12)
    assert law.spread == (pytest.approx(1.0), pytest.approx(1.0)) and law.log_rms < 1e-12
    assert law.joule_coefficient(10.0) == pytest.approx(7.0 * 10.0**-1.2, rel=1e-12)


def test_the_catalogue_fit_and_its_residuals():
    """The numbers docs/energy.md states: P_peak = 11.27 τ^1.005 W over the 21 catalogue
    actuators, within ×0.436–×2.01 of it (log RMS 0.41); each residual is the actuator's own
    c τ_peak² over the law, and the log residuals sum to zero (least squares with an
    intercept)."""
    law = catalogue_law()
    assert law.members == tuple(sorted(CATALOGUE)) and len(law.members) == 21
    assert (f"{law.coefficient:.4g}", f"{law.exponent:.4g}") == ("11.27", "1.005")
    lo, hi = law.spread
    assert (f"{lo:.3g}", f"{hi:.3g}", f"{law.log_rms:.2g}") == ("0.436", "2.01", "0.41")
    for name, ratio in zip(law.members, law.ratios, strict=True):
        m = CATALOGUE[name]
        own = m.joule_coefficient * m.stall_torque**2
        assert ratio == pytest.approx(own / (law.coefficient * m.stall_torque**law.exponent),
                                      rel=1e-12)
    assert abs(np.sum(np.log(law.ratios))) < 1e-9
    assert law.members[int(np.argmax(law.ratios))] == "MiniCheetah-hip"
    assert law.members[int(np.argmin(law.ratios))] == "XM540-W270"


@pytest.mark.parametrize("left_out", ["Cheetah3", "A1", "AX", "ODRI", "MiniCheetah"])
def test_a_law_fitted_without_a_family_brackets_it(left_out):
    """Leave-one-out: the law fitted on the catalogue without one actuator family, with that
    fit's spread, brackets the left-out actuators' Joule loss at their own peak torque —
    Cheetah 3 six times above every torque left in the fit (the ANYmal class), A1's empirical
    model, the hexapod's AX servos, the ODRI module and the Katz firmware's Mini Cheetah."""
    rest = {n: m for n, m in CATALOGUE.items() if family(n) != left_out}
    out = {n: m for n, m in CATALOGUE.items() if family(n) == left_out}
    assert out and len(rest) + len(out) == len(CATALOGUE)
    law = fit(rest)
    lo, hi = law.spread
    for name, m in out.items():
        if name == "MiniCheetah-hip":
            continue  # Cheetah-Software's R: outside, as the next test says
        ratio = m.joule_coefficient * m.stall_torque**2 / law.peak_loss(m.stall_torque)
        assert lo <= ratio <= hi, name


def test_leave_one_out_misses_two_of_twenty_one():
    """The same over every family: 19 of the 21 actuators are bracketed; the two outside are the
    fit's own extremes (Cheetah-Software's Mini Cheetah hip, 2.3 × the law without its family,
    and the XM540-W270, 0.41 ×) — the spread is the catalogue's, not a guarantee."""
    outside = []
    for f in sorted({family(n) for n in CATALOGUE}):
        law = fit({n: m for n, m in CATALOGUE.items() if family(n) != f})
        lo, hi = law.spread
        for name, m in CATALOGUE.items():
            if family(name) == f:
                ratio = m.joule_coefficient * m.stall_torque**2 / law.peak_loss(m.stall_torque)
                if not lo <= ratio <= hi:
                    outside.append(name)
    assert sorted(outside) == ["MiniCheetah-hip", "XM540-W270"]


def test_an_actuator_from_the_law_is_labelled_assumed():
    """Every actuator the law gives says it is assumed (its notes open with LAW_MARK), has the
    law's c at the joint's effort and the catalogue's η range, and regenerates nothing."""
    law = catalogue_law()
    for end in ENDS:
        m = law.motor(80.0, 8.5, end)
        assert m.notes.startswith(LAW_MARK) and "not a motor's" in m.notes
        assert "Wensing" in m.source
        assert m.joule_coefficient == pytest.approx(law.joule_coefficient(80.0, end), rel=1e-12)
        assert m.stall_torque == 80.0 and m.regeneration is False
    lo, mid, hi = (law.motor(80.0, 8.5, end) for end in ENDS)
    assert lo.joule_coefficient < mid.joule_coefficient < hi.joule_coefficient
    etas = [CATALOGUE[n].gearbox_efficiency for n in CATALOGUE]
    assert (lo.gearbox_efficiency, hi.gearbox_efficiency) == (max(etas), min(etas))
    assert law.as_dict()["assumed"] is True and law.as_dict()["is_bound"] is False


def test_bad_input_names_the_value():
    law = catalogue_law()
    with pytest.raises(InvalidParameterError, match="end"):
        law.joule_coefficient(10.0, "middle")
    with pytest.raises(InvalidParameterError, match="effort"):
        law.motor(0.0, 1.0)
    with pytest.raises(InvalidParameterError, match="speed"):
        law.motor(10.0, 0.0)
    with pytest.raises(InvalidParameterError, match="two distinct"):
        fit({"a": CATALOGUE["AX-12A"], "b": CATALOGUE["XL430-W250"]})  # both 1.5 N·m


def test_docs_state_the_law_its_fit_and_spread():
    """docs/energy.md's law section at the digits the fit gives: the law, β's standard error,
    the motor-constant form, the spread and its extremes, leave-one-out's 19 of 21, the assumed
    η, and the law's c at the A1's and the AX-18A's classes beside their own."""
    from pathlib import Path

    text = " ".join((Path(__file__).resolve().parents[2] / "docs" / "energy.md").read_text()
                    .split())
    law = catalogue_law()
    lo, hi = law.spread
    t = np.log(law.torques)
    resid = np.log(law.ratios)
    se = np.sqrt(resid.var() * len(t) / (len(t) - 2) / ((t - t.mean()) ** 2).sum())
    assert (f"**P_peak = {law.coefficient:.4g} τ_peak^{law.exponent:.4g} W** (τ in N·m; β's "
            f"standard error {se:.2g})") in text
    assert (f"1/√c = {law.coefficient ** -0.5:.3g} τ_peak^{1 - law.exponent / 2:.3g} N·m/√W"
            in text)
    assert f"**×{lo:.3g}–×{hi:.3g}** of the law (log RMS {law.log_rms:.2g})" in text
    assert f"the XM540-W270 (×{min(law.ratios):.3g})" in text
    assert f"Mini Cheetah hip (×{max(law.ratios):.3g}; Katz's firmware gives" in text
    katz = law.ratios[law.members.index("MiniCheetah-hip-Katz")]
    assert f"the same motor ×{katz:.3g})" in text
    assert "brackets **19 of the 21**" in text  # test_leave_one_out_misses_two_of_twenty_one
    assert (f"c = {law.coefficient:.4g} E^({law.exponent:.4g} − 2) at the law, and ×{lo:.3g} or "
            f"×{hi:.3g}") in text
    assert (f"median ({law.efficiency('central'):.3g}) at the law, their highest "
            f"({law.efficiency('low'):.1f}) with the low end and their lowest "
            f"({law.efficiency('high'):.3g})") in text
    for name, effort in (("A1-Yang2021", 33.5), ("AX-18A", 1.8)):
        own = CATALOGUE[name].joule_coefficient
        cs = [law.joule_coefficient(effort, end) for end in ENDS]
        assert (f"| {own:.3f} | {cs[1]:.3g} ({cs[0]:.3g}–{cs[2]:.3g}) |") in text, name
