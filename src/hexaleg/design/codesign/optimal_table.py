"""The optimal motion's table (issue #56): its rows and what backs them, printed and written.

The four rows (:data:`LABELS`), each a motion predicted and simulated (:class:`MotionRow`; how
they are computed: :mod:`~hexaleg.design.codesign.optimal_rows`), and the stage's record
(:class:`OptimalRows`): the solver's results, the alternation, the springs to buy for the
optimal motion (the full spring rules on it) and whether a simulation proves them, printed for
the terminal (:meth:`OptimalRows.lines`) and written to ``codesign.json`` (:meth:`OptimalRows.
data`). Each optimal figure is printed to the digits its spread leaves
(:func:`~hexaleg.design.codesign.alternation.decimals`).
"""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import Any

from hexaleg.design.chain.result import DesignResult
from hexaleg.design.codesign.alternation import (
    MARGIN,
    MOVES,
    Alternation,
    Spread,
    decimals,
)
from hexaleg.design.codesign.gait_evaluation import Constraints
from hexaleg.design.codesign.landing_choice import Landing
from hexaleg.design.codesign.rules import rule_data, rule_lines
from hexaleg.design.codesign.rules_spread import RulesSpread
from hexaleg.design.codesign.starts import StartSearch
from hexaleg.design.codesign.timing import TimingSearch
from hexaleg.design.springs.law_json import spring_entry
from hexaleg.motion.trajectory import Motion
from hexaleg.quantities import quantity as q
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet

LABELS = ("default gait, no springs", "parametric co-design (its gait and springs)",
          "optimal motion, no springs", "optimal motion, its springs")
"""The rows' labels, in order (module docstring)."""


@dataclass(frozen=True)
class MotionRow:
    """One row: a motion with or without springs, predicted and simulated.

    Attributes:
        label: What the row is (:data:`LABELS`).
        predicted: Electrical energy per metre predicted, J/m (module docstring); None where
            the analysis has no answer for the motion (:attr:`unpredicted` says why).
        simulated: Controller → simulated electrical energy per metre walked, J/m; None where
            it did not walk.
        verdicts: Controller → ``"walks"`` or what happened.
        loops: Controller → ``"balance feedback"``, ``"open loop"`` or ``""`` (it raised).
        unpredicted: Why there is no prediction (the analysis' error), else ``""``.
        spread: How far an optimal motion's figures move with its start (its solve, or the
            whole alternation, repeated from moved starts:
            :class:`~hexaleg.design.codesign.alternation.Spread`); None for a parametric gait
            (the co-design's rows, not an optimal-control solve) or a cycle not rebuilt.
        friction_use: The largest share of the floor's friction cone a stance foot's planned
            force behind :attr:`predicted` uses over the cycle, ``max |f_t| / (μ f_n)`` (1:
            about to slip); None without a prediction.
        beyond: Why :attr:`predicted` is the whole cone's: the force program has no answer
            inside the planners' friction margin (its ``friction_use`` is above it); ``""``
            for a prediction inside the margin.
        landing: For an optimal row, which of its answers without and with the landing
            effort's cost it kept (:class:`Landing`); None for a parametric gait's row.
    """

    label: str
    predicted: float | None
    simulated: Mapping[str, float | None]
    verdicts: Mapping[str, str]
    loops: Mapping[str, str] = field(default_factory=dict)
    unpredicted: str = ""
    spread: Spread | None = None
    friction_use: float | None = None
    beyond: str = ""
    landing: Landing | None = None

    @property
    def decimals(self) -> int:
        """The decimals its J/m are printed to: two, fewer where :attr:`spread` leaves fewer
        (:func:`~hexaleg.design.codesign.alternation.decimals`)."""
        return decimals(None if self.spread is None else self.spread.value)

    @property
    def walks(self) -> bool:
        """Whether it walked under every controller."""
        return bool(self.simulated) and all(v is not None for v in self.simulated.values())

    def data(self) -> dict[str, Any]:
        """codesign.json's row; ``decimals``, those its J/m are printed to (:attr:`decimals`)."""
        return {"label": self.label, "predicted": q(self.predicted, "J/m"),
                "decimals": self.decimals,
                "simulated": {k: None if v is None else q(v, "J/m")
                              for k, v in self.simulated.items()},
                "verdicts": dict(self.verdicts), "loops": dict(self.loops),
                "friction_use": q(self.friction_use, "1"),
                "within_margin": self.predicted is not None and not self.beyond,
                **({"beyond": self.beyond} if self.beyond else {}),
                **({"unpredicted": self.unpredicted} if self.unpredicted else {}),
                **({"spread": self.spread.data()} if self.spread is not None else {}),
                **({"landing": self.landing.data()} if self.landing is not None else {})}


@dataclass(frozen=True, eq=False)
class OptimalRows:
    """The optimal motion's table and what backs it.

    Attributes:
        rows: The four rows (:data:`LABELS`).
        springs: The last row's springs (the alternation's).
        family: Their family.
        bare: The optimal motion without springs
            (:class:`~hexaleg.optimal.solve.OptimalResult`).
        alternation: The optimal motion with springs
            (:class:`~hexaleg.design.codesign.alternation.Alternation`).
        robot: The robot (the motion files are written for it).
        servo: The servo the rows were simulated under.
        wall: Wall time of this stage, s.
        feedback: The simulations' balance feedback setting, the same for every row
            (:data:`~hexaleg.simulation.balance.MODES`).
        timing: The contact timing's search, when the optimal motions' timing was searched
            (:class:`~hexaleg.design.codesign.timing.TimingSearch`); None: the chosen gait's.
        starts: The multi-start, when the optimal motions' start was searched
            (:class:`~hexaleg.design.codesign.starts.StartSearch`); None: the gait's. The
            alternation runs from its start chosen with the co-design's springs.
        bare_starts: The same lattice solved without springs, whose start chosen the optimal
            motion without springs runs from; None where no start was searched.
        margin: The planners' friction margin every row is predicted inside
            (``[codesign.constraints] friction_margin``).
        rules: The full spring rules on the optimal motion with its springs
            (:class:`~hexaleg.design.chain.result.DesignResult`; module docstring), the error's
            message where they could not run, None where none ran (the alternation kept the
            co-design's gait, or none were asked for).
        repeats: The last row's answer repeated from its start moved by each of
            :data:`~hexaleg.design.codesign.alternation.MOVES` (its spread): each repeat's
            motion, None where that repeat kept the gait; empty where no spread was measured.
        rules_spread: The springs to buy designed again on each of :attr:`repeats`
            (:mod:`~hexaleg.design.codesign.rules_spread`); None where they were not.
    """

    rows: tuple[MotionRow, ...]
    springs: SpringSet
    family: str
    bare: Any
    alternation: Alternation
    robot: Robot
    servo: str
    wall: float
    feedback: str = "auto"
    timing: TimingSearch | None = None
    starts: StartSearch | None = None
    margin: float = Constraints.friction_margin
    rules: DesignResult | str | None = None
    bare_starts: StartSearch | None = None
    repeats: tuple[Motion | None, ...] = ()
    rules_spread: RulesSpread | None = None

    @property
    def best(self) -> Any:
        """The optimal motion with its springs (:class:`~hexaleg.optimal.solve.OptimalResult`)."""
        return self.alternation.best

    @property
    def bought(self) -> DesignResult | None:
        """The full spring rules' result on the optimal motion, where they ran (:attr:`rules`)."""
        return self.rules if isinstance(self.rules, DesignResult) else None

    @property
    def unproven(self) -> str:
        """Why the springs to buy are not proven, ``""`` when they are: the last row's forces
        must be planned inside the friction margin, and the springs to buy must walk under
        every controller — the full rules' on the optimal motion by their proof where they
        ran, else the last row's motion with its springs."""
        last = self.rows[-1]
        why = []
        if last.beyond:
            use = "" if last.friction_use is None else f"{last.friction_use:.2f} of "
            why.append(f"its forces need {use}the friction cone, beyond the {self.margin:g} "
                       "margin")
        if self.bought is not None:
            if not self.bought.pays:
                why.append("no springs pay on it net of their mass")
            elif self.bought.unproven:
                why.append(self.bought.unproven)
        elif not last.walks:
            why.append("it does not walk under " + " and ".join(
                k for k, v in last.simulated.items() if v is None))
        return "; ".join(why)

    @property
    def proven(self) -> bool:
        """Whether a simulation backs the springs to buy and the last row's forces are planned
        inside the friction margin (:attr:`unproven`)."""
        return not self.unproven

    @property
    def motions(self) -> dict[str, Motion]:
        """The optimal motions by file stem, ``optimal_no_springs`` and ``optimal_springs``: each
        cycle rebuilt in task space, as the rows play it (the latter the co-design's gait when
        the alternation kept it; the former left out when it is not rebuilt)."""
        bare = {} if self.bare.task_space is None else {
            "optimal_no_springs": self.bare.task_space}
        return bare | {"optimal_springs": self.alternation.motion}

    def data(self) -> dict[str, Any]:
        """codesign.json's ``optimal`` key: the rows, the springs to buy and whether a
        simulation backs them, each optimal motion's solver figures and dynamics residual
        (Newton–Euler of the trajectory against its motor plus spring torques, by the check its
        ``residual_check`` names, :mod:`~hexaleg.optimal.residual`; its knots' ``defect``), the
        alternation's energies."""
        def solver(r: Any) -> dict[str, Any]:
            return {"energy_per_metre": q(r.energy_per_metre, "J/m"),
                    "residual": q(r.residual, "N·m"), "residual_check": r.residual_check,
                    "defect": q(r.defect, "1"), "iterations": r.iterations,
                    "converged": r.converged, "stationarity": q(r.stationarity, "1"),
                    "threshold": q(r.threshold, "1"), "dynamic_gap": q(r.dynamic_gap, "1"),
                    "periodicity": q(r.periodicity, "1"),
                    "friction_use": q(r.friction_use, "1"), "slip": q(r.slip, "m/s"),
                    "drift": q(r.drift, "m"),
                    "knots": len(r.torques), "wall": q(r.seconds, "s")}

        alt = self.alternation
        return {
            "rows": [r.data() for r in self.rows], "servo": self.servo,
            "feedback": self.feedback,
            "timing": None if self.timing is None else self.timing.data(),
            "starts": None if self.starts is None else self.starts.data(),
            "starts_no_springs": None if self.bare_starts is None else self.bare_starts.data(),
            "springs": [spring_entry(j, s) for j, s in self.springs.items()],
            "family": self.family, "proven": self.proven,
            **({"unproven": self.unproven} if self.unproven else {}),
            "friction_margin": q(self.margin, "1"),
            "full_rules": None if self.rules is None else (
                {"applied_to": ON, "error": self.rules, "pays": False}
                if isinstance(self.rules, str) else
                rule_data(self.rules, self.alternation.motion.distance, ON)),
            "rules_spread": None if self.rules_spread is None else self.rules_spread.data(),
            "residual": q(max(self.bare.residual, self.best.residual), "N·m"),
            "no_springs": solver(self.bare), "springs_motion": solver(self.best),
            "alternation": {"energies": [q(e, "J/m") for e in alt.energies],
                            "measure": "hexaleg's prediction of the rebuilt cycle (first: the "
                                       "gait it starts from)",
                            "kept_gait": alt.kept_gait,
                            "rounds": len(alt.rounds), "gap": q(alt.gap, "1")},
            "wall": q(self.wall, "s"),
        }

    def lines(self) -> list[str]:
        """Lines for the terminal: the rows and the springs' proof."""
        controllers = list(self.rows[0].simulated)
        out = ["  optimal motion (whole-body optimal control, the springs in the dynamics): "
               f"J/m predicted with the foot forces inside {self.margin:g} of the friction cone "
               "(their friction use), simulated " + ", ".join(controllers)
               + f" (balance feedback {self.feedback})"]
        for r in self.rows:
            if r.unpredicted and set(r.verdicts.values()) == {r.unpredicted}:
                out.append(f"    {r.label:46s}       — ({r.unpredicted})")  # not rebuilt
                continue
            d = r.decimals
            sims = ", ".join((f"{v:.{d}f}" if v is not None else f"— ({r.verdicts[k]})")
                             + (f" ({r.loops[k]})" if r.loops.get(k) else "")
                             for k, v in r.simulated.items())
            said = (f"{r.predicted:7.{d}f}" if r.predicted is not None else
                    f"      — (no prediction: {r.unpredicted})")
            out.append(f"    {r.label:46s} {said}{_stated(r.spread, d)}"
                       f"{self._friction(r)}   {sims}")
        out += [f"    {r.label}: predicted in the whole friction cone, {r.beyond}"
                for r in self.rows if r.beyond]
        chosen = [(r, r.landing) for r in self.rows if r.landing is not None]
        if chosen:
            weight = max(c.weight for _, landing in chosen for c in landing.candidates)
            out.append("    each optimal row solved without and with the landing legs' "
                       f"position-servo effort in its cost (weight {weight:g}), kept the one "
                       "walking cheaper under the worse servo:")
            out += [landing.line(r.label, r.decimals) for r, landing in chosen]
        if self.timing is not None:
            out.append(self.timing.line())
        if self.starts is not None:
            out.append(self.starts.line())
        if self.bare_starts is not None and (self.starts is None
                                             or self.bare_starts.springs != self.starts.springs):
            out.append(self.bare_starts.line())  # not when both were solved without springs
        b = self.best
        bare, last = self.rows[2].spread, self.rows[3].spread
        if bare is not None or last is not None:
            out.append("    ±: the prediction's spread over the row's answer repeated from its "
                       "start moved by " + ", ".join(f"{m:+.0e}" for m in MOVES) + " m (the "
                       f"base's height), times {MARGIN:g}, rounded up to the digit printed; the "
                       "simulated J/m to the same digit")
        places = decimals(None if last is None else last.value, 3)
        trail = " → ".join("—" if e is None else f"{e:.{places}f}"
                           for e in self.alternation.energies)
        out.append("    the solver's own J/m at its knots: "
                   f"{_figure(self.bare.energy_per_metre, bare)} (no springs), "
                   f"{_figure(b.energy_per_metre, last)} (its springs); the rows predict and "
                   "play each cycle rebuilt in task space")
        stopped = max([b.stationarity, *(() if last is None else last.stationarity)])
        residual = max(self.bare.residual, b.residual)
        out.append(f"    residual {_residual(residual)} N·m, stationarity "
                   f"{'' if last is None else 'up to '}{stopped:.0e} after {b.iterations} "
                   f"iterations{'' if last is None else ' (its moved starts too)'} (threshold "
                   f"{b.threshold:.2g}), friction use {b.friction_use:.2f}, alternation "
                   f"{trail} J/m predicted (from the gait's)")
        if self.alternation.kept_gait:
            why = ("no optimal cycle was predicted below the co-design's gait"
                   if self.best.task_space is not None else
                   "the optimal cycle with springs was not rebuilt in task space")
            out.append(f"    {why}: the last row is that gait with its springs")
        names = ", ".join(self.springs) or "none"
        if self.bought is not None:
            out.append(f"    its springs ({self.family}, the alternation's): {names}")
            out += ["    " + line for line in rule_lines(
                self.bought, self.alternation.motion.distance, "the optimal motion")]
            if self.rules_spread is not None:
                out.append("      " + self.rules_spread.line())
            if self.rows[-1].beyond:  # the rules' own head does not know the margin
                out.append(f"    unproven: {self.unproven}")
            return out
        if isinstance(self.rules, str):
            out.append(f"    full spring rules could not run on the optimal motion "
                       f"({self.rules}): its own springs named")
        elif self.alternation.kept_gait and self.rules is None:
            out.append("    springs to buy for it: the co-design's (above)")
            return out
        out.append(f"    springs to buy for it ({self.family}): {names}" + (
            "" if self.proven else f" — unproven: {self.unproven}"))
        return out


    def _friction(self, row: MotionRow) -> str:
        """A row's friction use beside its prediction, flagged where it is beyond the margin
        (``""`` without a prediction)."""
        if row.friction_use is None:
            return ""
        if row.beyond:
            return f" (friction {row.friction_use:.2f}, beyond the {self.margin:g} margin)"
        return f" (friction {row.friction_use:.2f})"


def _stated(spread: Spread | None, places: int) -> str:
    """The spread beside a figure printed to ``places`` decimals: the unit of its last digit
    (at least :data:`~hexaleg.design.codesign.alternation.MARGIN` times the spread,
    :func:`~hexaleg.design.codesign.alternation.decimals`), and how many moved starts have no
    prediction (a spread over the others only; none to state with fewer than two predicted);
    ``""`` for a row without one."""
    if spread is None:
        return ""
    missing = f"{spread.unjudged} of {len(spread.judged)} not predicted"
    if spread.value is None:
        return f" (no spread: {missing})"
    return f" ±{10.0 ** -places:.{places}f}" + (f" ({missing})" if spread.unjudged else "")


ON = "the optimal motion with its springs (its cycle rebuilt in task space)"
"""What the full spring rules on the optimal motion ran on, as ``codesign.json`` says it."""

ROUND_OFF = 1e-12
"""A Newton–Euler residual below this is round-off, N·m: printed as ``≤ 1e-12`` (its digits
are the floating point's, and move with any input; the issue's bound is 1e-6)."""


def _residual(value: float) -> str:
    """A residual for the table: its one digit, or ``≤ 1e-12`` at round-off (:data:`ROUND_OFF`)."""
    return f"≤ {ROUND_OFF:.0e}" if value <= ROUND_OFF else f"{value:.1g}"


def _figure(value: float, spread: Spread | None) -> str:
    """The solver's own J/m printed to the digits its spread leaves (two without one)."""
    places = decimals(None if spread is None else spread.solver_value)
    return f"{value:.{places}f}"


__all__ = ["LABELS", "ON", "ROUND_OFF", "MotionRow", "OptimalRows"]
