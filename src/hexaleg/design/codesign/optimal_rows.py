"""The optimal motion's rows of ``hexaleg codesign --motion optimal`` (issue #56).

After the parametric co-design has chosen its gait and springs, the motion itself is optimised
from that gait (:mod:`hexaleg.optimal`: the whole robot's cycle by box-FDDP, the gait's contact
timing fixed) without springs, and with springs by the alternation
(:mod:`hexaleg.design.codesign.alternation`, warm-started from the co-design's springs). The four
rows, each in electrical J/m:

1. the default gait without springs,
2. the parametric co-design (its chosen gait with its inner-program springs),
3. the optimal motion without springs,
4. the optimal motion with its springs (the alternation's); the co-design's gait with its
   springs again when no optimal cycle is predicted below it (the alternation never ends worse
   than the gait it starts from: ``kept_gait``).

The springs to buy for the optimal motion are, as the parametric co-design's are for its gait,
what ``hexaleg design``'s full spring rules choose on that motion (:attr:`OptimalRows.rules`,
:func:`~hexaleg.design.codesign.full_rules.motion_rules`: parsimony, stop tolerance, envelope and
hard stop, fatigue, arbor, simulated under the servo); the alternation's own springs (a smooth
family on every group: what the solver can differentiate) are row 4's, not parts. Where the rules
could not run, the alternation's springs are the ones named, proven by row 4's simulation; where
the alternation kept the gait, the springs to buy are the co-design's.

An optimal motion is played and predicted as the cycle rebuilt in task space
(:attr:`~hexaleg.optimal.solve.OptimalResult.task_space`: its base and swing feet through the
solver's knots, its stance feet on their footholds, the legs by inverse kinematics), not as the
solver's knots: a servo that interpolates the knots' joint angles moves the stance feet between
knots and loads the legs against each other (on the default robot's co-design gait with its
springs, 40 knots: the knots walk for 10.90 J/m under feedforward servos where the solver
booked 9.21; the rebuilt cycle for 9.44, predicted 9.45).

*Predicted* is hexaleg's analysis of each row's motion with its springs, every row by the same
function (:func:`~hexaleg.design.codesign.alternation.predict`; an optimal cycle through
:func:`~hexaleg.design.codesign.alternation.judged`, the alternation's judge, which also refuses
a cycle not rebuilt or short of its stride): the force program's electrical energy per metre
(objective ``joule``, the simulation's feedforward; an optimal motion's on its task-space
cycle) with the foot forces inside the planners' friction margin (``[codesign.constraints]
friction_margin``, 0.7 of the cone: the issue's "friction use ≤ 0.7", where the parametric
co-design and the solver plan), and the friction use of those forces at the floor's μ. A row
whose motion has no forces inside the margin is predicted in the whole cone, its friction use
beyond the margin said beside it; springs to buy on such a row are unproven. The
solver's own figure at its knots (the exact energy model at its motor torques,
:attr:`~hexaleg.optimal.solve.OptimalResult.energy_per_metre`) is reported beside it; the
alternation designs its springs on the rebuilt cycle and judges its rounds by this prediction.
*Simulated* is MuJoCo's (:func:`hexaleg.simulation.run.simulate`,
default settings, the feedforward of each motion from the force program on it) electrical
energy per metre walked under each controller of the servo, every row with the same
``feedback`` setting (``"auto"``: balance feedback where the gait needs it or where it fell
open loop; ``"on"``: every row closed loop, where a position servo is asked for the plan's
torque); each row says which ran (``loops``). A row that does not walk under a controller has
no simulated number there and says why; the springs of row 4 are proven only when it walks
under every controller. An optimal cycle that cannot be rebuilt in task space
(:attr:`~hexaleg.optimal.solve.OptimalResult.unbuilt`) is neither predicted nor played: its row
says ``not rebuilt`` and why, the other rows are computed, and row 4 is then the co-design's gait
with its springs (the alternation keeps the gait when its cycle is not rebuilt).
"""

from __future__ import annotations

import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass, field
from typing import Any

from hexaleg.checks import one_of
from hexaleg.design.chain.result import DesignResult
from hexaleg.design.codesign.alternation import (
    MARGIN,
    MOVES,
    PROGRESS,
    SMOOTH_FAMILIES,
    Alternation,
    Case,
    Keep,
    Prediction,
    Spread,
    alternate,
    apart,
    computed,
    decimals,
    judged,
    predict,
    spreads,
)
from hexaleg.design.codesign.gait_evaluation import Constraints
from hexaleg.design.codesign.rules import rule_data, rule_lines
from hexaleg.design.codesign.servo import simulated_run
from hexaleg.design.codesign.starts import STARTS, StartSearch, search_starts
from hexaleg.design.codesign.timing import TIMINGS, TimingSearch, search_timing
from hexaleg.design.search.optimal import Groups
from hexaleg.design.springs.law_json import spring_entry
from hexaleg.dynamics.contact import ContactParams
from hexaleg.motion.legged import gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.quantities import quantity as q
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation.balance import MODES as FEEDBACK
from hexaleg.simulation.controllers import controllers_of

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
                **({"spread": self.spread.data()} if self.spread is not None else {})}


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
            (:class:`~hexaleg.design.codesign.starts.StartSearch`); None: the gait's.
        margin: The planners' friction margin every row is predicted inside
            (``[codesign.constraints] friction_margin``).
        rules: The full spring rules on the optimal motion with its springs
            (:class:`~hexaleg.design.chain.result.DesignResult`; module docstring), the error's
            message where they could not run, None where none ran (the alternation kept the
            co-design's gait, or none were asked for).
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
            "springs": [spring_entry(j, s) for j, s in self.springs.items()],
            "family": self.family, "proven": self.proven,
            **({"unproven": self.unproven} if self.unproven else {}),
            "friction_margin": q(self.margin, "1"),
            "full_rules": None if self.rules is None else (
                {"applied_to": ON, "error": self.rules, "pays": False}
                if isinstance(self.rules, str) else
                rule_data(self.rules, self.alternation.motion.distance, ON)),
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
        if self.timing is not None:
            out.append(self.timing.line())
        if self.starts is not None:
            out.append(self.starts.line())
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


def optimal_rows(robot: Robot, motor: Any, contact: ContactParams, default: GaitParams,
                 chosen: GaitParams, springs: SpringSet, *,
                 margin: float = Constraints.friction_margin, family: str = "linear",
                 groups: Groups | None = None, servo: str = "both",
                 params: Any = None, rounds: int = 4, feedback: str = "auto",
                 timing: str = "gait", starts: str = "gait", min_step: float = 0.0,
                 say: Callable[[str], None] | None = None, keep: Keep | None = None
                 ) -> OptimalRows:
    """The four rows (module docstring).

    Args:
        robot: The robot (free flyer).
        motor: Its motors (a Motor or a MotorSet).
        contact: The floor (the simulation's contact; the force programs plan inside
            ``margin`` of its friction cone).
        default: The default gait. chosen: The parametric co-design's gait.
        springs: The co-design's springs on ``chosen`` (the alternation's start).
        margin: The planners' friction margin (``[codesign.constraints] friction_margin``),
            in (0, 1]: every row predicted inside ``margin · μ``
            (:func:`~hexaleg.design.codesign.alternation.predict`), the alternation, the
            timing and the starts judged there, and the solver's friction pyramid at
            ``margin`` of the floor's μ when ``params`` is None.
        family: The spring family of the alternation: the co-design's when it is one of
            :data:`~hexaleg.design.codesign.alternation.SMOOTH_FAMILIES`, else ``linear``
            from no springs (a preload's step has no derivative for DDP).
        groups: The co-design's spring groups (its ``grouping``), which the alternation
            designs on; None: one per joint class.
        servo: The servo (:data:`~hexaleg.simulation.controllers.SERVOS`).
        params: :class:`~hexaleg.optimal.problem.OptimalParams` (None: defaults on the
            floor's μ and ``margin``).
        rounds: The alternation's rounds at most.
        feedback: The simulations' balance feedback, the same for every row (``"auto"``,
            ``"on"``, ``"off"``: :class:`hexaleg.simulation.run.Settings`).
        timing: ``"gait"``: the optimal motions take ``chosen``'s contact timing;
            ``"search"``: the timing searched about it
            (:func:`~hexaleg.design.codesign.timing.search_timing`, with the alternation's
            starting springs), and both optimal motions take the timing chosen.
        starts: ``"gait"``: the optimal motions start from the gait at that timing;
            ``"lattice"``: from the best of a fixed lattice of starts about it
            (:func:`~hexaleg.design.codesign.starts.search_starts`, with the alternation's
            starting springs: its gait and solver settings), the alternation run from it.
        min_step: The least step height a start may take, m (the co-design's least foot
            clearance).
        say: Where progress lines go.
        keep: Runs each optimal-control solve, given what defines it
            (:data:`~hexaleg.design.codesign.alternation.Keep`; a kept one reads back the
            solves of the run's killed process); None: every solve computed.

    Raises:
        BackendError: no usable Crocoddyl (the ``optimal`` extra). UnknownNameError: a
            ``feedback`` outside :data:`~hexaleg.simulation.balance.MODES`.
    """
    feedback = one_of("feedback", feedback, FEEDBACK)
    timing = one_of("timing", timing, TIMINGS)
    starts = one_of("starts", starts, STARTS)
    from hexaleg.optimal.problem import OptimalParams, build_problem  # needs Crocoddyl
    from hexaleg.optimal.solve import solve

    tell = say or (lambda _line: None)
    began = time.perf_counter()
    params = params or OptimalParams(mu=contact.mu, friction_use=margin)
    start = springs
    if family not in SMOOTH_FAMILIES:
        family, start = "linear", SpringSet()
    searched = None
    timed = chosen
    if timing == "search":
        tell("contact timing searched about the co-design's gait, with its springs")
        searched = search_timing(robot, chosen, motor, start, contact, params,
                                 say=lambda line: tell(f"timing: {line}"), keep=keep,
                                 margin=margin)
        timed = searched.chosen.params
        tell(f"timing chosen: duty factor {timed.duty_factor:.3g}, period {timed.period:.4g} s")
    first = None if searched is None else searched.chosen.result
    multi = None
    if starts == "lattice":
        tell("starts of the optimal motion tried at that timing, with the co-design's springs")
        multi = search_starts(robot, timed, motor, start, contact, params, min_step,
                              first=first, say=lambda line: tell(f"starts: {line}"), keep=keep,
                              margin=margin)
        timed, params, first = multi.chosen.params, multi.chosen.settings, multi.chosen.result
        tell(f"start chosen: {multi.chosen.label}")
    motion = gait(robot, timed)
    tell("optimal motion without springs, from the co-design's gait"
         + ("" if searched is None else " at the timing chosen"))
    bare_job = (("no springs", SpringSet(), params,
                 *(() if searched is None and multi is None else (timed,))),
                lambda: solve(robot, build_problem(robot, motion, motor, SpringSet(), params),
                              say=lambda line: tell(f"no springs: {line}"), every=PROGRESS))
    if first is None:  # the alternation's start beside it: the two solves are independent
        tell("optimal motion with springs (alternation), from the co-design's gait and springs:"
             " its start solved beside the motion without springs")
        start_job = (("start", start, params),
                     lambda: solve(robot, build_problem(robot, motion, motor, start, params),
                                   say=lambda line: tell(f"alternation: start: {line}"),
                                   every=PROGRESS))
        (bare, _), (first, _) = apart([bare_job, start_job], robot, keep)
    else:
        bare = (keep or computed)(*bare_job)
    tell(f"optimal motion without springs: {bare.energy_per_metre:.3f} J/m "
         f"({bare.iterations} iterations, {bare.seconds:.0f} s)")
    tell("optimal motion with springs (alternation), from the co-design's gait and springs")
    alt = alternate(robot, motion, motor, contact, springs=start, params=params, family=family,
                    groups=groups, rounds=rounds, say=lambda line: tell(f"alternation: {line}"),
                    keep=keep, first=first, margin=margin)
    controllers = controllers_of(servo)

    def bare_again(move: float) -> Any:
        """Row 3's solve from its start moved by ``move`` m."""
        return solve(robot, build_problem(robot, motion, motor, SpringSet(), params), move=move)

    def alt_again(move: float) -> Alternation:
        """Row 4's alternation from its start moved by ``move`` m."""
        return alternate(robot, motion, motor, contact, springs=start, params=params,
                         family=family, groups=groups, rounds=rounds, move=move, margin=margin)

    def bare_judged(result: Any) -> Prediction:
        """Row 3's prediction: the one judge of an optimal cycle, as row 4's."""
        return judged(robot, result, motion, motor, SpringSet(), contact, margin)

    unbuilt = "" if bare.task_space is not None else f"not rebuilt: {bare.unbuilt}"
    bare_said = bare_judged(bare)
    cases: list[Case] = []
    if not unbuilt:
        cases.append(((bare_said.value, bare.energy_per_metre, bare.stationarity),
                      ("no springs", params, timed), bare_again,
                      lambda r: (bare_judged(r).value, r.energy_per_metre, r.stationarity)))
    if not alt.kept_gait:
        cases.append(((alt.predicted, alt.best.energy_per_metre, alt.best.stationarity),
                      ("alternation", start, params, family, groups, rounds, timed),
                      alt_again,
                      lambda a: (a.predicted, a.best.energy_per_metre, a.best.stationarity)))
    again = [name for name, repeated in (("the solve without springs", not unbuilt),
                                          ("the alternation", not alt.kept_gait)) if repeated]
    if again:
        tell(f"spread: {' and '.join(again)} again from {len(MOVES)} starts moved by "
             + ", ".join(f"{m:+.0e}" for m in MOVES) + " m")
    measured = iter(spreads(robot, cases, keep))
    spread = (None if unbuilt else next(measured), None if alt.kept_gait else next(measured))
    walks = (gait(robot, default), gait(robot, chosen))
    last = (predict(robot, alt.motion, motor, alt.springs, contact, margin) if alt.kept_gait
            else judged(robot, alt.best, motion, motor, alt.springs, contact, margin))
    table = ((LABELS[0], predict(robot, walks[0], motor, SpringSet(), contact, margin),
              walks[0], SpringSet(), None),
             (LABELS[1], predict(robot, walks[1], motor, springs, contact, margin), walks[1],
              springs, None),
             (LABELS[2], bare_said, bare.task_space, SpringSet(), spread[0]),
             (LABELS[3], last, alt.motion, alt.springs, spread[1]))
    rows = []
    for label, said, played, fitted, stated in table:
        if played is None:  # the bare cycle not rebuilt: nothing to predict or play
            rows.append(MotionRow(label, None, dict.fromkeys(controllers), dict.fromkeys(
                controllers, unbuilt), {}, unbuilt))
            tell(f"{label}: {unbuilt}")
            continue
        sims: dict[str, float | None] = {}
        verdicts: dict[str, str] = {}
        loops: dict[str, str] = {}
        for k in controllers:
            sims[k], verdicts[k], closed = simulated_run(robot, played, motor, fitted, k,
                                                         contact, feedback)
            loops[k] = "" if closed is None else "balance feedback" if closed else "open loop"
        rows.append(MotionRow(label, said.value, sims, verdicts, loops,
                              said.why if said.value is None else "", stated,
                              said.friction_use, said.why if said.beyond else ""))
        tell(f"simulated {label} under {' and '.join(controllers)}")
    return OptimalRows(tuple(rows), alt.springs, family, bare, alt, robot, servo,
                       time.perf_counter() - began, feedback, searched, multi, margin)


__all__ = ["LABELS", "MotionRow", "OptimalRows", "optimal_rows"]
