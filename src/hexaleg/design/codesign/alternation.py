"""The optimal motion and its springs designed together, by alternation (issue #56).

Block-coordinate descent (Bertsekas, *Nonlinear Programming*, 3rd ed., §3.7) on the pair
(motion, springs):

1. the motion: the whole-body optimal cycle with the springs in its dynamics
   (:mod:`hexaleg.optimal`), warm-started from the previous cycle with the motor torques that
   keep its joint torques (``u' = u + τ_s − τ_s'``);
2. the springs: the project's global convex design (:func:`hexaleg.design.search.optimal.
   optimal_springs`, electrical metric) on that cycle.

Both steps, and the verdict on a round, work on the motion hexaleg plays and predicts: the
solver's cycle rebuilt in task space (:attr:`~hexaleg.optimal.solve.OptimalResult.task_space`,
its stance feet held on their footholds), not the solver's knots. The springs are designed on
the rebuilt cycle, and a round is judged by :func:`judged` (:func:`predict`, where the rebuilt
cycle covers its gait's stride) — the force program's electrical energy per metre of the
rebuilt cycle with the round's springs, its foot forces inside the planners' friction margin
(``[codesign.constraints] friction_margin``, 0.7 of the cone: the issue's friction-use target,
as the parametric co-design and the solver plan), the figure the rows of ``codesign --motion
optimal`` show — not by the solver's own figure at its knots (which books
a spring's work by a left Riemann sum and lets a stance foot slide between knots: 9.21 J/m on
the co-design's gait where the rebuilt cycle predicts 9.45). The two steps minimise different
programs (the force program's energy, the optimal-control cost at the solver's own contact
forces plus its regularisation), so a round is accepted only when that prediction falls: the
sequence of accepted predictions never rises, by construction, and the loop stops when a round
gains less than ``tolerance`` (the stated gap: the last relative gain) or after ``rounds``.

It never ends worse than the gait it starts from, by the same measure: the gait itself with the
starting springs is predicted first (:attr:`Alternation.baseline`), and when no optimal cycle is
predicted below it the answer is that gait with those springs (:attr:`Alternation.kept_gait`).

The answer is a local optimum of a nonconvex problem, and the solver stops at its iteration
budget far from stationary (box-FDDP's stopping criterion 2e-3 to 3e-2 against a threshold of
1e-8 on the default robot's co-design gait), where its iterates zig-zag, the line search's
step jumping between 1/64 and 1/2: two solves of gaits whose body heights are 1e-9 m apart
(their starts 3e-8 apart) agree to 7e-7 for 30 iterations, then part by a factor of about 2 an
iteration, to 1e-3 in the knots' states by iteration 38
(``analysis/bench_optimal_same_answer.py``); the command with its body height bound moved by
1e-9 printed this alternation's answer 10.39 J/m predicted where it printed 10.41. No start is
guaranteed to land on the same digits, so the spread is stated (Nocedal & Wright, *Numerical
Optimization*, 2nd ed., §2.1: a local method's answer depends on its start; the spread is
measured, not bounded): :func:`spreads` computes a row's answer again — the solve without
springs, or this whole alternation (``move``: its start's solve moved, its rounds after it) —
from its start moved by each of :data:`MOVES` (the base's height,
:func:`hexaleg.optimal.solve.solve`'s ``move``), side by side on the command's workers, and
:class:`Spread` holds the judged figure, the solver's and its stationarity of every answer; the
rows print each optimal figure to the digits its spread leaves (:func:`decimals`, with a
margin: :data:`MARGIN`) with the unit of the last digit beside it.

Only families whose torque is continuous in the angle enter DDP's dynamics well (``linear``,
``dead_zone``); a preload's step has no derivative, and the solver then lets a stance foot slip.
"""

from __future__ import annotations

import dataclasses
import functools
import math
import time
from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.checks import integer, one_of, real
from hexaleg.design.codesign.gait_evaluation import Constraints
from hexaleg.design.search.optimal import Groups, optimal_springs
from hexaleg.dynamics.contact import ContactParams, friction_usage
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import HexalegError
from hexaleg.motion.trajectory import Motion
from hexaleg.parallel.forked import fork_map, robot_objects
from hexaleg.quantities import quantity as q
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet

SMOOTH_FAMILIES = ("linear", "dead_zone")
"""Families whose torque is continuous in the angle (module docstring)."""


MOVES = (-2e-9, -1e-9, 1e-9, 2e-9)
"""The moves of a solve's start that measure its spread, m (module docstring): the base's
height at every knot of the start, by the same-answer rule's 1e-9 and twice it, either way."""

PROGRESS = 20
"""A solve's progress line every this many box-FDDP iterations (a hundred take minutes)."""

Keep = Callable[[tuple[Any, ...], Callable[[], Any]], Any]
"""How a solve is run: ``keep(inputs, compute)`` is ``compute()``'s result, where ``inputs``
(a label, the springs, the solver's settings, the cycle a warm start comes from) are
everything that defines it beside the run itself (its robot, gait, motors, floor)."""


def predicted_per_metre(robot: Robot, motion: Motion, motor: Any, springs: SpringSet,
                        contact: ContactParams) -> tuple[float | None, str]:
    """hexaleg's prediction of ``motion`` with ``springs``: the force program's (objective
    ``joule``, the simulation's feedforward) electrical energy per metre, J/m, and ``""``; or
    None and why, when the analysis has no answer (no admissible forces, a torque beyond the
    stall torque: the error's message)."""
    value, why, _ = _analysed(robot, motion, motor, springs, contact)
    return value, why


def _analysed(robot: Robot, motion: Motion, motor: Any, springs: SpringSet,
              contact: ContactParams) -> tuple[float | None, str, float | None]:
    """:func:`predicted_per_metre` and its forces' friction use at ``contact``'s μ, the
    largest ``|f_t| / (μ f_n)`` of a stance foot over the cycle
    (:func:`hexaleg.dynamics.contact.friction_usage`; None without an answer)."""
    try:
        analysis = prepare(robot, motion, motor=motor, contact=contact).evaluate(springs, "joule")
    except HexalegError as err:
        return None, f"{type(err).__name__}: {err}", None
    usage = friction_usage(analysis.forces, analysis.motion.stance.astype(bool), contact.mu,
                           analysis.motion.normal)
    return (float(analysis.metrics["total"]["electrical"]) / motion.distance, "",
            float(usage.max()) if usage.size else 0.0)


@dataclass(frozen=True)
class Prediction:
    """hexaleg's prediction of a motion inside the planners' friction margin (issue #56's
    "friction use ≤ 0.7 of the cone"; :func:`predict`).

    Attributes:
        value: Electrical energy per metre, J/m (:func:`predicted_per_metre`): with the foot
            forces inside ``margin · μ`` where the force program has an answer there
            (:attr:`within`; ``[codesign.constraints] friction_margin``), else at the floor's
            full μ; None where it has none at all.
        friction_use: The largest share of the floor's friction cone a stance foot's force
            behind :attr:`value` uses over the cycle, ``max |f_t| / (μ f_n)`` at the floor's μ
            (1: about to slip); None without a value.
        within: Whether :attr:`value` keeps the forces inside ``margin · μ``.
        why: Why there is no value inside the margin (the force program's error, or why an
            optimal cycle is not judged: :func:`judged`); ``""`` when :attr:`within`.
    """

    value: float | None
    friction_use: float | None
    within: bool
    why: str = ""

    @property
    def judged(self) -> float | None:
        """The figure a choice is made by: :attr:`value` inside the margin, else None (a
        motion whose forces leave the margin is never chosen)."""
        return self.value if self.within else None

    @property
    def beyond(self) -> bool:
        """Whether the value is the floor's full cone's, its forces beyond the margin."""
        return self.value is not None and not self.within


def predict(robot: Robot, motion: Motion, motor: Any, springs: SpringSet,
            contact: ContactParams, margin: float) -> Prediction:
    """``motion`` with ``springs`` predicted inside ``margin`` of the floor's friction cone
    (the force program at ``margin · μ``, as the parametric co-design's planning contact,
    :meth:`~hexaleg.design.codesign.gait_evaluation.Constraints.planning_contact`), its
    friction use stated at the floor's μ (``contact``); where the force program has no answer
    inside the margin, at the floor's full μ, said (:class:`Prediction`)."""
    margin = real("friction margin", margin, low=0.0, high=1.0, low_open=True,
                  allowed="a fraction in (0, 1] of the friction cone")
    narrowed = dataclasses.replace(contact, mu=margin * contact.mu)
    value, why, use = _analysed(robot, motion, motor, springs, narrowed)
    if value is not None and use is not None:
        return Prediction(value, margin * use, True)
    inside = f"no admissible forces within {margin:g} of the friction cone ({why})"
    value, why, use = _analysed(robot, motion, motor, springs, contact)
    return Prediction(value, use, False,
                      inside if value is not None else f"{inside}; nor in the whole cone ({why})")


COVERED = 0.01
"""How far an optimal cycle's rebuilt distance may be from its gait's, relative, and still be
judged: a cycle whose knots fall short of the stride walks slower than the required speed, and
its energy per metre is another task's (an unconverged solve covered 87 % of it)."""


def judged(robot: Robot, result: Any, gait: Motion, motor: Any, springs: SpringSet,
           contact: ContactParams, margin: float) -> Prediction:
    """The one judge of an optimal cycle — the alternation's rounds, the timing and the starts
    searches, and the optimal rows: :func:`predict` of its cycle rebuilt in task space with
    ``springs`` inside ``margin`` of ``contact``'s cone, where it covers ``gait``'s distance
    within :data:`COVERED`; else (or where it is not rebuilt) no value, and why."""
    played = result.task_space
    if played is None:
        return Prediction(None, None, False, f"not rebuilt: {result.unbuilt}")
    if abs(played.distance / gait.distance - 1.0) > COVERED:
        return Prediction(None, None, False, (
            f"its rebuilt cycle covers {played.distance / gait.distance:.1%} of the "
            f"gait's {gait.distance:.4g} m a cycle (not the required speed)"))
    return predict(robot, played, motor, springs, contact, margin)


def _below(new: float | None, old: float | None) -> bool:
    """Whether the prediction ``new`` beats ``old`` (None: no prediction, beaten by any)."""
    return new is not None and (old is None or new < old)


def least(predicted: Sequence[float | None]) -> int:
    """The index of the least prediction in a lattice's order; a tie, or no prediction, keeps
    the earlier (the first when none has one): the choice of the contact timing search and of
    the starts (:mod:`~hexaleg.design.codesign.timing`, :mod:`~hexaleg.design.codesign.starts`),
    the same on any machine."""
    best = 0
    for k, value in enumerate(predicted):
        if _below(value, predicted[best]):
            best = k
    return best


def computed(_inputs: tuple[Any, ...], compute: Callable[[], Any]) -> Any:
    """Every solve computed (:data:`Keep`)."""
    return compute()


class _NotKept(Exception):
    """The probe of :func:`apart`: a solve ``keep`` would have to compute."""


def _not_kept() -> Any:
    raise _NotKept


Job = tuple[tuple[Any, ...], Callable[[], Any]]
"""One solve of :func:`apart`: its inputs (:data:`Keep`'s) and how it is computed."""


def apart(jobs: Sequence[Job], robot: Robot, keep: Keep | None = None,
          then: Callable[[int, Any], Any] | None = None) -> list[tuple[Any, Any]]:
    """Independent solves on the command's workers: each job's ``keep(inputs, compute)`` and
    ``then(index, result)``, in the order of ``jobs``.

    The solves kept already are read back here first (``keep`` probed with a compute that
    raises before anything is kept); the others are computed in forked workers
    (:func:`~hexaleg.parallel.forked.fork_map`: one per core, the robot shared, the workers
    killed with this process, results in order and the same as computed here), and each is
    passed through ``keep`` in this process as it ends — a run killed meanwhile keeps the solves
    that ended and repeats only the others. ``then`` (the judging of a result, seconds) runs in
    the workers too.

    Args:
        jobs: The solves.
        robot: The run's robot (its objects are sent back as references, not copies).
        keep: How each solve is kept (:data:`Keep`); None: computed.
        then: Work on each result in the worker (None: none).

    Returns:
        ``(result, then(index, result))`` of each job, in order.
    """
    once = keep or computed
    after = then or (lambda _index, _result: None)
    kept: dict[int, Any] = {}
    for index, (inputs, _) in enumerate(jobs):
        try:
            kept[index] = once(inputs, _not_kept)
        except _NotKept:
            pass

    def work(index: int) -> tuple[Any, Any]:
        result = kept[index] if index in kept else jobs[index][1]()
        return result, after(index, result)

    def done(index: int, out: tuple[Any, Any]) -> None:
        if index not in kept:
            once(jobs[index][0], lambda: out[0])

    return fork_map(work, range(len(jobs)), shared=robot_objects(robot), done=done)


@dataclass(frozen=True)
class Spread:
    """How far a row's figures move when its start moves (module docstring).

    Attributes:
        moves: The start's moves, m, in the order of the figures after the first
            (:data:`MOVES`).
        judged: The judged figure (the row's: hexaleg's prediction of the rebuilt cycle), J/m,
            of the answer itself then of each moved one; None where one has no answer.
        solver: The solver's own J/m at its knots, in the same order.
        stationarity: The solver's stopping criterion at the end, in the same order.
    """

    moves: tuple[float, ...]
    judged: tuple[float | None, ...]
    solver: tuple[float, ...]
    stationarity: tuple[float, ...]

    @property
    def value(self) -> float | None:
        """The judged figures' spread, largest less least, J/m (None: fewer than two have an
        answer)."""
        known = [v for v in self.judged if v is not None]
        return max(known) - min(known) if len(known) > 1 else None

    @property
    def unjudged(self) -> int:
        """How many of the solves have no judged figure (a moved start whose cycle is not
        rebuilt, or has no prediction: a spread the figures cannot show)."""
        return sum(v is None for v in self.judged)

    @property
    def solver_value(self) -> float:
        """The solver's own figures' spread, J/m."""
        return max(self.solver) - min(self.solver)

    def data(self) -> dict[str, Any]:
        """codesign.json's record of the spread."""
        return {"value": q(self.value, "J/m"), "moves": q(list(self.moves), "m"),
                "judged": [q(v, "J/m") for v in self.judged],
                "unjudged": self.unjudged, "solver_value": q(self.solver_value, "J/m"),
                "solver": q(list(self.solver), "J/m"),
                "stationarity": q(list(self.stationarity), "1")}


MARGIN = 4.0
"""How many times a spread the unit of a printed figure's last digit is at least
(:func:`decimals`): the spread of five starts is itself a sample, and the command run twice
with an input moved by 1e-9 measured 0.0042 and 0.0039 J/m on the optimal motion without
springs, 0.0117 and 0.0111 with them, the solver's own figures 0.008 to 0.019; at four times
the spread each lands on one decimal in both runs, where at once the spread the solver's own
figure without springs was printed to one decimal in one run and two in the other."""


def decimals(spread: float | None, most: int = 2) -> int:
    """The decimals a figure of this ``spread`` (J/m) is printed to: the most, at most
    ``most``, whose last digit's unit is at least :data:`MARGIN` times the spread (a spread of
    0.002 J/m leaves two, 0.004 or 0.02 one, 0.03 none; None or 0 leaves ``most``)."""
    if spread is None or spread <= 0.0:
        return most
    return max(0, min(most, math.floor(-math.log10(MARGIN * spread))))


Figures = tuple[float | None, float, float]
"""A solve's figures a :class:`Spread` holds: judged (J/m or None), the solver's own J/m,
stationarity."""

Case = tuple[Figures, tuple[Any, ...], Callable[[float], Any], Callable[[Any], Figures]]
"""One row's spread to measure: its answer's :data:`Figures`, what defines its moved solves
beside the move (:data:`Keep`'s inputs), how the row's answer is computed again from its start
moved by so many metres, and how that answer's figures are read."""


def spreads(robot: Robot, cases: Sequence[Case], keep: Keep | None = None
            ) -> list[tuple[Spread, tuple[Any, ...]]]:
    """Each case's :class:`Spread` and its moved answers (in :data:`MOVES`' order): its answer
    computed again from its start moved by each of :data:`MOVES`, every moved answer of every
    case side by side on the command's workers (:func:`apart`: each read there, and kept by
    ``keep`` as it ends).

    Args:
        robot: The robot.
        cases: The rows' spreads to measure (:data:`Case`).
        keep: How each moved answer is kept (:data:`Keep`); None: computed.
    """
    jobs: list[Job] = []
    reads: list[Callable[[Any], Figures]] = []
    for _answer, inputs, again, read in cases:
        for move in MOVES:
            jobs.append((("moved", move, *inputs), functools.partial(again, move)))
            reads.append(read)
    out = apart(jobs, robot, keep, then=lambda index, result: reads[index](result))
    found = []
    for k, (answer, *_rest) in enumerate(cases):
        moved = out[k * len(MOVES):(k + 1) * len(MOVES)]
        judged_, solver, stopped = zip(answer, *(f for _, f in moved), strict=True)
        found.append((Spread(MOVES, tuple(judged_), tuple(solver), tuple(stopped)),
                      tuple(r for r, _ in moved)))
    return found


@dataclass(frozen=True)
class Round:
    """One round of the alternation.

    Attributes:
        springs: The springs designed on the previous best cycle rebuilt in task space.
        designed: Their energy per metre on that rebuilt cycle by the force program, J/m.
        energy_per_metre: The cycle re-optimised with them, the solver's exact energy per
            metre at its knots, J/m (reported, not judged).
        predicted: The re-optimised cycle rebuilt in task space with them, hexaleg's
            prediction (:func:`predicted_per_metre`), J/m; None where it has no answer.
        accepted: Whether ``predicted`` lowered the best prediction.
        seconds: Wall time of the round, s.
    """

    springs: SpringSet
    designed: float
    energy_per_metre: float
    predicted: float | None
    accepted: bool
    seconds: float


@dataclass(frozen=True)
class Alternation:
    """The alternation's answer.

    Every energy judged is hexaleg's prediction (:func:`predicted_per_metre`) of a motion
    played as the rows play it: the gait, or an optimal cycle rebuilt in task space.

    Attributes:
        gait: The gait it starts from.
        baseline: The gait with the starting springs predicted, J/m (None: no answer).
        start: The optimal cycle with the starting springs
            (:class:`~hexaleg.optimal.solve.OptimalResult`).
        start_predicted: Its rebuilt cycle with them predicted, J/m (None: no answer).
        best: The best optimal cycle found by prediction (the start when no round was
            accepted).
        springs: The answer's springs: the best cycle's, or the starting springs when the
            gait is kept.
        rounds: Every round, in order.
        gap: The last round's relative gain ``1 − E_new / E_best`` of the predictions (≤
            ``tolerance`` when it stopped by converging; negative for a round that rose; 0
            where the round has no prediction, 1 where only the round has one).
        kept_gait: Whether no optimal cycle was predicted below :attr:`baseline`, or none
            was rebuilt in task space: the answer is then the gait with the starting springs.
    """

    gait: Motion
    baseline: float | None
    start: Any
    start_predicted: float | None
    best: Any
    springs: SpringSet
    rounds: tuple[Round, ...]
    gap: float
    kept_gait: bool

    @property
    def energies(self) -> list[float | None]:
        """The best prediction so far, J/m: the gait's, then after the start and after each
        round (never rising; None until one has an answer); the last is the answer's."""
        out = [self.baseline]
        for new in (self.start_predicted, *(r.predicted for r in self.rounds)):
            out.append(new if _below(new, out[-1]) else out[-1])
        return out

    @property
    def predicted(self) -> float | None:
        """The answer's prediction, J/m (the last of :attr:`energies`)."""
        return self.energies[-1]

    @property
    def motion(self) -> Motion:
        """The answer's motion: the best cycle rebuilt in task space, or the gait when kept."""
        return self.gait if self.kept_gait else self.best.task_space


def alternate(robot: Robot, gait: Motion, actuator: Any, contact: ContactParams, *,
              springs: SpringSet | None = None, params: Any = None, family: str = "linear",
              groups: Groups | None = None, rounds: int = 4, tolerance: float = 0.01,
              say: Callable[[str], None] | None = None, keep: Keep | None = None,
              first: Any = None, move: float = 0.0,
              margin: float = Constraints.friction_margin) -> Alternation:
    """Alternate the optimal motion and its springs (module docstring).

    Args:
        robot: The robot.
        gait: The gait whose contact timing and path the optimal-control problem takes, and
            the answer when no optimal cycle is predicted below it.
        actuator: The motors (:class:`~hexaleg.robot.motor.Motor` or a ``MotorSet``).
        contact: The floor (its μ, the torque limits): the springs are designed and every
            cycle judged inside ``margin`` of its friction cone (:func:`judged`).
        springs: The springs to start from (None: none).
        params: :class:`~hexaleg.optimal.problem.OptimalParams` (None: defaults).
        family: The spring family designed, one of :data:`SMOOTH_FAMILIES`.
        groups: One spring design per group (``{name: joints}``, as the co-design's
            ``grouping``; Solo-12's front and hind knees bend opposite ways, so a design per
            class cancels there); None: one per joint class.
        rounds: Rounds at most, ≥ 1.
        tolerance: Relative gain under which it stops, in [0, 1).
        say: Where progress lines go.
        keep: Runs each solve, given what defines it (:data:`Keep`): a kept one
            (:class:`~hexaleg.design.codesign.optimal_stage.KeptSolves`) reads back a solve
            the run made before a kill; None: every solve computed.
        first: The optimal cycle of ``gait`` with ``springs`` and ``params`` when it is solved
            already (:mod:`~hexaleg.design.codesign.timing`'s choice); None: solved here.
        move: The start's solve from the gait's start moved by this much, m
            (:func:`hexaleg.optimal.solve.solve`'s ``move``: the rows' spread, :func:`spreads`).
        margin: The planners' friction margin, in (0, 1] (``[codesign.constraints]
            friction_margin``): the force programs of the design and of every verdict plan
            inside ``margin · μ``, and a cycle with no forces there is never accepted.

    Raises:
        InvalidParameterError: a family outside :data:`SMOOTH_FAMILIES`, bad ``rounds``,
            ``tolerance`` or ``margin``; BackendError: no usable Crocoddyl.
    """
    one_of("family", family, SMOOTH_FAMILIES)
    rounds = integer("rounds", rounds, low=1)
    tolerance = real("tolerance", tolerance, low=0.0, high=1.0, high_open=True)
    from hexaleg.optimal.problem import OptimalParams, build_problem  # needs Crocoddyl
    from hexaleg.optimal.solve import solve
    params = params or OptimalParams()
    tell = say or (lambda _line: None)
    current = given = springs or SpringSet()
    once = keep or computed
    baseline = predict(robot, gait, actuator, current, contact, margin).judged
    planning = dataclasses.replace(contact, mu=margin * contact.mu)
    best = first if first is not None else once(
        ("start", current, params, *((move,) if move else ())),
        lambda: solve(robot, build_problem(robot, gait, actuator, current, params), say=tell,
                      every=PROGRESS, move=move))
    start = best
    best_predicted = judged(robot, best, gait, actuator, current, contact, margin).judged
    start_predicted = best_predicted
    tell(f"start: {shown(best_predicted)} J/m predicted rebuilt (the gait: "
         f"{shown(baseline)}; the solver's {shown(best.energy_per_metre)} at its knots; "
         f"{best.iterations} iterations, {best.seconds:.0f} s)")

    def warm_solve(springs: SpringSet, last: Any) -> Any:
        """The cycle solved with ``springs``, warm-started from ``last`` (module docstring)."""
        built = build_problem(robot, gait, actuator, springs, params)
        new_tau = np.array([built.actuation.spring_torques(x) for x in last.x[:-1]])
        warm = (last.x, last.torques + last.spring_torques - new_tau)
        return solve(robot, built, warm=warm, say=tell, every=PROGRESS)

    done: list[Round] = []
    gap = 0.0
    for k in range(rounds):
        began = time.perf_counter()
        played = best.task_space
        if played is None:  # the start's cycle: the rounds design springs on a rebuilt one
            tell(f"round {k + 1}: no springs designed: the cycle is not rebuilt")
            break
        try:
            design = optimal_springs(prepare(robot, played, motor=actuator, contact=planning),
                                     groups or list(robot.joint_classes), family=family,
                                     metric="electrical")
        except HexalegError as err:  # a rebuilt cycle the force program has no answer for
            tell(f"round {k + 1}: no springs designed on the rebuilt cycle "
                 f"({type(err).__name__}: {err})")
            break
        candidate = once(("round", design.springs, params, best.x, best.torques,
                          best.spring_torques),
                         functools.partial(warm_solve, design.springs, best))
        designed = design.analysis.metrics["total"]["electrical"] / played.distance
        value = judged(robot, candidate, gait, actuator, design.springs, contact, margin).judged
        gap = (0.0 if value is None else 1.0 if best_predicted is None
               else 1.0 - value / best_predicted)
        accepted = _below(value, best_predicted)
        done.append(Round(design.springs, designed, candidate.energy_per_metre, value,
                          accepted, time.perf_counter() - began))
        tell(f"round {k + 1}: springs {shown(designed)} J/m on the rebuilt cycle, re-optimised "
             f"{shown(value)} J/m predicted rebuilt (the solver's "
             f"{shown(candidate.energy_per_metre)}; {'accepted' if accepted else 'rejected'})")
        if accepted:
            best, current, best_predicted = candidate, design.springs, value
        if gap < tolerance:
            break
    kept = best.task_space is None or (baseline is not None
                                       and not _below(best_predicted, baseline))
    if kept:
        tell(f"no optimal cycle predicted below the gait ({shown(best_predicted)} against "
             f"{shown(baseline)} J/m): the gait and its springs kept")
    return Alternation(gait, baseline, start, start_predicted, best,
                       given if kept else current, tuple(done), gap, kept)


def shown(value: float | None) -> str:
    """An energy per metre for a progress line, J/m, to 0.1 J/m (``—`` where there is none).

    A progress line is printed before its row's spread is measured (:data:`MOVES`), so it
    shows no digit the spread moves: 0.1 J/m is at least :data:`MARGIN` times the default
    robot's spreads (0.004–0.012 J/m on the rows, up to 0.019 on the solver's own figures; the
    rows' rule, :func:`decimals`), where four significant digits printed the solver's 9.527 as
    9.524 from a start moved by 1e-9 m. A robot whose rows spread wider (Solo-12's, about
    0.3 J/m) reads its figures from the rows, which print to their spread."""
    return "—" if value is None else f"{value:.1f}"
