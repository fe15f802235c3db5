"""The result of ``hexaleg codesign`` and its ``codesign.json``.

The four rows tell the gait's and the springs' shares apart: the default gait without springs
(the reference), with its best springs, the best gait without springs (the gait-alone search),
and the co-designed gait with its springs. With ``E₀`` the first row's energy per metre, the
gait's share is ``(E₀ − E_gait) / E₀`` and the springs' share of the co-design is
``(E_gait − E_codesign) / E₀`` (they add up to the co-design's saving). Every number in the JSON
is ``{value, unit}``; ``gait.parameters`` and ``recommended.springs`` are the keys
:func:`hexaleg.load_design` reads (:mod:`hexaleg.design.chain.design_file`), so the chosen gait and
springs run in ``hexaleg simulate --springs codesign.json`` and ``hexaleg report``. The springs
there are the ones to buy: by default those the full spring rules chose on the chosen gait
(:mod:`hexaleg.design.codesign.rules`, their figures in ``full_rules``), else the inner
program's optimum (``inner_springs`` holds it either way).
"""

from __future__ import annotations

import math
from dataclasses import asdict, dataclass
from typing import Any

from hexaleg.design.chain.design_file import gait_parameters
from hexaleg.design.chain.ranking import under
from hexaleg.design.codesign.box import Edge, edges
from hexaleg.design.codesign.floors import Floor, worst
from hexaleg.design.codesign.gait_evaluation import PARAMETERS, UNITS, Constraints, GaitPoint
from hexaleg.design.codesign.gait_search import SearchResult, Space
from hexaleg.design.codesign.optimal_table import OptimalRows
from hexaleg.design.codesign.rules import RULES, rule_data, rule_lines
from hexaleg.design.codesign.servo import Screened, choose
from hexaleg.design.springs.law_json import spring_entry
from hexaleg.dynamics.energy import G
from hexaleg.dynamics.plausibility import Plausibility, check_cost_of_transport
from hexaleg.motion.params import GaitParams
from hexaleg.quantities import file_data
from hexaleg.quantities import quantity as q
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation.controllers import BOTH


@dataclass(frozen=True)
class Row:
    """One of the four rows: a gait, with or without springs.

    Attributes:
        label: What the row is. params: The gait. springs: Whether with its springs.
        energy: Electrical energy per cycle, J. distance: m per cycle.
        per_metre: J/m. cost_of_transport: ``E / (m g d)``, 1.
    """

    label: str
    params: GaitParams
    springs: bool
    energy: float
    distance: float
    per_metre: float
    cost_of_transport: float

    @classmethod
    def of(cls, label: str, point: GaitPoint, springs: bool, mass: float) -> Row:
        """The row of an evaluated gait (with its springs when ``springs``)."""
        energy = point.sprung if springs else point.baseline
        per = energy / point.distance
        return cls(label, point.params, springs, energy, point.distance, per,
                   per / (mass * G))


@dataclass(frozen=True)
class SpeedPoint:
    """One point of the energy-vs-speed curve: gait ``label`` at ``speed`` (m/s), J/m without
    and with its springs (NaN where the gait fails a constraint there)."""

    label: str
    speed: float
    per_metre: float
    per_metre_springs: float


@dataclass(frozen=True, eq=False)
class CodesignResult:
    """Everything ``hexaleg codesign`` found (:mod:`hexaleg.design.codesign.build`).

    Attributes:
        robot, title, mass (kg), speed (m/s), pattern, family: The problem.
        constraints: The constraints as used (the margin resolved).
        default: The default gait. chosen: The co-designed gait (at the rows' sampling).
        springs: Its inner-program springs. measures: Its constraints' values.
        inner_saving: The electrical saving of those springs on the chosen gait (fraction).
        rows: The four rows. sequential: The gait alone, then its springs.
        search: The co-design search. gait_search: The gait-alone search.
        curve: Energy per metre against speed. simulation: The MuJoCo check (or its error).
        rules: ``hexaleg design``'s result on the chosen gait (the full spring rules), its
            error's message when it could not run there, or None when not asked.
        samples: Samples a cycle in the search. wall: Total wall time, s.
        generic: Whether the robot's actuators are generic (from URDF limits), for the
            plausibility check's message.
        servo: The servo the finalists and the rules' designs were simulated under
            (:data:`~hexaleg.simulation.controllers.SERVOS`).
        finalists: The search's finalists simulated with their inner springs, in the search's
            order (:mod:`hexaleg.design.codesign.servo`); empty when not simulated.
        floors: The springs to buy's predicted saving on the chosen gait at each μ of
            :data:`~hexaleg.design.codesign.floors.FLOORS`.
        optimal: The optimal motion's rows (:class:`~hexaleg.design.codesign.optimal_table.
            OptimalRows`), or None when not asked (``motion="gait"``).
        duty_high: The searches' highest duty factor (``[codesign] duty_high``).
        body_high: The searches' highest body height, × the default gait's (``[codesign]
            body_high``).
        box: The box both searches searched (:func:`~hexaleg.design.codesign.box.
            default_space`); None in a result kept before it was recorded.
    """

    robot: str
    title: str
    mass: float
    speed: float
    pattern: str | None
    family: str
    constraints: Constraints
    default: GaitParams
    chosen: GaitParams
    springs: SpringSet
    measures: dict[str, tuple[float, float, str, str]]
    inner_saving: float
    rows: tuple[Row, ...]
    sequential: Row
    search: SearchResult
    gait_search: SearchResult
    curve: tuple[SpeedPoint, ...]
    simulation: dict[str, Any]
    rules: Any
    samples: int
    wall: float
    generic: bool = False
    servo: str = BOTH
    finalists: tuple[Screened, ...] = ()
    floors: tuple[Floor, ...] = ()
    optimal: OptimalRows | None = None
    duty_high: float = 0.8
    body_high: float = 1.3
    box: Space | None = None

    @property
    def edges(self) -> tuple[Edge, ...]:
        """The box's edges the chosen gait lies on (:func:`~hexaleg.design.codesign.box.
        edges`; none when the box was not recorded)."""
        if self.box is None:
            return ()
        return edges(self.box, self.chosen, self.duty_high, self.body_high)

    def edge_lines(self) -> list[str]:
        """A line naming the box's edges the chosen gait lies on and what moves each: the
        co-design is then the box's optimum, a cheaper gait may lie past them (none when it
        lies on no edge)."""
        if not self.edges:
            return []
        each = "; ".join(
            f"{e.parameter.replace('_', ' ')} {e.value:.4g}"
            + ("" if UNITS[e.parameter] == "1" else f" {UNITS[e.parameter]}")
            + f" at the box's {e.side} (" + (e.moved_by or "fixed") + ")" for e in self.edges)
        return [f"  on the search box's edge: {each} — the co-design is this box's optimum; a "
                "cheaper gait may lie past an edge"]

    @property
    def chosen_finalist(self) -> int | None:
        """The chosen gait's place among the finalists (0-based), or None when none walked or
        they were not simulated (the search's best then chosen)."""
        pick = choose(self.finalists)
        return None if pick is None else self.finalists.index(pick)

    @property
    def plausibility(self) -> Plausibility:
        """The default gait's electrical cost of transport without springs against the
        plausible band for the robot's mass (:func:`hexaleg.dynamics.plausibility.
        check_cost_of_transport`, as ``hexaleg design`` and ``report`` check theirs)."""
        return check_cost_of_transport(self.rows[0].cost_of_transport, self.mass,
                                       generic=self.generic)

    @property
    def shares(self) -> dict[str, float]:
        """The saving against the default gait without springs, split (module docstring)."""
        e0, _, eg, ec = (r.per_metre for r in self.rows)
        return {"gait": (e0 - eg) / e0, "springs": (eg - ec) / e0, "codesign": (e0 - ec) / e0,
                "default springs": (e0 - self.rows[1].per_metre) / e0}

    @property
    def recommended(self) -> tuple[SpringSet, str]:
        """The springs to fit and where they come from: the full rules' recommendation when
        they ran and it pays, else the inner program's optimum on the chosen gait."""
        if self.rules is not None and not isinstance(self.rules, str) and self.rules.pays:
            return (self.rules.recommended.optimum.springs,
                    f"hexaleg design's full spring rules on the chosen gait ({', '.join(RULES)})")
        return self.springs, f"inner program ({self.family} family, global optimum)"

    def summary(self) -> str:
        """Lines for the terminal: the rows, the chosen gait, the search."""
        lines = [f"{self.title} at {self.speed:g} m/s: electrical energy per metre"]
        lines += [f"  {r.label:48s} {r.per_metre:7.2f} J/m  CoT {r.cost_of_transport:5.2f}"
                  for r in (*self.rows, self.sequential)]
        s = self.shares
        lines.append(f"  gait share {100 * s['gait']:+.1f} %, springs share "
                     f"{100 * s['springs']:+.1f} %, co-design {100 * s['codesign']:+.1f} %")
        lines.append("  chosen gait: " + ", ".join(
            f"{p} {getattr(self.chosen, p):.4g}" + ("" if UNITS[p] == "1" else f" {UNITS[p]}")
            for p in PARAMETERS))
        lines += self.finalist_lines()
        if "friction" in self.measures:
            use = self.measures["friction"][0]
            lines.append(f"  planned friction use {use:.2f} of the cone at μ "
                         f"{self.constraints.mu:g} (at most "
                         f"{self.constraints.friction_margin:g}: [codesign.constraints] "
                         "friction_margin)")
        lines.append(f"  search: duty factor ≤ {self.duty_high:g} ([codesign] duty_high), "
                     f"body height ≤ {self.body_high:g} × the default gait's ([codesign] "
                     f"body_high), "
                     f"{self.search.evaluations} evaluations, "
                     f"{self.search.wall:.1f} s, restarts {self.search.spread:.3f} J/m apart; "
                     f"total {self.wall:.1f} s")
        lines += self.edge_lines()
        if isinstance(self.rules, str):
            lines.append(f"  full spring rules could not run on the chosen gait ({self.rules}):"
                         f" the inner program's springs are recommended")
        elif self.rules is not None:
            lines += ["  " + line for line in rule_lines(self.rules, self.chosen.stride)]
        else:
            lines.append("  springs: the inner program's optimum (the full spring rules were "
                         "not applied)")
        lines += self.floor_lines()
        if self.optimal is not None:
            lines += self.optimal.lines()
            lines += self.bound_lines()
        if not self.plausibility.plausible:
            lines.append(f"WARNING default gait's energy {self.plausibility.message}")
        return "\n".join(lines)

    def finalist_lines(self) -> list[str]:
        """The servo check's lines: each finalist's predicted and simulated J/m, the chosen
        one marked (none when the finalists were not simulated)."""
        if not self.finalists:
            return []
        k = self.chosen_finalist
        out = [f"  chosen among the search's {len(self.finalists)} best distinct gaits by their "
               f"simulated J/m with their springs under {under(self.servo)}"
               + ("" if k is not None else ": none walked, the search's best kept")]
        for i, f in enumerate(self.finalists):
            head = (f"  {'→' if i == k else ' '} {i + 1}. duty factor "
                    f"{f.point.params.duty_factor:.3f}, period {f.point.params.period:.3f} s: ")
            if f.point.error is not None:
                out.append(f"{head}no numbers at the rows' sampling ({f.point.error})")
                continue
            sims = ", ".join(f"{c} {v:.2f}" if v is not None else f"{c}: {f.verdicts[c]}"
                             for c, v in f.per_metre.items())
            out.append(f"{head}predicted {f.point.per_metre_springs:.2f} J/m, simulated {sims}")
        return out

    def bound_lines(self) -> list[str]:
        """Where the optimal motion's contact timing or start was searched past the parametric
        search's box, a line for each that says so: the co-design row was then searched in a
        narrower family than the optimal motion's (none otherwise). The timing is past it when
        its duty factor is above ``duty_high``; a start (the alternation's, and the motion
        without springs' own) when its body height is above ``body_high`` × the default
        gait's."""
        out: list[str] = []
        timing = self.optimal.timing if self.optimal is not None else None
        if timing is not None and timing.chosen.params.duty_factor > self.duty_high:
            duty = timing.chosen.params.duty_factor
            out.append(f"    the timing chosen (duty factor {duty:.3g}) lies above the parametric "
                       f"search's bound ({self.duty_high:g}): the co-design row was searched in "
                       f"a narrower family (--duty-high {duty:.3g} or more compares them at one "
                       "bound)")
        for starts, which in (
                (getattr(self.optimal, "starts", None), "the start chosen"),
                (getattr(self.optimal, "bare_starts", None), "the start chosen without springs")):
            if starts is None:
                continue
            body = starts.chosen.params.body_height
            assert body is not None and self.default.body_height is not None
            ratio = body / self.default.body_height
            if ratio > self.body_high * (1 + 1e-9):
                wider = math.ceil(ratio * 100 - 1e-9) / 100
                out.append(f"    {which} (body height {1e3 * body:.1f} mm, {ratio:.4g} × "
                           f"the default gait's) lies above the parametric search's box "
                           f"({self.body_high:g} ×): the co-design row was searched in a "
                           f"narrower family (--body-high {wider:g} or more compares them in "
                           "one box)")
        return out

    def floor_lines(self) -> list[str]:
        """The springs to buy on other floors: the saving at each μ and the worst."""
        if not self.floors:
            return []
        low = worst(self.floors)
        each = ", ".join(f"μ {f.mu:g} " + (f"{100 * f.saving:+.2f} %" if f.saving is not None
                                           else "no admissible forces") for f in self.floors)
        tail = ("" if low is None else
                f"; worst {100 * (low.saving or 0.0):+.2f} % at μ {low.mu:g}")
        return [f"  on other floors, predicted electrical saving of the springs to buy: "
                f"{each}{tail}"]

    def to_dict(self) -> dict[str, Any]:
        """``codesign.json`` (module docstring)."""
        springs, source = self.recommended
        entries = [spring_entry(j, s) for j, s in springs.items()]
        saving = self.inner_saving
        if self.rules is not None and not isinstance(self.rules, str) and self.rules.pays:
            saving = float(self.rules.recommended.row["saving.electrical"])
        return file_data({
            "robot": {"name": self.robot, "title": self.title, "mass": q(self.mass, "kg")},
            "speed": q(self.speed, "m/s"), "pattern": self.pattern,
            "settings": {"metric": "electrical", "family": self.family,
                         "samples": self.samples, "final_samples": self.chosen.samples,
                         "duty_high": q(self.duty_high, "1"),
                         "body_high": q(self.body_high, "1")},
            "constraints": {k: (q(v, _CONSTRAINT_UNITS[k]) if isinstance(v, float) else v)
                            for k, v in asdict(self.constraints).items()},
            "gait": {"parameters": gait_parameters(self.chosen),
                     "default": gait_parameters(self.default)},
            "measures": {k: {"value": q(v, u), "bound": q(b, u), "kind": kind}
                         for k, (v, b, u, kind) in self.measures.items()},
            "rows": [{"label": r.label, "springs": r.springs, "energy": q(r.energy, "J"),
                      "distance": q(r.distance, "m"), "per_metre": q(r.per_metre, "J/m"),
                      "cost_of_transport": q(r.cost_of_transport, "1")}
                     for r in (*self.rows, self.sequential)],
            "shares": {k: q(100 * v, "%") for k, v in self.shares.items()},
            "recommended": {"source": source, "springs": entries,
                            "saving": {"electrical": q(100 * saving, "%")}},
            "inner_springs": [spring_entry(j, s) for j, s in self.springs.items()],
            "search": {name: {"method": s.method, "evaluations": s.evaluations,
                              "wall": q(s.wall, "s"),
                              "restarts": [q(x, "J/m") for x in s.restarts],
                              "spread": q(s.spread, "J/m"), "value": q(s.value, "J/m")}
                       for name, s in (("codesign", self.search), ("gait", self.gait_search))},
            "box": None if self.box is None else {
                "bounds": {n: [q(lo, UNITS[n]), q(hi, UNITS[n])]
                           for n, (lo, hi) in self.box.bounds.items()},
                "edges": [{"parameter": e.parameter, "side": e.side,
                           "value": q(e.value, UNITS[e.parameter]), "moved_by": e.moved_by}
                          for e in self.edges]},
            "curve": [{"gait": p.label, "speed": q(p.speed, "m/s"),
                       "per_metre": q(p.per_metre, "J/m"),
                       "per_metre_springs": q(p.per_metre_springs, "J/m")} for p in self.curve],
            "simulation": {k: (q(v, _SIM_UNITS[k]) if k in _SIM_UNITS else v)
                           for k, v in self.simulation.items()},
            "floors": {"rows": [f.data() for f in self.floors],
                       "worst": None if (low := worst(self.floors)) is None else low.data()},
            "finalists": {"servo": self.servo, "chosen": self.chosen_finalist,
                          "rows": [f.data() for f in self.finalists]},
            "full_rules": None if self.rules is None else (
                {"applied_to": "the chosen gait only", "error": self.rules, "pays": False}
                if isinstance(self.rules, str) else rule_data(self.rules, self.chosen.stride)),
            "plausibility": self.plausibility.as_dict(),
            "optimal": None if self.optimal is None else {
                **self.optimal.data(),
                "beyond_box": [line.strip() for line in self.bound_lines()]},
            "wall": q(self.wall, "s"),
        })


_CONSTRAINT_UNITS = {"min_static_margin": "m", "speed_fraction": "1", "mu": "1",
                     "friction_margin": "1",
                     "min_foot_clearance": "m", "min_body_clearance": "m"}
_SIM_UNITS = {"planned": "m", "walked": "m", "walked_baseline": "m", "predicted": "1",
              "simulated": "1"}

__all__ = ["CodesignResult", "Row", "SpeedPoint", "q"]
