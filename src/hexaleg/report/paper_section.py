"""The paper's single-joint numbers, re-keyed for the report page (each with its unit).

The numbers are those of :func:`hexaleg.paper.reproduce.reproduce` (Table 6 lever driven
through θ = A sin ωt, eq. 25; k_M of eq. 19; the printed k_E and 52.81 % saving), not recomputed.
"""

from __future__ import annotations

import functools
import json
from typing import Any


@functools.lru_cache(maxsize=4)
def _paper_reproduction(n: int) -> str:
    """:func:`hexaleg.paper.reproduce.reproduce` as JSON text, cached (it takes seconds
    and is constant)."""
    # scipy.optimize: imported only when the report is made
    from hexaleg.paper.reproduce import reproduce

    return json.dumps(reproduce(n=n))


def paper_reference(n: int = 1024) -> dict[str, Any]:
    """The paper's single-joint numbers (Table 6 lever, eq. 25) for the report, with units.

    Taken from :func:`hexaleg.paper.reproduce.reproduce` (not recomputed): eq. 19 k_M as
    printed and in SI, the closed-form no-gravity optima and peak-torque saving, the numerically
    optimal stiffness and saving per metric without gravity, and the verdicts on the printed k_E
    and 52.81 % saving.

    Args:
        n: Samples per period of the single-joint model.
    """
    r = json.loads(_paper_reproduction(n))
    m, cf = r["model"], r["closed_forms_no_gravity"]
    k_unit = "N·m/rad"
    return {
        "model": {"amplitude": {"value": m["amplitude_rad"], "unit": "rad"},
                  "omega": {"value": m["omega_rad_per_s"], "unit": "rad/s"},
                  "theta_k": {"value": m["theta_k_rad"], "unit": "rad"},
                  "alpha": {"value": m["alpha"], "unit": "1"},
                  "J": {"value": m["J_axis_kg_m2"], "unit": "kg·m²"},
                  "convention": m["convention"]},
        "k_M_printed": {"value": r["k_M_paper_printed"], "unit": "paper eq. 19 number"},
        "k_M_paper_number": {"value": r["k_M_paper_units"], "unit": "paper eq. 19 number"},
        "k_M_paper_units_are": r["k_M_paper_units_are"],
        "k_M": {"value": r["k_M_SI_Nm_per_rad"], "unit": k_unit},
        "peak_flat_interval": {"value": cf["peak_flat_interval_N_m_per_rad"], "unit": k_unit},
        "peak_saving": {"value": cf["peak_saving_percent"], "unit": "%"},
        "closed_form_optima": {
            key: {"value": cf[key]["N_m_per_rad"], "unit": k_unit}
            for key in ("int_sq", "mean_abs", "positive_and_absolute_work")},
        "optima_no_gravity": {
            key: {"stiffness": {"value": o["k_N_m_per_rad"], "unit": k_unit},
                  "saving": {"value": o["saving_percent"], "unit": "%"}}
            for key, o in r["optima"]["no_gravity"].items()},
        "k_E_printed": {"value": r["k_E"]["paper_printed"], "unit": "paper eq. 19 number"},
        "k_E_verdict": r["k_E"]["verdict"],
        "saving_printed": {"value": r["saving_52_81"]["paper_printed_percent"], "unit": "%"},
        "saving_verdict": r["saving_52_81"]["verdict"],
        "samples": n,
    }
