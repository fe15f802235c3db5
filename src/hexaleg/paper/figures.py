"""The data of the paper's Figs 5–13, computed on the joint and drawn by
:mod:`hexaleg.outputs.paper_figures`; :func:`forward_figures` sets the forward runs of the Adams
experiment (:mod:`hexaleg.paper.forward`) beside the analytic curves.

No gravity unless labelled; stiffnesses are given in the paper's eq. 19 units (kg·mm²·s⁻²/rad =
1e-6 N·m/rad), the unit its 713.547 is really in, so the curves compare with its figures.
"""

from __future__ import annotations

import dataclasses

import numpy as np
from matplotlib.figure import Figure

from hexaleg.outputs import paper_figures as draw
from hexaleg.paper.forward import ForwardStudy
from hexaleg.paper.joint import PaperJoint
from hexaleg.paper.metrics import energy_ratio, metric
from hexaleg.paper.readings import (
    PAPER_K_E,
    PAPER_TABLE4_NMM_PER_DEG,
    k_M_paper_number,
    paper_number_to_si,
    si_to_paper_number,
)
from hexaleg.units import nmm_per_deg_to_nm_per_rad


def make_figures(joint: PaperJoint, n: int) -> dict[str, Figure]:
    """The analogues of the paper's Figs 5–13, file name (PNG) → figure, in writing order.

    Args:
        joint: The joint.
        n: Samples per period of the torque curves and of the costs.
    """
    return {**_torque_figures(joint, n), **_cost_figures(joint, n)}


def _torque_figures(j: PaperJoint, n: int) -> dict[str, Figure]:
    """Figs 5–8 and 11: the motor torque over one period, baseline and with springs."""
    t = j.times(n)
    ju = dataclasses.replace(j, posture="upright")
    k_m = k_M_paper_number(j)
    baseline = j.baseline_torque(t, False)

    def by_stiffness(title: str, ks_paper: list[float]) -> Figure:
        torques = [(kp, j.motor_torque(t, float(paper_number_to_si(kp)), False))
                   for kp in ks_paper]
        return draw.torques_by_stiffness(t, baseline, torques, title)

    k400 = float(nmm_per_deg_to_nm_per_rad(PAPER_TABLE4_NMM_PER_DEG))
    k_work = float(si_to_paper_number(j.closed_form_work()))
    return {
        "fig05_rigid_torque.png": draw.baseline_torque(
            t, baseline, j.baseline_torque(t, True), ju.baseline_torque(t, True)),
        "fig06_torque_k400.png": draw.table4_spring(
            t, baseline, j.motor_torque(t, k400, False),
            j.motor_torque(t, float(paper_number_to_si(400.0)), False)),
        "fig07_torque_vs_stiffness.png": by_stiffness(
            "Fig. 7 analogue: 100–1200 (eq. 19 units)", [100.0, 300.0, 500.0, 700.0, 900.0,
                                                         1200.0]),
        "fig08_torque_around_kM.png": by_stiffness(
            f"Fig. 8 analogue: around k_M = {k_m:.1f}", [0.8 * k_m, k_m, 740.0, 1.2 * k_m]),
        "fig11_torque_around_kE.png": by_stiffness(
            "Fig. 11 analogue: around k_E (784.717) and the work optimum "
            f"{k_work:.0f}", [PAPER_K_E, k_work, 0.8 * k_work, 1.2 * k_work]),
    }


def _cost_figures(j: PaperJoint, n: int) -> dict[str, Figure]:
    """Figs 9, 10, 12, 13: the mean |M| and ε (eq. 24) against stiffness, optima marked."""
    k_m = k_M_paper_number(j)
    k_work = float(si_to_paper_number(j.closed_form_work()))
    marks_t = {"k_M (eq. 19)": k_m, "740 (paper)": 740.0,
               "mean|M| closed form": float(si_to_paper_number(j.closed_form_mean_abs()))}
    marks_e = {"k_E (paper)": PAPER_K_E, "800 (paper)": 800.0, "work closed form": k_work,
               "k_M": k_m}

    def grid(kmax: float) -> tuple[np.ndarray, np.ndarray]:
        kp = np.linspace(0.0, kmax, 301)
        return kp, np.asarray(paper_number_to_si(kp))

    def mean_torque(title: str, kmax: float) -> Figure:
        kp, ks = grid(kmax)
        return draw.mean_torque_vs_stiffness(kp, metric(j, "mean_abs", ks, False, n), marks_t,
                                             title)

    def epsilon(title: str, kmax: float) -> Figure:
        kp, ks = grid(kmax)
        return draw.epsilon_vs_stiffness(kp, energy_ratio(j, ks, False, n), marks_e, title)

    return {
        "fig09_mean_torque_vs_stiffness.png": mean_torque(
            "Fig. 9 analogue: average |torque|", 3000.0),
        "fig10_mean_torque_around_kM.png": mean_torque("Fig. 10 analogue: around k_M", 1600.0),
        "fig12_epsilon_vs_stiffness.png": epsilon(
            "Fig. 12 analogue: energy ratio ε (eq. 24)", 3000.0),
        "fig13_epsilon_around_kE.png": epsilon("Fig. 13 analogue: ε around k_E", 1800.0),
    }


PANEL_TITLES = {"rigid": "rigid joint (Fig. 5)", "table4_400": "k = 400, Table 4 (Fig. 6)",
                "k_M": "k = k_M = 713.547, eq. 19 (Fig. 8)",
                "paper_740": "k = 740, the paper's mean-torque optimum"}
"""Panel titles of the required torques, by key of :data:`hexaleg.paper.forward.NAMED`."""


def forward_figures(study: ForwardStudy, n: int) -> dict[str, Figure]:
    """The forward runs beside the analytic model, file name (PNG) → figure: the required torque
    at rigid, 400, k_M and 740 (Figs 5–8), the mean |M| (Figs 9–10) and ε (Figs 12–13) against k.

    Args:
        study: :func:`~hexaleg.paper.forward.forward_study`'s result.
        n: Samples per period of the analytic curves against k.
    """
    j = study.model.joint
    first = study.torques[0]
    torques = draw.forward_torques(
        first.t, [(PANEL_TITLES[r.key], r.torque) for r in study.torques],
        "Figs 5–8 forward: required torque, no gravity (k in eq. 19 units)")
    kp = np.linspace(0.0, float(study.grid[-1]), 301)
    ks = np.asarray(paper_number_to_si(kp))
    k_runs = np.concatenate([[0.0], study.grid])

    def runs(name: str) -> np.ndarray:
        return np.column_stack([study.baseline[name][1:], study.curves[name][1:]])

    def marks(name: str) -> dict[str, float]:
        o = study.optima[name]
        return {"closed form": o.closed_form, "forward": o.simulated,
                "forward, friction": o.friction, "paper's Adams reading": o.paper}

    return {
        "sim_fig05_08_required_torque.png": torques,
        "sim_fig09_10_mean_torque_vs_stiffness.png": draw.forward_mean_torque(
            kp, metric(j, "mean_abs", ks, False, n), k_runs, runs("mean_abs"),
            marks("mean_abs"), "Figs 9–10 forward: average |torque|"),
        "sim_fig12_13_epsilon_vs_stiffness.png": draw.forward_epsilon(
            kp, energy_ratio(j, ks, False, n), k_runs, runs("epsilon"), marks("epsilon"),
            "Figs 12–13 forward: energy ratio ε (eq. 24)"),
    }
