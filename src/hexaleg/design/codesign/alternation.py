"""The optimal motion and its springs designed together, by alternation (issue #56).

Block-coordinate descent (Bertsekas, *Nonlinear Programming*, 3rd ed., §3.7) on the pair
(motion, springs):

1. the motion: the whole-body optimal cycle with the springs in its dynamics
   (:mod:`hexaleg.optimal`), warm-started from the previous cycle with the motor torques that
   keep its joint torques (``u' = u + τ_s − τ_s'``);
2. the springs: the project's global convex design (:func:`hexaleg.design.search.optimal.
   optimal_springs`, electrical metric) on that cycle.

The two steps minimise different programs — the design step the force program's energy of the
cycle, the motion step the optimal-control cost (energy at the solver's own contact forces plus
its small regularisation) — so a round is accepted only when the re-optimised cycle's exact
energy per metre (:attr:`~hexaleg.optimal.solve.OptimalResult.energy_per_metre`) falls: the
sequence of accepted energies never rises, by construction, and the loop stops when a round
gains less than ``tolerance`` (the stated gap: the last relative gain) or after ``rounds``.
It starts from the springs given (the parametric co-design's, or none), so it never ends worse
than its start.

Only families whose torque is continuous in the angle enter DDP's dynamics well (``linear``,
``dead_zone``); a preload's step has no derivative, and the solver then lets a stance foot slip.
"""

from __future__ import annotations

import functools
import time
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.checks import integer, one_of, real
from hexaleg.design.search.optimal import Groups, optimal_springs
from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import prepare
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet

SMOOTH_FAMILIES = ("linear", "dead_zone")
"""Families whose torque is continuous in the angle (module docstring)."""


PROGRESS = 20
"""A solve's progress line every this many box-FDDP iterations (a hundred take minutes)."""

Keep = Callable[[tuple[Any, ...], Callable[[], Any]], Any]
"""How a solve is run: ``keep(inputs, compute)`` is ``compute()``'s result, where ``inputs``
(a label, the springs, the solver's settings, the cycle a warm start comes from) are
everything that defines it beside the run itself (its robot, gait, motors, floor)."""


def computed(_inputs: tuple[Any, ...], compute: Callable[[], Any]) -> Any:
    """Every solve computed (:data:`Keep`)."""
    return compute()


@dataclass(frozen=True)
class Round:
    """One round of the alternation.

    Attributes:
        springs: The springs designed on the previous best cycle.
        designed: Their energy per metre on that cycle by the force program, J/m.
        energy_per_metre: The cycle re-optimised with them, exact energy per metre, J/m.
        accepted: Whether it lowered the best energy per metre.
        seconds: Wall time of the round, s.
    """

    springs: SpringSet
    designed: float
    energy_per_metre: float
    accepted: bool
    seconds: float


@dataclass(frozen=True)
class Alternation:
    """The alternation's answer.

    Attributes:
        start: The optimal cycle with the starting springs.
        best: The best cycle found (the start when no round was accepted).
        springs: Its springs.
        rounds: Every round, in order.
        gap: The last round's relative gain ``1 − E_new / E_best`` (≤ ``tolerance`` when it
            stopped by converging; negative for a round that rose).
    """

    start: Any
    best: Any
    springs: SpringSet
    rounds: tuple[Round, ...]
    gap: float

    @property
    def energies(self) -> list[float]:
        """The best energy per metre after the start and after each round, J/m (never rising)."""
        out = [self.start.energy_per_metre]
        for r in self.rounds:
            out.append(min(out[-1], r.energy_per_metre) if r.accepted else out[-1])
        return out


def alternate(robot: Robot, gait: Motion, actuator: Any, contact: ContactParams, *,
              springs: SpringSet | None = None, params: Any = None, family: str = "linear",
              groups: Groups | None = None, rounds: int = 4, tolerance: float = 0.01,
              say: Callable[[str], None] | None = None, keep: Keep | None = None
              ) -> Alternation:
    """Alternate the optimal motion and its springs (module docstring).

    Args:
        robot: The robot.
        gait: The gait whose contact timing and path the optimal-control problem takes.
        actuator: The motors (:class:`~hexaleg.robot.motor.Motor` or a ``MotorSet``).
        contact: The contact settings of the spring design's force program.
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

    Raises:
        InvalidParameterError: a family outside :data:`SMOOTH_FAMILIES`, bad ``rounds`` or
            ``tolerance``; BackendError: no usable Crocoddyl.
    """
    one_of("family", family, SMOOTH_FAMILIES)
    rounds = integer("rounds", rounds, low=1)
    tolerance = real("tolerance", tolerance, low=0.0, high=1.0, high_open=True)
    from hexaleg.optimal.problem import OptimalParams, build_problem  # needs Crocoddyl
    from hexaleg.optimal.solve import solve
    params = params or OptimalParams()
    tell = say or (lambda _line: None)
    current = springs or SpringSet()
    once = keep or computed
    best = once(("start", current, params),
                lambda: solve(robot, build_problem(robot, gait, actuator, current, params),
                              say=tell, every=PROGRESS))
    start = best
    tell(f"start: {best.energy_per_metre:.4g} J/m ({best.iterations} iterations, "
         f"{best.seconds:.0f} s)")

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
        prepared = prepare(robot, best.motion, motor=actuator, contact=contact)
        design = optimal_springs(prepared, groups or list(robot.joint_classes),
                                 family=family, metric="electrical")
        candidate = once(("round", design.springs, params, best.x, best.torques,
                          best.spring_torques),
                         functools.partial(warm_solve, design.springs, best))
        designed = design.analysis.metrics["total"]["electrical"] / best.motion.distance
        gap = 1.0 - candidate.energy_per_metre / best.energy_per_metre
        accepted = gap > 0.0
        done.append(Round(design.springs, designed, candidate.energy_per_metre, accepted,
                          time.perf_counter() - began))
        tell(f"round {k + 1}: springs {designed:.4g} J/m on the cycle, re-optimised "
             f"{candidate.energy_per_metre:.4g} J/m ({'accepted' if accepted else 'rejected'})")
        if accepted:
            best, current = candidate, design.springs
        if gap < tolerance:
            break
    return Alternation(start, best, current, tuple(done), gap)
