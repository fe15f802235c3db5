"""Tests of hexaleg.dynamics.energy: closed-form cycle integrals, the paper's single joint,
savings."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest

from hexaleg.dynamics.energy import cost_of_transport, epsilon, metrics, saving, savings
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.catalogue import motor
from hexaleg.units import G, kgmm2_to_kgm2, mm_to_m

# Paper Table 6 and eq. 25: f(t) = 0.3 sin(2t), l = 47.141 mm, m = 0.03611 kg, I = 107.059 kg·mm².
A, OMEGA = 0.3, 2.0
L_COM, MASS, INERTIA = mm_to_m(47.141), 3.611e-2, kgmm2_to_kgm2(107.059)
J = MASS * L_COM**2 + INERTIA  # eq. 5: kinetic energy ½ (m l² + I) θ̇²
N = 400


def grid(n: int = N, period: float = 2 * math.pi / OMEGA) -> tuple[np.ndarray, float]:
    dt = period / n
    return np.arange(n) * dt, dt


def paper_joint(stiffness: float = 0.0, gravity: bool = False
                ) -> tuple[np.ndarray, np.ndarray, float]:
    """Motor torque and speed of the paper's single joint on f = A sin ωt (eq. 14 with θ_k = 0,
    α = 1 and the spring's restoring torque −k θ)."""
    t, dt = grid()
    q = A * np.sin(OMEGA * t)
    qd = A * OMEGA * np.cos(OMEGA * t)
    qdd = -OMEGA**2 * q
    tau = J * qdd + stiffness * q + (MASS * G * L_COM * np.sin(q) if gravity else 0.0)
    return tau, qd, dt


def ideal(eta: float = 1.0, regeneration: bool = False):
    return dataclasses.replace(motor(), gearbox_efficiency=eta, regeneration=regeneration)


def test_joule_closed_form() -> None:
    t, dt = grid()
    amp = 0.7
    tau = amp * np.sin(OMEGA * t)[:, None] * np.array([1.0, 2.0])
    m = motor()
    res = metrics(tau, np.zeros_like(tau), dt, m)
    period = 2 * math.pi / OMEGA
    # ∫ c (a sin ωt)² dt over a period = c a² T / 2 (exact on the periodic grid).
    np.testing.assert_allclose(res["joint"]["joule"],
                               m.joule_coefficient * (amp * np.array([1.0, 2.0])) ** 2 * period / 2,
                               rtol=1e-12)
    np.testing.assert_allclose(res["joint"]["rms_torque"],
                               amp * np.array([1.0, 2.0]) / math.sqrt(2))
    assert res["total"]["peak_torque"] == pytest.approx(2 * amp)
    # No motion: no work, and electrical energy equals the Joule loss.
    assert res["total"]["positive_work"] == 0.0
    assert res["total"]["electrical"] == pytest.approx(res["total"]["joule"])
    assert res["duration"] == pytest.approx(period)


def test_motion_with_both_ends_uses_the_trapezoidal_rule() -> None:
    """τ = t, q̇ = 1 on [0, 1] with both ends stored: ∫ τ q̇ = 1/2 and ∫ τ² = 1/3 + dt²/6
    (trapezoid on t²), RMS over the 1 s duration; Σ x dt would add dt/2 to the work."""
    t = np.linspace(0.0, 1.0, 101)
    dt = t[1] - t[0]
    m = ideal()
    res = metrics(t, np.ones_like(t), dt, m, periodic=False)
    assert res["duration"] == pytest.approx(1.0, abs=1e-15)
    assert res["total"]["net_work"] == pytest.approx(0.5, abs=1e-14)
    joule = m.joule_coefficient * (1 / 3 + dt**2 / 6)
    assert res["total"]["joule"] == pytest.approx(joule, rel=1e-12)
    assert res["total"]["rms_torque"] == pytest.approx(math.sqrt(1 / 3 + dt**2 / 6), rel=1e-12)
    assert res["total"]["mean_abs_torque"] == pytest.approx(0.5, rel=1e-12)
    assert metrics(t, np.ones_like(t), dt, m)["total"]["net_work"] == pytest.approx(0.5 + dt / 2)
    with pytest.raises(InvalidParameterError, match="T ≥ 2"):
        metrics(t[:1], t[:1], dt, m, periodic=False)


def test_electrical_regen_is_mechanical_plus_joule() -> None:
    rng = np.random.default_rng(3)
    tau, qdot = rng.normal(size=(300, 18)), rng.normal(size=(300, 18)) * 4
    res = metrics(tau, qdot, 0.01, ideal(1.0))
    np.testing.assert_allclose(res["joint"]["electrical_regen"],
                               res["joint"]["net_work"] + res["joint"]["joule"], rtol=1e-12)
    tot = res["total"]
    assert np.all(res["joint"]["electrical_noregen"] >= res["joint"]["electrical_regen"])
    # A shared supply that takes nothing back lies between full and no regeneration.
    eps = 1e-9 * tot["electrical_noregen"]
    assert tot["electrical_regen"] - eps <= tot["electrical_bus"] <= tot["electrical_noregen"] + eps
    assert tot["electrical"] == tot["electrical_noregen"]  # motor without regeneration
    # Lossy gearbox costs more.
    lossy = metrics(tau, qdot, 0.01, ideal(0.6))["total"]
    assert lossy["electrical_regen"] > tot["electrical_regen"]
    assert lossy["joule"] == pytest.approx(tot["joule"])


def test_sinusoidal_power_positive_is_half_absolute() -> None:
    t, dt = grid(2000)
    tau, qdot = np.cos(OMEGA * t), np.sin(OMEGA * t)  # P = ½ sin 2ωt
    res = metrics(tau, qdot, dt, motor())["total"]
    period = 2 * math.pi / OMEGA
    assert res["positive_work"] == pytest.approx(res["absolute_work"] / 2, rel=1e-12)
    assert res["absolute_work"] == pytest.approx(period / math.pi, rel=1e-5)
    assert abs(res["net_work"]) < 1e-12


def test_conservative_periodic_motion_does_no_net_work() -> None:
    # Inertia, gravity and a spring are all conservative: eq. 20 gives zero over a cycle.
    tau, qd, dt = paper_joint(stiffness=0.5, gravity=True)
    res = metrics(tau, qd, dt, motor())
    assert abs(res["total"]["net_work"]) < 1e-14
    assert res["total"]["positive_work"] > 0


def test_paper_single_joint_epsilon_closed_form() -> None:
    tau, qd, dt = paper_joint()
    res = metrics(tau, qd, dt, motor(), joint_names=["femur"])
    # The kinetic energy ½ J A² ω² is supplied twice per cycle: positive work J A² ω².
    assert res["total"]["positive_work"] == pytest.approx(J * A**2 * OMEGA**2, rel=1e-4)
    # Eq. 24 with the angle travelled in a cycle, 4 A, and "the moment of inertia about the
    # rotation axis", J = m l² + I: ε = J A² ω² / (J 4 A) = A ω² / 4, whatever J is.
    eps = epsilon(res["total"]["positive_work"], J, 4 * A)
    assert eps == pytest.approx(A * OMEGA**2 / 4, rel=1e-4)
    assert res["joint_names"] == ("femur",)
    # metrics() gives the same per joint from the inertia, with the angle it integrates itself.
    per_joint = metrics(tau, qd, dt, motor(), inertia=[J])["epsilon"]
    assert per_joint["angle"][0] == pytest.approx(4 * A, rel=1e-4)
    assert per_joint["positive_work"][0] == pytest.approx(A * OMEGA**2 / 4, rel=1e-4)


def test_epsilon_of_a_joint_that_does_not_move_is_zero() -> None:
    tau, qd, dt = paper_joint()
    two = metrics(np.column_stack([tau, tau]), np.column_stack([qd, 0 * qd]), dt, motor(),
                  inertia=[J, J])["epsilon"]
    assert two["angle"][1] == 0.0 and two["positive_work"][1] == 0.0
    with pytest.raises(InvalidParameterError, match=r"inertia.*2 finite numbers > 0"):
        metrics(np.column_stack([tau, tau]), np.column_stack([qd, qd]), dt, motor(),
                inertia=[J, 0.0])


def test_spring_savings_closed_form() -> None:
    # Eq. 19 (α = 1, θ_k = 0): k = ω² (m l² + I) cancels the motor torque.
    rigid = metrics(*paper_joint()[:2], paper_joint()[2], motor(), mass=MASS, distance=1.0)
    resonant = metrics(*paper_joint(OMEGA**2 * J)[:2], paper_joint()[2], motor(),
                       mass=MASS, distance=1.0)
    half = metrics(*paper_joint(OMEGA**2 * J / 2)[:2], paper_joint()[2], motor(),
                   mass=MASS, distance=1.0)
    full = savings(resonant, rigid)
    for key in ("positive_work", "absolute_work", "joule", "electrical", "peak_torque"):
        assert full["total"][key] == pytest.approx(1.0)
    assert "net_work" not in full["total"]  # signed, ≈ 0 for both: no meaningful fraction
    # Half the stiffness halves the torque: half the work and torque, a quarter of the Joule loss.
    s = savings(half, rigid)
    for key in ("positive_work", "absolute_work", "peak_torque", "rms_torque"):
        assert s["total"][key] == pytest.approx(0.5)
        assert s["joint"][key][0] == pytest.approx(0.5)
    assert s["total"]["joule"] == pytest.approx(0.75)
    assert s["cost_of_transport"]["electrical"] == pytest.approx(s["total"]["electrical"])
    # The other way round costs energy: a negative saving.
    assert savings(rigid, half)["total"]["joule"] == pytest.approx(-3.0)


def test_savings_reference_zero_is_not_nan() -> None:
    tau = np.zeros((4, 2))
    zero = metrics(tau, tau, 0.1, motor())
    some = metrics(tau + np.array([0.0, 1.0]), tau, 0.1, motor())
    s = savings(some, zero)
    assert s["joint"]["joule"][0] == 0.0 and s["joint"]["joule"][1] == -np.inf
    assert not any(np.isnan(v) for v in s["total"].values())
    other = metrics(tau, tau, 0.1, motor(), joint_names=["a", "b"])
    with pytest.raises(InvalidParameterError, match="joint_names"):
        savings(other, zero)


def test_saving_is_the_fraction_of_the_baseline_saved() -> None:
    """(without − with) / |without|: the sign says who spends less, the denominator is the size of
    the baseline whatever its sign."""
    assert saving(0.75, 1.0) == pytest.approx(0.25)  # less with springs: positive
    assert saving(3.0, 2.0) == pytest.approx(-0.5)  # more with springs: negative
    assert saving(0.0, 2.0) == 1.0  # all of it saved
    # A signed baseline: dividing by it instead of its size would flip the sign.
    assert saving(-3.0, -2.0) == pytest.approx(0.5)
    assert saving(-1.0, -2.0) == pytest.approx(-0.5)
    assert isinstance(saving(1.0, 2.0), float)
    np.testing.assert_allclose(saving(np.array([1.0, 2.0, 5.0]), 4.0), [0.75, 0.5, -0.25])


def test_saving_against_a_zero_baseline() -> None:
    """0 when both are 0; ±inf (sign of without − with) otherwise; NaN only from a NaN input."""
    out = saving(np.array([0.0, 2.0, -1.0, 1.0]), np.array([0.0, 0.0, 0.0, 4.0]))
    np.testing.assert_array_equal(out, [0.0, -np.inf, np.inf, 0.75])
    assert saving(0.0, 0.0) == 0.0
    assert saving(1e-300, 0.0) == -np.inf
    assert math.isnan(saving(float("nan"), 1.0)) and math.isnan(saving(1.0, float("nan")))


def test_cost_of_transport_hand_example() -> None:
    assert cost_of_transport(10.0, 2.0, 0.5) == pytest.approx(10.0 / (2.0 * 9.81 * 0.5))
    assert cost_of_transport(10.0, 2.0, 0.5, g=1.0) == pytest.approx(10.0)
    rng = np.random.default_rng(4)
    tau, qdot = rng.normal(size=(100, 3)), rng.normal(size=(100, 3))
    res = metrics(tau, qdot, 0.02, motor(), mass=1.5, distance=0.2)
    for key, value in res["cost_of_transport"].items():
        assert value == pytest.approx(res["total"][key] / (1.5 * 9.81 * 0.2))
    assert "cost_of_transport" not in metrics(tau, qdot, 0.02, motor(), mass=1.5, distance=0.0)
    # a subnormal stride (hypothesis drew one) walks in place: no inf cost, no NaN saving
    tiny = metrics(tau, qdot, 0.02, motor(), mass=1.5, distance=5e-324)
    assert "cost_of_transport" not in tiny
    assert "cost_of_transport" in metrics(tau, qdot, 0.02, motor(), mass=1.5, distance=1e-6)


@pytest.mark.parametrize("kwargs, match", [
    ({"dt": 0.0}, "dt"), ({"dt": float("nan")}, "dt"), ({"mass": -1.0, "distance": 1.0}, "mass"),
    ({"mass": 1.0, "distance": -1.0}, "distance"), ({"joint_names": ["a"]}, "joint_names"),
])
def test_bad_metrics_arguments(kwargs: dict, match: str) -> None:
    args = {"dt": 0.1, **kwargs}
    with pytest.raises(InvalidParameterError, match=match):
        metrics(np.ones((5, 2)), np.ones((5, 2)), motor=motor(), **args)


def test_bad_metrics_arrays() -> None:
    bad = np.ones((5, 2))
    bad[3, 1] = np.nan
    with pytest.raises(InvalidParameterError, match=r"tau.*\(3, 1\)"):
        metrics(bad, np.ones((5, 2)), 0.1, motor())
    with pytest.raises(InvalidParameterError, match="qdot"):
        metrics(np.ones((5, 2)), np.ones((5, 3)), 0.1, motor())
    with pytest.raises(InvalidParameterError, match="tau"):
        metrics(np.ones((5, 2, 1)), np.ones((5, 2, 1)), 0.1, motor())


@pytest.mark.parametrize("args, match", [
    ((1.0, 0.0, 1.0), "inertia"), ((1.0, 1.0, -1.0), "angle"), ((float("nan"), 1.0, 1.0), "energy"),
])
def test_bad_epsilon(args: tuple, match: str) -> None:
    with pytest.raises(InvalidParameterError, match=match):
        epsilon(*args)
    with pytest.raises(InvalidParameterError, match="distance"):
        cost_of_transport(1.0, 1.0, 0.0)
