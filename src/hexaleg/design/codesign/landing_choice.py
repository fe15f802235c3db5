"""Which answer an optimal row keeps: the one walking cheaper under the worse servo (issue #56).

Each optimal row's answer — the motion without springs, and the alternation with its springs — is
solved twice, without and with the landing legs' position-servo effort in the cost
(:class:`~hexaleg.optimal.servo_effort.ServoEffortCost`, weight :data:`SERVO_LANDING`, or
``servo_landing_weight`` where the problem's parameters set one), both predicted and simulated
under every controller, and the row keeps the one walking cheaper under its worse controller
(:func:`by_worse_servo`, as the parametric co-design chooses its gait among its finalists,
:func:`~hexaleg.design.codesign.servo.choose`; within :data:`~hexaleg.design.codesign.servo.TIE` of
each other the cheaper prediction, then the one without the cost). The cost lets a position servo
land the feet where the plan puts them (the hexapod's optimal motion with its springs walks under
position servos for 13.9 J/m with it against 17.5 without,
``analysis/bench_logs/bench_optimal_servo.log``), but it does not help every motion: on Solo-12's
trot without springs the weighted plan is the same plan to the prediction's digits and its
simulated figure, which moves with the simulation's timestep by more than the weight moves it,
doubles (``analysis/bench_logs/bench_optimal_landing.log``). The table says which each row kept
(:class:`Landing`).

The rows are computed in :mod:`~hexaleg.design.codesign.optimal_rows`; this module holds the
answers' figures, the rule and the record of the choice.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any

from hexaleg.design.codesign.servo import TIE
from hexaleg.quantities import quantity as q

SERVO_LANDING = 30.0
"""The landing effort's weight of each optimal row's second answer, W/(N·m)²
(:attr:`~hexaleg.optimal.problem.OptimalParams.servo_landing_weight` where the problem's
parameters set none): from the hexapod's optimal motion with its springs' sweep of 3 to 1000,
the weight past which its position-servo bill stops falling (13.9 J/m at 30, 13.7 at 100, 13.9
at 300: ``analysis/bench_logs/bench_optimal_servo.log``) and its feedforward bill has not yet
risen (10.25, 10.33, 10.44)."""


@dataclass(frozen=True)
class Candidate:
    """One answer of an optimal row, solved without or with the landing effort in its cost,
    predicted and simulated (module docstring).

    Attributes:
        weight: Its landing effort's weight, W/(N·m)² (0: without the cost).
        predicted: Its J/m predicted (the rows' judge); None without a prediction.
        simulated: Controller → J/m walked; None where it did not walk.
        verdicts: Controller → ``"walks"`` or what happened.
        loops: Controller → the balance feedback that ran (:attr:`MotionRow.loops`).
    """

    weight: float
    predicted: float | None
    simulated: Mapping[str, float | None]
    verdicts: Mapping[str, str]
    loops: Mapping[str, str] = field(default_factory=dict)

    @property
    def worst(self) -> float:
        """J/m walked under its worse controller (∞ where it did not walk under one of them,
        or was not simulated)."""
        values = list(self.simulated.values())
        if not values or any(v is None for v in values):
            return math.inf
        return max(float(v) for v in values if v is not None)

    def data(self) -> dict[str, Any]:
        """codesign.json's entry: the weight, the predicted and the simulated J/m."""
        return {"servo_landing_weight": q(self.weight, "W/(N·m)^2"),
                "predicted": q(self.predicted, "J/m"),
                "simulated": {k: None if v is None else q(v, "J/m")
                              for k, v in self.simulated.items()},
                "verdicts": dict(self.verdicts)}


def by_worse_servo(candidates: Sequence[Candidate]) -> int:
    """The index of the candidate a row keeps: the least J/m walked under the worse controller
    (:attr:`Candidate.worst`), as the parametric co-design chooses its gait
    (:func:`~hexaleg.design.codesign.servo.choose`); among those within
    :data:`~hexaleg.design.codesign.servo.TIE` of it — a forward simulation's rounding on
    another machine cannot tell them apart — the cheaper prediction, then the first (the
    answer without the cost). Where none walked under every controller, the cheaper
    prediction, then the first."""
    least = min(c.worst for c in candidates)
    tied = [i for i, c in enumerate(candidates)
            if c.worst <= least * (1.0 + TIE) or not math.isfinite(least)]
    return min(tied, key=lambda i: (math.inf if candidates[i].predicted is None
                                    else candidates[i].predicted, i))


@dataclass(frozen=True)
class Landing:
    """Which answer an optimal row kept (module docstring).

    Attributes:
        candidates: The answers without and with the landing effort's cost
            (:class:`Candidate`), in that order.
        kept: The index of the one kept (:func:`by_worse_servo`).
    """

    candidates: tuple[Candidate, ...]
    kept: int

    @property
    def weight(self) -> float:
        """The landing effort's weight of the answer kept, W/(N·m)² (0: without the cost)."""
        return self.candidates[self.kept].weight

    def line(self, label: str, places: int) -> str:
        """The table's line: which answer ``label``'s row kept, each one's worse-servo and
        predicted J/m to ``places`` decimals."""
        def said(c: Candidate) -> str:
            worse = (f"{c.worst:.{places}f}" if math.isfinite(c.worst)
                     else "not walking under both servos")
            pred = "—" if c.predicted is None else f"{c.predicted:.{places}f}"
            how = "with it" if c.weight > 0 else "without it"
            return f"{how} {worse} under the worse servo ({pred} predicted)"

        kept = self.candidates[self.kept]
        others = [said(c) for i, c in enumerate(self.candidates) if i != self.kept]
        return (f"    {label}: kept the answer {'with' if kept.weight > 0 else 'without'} "
                f"the landing cost — {said(kept)}; " + "; ".join(others))

    def data(self) -> dict[str, Any]:
        """codesign.json's ``landing`` of a row: the candidates and the weight kept."""
        return {"candidates": [c.data() for c in self.candidates], "kept": self.kept,
                "servo_landing_weight": q(self.weight, "W/(N·m)^2"),
                "rule": "the least J/m walked under the worse servo (within "
                        f"{TIE:g} of it, the cheaper prediction, then without the cost)"}


__all__ = ["SERVO_LANDING", "Candidate", "Landing", "by_worse_servo"]
