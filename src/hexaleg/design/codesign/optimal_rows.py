"""The optimal motion's rows of ``hexaleg codesign --motion optimal`` (issue #56).

After the parametric co-design has chosen its gait and springs, the motion itself is optimised
from that gait, or from each row's best start about it (:mod:`hexaleg.design.codesign.starts`)
(:mod:`hexaleg.optimal`: the whole robot's cycle by box-FDDP, the gait's contact timing fixed)
without springs, and with springs by the alternation
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

*Under the worse servo* (issue #56): each optimal row's answer — the motion without springs,
and the alternation with its springs — is solved twice, without and with the landing legs'
position-servo effort in the cost, both predicted and simulated under every controller, and the
row keeps the one walking cheaper under its worse controller
(:mod:`~hexaleg.design.codesign.landing_choice`).

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

import dataclasses
import time
from collections.abc import Callable
from typing import Any

from hexaleg.checks import one_of
from hexaleg.design.codesign.alternation import (
    MOVES,
    PROGRESS,
    SMOOTH_FAMILIES,
    Alternation,
    Case,
    Keep,
    Prediction,
    alternate,
    apart,
    judged,
    predict,
    shown,
    spreads,
)
from hexaleg.design.codesign.gait_evaluation import Constraints
from hexaleg.design.codesign.landing_choice import SERVO_LANDING, Candidate, Landing, by_worse_servo
from hexaleg.design.codesign.optimal_table import LABELS, MotionRow, OptimalRows
from hexaleg.design.codesign.servo import simulated_run
from hexaleg.design.codesign.starts import STARTS, search_starts
from hexaleg.design.codesign.timing import TIMINGS, search_timing
from hexaleg.design.search.optimal import Groups
from hexaleg.dynamics.contact import ContactParams
from hexaleg.motion.legged import gait
from hexaleg.motion.params import GaitParams
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet
from hexaleg.simulation.balance import MODES as FEEDBACK
from hexaleg.simulation.controllers import controllers_of


def optimal_rows(robot: Robot, motor: Any, contact: ContactParams, default: GaitParams,
                 chosen: GaitParams, springs: SpringSet, *,
                 margin: float = Constraints.friction_margin, family: str = "linear",
                 groups: Groups | None = None, servo: str = "both",
                 params: Any = None, rounds: int = 4, feedback: str = "auto",
                 timing: str = "gait", starts: str = "lattice", min_step: float = 0.0,
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
            ``"lattice"``: each from the best of a fixed lattice of starts about it
            (:func:`~hexaleg.design.codesign.starts.search_starts`: a start's gait and solver
            settings), the lattice solved with the alternation's starting springs for the
            alternation and without springs for the motion without springs (once where the
            alternation starts without springs).
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
    weight = params.servo_landing_weight or SERVO_LANDING
    params = dataclasses.replace(params, servo_landing_weight=0.0)  # the searches' problem
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
    multi = bare_multi = None
    bare_timed, bare_params, bare_first = timed, params, None
    if starts == "lattice":
        named_springs = "the co-design's springs" if start else "no springs"
        tell(f"starts of the optimal motion tried at that timing, with {named_springs}")
        multi = search_starts(robot, timed, motor, start, contact, params, min_step,
                              first=first, say=lambda line: tell(f"starts: {line}"), keep=keep,
                              margin=margin, springs_named=named_springs)
        tell(f"start chosen: {multi.chosen.label}")
        if start:
            tell("starts of the optimal motion without springs tried at that timing")
            bare_multi = search_starts(robot, timed, motor, SpringSet(), contact, params,
                                       min_step,
                                       say=lambda line: tell(f"starts without springs: {line}"),
                                       keep=keep, margin=margin, springs_named="no springs")
        else:  # the alternation starts without springs (a family it cannot hold): one lattice
            bare_multi = multi
        tell(f"start chosen without springs: {bare_multi.chosen.label}")
        bare_timed, bare_params = bare_multi.chosen.params, bare_multi.chosen.settings
        bare_first = bare_multi.chosen.result
        timed, params, first = multi.chosen.params, multi.chosen.settings, multi.chosen.result
    landed = dataclasses.replace(params, servo_landing_weight=weight)
    settings = (params, landed)  # each optimal row's two answers: without, with the cost
    bare_settings = (bare_params, dataclasses.replace(bare_params, servo_landing_weight=weight))
    motion, bare_motion = gait(robot, timed), gait(robot, bare_timed)
    moved_bare = () if searched is None and bare_multi is None else (bare_timed,)
    named = ("", f", landing cost {weight:g}")

    def bare_job(i: int) -> Any:
        """Row 3's solve with ``bare_settings[i]`` from its own start (a
        :data:`~hexaleg.design.codesign.alternation.Job`)."""
        return (("no springs", SpringSet(), bare_settings[i], *moved_bare),
                lambda: solve(robot, build_problem(robot, bare_motion, motor, SpringSet(),
                                                   bare_settings[i]),
                              say=lambda line: tell(f"no springs{named[i]}: {line}"),
                              every=PROGRESS))

    def start_job(i: int) -> Any:
        """The alternation's start with ``settings[i]``."""
        return (("start", start, settings[i]),
                lambda: solve(robot, build_problem(robot, motion, motor, start, settings[i]),
                              say=lambda line: tell(f"alternation{named[i]}: start: {line}"),
                              every=PROGRESS))

    origin = ("the co-design's gait" if multi is None else
              f"the start chosen ({multi.chosen.label})")
    bare_origin = ("the co-design's gait" if bare_multi is None else
                   f"its own start chosen ({bare_multi.chosen.label})")
    tell(f"optimal motion without springs, from {bare_origin}"
         + ("" if searched is None else " at the timing chosen")
         + f", without and with the landing cost (weight {weight:g})")
    starting = [1] if first is not None else [0, 1]  # the searches' start has no cost
    bare_starting = [1] if bare_first is not None else [0, 1]
    tell(f"optimal motion with springs (alternation), from {origin} and the co-design's springs:"
         " its start" + ("" if first is not None else "s") + " solved beside the motion without"
         " springs")
    solved = [r for r, _ in apart([*(bare_job(i) for i in bare_starting),
                                   *(start_job(i) for i in starting)], robot, keep)]
    bares = ([bare_first] if bare_first is not None else []) + solved[:len(bare_starting)]
    solved = solved[len(bare_starting):]
    firsts = [first, solved[0]] if first is not None else solved
    for i, bare in enumerate(bares):
        tell(f"optimal motion without springs{named[i]}: {shown(bare.energy_per_metre)} J/m "
             f"({bare.iterations} iterations, {bare.seconds:.0f} s)")
    def told(i: int) -> Callable[[str], None]:
        """Where the alternation with ``settings[i]`` says its progress."""
        return lambda line: tell(f"alternation{named[i]}: {line}")

    alts = []
    for i in range(2):
        tell(f"optimal motion with springs (alternation{named[i]}), from {origin} and the "
             "co-design's springs")
        alts.append(alternate(robot, motion, motor, contact, springs=start, params=settings[i],
                              family=family, groups=groups, rounds=rounds, say=told(i),
                              keep=keep, first=firsts[i], margin=margin))
    controllers = controllers_of(servo)

    def played(label: str, motion_played: Motion | None, fitted: SpringSet
               ) -> tuple[dict[str, float | None], dict[str, str], dict[str, str]]:
        """``motion_played`` with ``fitted`` simulated under each controller: J/m, verdicts,
        loops (a cycle not rebuilt: none, its verdicts left to the caller)."""
        sims: dict[str, float | None] = {}
        verdicts: dict[str, str] = {}
        loops: dict[str, str] = {}
        if motion_played is None:
            return sims, verdicts, loops
        for k in controllers:
            sims[k], verdicts[k], closed = simulated_run(robot, motion_played, motor, fitted, k,
                                                         contact, feedback)
            loops[k] = "" if closed is None else "balance feedback" if closed else "open loop"
        tell(f"simulated {label} under {' and '.join(controllers)}")
        return sims, verdicts, loops

    def bare_judged(result: Any) -> Prediction:
        """Row 3's prediction: the one judge of an optimal cycle, as row 4's."""
        return judged(robot, result, bare_motion, motor, SpringSet(), contact, margin)

    def alt_judged(alt: Alternation) -> Prediction:
        """Row 4's prediction: the gait with its springs where the alternation kept it."""
        return (predict(robot, alt.motion, motor, alt.springs, contact, margin) if alt.kept_gait
                else judged(robot, alt.best, motion, motor, alt.springs, contact, margin))

    def chosen_of(label: str, answers: list[tuple[Prediction, Motion | None, SpringSet]]
                  ) -> tuple[int, Landing, tuple[Any, ...]]:
        """The answer ``label``'s row keeps among ``answers`` (without, with the cost), its
        :class:`Landing` and its simulations."""
        runs = [played(f"{label}{named[i]}", m, f) for i, (_, m, f) in enumerate(answers)]
        landing = Landing(tuple(Candidate(settings[i].servo_landing_weight, said.value,
                                          runs[i][0], runs[i][1], runs[i][2])
                                for i, (said, _, _) in enumerate(answers)), 0)
        kept = by_worse_servo(landing.candidates)
        landing = dataclasses.replace(landing, kept=kept)
        tell(f"{label}: kept the answer {'with' if kept else 'without'} the landing cost")
        return kept, landing, runs[kept]

    said_bare = [bare_judged(b) for b in bares]
    k3, landing3, runs3 = chosen_of(LABELS[2], [(said_bare[i], bares[i].task_space,
                                                  SpringSet()) for i in range(2)])
    if all(a.kept_gait for a in alts):  # both the co-design's gait: one answer, nothing to keep
        k4 = 0
        said_alt = [alt_judged(alts[0])]
        landing4, runs4 = None, played(LABELS[3], alts[0].motion, alts[0].springs)
    else:
        said_alt = [alt_judged(a) for a in alts]
        k4, landing4, runs4 = chosen_of(LABELS[3], [(said_alt[i], alts[i].motion,
                                                     alts[i].springs) for i in range(2)])
    bare, alt, params = bares[k3], alts[k4], bare_settings[k3]
    alt_params = settings[k4]

    def bare_again(move: float) -> Any:
        """Row 3's solve from its start moved by ``move`` m."""
        return solve(robot, build_problem(robot, bare_motion, motor, SpringSet(), params),
                     move=move)

    def alt_again(move: float) -> Alternation:
        """Row 4's alternation from its start moved by ``move`` m."""
        return alternate(robot, motion, motor, contact, springs=start, params=alt_params,
                         family=family, groups=groups, rounds=rounds, move=move, margin=margin)

    unbuilt = "" if bare.task_space is not None else f"not rebuilt: {bare.unbuilt}"
    cases: list[Case] = []
    if not unbuilt:
        cases.append(((said_bare[k3].value, bare.energy_per_metre, bare.stationarity),
                      ("no springs", params, bare_timed), bare_again,
                      lambda r: (bare_judged(r).value, r.energy_per_metre, r.stationarity)))
    if not alt.kept_gait:
        cases.append(((alt.predicted, alt.best.energy_per_metre, alt.best.stationarity),
                      ("alternation", start, alt_params, family, groups, rounds, timed),
                      alt_again,
                      lambda a: (a.predicted, a.best.energy_per_metre, a.best.stationarity)))
    again = [name for name, repeated in (("the solve without springs", not unbuilt),
                                          ("the alternation", not alt.kept_gait)) if repeated]
    if again:
        tell(f"spread: {' and '.join(again)} (the answers kept) again from {len(MOVES)} starts "
             "moved by " + ", ".join(f"{m:+.0e}" for m in MOVES) + " m")
    measured = iter(spreads(robot, cases, keep))
    bare_spread = None if unbuilt else next(measured)[0]
    alt_spread, moved = (None, ()) if alt.kept_gait else next(measured)
    spread = (bare_spread, alt_spread)
    walks = (gait(robot, default), gait(robot, chosen))
    table = ((LABELS[0], predict(robot, walks[0], motor, SpringSet(), contact, margin),
              walks[0], SpringSet(), None, None, None),
             (LABELS[1], predict(robot, walks[1], motor, springs, contact, margin), walks[1],
              springs, None, None, None),
             (LABELS[2], said_bare[k3], bare.task_space, SpringSet(), spread[0], landing3,
              runs3),
             (LABELS[3], said_alt[k4], alt.motion, alt.springs, spread[1], landing4, runs4))
    rows = []
    for label, said, motion_played, fitted, stated, landing, runs in table:
        if motion_played is None:  # the bare cycle not rebuilt: nothing to predict or play
            rows.append(MotionRow(label, None, dict.fromkeys(controllers), dict.fromkeys(
                controllers, unbuilt), {}, unbuilt, landing=landing))
            tell(f"{label}: {unbuilt}")
            continue
        sims, verdicts, loops = runs if runs is not None else played(label, motion_played,
                                                                     fitted)
        rows.append(MotionRow(label, said.value, sims, verdicts, loops,
                              said.why if said.value is None else "", stated,
                              said.friction_use, said.why if said.beyond else "", landing))
    return OptimalRows(tuple(rows), alt.springs, family, bare, alt, robot, servo,
                       time.perf_counter() - began, feedback, searched, multi, margin,
                       bare_starts=bare_multi,
                       repeats=tuple(None if a.kept_gait else a.motion for a in moved))


__all__ = ["optimal_rows"]
