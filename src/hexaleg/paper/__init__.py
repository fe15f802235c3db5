"""The paper's single elastic joint: model and closed forms, costs and optimal stiffness, the
readings of its printed numbers, a Pinocchio cross-check, its Adams experiment forward in
MuJoCo, and the files of ``hexaleg paper``.

``from hexaleg import paper`` gives the public names below (``paper.PaperJoint``,
``paper.optimal_stiffness``, …). Modules: :mod:`~hexaleg.paper.joint`,
:mod:`~hexaleg.paper.metrics`, :mod:`~hexaleg.paper.readings`,
:mod:`~hexaleg.paper.crosscheck`, :mod:`~hexaleg.paper.forward`,
:mod:`~hexaleg.paper.reproduce`,
:mod:`~hexaleg.paper.figures`, :mod:`~hexaleg.paper.summary`,
and the command's files: :mod:`hexaleg.commands.paper`.
"""

from hexaleg.paper.crosscheck import pinocchio_femur_torque
from hexaleg.paper.figures import forward_figures, make_figures
from hexaleg.paper.forward import ForwardOptimum, ForwardStudy, forward_study
from hexaleg.paper.joint import POSTURES, PaperJoint
from hexaleg.paper.metrics import (
    JOINT_METRICS,
    StiffnessOptimum,
    energy_ratio,
    metric,
    optimal_stiffness,
)
from hexaleg.paper.readings import (
    PAPER_K_E,
    PAPER_K_M,
    PAPER_RANGE_NMM_PER_DEG,
    PAPER_SAVING,
    PAPER_TABLE4_NMM_PER_DEG,
    k_E_readings,
    k_M_paper_number,
    paper_number_to_si,
    saving_readings,
    si_to_paper_number,
    stiffness_units,
)
from hexaleg.paper.reproduce import reproduce, simulation_section
from hexaleg.paper.summary import markdown_summary

__all__ = [
    "JOINT_METRICS",
    "PAPER_K_E",
    "PAPER_K_M",
    "PAPER_RANGE_NMM_PER_DEG",
    "PAPER_SAVING",
    "PAPER_TABLE4_NMM_PER_DEG",
    "POSTURES",
    "ForwardOptimum",
    "ForwardStudy",
    "PaperJoint",
    "StiffnessOptimum",
    "energy_ratio",
    "forward_figures",
    "forward_study",
    "k_E_readings",
    "k_M_paper_number",
    "make_figures",
    "markdown_summary",
    "metric",
    "optimal_stiffness",
    "paper_number_to_si",
    "pinocchio_femur_torque",
    "reproduce",
    "saving_readings",
    "si_to_paper_number",
    "simulation_section",
    "stiffness_units",
]
