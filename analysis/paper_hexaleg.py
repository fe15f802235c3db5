"""The paper's single nonlinear elastic joint without gravity: k_M, what it saves, and the optimum.

Run:  python analysis/paper_hexaleg.py       (expected output: analysis/logs/paper_hexaleg.log)

The femur lever of Table 6 (m = 36.11 g, l = 47.141 mm, I = 107.059 kg·mm² about the centre of
mass, so J = m l² + I about the axis, eq. 5) on θ(t) = A sin ωt, A = 0.3 rad, ω = 2 rad/s
(eq. 25), with the paper's dead-zone spring: θ_k = 7.32°, α = 1.05 (Section 4.2), torque
k α (θ − θ_k sgn θ) beyond ±θ_k in the paper's eq. 14 convention (``hexaleg.DeadZoneSpring``).
Without gravity the motor torque is M = J θ̈ − τ_spring (eq. 13/14 with g = 0).

* k_M = ω² J / α (eq. 19), in SI and in the paper's arithmetic (m in kg, l in mm, I in kg·mm²,
  which the paper prints as 713.547 "N·mm/deg"; docs/paper.md);
* peak |M| is flat at J ω² θ_k for κ = kα in [J ω², J ω² (A + θ_k)/(A − θ_k)]: saving 1 − θ_k/A;
* positive work per period is least at κ = J ω² (1 + √2 θ_k/(A − θ_k)) (closed forms derived in
  docs/paper.md), checked here by a bounded scalar search on the sampled cost
  (``hexaleg.dynamics.energy.metrics``: positive work ∫ max(0, M θ̇) dt, peak and RMS torque;
  sampled at 4096 points per period, so the peaks and the optimum agree with the closed forms to ≈
  1e-3).
"""

from __future__ import annotations

import math

import numpy as np
from scipy.optimize import minimize_scalar

import hexaleg
import hexaleg.dynamics.energy
from hexaleg import units
from hexaleg.robot.catalogue import CATALOGUE, DEFAULT_MOTOR

MASS, COM_MM, INERTIA_KGMM2 = 3.611e-2, 47.141, 107.059  # Table 6
A, OMEGA, THETA_K_DEG, ALPHA = 0.3, 2.0, 7.32, 1.05  # eq. 25, Section 4.2
N = 4096  # samples per period
MOTOR = CATALOGUE[DEFAULT_MOTOR]  # only its Joule/electrical terms use it

J = MASS * float(units.mm_to_m(COM_MM)) ** 2 + float(units.kgmm2_to_kgm2(INERTIA_KGMM2))
T = np.arange(N) * (2 * math.pi / OMEGA) / N
THETA, THETA_DOT = A * np.sin(OMEGA * T), A * OMEGA * np.cos(OMEGA * T)
THETA_DDOT = -(OMEGA**2) * THETA


def metrics(k: float) -> dict[str, float]:
    """Totals of ``hexaleg.dynamics.energy.metrics`` for the motor torque with the spring of
    stiffness k."""
    spring = hexaleg.DeadZoneSpring.from_paper(0.0, THETA_K_DEG, ALPHA, convention="eq14")
    tau = J * THETA_DDOT - spring.with_stiffness(k).torque(THETA)
    return hexaleg.dynamics.energy.metrics(tau, THETA_DOT, T[1], MOTOR)["total"]


def main() -> None:
    rigid = metrics(0.0)
    theta_k = float(units.deg_to_rad(THETA_K_DEG))
    k_M = OMEGA**2 * J / ALPHA
    print(f"J = m l² + I = {J:.5g} kg·m², θ_k = {theta_k:.5g} rad, θ_k/A = {theta_k / A:.4f}")
    print(f"k_M (eq. 19) = {k_M:.5g} N·m/rad = {float(units.kgm2_to_kgmm2(k_M)):.6g} in the "
          f"paper's arithmetic (printed 713.547) = "
          f"{float(units.nm_per_rad_to_nmm_per_deg(k_M)):.4g} N·mm/deg")
    print(f"\n{'':26s} {'k [N·m/rad]':>11s} {'peak |M|':>11s} {'RMS M':>11s} {'E+ [J]':>11s}")
    c = J * OMEGA**2  # κ = k α at k_M
    k_hi = c * (A + theta_k) / (A - theta_k) / ALPHA
    k_work = c * (1 + math.sqrt(2) * theta_k / (A - theta_k)) / ALPHA
    found = minimize_scalar(lambda k: metrics(k)["positive_work"], bounds=(0.5 * k_M, 3 * k_M),
                            method="bounded", options={"xatol": 1e-12}).x
    rows = (("rigid (k = 0)", 0.0), ("k_M", k_M), ("upper end of the flat peak", k_hi),
            ("least E+, closed form", k_work), ("least E+, numerical", found))
    for label, k in rows:
        m = metrics(k)
        print(f"{label:26s} {k:11.4e} {m['peak_torque']:11.4e} {m['rms_torque']:11.4e} "
              f"{m['positive_work']:11.4e}")
    print("\nsavings against the rigid joint [%]:")
    for label, k in rows[1:]:
        m = metrics(k)
        s = {key: 100 * (1 - m[key] / rigid[key]) for key in
             ("peak_torque", "rms_torque", "positive_work")}
        print(f"  {label:26s} peak {s['peak_torque']:6.2f}  RMS {s['rms_torque']:6.2f}  "
              f"E+ {s['positive_work']:6.2f}")
    print(f"1 − θ_k/A = {100 * (1 - theta_k / A):.2f} %; numerical / closed-form optimum = "
          f"{found / k_work:.4f}")


if __name__ == "__main__":
    main()
