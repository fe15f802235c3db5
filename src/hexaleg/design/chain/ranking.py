"""The servo you run: every ranked design simulated under it, the best simulated one recommended.

The design program predicts a saving with the planned foot forces and exact tracking. A servo
robot realises neither: under a position-only servo (what most hobby hexapods run) the stance
feet's internal forces are whatever the position errors make them, so a design can lose its
saving (the femur-only constant-torque springs: +8.2 % predicted, −2.4 % simulated) while another
keeps it. So each candidate is simulated forward in MuJoCo under the servo the user runs
(:func:`hexaleg.simulation.run.simulate`, the baseline simulated once a controller and reused) —
by default (``"both"``, :data:`~hexaleg.simulation.controllers.SERVOS`) under each controller —
and ranked by its *simulated* saving net of its springs' mass, the worse of its controllers':
the simulated gross saving plus the mass penalty the analysis predicts (the simulated robot does
not carry the springs: ``net − gross`` of :class:`~hexaleg.design.chain.candidates.Candidate`).
A design that does not walk under one of them is not recommended. A run whose simulated saving
is below :data:`FLAG_FRACTION` of its prediction is flagged.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from hexaleg.design.chain.candidates import Candidate
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import HexalegError
from hexaleg.simulation.controllers import BOTH, controllers_of
from hexaleg.simulation.result import Simulation
from hexaleg.simulation.run import simulate
from hexaleg.simulation.settings import Settings

FLAG_FRACTION = 0.5
"""A simulated saving below this fraction of the predicted one is flagged on the page."""


@dataclass(frozen=True, eq=False)
class Simulated:
    """One candidate simulated under the design's controller.

    Attributes:
        candidate: The design.
        controller: The controller it was simulated under.
        predicted: The analysis' saving of the metric, fraction (gross of the springs' mass).
        simulated: The simulated saving, fraction; None when a run did not walk.
        verdict: ``"walks"`` or what happened.
        net: The simulated saving net of the springs' mass (module docstring), fraction; −∞ when
            a run did not walk.
        feedback: Whether the balance controller ran (``[simulate] feedback``'s default,
            ``"auto"``: where the gait stands on fewer than three feet or open loop fell;
            :mod:`hexaleg.simulation.balance`).
    """

    candidate: Candidate
    controller: str
    predicted: float
    simulated: float | None
    verdict: str
    net: float
    feedback: bool = False

    @property
    def flagged(self) -> bool:
        """Whether the simulated saving falls below :data:`FLAG_FRACTION` of the prediction (or
        the design did not walk)."""
        return self.simulated is None or (
            self.predicted > 0 and self.simulated < FLAG_FRACTION * self.predicted)


def simulate_candidates(prepared: Prepared, candidates: Sequence[Candidate], servo: str,
                        metric: str, settings: Settings | None = None) -> list[Simulated]:
    """Each distinct candidate simulated under each controller of ``servo`` (module docstring):
    the rows of the first controller in the candidates' order, then the next controller's.

    Args:
        prepared: The nominal gait, prepared with the design's motor and contact.
        candidates: The designs (the same object twice is simulated once).
        servo: One of :data:`hexaleg.simulation.controllers.SERVOS`.
        metric: The ranking metric (``electrical`` or ``joule``).
        settings: The other simulation settings (default: :class:`Settings` without the
            foot-force comparison).

    Raises:
        UnknownNameError: an unknown servo (lists them).
    """
    return [row for controller in controllers_of(servo)
            for row in _under(prepared, candidates, controller, metric, settings)]


def _under(prepared: Prepared, candidates: Sequence[Candidate], controller: str, metric: str,
           settings: Settings | None) -> list[Simulated]:
    """Each distinct candidate simulated under one controller, in order."""
    import dataclasses

    settings = dataclasses.replace(settings or Settings(force_samples=0), controller=controller)
    base: Simulation | None = None
    out: dict[int, Simulated] = {}
    for c in candidates:
        if id(c) in out:
            continue
        predicted = float(c.row[f"saving.{metric}"])
        try:
            s = simulate(prepared.robot, prepared.motion, prepared.motor, c.optimum.springs,
                         settings, contact=prepared.contact, objective="joule",
                         prepared=prepared, baseline=base)
        except HexalegError as e:
            out[id(c)] = Simulated(c, controller, predicted, None, f"{type(e).__name__}: {e}",
                                   -np.inf)
            continue
        base = base or s
        if not s.walks:
            verdict = "; ".join(f"{r.name} {r.verdict}" for r in (s.with_springs, s.baseline)
                                if not r.walks)
            out[id(c)] = Simulated(c, controller, predicted, None, verdict, -np.inf,
                                   s.with_springs.feedback)
            continue
        saved = float(s.simulated(metric)[2])
        penalty = float(c.net[metric]) - predicted
        out[id(c)] = Simulated(c, controller, predicted, saved, "walks", saved + penalty,
                               s.with_springs.feedback)
    return list(out.values())


def under(servo: str) -> str:
    """What the designs were simulated under, in words: ``"the position servo"`` or, for
    ``"both"``, ``"both servos, by the worse"``."""
    return "both servos, by the worse" if servo == BOTH else f"the {servo} servo"


def best_simulated(rows: Sequence[Simulated]) -> Simulated | None:
    """The buildable design whose worse controller's simulated net saving is the best (the first
    of equals in the rows' order), as that worse row; None when no buildable design walked under
    every controller it was simulated under."""
    worst: dict[int, Simulated] = {}
    for r in rows:
        held = worst.get(id(r.candidate))
        if held is None or r.net < held.net:
            worst[id(r.candidate)] = r
    eligible = [r for r in worst.values() if r.simulated is not None and r.candidate.buildable]
    return max(eligible, key=lambda r: r.net, default=None)


__all__ = ["FLAG_FRACTION", "Simulated", "best_simulated", "simulate_candidates", "under"]
