"""The paper's printed numbers (Section 4.2, Table 4, Fig. 7), its unit, and the readings tried.

Eq. 19 with Table 6 gives the printed k_M = 713.547 only with m in kg, l in mm and I in kg·mm²:
the number is in kg·mm²·s⁻²/rad = 1e-6 N·m/rad ("eq. 19 units"), though the paper labels it
N·mm/deg (docs/paper.md). :func:`paper_number_to_si` and :func:`si_to_paper_number` convert that
unit; :func:`k_E_readings` and :func:`saving_readings` evaluate every reading of the paper's k_E
and "up to 52.81 %" saving that this model can check.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.dynamics.energy import saving
from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.metrics import energy_ratio, optimal_stiffness
from hexaleg.units import (
    kgm2_to_kgmm2,
    kgmm2_to_kgm2,
    m_to_mm,
    nm_per_rad_to_nmm_per_deg,
)

PAPER_K_M = 713.547
"""Section 4.2: k_M as printed (labelled N·mm/deg)."""
PAPER_K_E = 784.717
"""Section 4.2: k_E as printed (labelled N·mm/deg)."""
PAPER_SAVING = 52.81
"""Section 4.2: the largest energy saving, percent."""
PAPER_RANGE_NMM_PER_DEG = (100.0, 1200.0)
"""Section 4.2 / Fig. 7: the stiffnesses simulated, N·mm/deg."""
PAPER_TABLE4_NMM_PER_DEG = 400.0
"""Table 4 / Fig. 6: the main spring's stiffness, N·mm/deg."""
EQ19_UNIT = "kg·mm²·s⁻²/rad"
"""The unit of the paper's stiffness numbers ("eq. 19 units", 1e-6 N·m/rad): the one in which
eq. 19 with Table 6 gives 713.5, though the paper labels it N·mm/deg."""


def k_M_paper_number(joint: PaperJoint | None = None) -> float:
    """Eq. 19 evaluated as the paper did: m in kg, l in mm, I in kg·mm², ω in rad/s.

    The result (713.547 for Table 6) is in kg·mm²·s⁻²/rad = 1e-6 N·m/rad, though the paper labels
    it N·mm/deg. Equal to ``joint.k_M() * kgm2_to_kgmm2(1)``.
    """
    j = joint or PaperJoint()
    l_mm = float(m_to_mm(j.com))
    return j.omega**2 * (j.mass * l_mm**2 + float(kgm2_to_kgmm2(j.inertia))) / j.transmission


def paper_number_to_si(x: ArrayLike) -> float | np.ndarray:
    """A stiffness in the paper's eq. 19 unit (kg·mm²·s⁻²/rad) → N·m/rad."""
    return kgmm2_to_kgm2(x)


def si_to_paper_number(x: ArrayLike) -> float | np.ndarray:
    """A stiffness in N·m/rad → the paper's eq. 19 unit (kg·mm²·s⁻²/rad)."""
    return kgm2_to_kgmm2(x)


def stiffness_units(k_si: float) -> dict[str, float]:
    """One stiffness in every unit the paper study reports: N·m/rad, N·mm/deg, the eq. 19
    number."""
    return {"N_m_per_rad": float(k_si), "N_mm_per_deg": float(nm_per_rad_to_nmm_per_deg(k_si)),
            "paper_number_kg_mm2_per_s2_rad": float(si_to_paper_number(k_si))}


def k_E_readings(joint: PaperJoint | None = None) -> dict[str, dict[str, object]]:
    """The readings of "eq. 21 integrated over the interval θ_k to π/4" tried for k_E = 784.717.

    For ω = 2, π/4 s is a quarter period: the joint moves from θ = 0 to the turning point θ = A,
    and it reaches θ_k at t_k = arcsin(θ_k/A)/ω. Each reading gives the stiffness in N·m/rad and in
    the paper's eq. 19 number (comparable with 784.717), or None with the reason.

    Returns:
        Reading name → ``{"description", "k_SI", "k_paper_number", "note"}``.
    """
    j = joint or PaperJoint()
    out: dict[str, dict[str, object]] = {}
    tk, tq = j.contact_time(), (math.pi / 2 - j.phase) / j.omega

    def add(key: str, desc: str, k: float | None, note: str) -> None:
        out[key] = {"description": desc, "k_SI": k,
                    "k_paper_number": None if k is None else float(si_to_paper_number(k)),
                    "note": note}

    e0, e1 = j.energy(0.0, tk, tq, gravity=False), j.energy(1.0, tk, tq, gravity=False)
    add("eq21_time_tk_to_quarter",
        "min over k of eq. 21 E(k) = ∫ M θ̇ dt from t_k to π/4 s (no gravity)", None,
        f"E(k) is linear in k with slope dE/dk = {e1 - e0:.6g} J per N·m/rad > 0 (the spring "
        "stores ½κ(A − θ_k)²): dg/dk = 0 has no solution, there is no minimum")
    add("eq21_zero_work_quarter", "E(k) = 0 on t_k → π/4 s: the spring absorbs the kinetic "
        "energy at contact", j.closed_form_zero_work_quarter(), "closed form J ω² (A+θ_k)/"
        "(α(A−θ_k)) (eq14)")
    for g in (False, True):
        for name in ("absolute_work", "positive_work"):
            opt = optimal_stiffness(j, name, gravity=g)
            flat = opt.flat[1] > opt.flat[0]
            add(f"{name}_period_{'gravity' if g else 'no_gravity'}",
                f"min over k of the {name.replace('_', ' ')} per period "
                f"({'with' if g else 'without'} gravity, {j.posture})",
                None if flat else opt.k,
                "flat optimum on [{:.6g}, {:.6g}] N·m/rad".format(*opt.flat) if flat else
                ("equals the closed form J ω² (1 + √2 θ_k/(A−θ_k))/α" if not g else ""))
    theta_q = math.pi / 4  # π/4 read as an angle, rad
    add("eq21_angle_thk_to_pi_over_4", "eq. 21 over the joint angle θ_k → π/4 rad", None,
        f"π/4 rad = 45° exceeds the amplitude A = {j.amplitude} rad = "
        f"{math.degrees(j.amplitude):.2f}°: the trajectory never reaches θ = {theta_q:.4f} rad")
    return out


def saving_readings(joint: PaperJoint | None = None) -> dict[str, float]:
    """Candidate readings of the paper's "up to 52.81%" energy saving, in percent.

    Each is ``100 (1 − cost(k)/cost(k = 0))`` for one energy cost at its optimal stiffness, or for
    ε (eq. 24) at k_M and at the printed k_E read in eq. 19 units, with and without gravity.
    """
    j = joint or PaperJoint()
    out = {}
    for g in (False, True):
        tag = "gravity" if g else "no_gravity"
        for name in ("positive_work", "absolute_work", "joule"):
            out[f"{name}_{tag}"] = 100 * optimal_stiffness(j, name, gravity=g).saving
        eps0 = float(energy_ratio(j, 0.0, g))
        k_m = j.k_M()
        out[f"epsilon_at_k_M_{tag}"] = 100 * saving(float(energy_ratio(j, k_m, g)), eps0)
        k_e = float(paper_number_to_si(PAPER_K_E))  # the printed k_E read in eq. 19 units
        out[f"epsilon_at_printed_k_E_{tag}"] = 100 * saving(float(energy_ratio(j, k_e, g)), eps0)
    return out
