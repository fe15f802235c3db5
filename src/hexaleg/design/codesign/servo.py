"""The servo-aware choice of the co-designed gait (issue #41): the search's finalists simulated.

The co-design's search ranks gaits by the energy the analysis predicts: planned foot forces,
tracked exactly. A position-only servo (most hexapods of this class) realises neither: with four
or five feet down the stance legs' internal forces are whatever the position errors make them,
and the saving the springs were sized for shrinks. On the default hexapod at 0.06 m/s, the
search's best gait (duty factor 0.79) kept 0.73 of its predicted saving under position-only
servos, where the same gait at duty factor 0.7 kept 0.96 and, simulated, drew less.

So the search hands on its best distinct feasible gaits
(:attr:`~hexaleg.design.codesign.gait_search.SearchResult.finalists`), each is re-evaluated at
the rows' sampling with its inner springs and simulated forward in MuJoCo
(:func:`hexaleg.simulation.run.simulate`, default settings) under each controller of the servo
the robot runs (:func:`~hexaleg.simulation.controllers.controllers_of`: by default both), and
the chosen gait is the finalist whose *simulated* electrical energy per metre walked, with its
springs, is least under its worse controller. A finalist that does not walk under one of them
(or has no numbers at the rows' sampling) is never chosen, and the result says why. Each
simulation takes about a second on the default robot.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.design.chain.design_file import gait_parameters
from hexaleg.design.codesign.gait_evaluation import Constraints, GaitPoint
from hexaleg.dynamics.contact import ContactParams
from hexaleg.errors import HexalegError
from hexaleg.motion.legged import gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.quantities import quantity
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation.controllers import controllers_of

TIE = 0.002
"""Fraction of the least simulated energy per metre within which finalists tie (the first in
the search's order is chosen): a forward simulation is sensitive to rounding — a 1e-9 s change
of the gait's period moves its energy by ~0.1 % (measured on the default robot) — so a closer
difference is not one the simulation can tell on another machine."""


@dataclass(frozen=True, eq=False)
class Screened:
    """One finalist gait with its inner springs, simulated under each controller.

    Attributes:
        point: The finalist evaluated at the rows' sampling (its predicted energies).
        per_metre: Controller → simulated electrical energy per metre walked with its springs,
            J/m; None where it did not walk.
        verdicts: Controller → ``"walks"`` or what happened.
    """

    point: GaitPoint
    per_metre: Mapping[str, float | None]
    verdicts: Mapping[str, str]

    @property
    def worst(self) -> float:
        """The simulated energy per metre under the worse controller, J/m (∞ when it did not
        walk under one of them, or was not simulated)."""
        values = list(self.per_metre.values())
        if not values or any(v is None for v in values):
            return float("inf")
        return max(float(v) for v in values if v is not None)

    def data(self) -> dict[str, Any]:
        """codesign.json's row: the gait (as ``gait.parameters``), the predicted and the
        simulated J/m with its springs and the verdicts, or the error at the rows' sampling."""
        head = {"gait": gait_parameters(self.point.params)}
        if self.point.error is not None:
            return {**head, "error": self.point.error}
        return {**head, "predicted": quantity(self.point.per_metre_springs, "J/m"),
                "simulated": {k: None if v is None else quantity(v, "J/m")
                              for k, v in self.per_metre.items()},
                "verdicts": dict(self.verdicts)}


def screen(robot: Robot, points: Sequence[GaitPoint], servo: str, c: Constraints, motor: Any,
           final: Callable[[GaitParams], GaitPoint],
           progress: Callable[[str], None] | None = None) -> tuple[Screened, ...]:
    """Each finalist at the rows' sampling (``final``: a gait → its point at that sampling,
    with its springs) simulated with its springs under each controller of ``servo``;
    ``progress`` is called with a line after each finalist (None: quiet).

    Raises:
        UnknownNameError: an unknown servo (lists them).
    """
    controllers = controllers_of(servo)
    out = []
    for p in points:
        point = final(p.params)
        if point.error is not None:
            out.append(Screened(point, {}, {k: point.error for k in controllers}))
            continue
        per_metre: dict[str, float | None] = {}
        verdicts: dict[str, str] = {}
        played = gait(robot, point.params)
        for k in controllers:
            per_metre[k], verdicts[k] = simulated_per_metre(robot, played, motor, point.springs,
                                                            k, c.contact())
        out.append(Screened(point, per_metre, verdicts))
        if progress is not None:
            progress(f"finalist {len(out)} of {len(points)} simulated under "
                     f"{' and '.join(controllers)}")
    return tuple(out)


def simulated_per_metre(robot: Robot, motion: Motion, motor: Any, springs: SpringSet,
                        controller: str, contact: ContactParams) -> tuple[float | None, str]:
    """``motion`` simulated with ``springs`` under ``controller``
    (:func:`hexaleg.simulation.run.simulate`, default settings: balance feedback where the gait
    needs it): its electrical energy per metre walked, J/m, and ``"walks"``; or None and what
    happened (the verdict and its message, or the error)."""
    per_metre, verdict, _ = simulated_run(robot, motion, motor, springs, controller, contact)
    return per_metre, verdict


def simulated_run(robot: Robot, motion: Motion, motor: Any, springs: SpringSet,
                  controller: str, contact: ContactParams, feedback: str = "auto"
                  ) -> tuple[float | None, str, bool | None]:
    """:func:`simulated_per_metre` with the simulation's ``feedback`` setting (``"auto"``,
    ``"on"``, ``"off"``: :class:`hexaleg.simulation.run.Settings`), and whether the balance
    controller ran (None when the simulation raised)."""
    from hexaleg.simulation.run import Settings, simulate

    try:
        sim = simulate(robot, motion, motor, springs, Settings(force_samples=0,
                                                               controller=controller,
                                                               feedback=feedback),
                       contact=contact)
    except HexalegError as err:
        return None, f"{type(err).__name__}: {err}", None
    run = sim.with_springs
    if not run.walks or run.walk is None:
        return None, f"{run.verdict}: {run.message}", run.feedback
    return float(run.metrics["electrical"] / run.walk.distance_per_cycle), "walks", run.feedback


def choose(screened: Sequence[Screened]) -> Screened | None:
    """The finalist with the least simulated energy per metre under its worse controller: the
    first (in the search's order, so the search's best on a tie) within :data:`TIE` of the
    least, so that a simulation's rounding on another machine does not change the choice;
    None when none walked under all."""
    walked = [s for s in screened if np.isfinite(s.worst)]
    if not walked:
        return None
    least = min(s.worst for s in walked)
    return next(s for s in walked if s.worst <= least * (1.0 + TIE))


__all__ = ["TIE", "Screened", "choose", "screen", "simulated_per_metre", "simulated_run"]
