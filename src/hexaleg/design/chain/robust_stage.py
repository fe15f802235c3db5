"""The robust stage of ``hexaleg design``: the recommended geometry's magnitudes for a box of
conditions (:func:`robust_design`), with its parts, beside the nominal design over the same box.

The box is the nominal gait and the corners of ``[design] robust_period``, ``robust_stride``,
``robust_payload`` and ``robust_mu`` (:func:`corners`); the magnitudes maximise the worst (or the
mean) saving over them in one convex program (:func:`hexaleg.design.robust.box.robust_springs`). A
corner the robot cannot walk, or where it has no forces without springs, is left out with a note
naming the keys that set it.
"""

from __future__ import annotations

import dataclasses
import itertools
from dataclasses import dataclass

import numpy as np

from hexaleg.design.chain.candidates import Candidate, candidate
from hexaleg.design.chain.config import METRICS, DesignParams
from hexaleg.design.chain.stages import Nominal
from hexaleg.design.robust.box import RobustSprings, robust_springs
from hexaleg.design.robust.conditions import condition_savings, condition_walks, same_motion
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import HexalegError, InfeasibleForcesError, TorqueLimitError
from hexaleg.scenario.condition import Condition


@dataclass(frozen=True, eq=False)
class RobustResult:
    """The robust design and both designs over the box of conditions.

    Attributes:
        conditions: The nominal gait and the box's corners.
        design: The robust program's result (savings per condition in its metric).
        candidate: The robust magnitudes as a design on the nominal gait, with its parts.
        savings: Metric (:data:`~hexaleg.design.chain.config.METRICS`) →
            ``{"robust": (n,), "nominal": (n,)}`` savings per condition.
    """

    conditions: tuple[Condition, ...]
    design: RobustSprings
    candidate: Candidate
    savings: dict[str, dict[str, np.ndarray]]

    def worst(self, metric: str, design: str = "robust") -> float:
        """The worst saving of ``design`` (robust or nominal) over the conditions."""
        return float(np.min(self.savings[metric][design]))


def corners(d: DesignParams) -> tuple[Condition, ...]:
    """The nominal gait and the corners of the robust box of the ``[design]`` table
    (duplicates once)."""
    boxes = [sorted(set(b)) for b in (d.robust_period, d.robust_stride, d.robust_payload,
                                      d.robust_mu)]
    out = [Condition()]
    for p, s, w, mu in itertools.product(*boxes):
        c = Condition(period=p, stride=s, payload=w, mu=mu)
        if c not in out:
            out.append(c)
    return tuple(out)


def robust_design(nom: Nominal, rec: Candidate) -> tuple[RobustResult | None, tuple[str, ...]]:
    """The recommended geometry's magnitudes for the box of conditions
    (:func:`hexaleg.design.robust.box.robust_springs`: its corners and the nominal gait, one convex
    program), with its own parts, and the notes of what was left out; no result when the box is
    the nominal gait alone, the motion is logged (:data:`~hexaleg.design.chain.stages.
    LOGGED_SKIP`) or ``[design] robustness`` is false (:data:`~hexaleg.design.chain.stages.
    UNMAPPED`).

    The stage never ends the design: a corner whose gait the legs cannot walk or that has no
    admissible forces without springs is left out with a note naming the ``[design] robust_*``
    keys that set it; when no corner is left, or the program fails, there is no robust design
    and a note says why (the candidates, ranking and checks stand).
    """
    d, prepared = nom.design, nom.prepared
    conditions = corners(d)
    if len(conditions) == 1 or nom.motion is not None or not d.robustness:
        return None, ()
    groups = same_motion(nom.run, conditions)  # each motion made once (μ does not change it)
    grouped = nom.fork_map(lambda g: list(condition_walks(
        nom.run, [conditions[i] for i in g], prepared.motion)), groups)
    walked: list[Prepared | str] = [""] * len(conditions)
    for g, done in zip(groups, grouped, strict=True):
        for i, p in zip(g, done, strict=True):
            walked[i] = p
    kept: list[Condition] = []
    preps: list[Prepared] = []
    notes: list[str] = []
    for c, p in zip(conditions, walked, strict=True):
        why = p if isinstance(p, str) else _no_baseline(p)
        if isinstance(p, str) or why:
            nominal_value = {"period": 1.0, "stride": 1.0, "payload": 0.0,
                             "mu": nom.run.contact.mu}
            keys = [f"robust_{n}" for n, v in nominal_value.items()
                    if getattr(c, n) not in (None, v)]
            notes.append(f"robust box corner {c.label()} left out (set by [design] "
                         f"{' and '.join(keys)}): {why}")
            continue
        kept.append(c)
        preps.append(p)
    if len(kept) == 1:
        return None, (*notes, "no robust design: no corner of the box is left to design for")
    try:
        design = robust_springs(rec.optimum, prepared, preps, d.robust_mode, d.metric,
                                max_torque=d.max_torque, max_deflection=d.deflection_bound,
                                prefer=0 if kept[0] == Condition() else None)
    except HexalegError as e:
        return None, (*notes, f"no robust design: {type(e).__name__}: {e}")
    analysis = prepared.evaluate(design.springs, "joule")
    optimum = dataclasses.replace(
        rec.optimum, magnitudes=design.magnitudes, springs=design.springs, analysis=analysis,
        value=float(analysis.metrics["total"]["joule"]), saving=float(design.saving[0]),
        notes=(), solver=design.solver)
    rows = {name: [condition_savings(p, s, "joule") for p in preps]
            for name, s in (("robust", design.springs), ("nominal", rec.optimum.springs))}
    savings = {m: {name: np.array([r[f"saving.{m}"] if r["status"] == "ok" else -np.inf
                                   for r in rs]) for name, rs in rows.items()}
               for m in METRICS}
    return RobustResult(conditions=tuple(kept), design=design,
                        candidate=candidate(optimum, prepared, nom.run, nom.gait,
                                            nom.outer_diameters, d),
                        savings=savings), tuple(notes)


def _no_baseline(prepared: Prepared) -> str:
    """Why ``prepared`` has no forces without springs, or '' when it has."""
    try:
        prepared.baseline("joule")
    except (InfeasibleForcesError, TorqueLimitError) as e:
        return f"no admissible forces without springs: {type(e).__name__}: {e}"
    return ""



__all__ = ["RobustResult", "corners", "robust_design"]
