"""Stand-ins of the optimal stage's records for the tests of its table and its choices: a
solver's figures (:func:`solved`), a four-row table (:func:`four_rows`), an answer of a row
(:func:`answer`)."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

import hexaleg
from hexaleg.design.codesign.alternation import Alternation, Round
from hexaleg.design.codesign.optimal_table import LABELS, MotionRow, OptimalRows


def solved(per_metre: float) -> SimpleNamespace:
    """The figures of an optimal cycle the table reads (an OptimalResult's)."""
    return SimpleNamespace(energy_per_metre=per_metre, residual=7e-15, iterations=100,
                           residual_check="euler_step", defect=0.0,
                           converged=False, stationarity=5e-5, threshold=1e-8, dynamic_gap=0.0,
                           periodicity=1e-3, friction_use=0.6, slip=4e-3, drift=2e-4,
                           torques=np.zeros((40, 18)), seconds=60.0, motion=None,
                           task_space=None)


def four_rows(position: float | None) -> OptimalRows:
    """The four rows with row 4 walking under position servos for ``position`` J/m (None: it
    fell), the springs a linear femur spring."""
    springs = hexaleg.SpringSet({"femur": hexaleg.LinearSpring(stiffness=0.5)})
    start, best = solved(9.2), solved(9.0)
    alt = Alternation(None, 10.0, start, 9.3, best, springs,
                      (Round(springs, 8.9, 9.0, 9.1, True, 1.0),), 0.02, False)
    sims = [MotionRow(label, e, {"feedforward": 1.1 * e, "position": 1.3 * e},
                      {"feedforward": "walks", "position": "walks"},
                      {"feedforward": "open loop", "position": "balance feedback"})
            for label, e in zip(LABELS[:3], (28.4, 10.0, 9.6), strict=True)]
    last = MotionRow(LABELS[3], 9.0, {"feedforward": 9.5, "position": position},
                     {"feedforward": "walks",
                      "position": "walks" if position is not None else "fell: at 1 s"})
    return OptimalRows((*sims, last), springs, "linear", solved(9.6), alt, hexaleg.load(),
                       "both", 200.0, "on")


def answer(weight: float, predicted: float | None, feedforward: float | None,
            position: float | None):
    from hexaleg.design.codesign.landing_choice import Candidate

    sims = {"feedforward": feedforward, "position": position}
    return Candidate(weight, predicted, sims,
                     {k: "walks" if v is not None else "fell" for k, v in sims.items()})
