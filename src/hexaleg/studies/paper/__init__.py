"""The paper's single elastic joint: model and closed forms, costs and optimal stiffness, the
readings of its printed numbers, a Pinocchio cross-check, its Adams experiment forward in
MuJoCo, and the files of ``hexaleg paper``.

``from hexaleg.studies import paper`` gives the public names below (``paper.PaperJoint``,
``paper.optimal_stiffness``, …). Modules: :mod:`~hexaleg.studies.paper.joint`,
:mod:`~hexaleg.studies.paper.metrics`, :mod:`~hexaleg.studies.paper.readings`,
:mod:`~hexaleg.studies.paper.crosscheck`, :mod:`~hexaleg.studies.paper.forward`,
:mod:`~hexaleg.studies.paper.reproduce`,
:mod:`~hexaleg.studies.paper.figures`, :mod:`~hexaleg.studies.paper.summary`,
:mod:`~hexaleg.studies.paper.write`, :mod:`~hexaleg.studies.paper.command` (the command).
"""

from hexaleg.studies.paper.crosscheck import pinocchio_femur_torque
from hexaleg.studies.paper.figures import forward_figures, make_figures
from hexaleg.studies.paper.forward import ForwardOptimum, ForwardStudy, forward_study
from hexaleg.studies.paper.joint import POSTURES, PaperJoint
from hexaleg.studies.paper.metrics import (
    JOINT_METRICS,
    StiffnessOptimum,
    energy_ratio,
    metric,
    optimal_stiffness,
)
from hexaleg.studies.paper.readings import (
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
from hexaleg.studies.paper.reproduce import reproduce, simulation_section
from hexaleg.studies.paper.summary import markdown_summary
from hexaleg.studies.paper.write import write_paper

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
    "write_paper",
]
