"""The springs to buy on the co-designed gait: what the full spring rules chose, and their figures.

``hexaleg codesign`` applies ``hexaleg design``'s rules (issue #30) to the gait it chose
(:func:`hexaleg.design.codesign.full_rules.full_rules`): **parsimony** (a joint class is fitted only
when it adds at least ``[design] min_group_saving``), the **stop tolerance** (the design kept for
its worst saving over the stops' mounting error, :mod:`hexaleg.design.search.tolerance`), the whole
**envelope** with the **hard stop** where a part would yield
(:mod:`hexaleg.design.springs.envelope`), **fatigue** at ``[design] life_cycles``
(:mod:`hexaleg.design.springs.fatigue`) and the **arbor** (the coil wound up to its largest
deflection still clears its pin). This module turns that
:class:`~hexaleg.design.chain.result.DesignResult` into the co-design's terminal lines
(:func:`rule_lines`) and ``codesign.json``'s ``full_rules`` section (:func:`rule_data`), every
number ``{value, unit}``.
"""

from __future__ import annotations

import math
from typing import Any

from hexaleg.design.chain.records import candidate_data, ranking_data
from hexaleg.design.chain.result import DesignResult, mounting_data, proof_data, tolerance_data
from hexaleg.design.springs.envelope import STRESS
from hexaleg.quantities import quantity
from hexaleg.simulation.sensitivity import sensitivity_row

RULES = ("parsimony", "stop tolerance", "envelope and hard stop", "fatigue", "arbor")
"""The rules the springs to buy come from, as the page and the summary name them."""


def per_metre(r: DesignResult, stride: float) -> float:
    """The chosen gait's electrical energy per metre with the springs to buy, J/m (the
    recommendation's predicted electrical energy per cycle over the stride)."""
    return float(r.recommended.row["electrical"]) / stride


def _pct(x: float) -> str:
    return f"{100 * x:+.2f} %"


def rule_lines(r: DesignResult, stride: float, on: str = "the chosen gait") -> list[str]:
    """The terminal lines of the springs to buy on ``on`` (the motion the rules ran on, as the
    lines name it; ``stride`` its distance a cycle, m): the recommendation, then one line per rule's
    figures (stop tolerance; parsimony; per part the wire, worst static safety over the
    envelope, hard stop, fatigue safety and arbor clearance), then its simulation under the
    servo the robot runs, the worse first; "unproven" and why where that simulation does not
    back the springs (:attr:`~hexaleg.design.chain.result.DesignResult.unproven`)."""
    rec, m, d = r.recommended, r.design.metric, r.design
    why = r.unproven
    head = ("no springs pay; the best would be" if not r.pays else
            f"unproven ({why}): springs the analysis would buy" if why else "springs to buy")
    out = [f"{head} (full spring rules on {on}: {', '.join(RULES)}): {rec.label} on "
           f"{', '.join(rec.optimum.groups)}, {per_metre(r, stride):.2f} J/m, {m} saving "
           f"{_pct(rec.row[f'saving.{m}'])} ({_pct(rec.net[m])} net of "
           f"{1e3 * rec.spring_mass:.1f} g of springs)"]
    t = r.tolerance
    if t is not None:
        out.append(f"  stops within ±{math.degrees(t.tolerance):g}°: worst "
                   f"{_pct(t.worst['tolerant'])} tolerant, {_pct(t.worst['blind'])} "
                   f"tolerance-blind: {t.chosen} design built")
    kept = ", ".join(f"{g} {_pct(v)}" for g, v in rec.marginal.items())
    dropped = ", ".join(f"{g} (would add {_pct(v)})" for g, v in rec.dropped.items())
    out.append(f"  parsimony (≥ {100 * d.min_group_saving:g} point a class): fitted {kept}"
               + (f"; not fitted {dropped}" if dropped else ""))
    for e, (p, f) in zip(r.envelope, r.fatigue, strict=True):
        s = p.spring
        assert s is not None  # the envelope holds the bought parts only
        stop = ("no hard stop needed" if e.stop is None else
                f"hard stop at {math.degrees(e.stop.angle_from_centre):+.1f}° from the centre"
                + ("" if e.stop.limit == STRESS else f" (set by its {e.stop.limit})"))
        arbor = ("clears its arbor" if e.clears_arbor else "does not clear its arbor")
        out.append(f"  {p.group} {p.side}: {s.material} d {1e3 * s.wire_diameter:.2f} mm, D "
                   f"{1e3 * s.mean_diameter:.2f} mm, {s.body_turns:g} turns; worst S_y/σ "
                   f"{e.safety_factor:.2f} (design factor {e.design_factor:g}), {stop}; fatigue "
                   f"n_f {f.safety_factor:.2f} at {d.life_cycles:,.0f} cycles; wound up it {arbor} "
                   f"({1e3 * e.held_inner_diameter:.2f} mm over {1e3 * e.arbor_diameter:.2f} mm)")
    rows = r.simulated()
    if rows:
        sims = [f"{row['label']} {_pct(row['simulated'])}" if row["simulated"] is not None
                else f"{row['label']}: {row['verdict']}" for row in rows]
        out.append(f"  simulated {m} saving, the worse servo first: {', '.join(sims)} "
                   f"(predicted {_pct(rows[0]['predicted'])})")
    return out


def rule_data(r: DesignResult, stride: float,
              applied_to: str = "the chosen gait only (too slow for the search's inner loop)"
              ) -> dict[str, Any]:
    """``codesign.json``'s ``full_rules`` (``applied_to``: the motion they ran on, said): the
    settings, the recommendation (savings, groups
    with their marginal saving, the groups left unfitted, the parts), where each part mounts on
    each joint (angles from the joint's zero), its energy per metre, the
    stop tolerance, the envelope and hard stops, fatigue, the ranking, the simulation (under the
    servo the robot runs, the worse first) and whether it proves the springs, the
    stages' wall times and the notes."""
    d = r.design
    return {
        "applied_to": applied_to,
        "rules": list(RULES), "summary": r.summary(), "pays": r.pays,
        "settings": {"families": list(d.families), "metric": d.metric,
                     "samples": r.gait.samples,
                     "stop_tolerance": quantity(d.stop_tolerance, "rad"),
                     "min_group_saving": quantity(100 * d.min_group_saving, "%"),
                     "safety_factor": quantity(d.safety_factor, "1"),
                     "arbor_diameter": quantity(d.arbor_diameter, "m"),
                     "life_cycles": quantity(d.life_cycles, "cycles"),
                     "robustness": d.robustness},
        "recommended": candidate_data(r.recommended, r.outer),
        "mounting": mounting_data(r),
        "per_metre": quantity(per_metre(r, stride), "J/m"),
        "stop_tolerance": None if r.tolerance is None else tolerance_data(r),
        "envelope": [e.table() for e in r.envelope],
        "fatigue": [{"group": p.group, "side": p.side, "role": p.role, **f.table()}
                    for p, f in r.fatigue],
        "ranking": [ranking_data(row) for row in r.ranking],
        "simulation": [sensitivity_row(row) for row in r.simulated()],
        "proof": proof_data(r),
        "timings": {k: quantity(v, "s") for k, v in r.timings.items()},
        "notes": list(r.notes),
    }


__all__ = ["RULES", "per_metre", "rule_data", "rule_lines"]
