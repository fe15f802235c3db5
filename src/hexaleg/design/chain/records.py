"""design.json's records of the chain's single products: a candidate design, a ranked design's
simulation, a robustness map, the robust design.

Each record is built from its own object, not from the whole
:class:`~hexaleg.design.chain.result.DesignResult`, so the files that hold such a product without a
whole design read it in the same form: :func:`candidate_data` is ``hexaleg report``'s quick
answer (:mod:`hexaleg.report.answer`) and the co-design's springs to buy
(:mod:`hexaleg.design.codesign.rules`) as well as ``design.json``'s ``recommended``,
``candidates`` and ``pareto``. Every number is ``{"value": …, "unit": …}``
(:func:`hexaleg.quantities.quantity`; savings in %, SI otherwise), each spring
``{"family", "joint", "parameters"}`` (:mod:`hexaleg.design.springs.law_json`).
"""

from __future__ import annotations

from typing import Any

import numpy as np

from hexaleg.design.chain.candidates import Candidate
from hexaleg.design.chain.ranking import Simulated
from hexaleg.design.chain.robust_stage import RobustResult
from hexaleg.design.evaluator import SAVING_METRICS
from hexaleg.design.robust.maps import RobustnessMap
from hexaleg.design.springs.law_json import spring_entry
from hexaleg.design.springs.parts import SpringPart
from hexaleg.dynamics.energy import metric_unit
from hexaleg.quantities import quantity

AXIS_UNITS = {"period": "1", "stride": "1", "payload": "1", "mu": "1", "slope": "rad"}
"""Units of the map axes: factors of the nominal gait, a fraction of the robot's mass, μ, the
ground's slope; a ``pattern`` axis holds names (a plain list of strings, no unit)."""


def _grid(values: np.ndarray, unit: str) -> dict[str, Any]:
    """A 2-D array as ``{value: [[…]], unit}`` (non-finite entries null in the file)."""
    return {"value": np.asarray(values, dtype=float).tolist(), "unit": unit}


def _part(p: SpringPart, source: str) -> dict[str, Any]:
    return {
        "group": p.group, "joints": list(p.joints), "side": p.side, "role": p.role,
        "rate": quantity(p.rate, "N·m/rad"),
        "preload_torque": quantity(p.preload_torque, "N·m"),
        "max_torque": quantity(p.max_torque, "N·m"),
        "engage": None if p.engage is None else quantity(p.engage, "rad"),
        "free": None if p.free is None else quantity(p.free, "rad"),
        "constant_torque": p.constant_torque,
        "max_outer_diameter": quantity(p.max_outer_diameter, "m"),
        "max_outer_diameter_source": source,
        "torsion_spring": p.spring.table() if p.spring else None,
        "nearest": p.nearest.table() if p.nearest else None,
        "problem": p.problem,
    }


def candidate_data(c: Candidate, outer: dict[str, tuple[float, str]]) -> dict[str, Any]:
    """One design: its savings (every metric, and net of the springs' mass), groups, the
    springs (JSON entries), the parts to buy."""
    o, a = c.optimum, c.optimum.analysis
    table = o.table()
    return {
        "label": c.label, "family": c.family,
        "max_torque": None if c.max_torque is None else quantity(c.max_torque, "N·m"),
        "buildable": c.buildable,
        "saving": {m: quantity(100 * c.row[f"saving.{m}"], "%") for m in SAVING_METRICS},
        "with_springs": {m: quantity(c.row[m], metric_unit(m)) for m in SAVING_METRICS},
        "net_saving": {m: quantity(100 * v, "%") for m, v in c.net.items()},
        "spring_mass": quantity(c.spring_mass, "kg"),
        "peak_spring_torque": quantity(np.abs(a.tau_spring).max(), "N·m"),
        "peak_spring_energy": quantity(a.spring_energy.max(), "J"),
        "groups": {g: {"joints": list(js),
                       "design": table[g],
                       "marginal_saving": quantity(100 * c.marginal[g], "%")}
                   for g, js in o.groups.items()},
        "springs": [spring_entry(j, s) for j, s in o.springs.items()],
        "parts": [_part(p, outer[p.group][1]) for p in c.parts],
        "dropped_groups": {g: {"marginal_saving": quantity(100 * v, "%")}
                           for g, v in c.dropped.items()},
        "notes": list(c.notes),
        # how its geometry was found: the search's stages (method, evaluations, convergence)
        "search": (c.searched or c.optimum).solver.get("search"),
    }


def ranking_data(r: Simulated) -> dict[str, Any]:
    """One ranked design simulated under one of the design's controllers."""
    return {"label": r.candidate.label, "controller": r.controller, "feedback": r.feedback,
            "verdict": r.verdict,
            "predicted_saving": quantity(100 * r.predicted, "%"),
            "simulated_saving": (None if r.simulated is None
                                 else quantity(100 * r.simulated, "%")),
            "simulated_net_saving": quantity(100 * r.net, "%"),
            "flagged": r.flagged}


def map_data(m: RobustnessMap) -> dict[str, Any]:
    """One robustness map: axes, values, saving grids in %, statuses."""
    out: dict[str, Any] = {"axes": list(m.axes),
                           "values": {a: [str(x) for x in v] if a == "pattern"
                                      else quantity(v, AXIS_UNITS[a])
                                      for a, v in zip(m.axes, m.values, strict=True)},
                           "saving": {k: _grid(100 * v, "%") for k, v in m.saving.items()},
                           "status": [list(row) for row in m.status]}
    out["worst"] = {}
    for k in m.saving:
        s, cond = m.worst(k)
        out["worst"][k] = {"saving": quantity(100 * s, "%"),
                           "condition": cond.label() if cond else None}
    return out


def robust_data(r: RobustResult, outer: dict[str, tuple[float, str]]) -> dict[str, Any]:
    """The robust design: conditions, both designs' savings per condition and worst cases."""
    d = r.design
    return {
        "mode": d.mode, "metric": d.metric, "conditions": [c.label() for c in r.conditions],
        "saving": {m: {k: quantity(100 * v, "%") for k, v in s.items()}
                   for m, s in r.savings.items()},
        "worst": {m: {k: quantity(100 * r.worst(m, k), "%") for k in s}
                  for m, s in r.savings.items()},
        "nominal_meets_the_limits_everywhere": d.nominal_feasible,
        "design": candidate_data(r.candidate, outer),
        "solver": d.solver,
    }


__all__ = ["AXIS_UNITS", "candidate_data", "map_data", "ranking_data", "robust_data"]
