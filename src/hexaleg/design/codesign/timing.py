"""The contact timing of the optimal motion as a decision (issue #56, ``codesign --motion optimal
--timing search``).

The optimal-control problem (:mod:`hexaleg.optimal.problem`) takes its contact timing — duty
factor and period — fixed from the gait it starts from. This is a small deterministic outer
search over that timing around the parametric co-design's chosen gait: a fixed lattice of
candidates (:func:`candidates`: the gait itself, its duty factor longer by :data:`DUTY_STEPS`
up to :data:`LATTICE_DUTY_HIGH`, its period scaled by :data:`PERIOD_FACTORS`), each solved with the
co-design's springs in its dynamics and judged by hexaleg's prediction of its cycle rebuilt in
task space (:func:`~hexaleg.design.codesign.alternation.judged`: the rows' prediction, where
the cycle covers its stride; the figure the alternation judges). A timing whose gait cannot be
made (a longer period's stride out of the legs' reach) is kept unsolved with its why, as the
starts keep theirs (:mod:`~hexaleg.design.codesign.starts`). The least prediction wins; a
tie or no prediction keeps the earlier candidate in the lattice's order, the co-design's own
timing first. It is an
enumeration, not a descent: the same inputs give the same candidates and the same choice on any
machine, and its answer is the best of the lattice (not of the continuum between).

The lattice widens the family past the parametric search's own duty-factor bound (0.8 by default,
``[codesign] duty_high``,
:func:`~hexaleg.design.codesign.box.default_space`): the parametric gait at the same
duty factors is a baseline of its own (the alternation's first figure, the chosen timing's gait
with the co-design's springs, is that gait).
"""

from __future__ import annotations

import dataclasses
import functools
from collections.abc import Callable
from dataclasses import dataclass
from typing import Any

from hexaleg.design.codesign.alternation import PROGRESS, Keep, apart, judged, least, shown
from hexaleg.design.codesign.gait_evaluation import Constraints
from hexaleg.dynamics.contact import ContactParams
from hexaleg.errors import HexalegError
from hexaleg.motion.legged import gait
from hexaleg.motion.params import GaitParams
from hexaleg.quantities import quantity as q
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet

DUTY_STEPS = (0.05, 0.1)
"""Duty factors tried beside the gait's: the gait's plus each of these (docs/optimal.md: a
longer stance was the documented lever, 0.785× on the solver's figure at 0.9)."""

LATTICE_DUTY_HIGH = 0.9
"""The longest duty factor the lattice tries (a tripod's swing at 0.9 is a tenth of the cycle;
above the parametric search's own default bound,
:data:`~hexaleg.design.codesign.box.DUTY_HIGH`, module docstring)."""

PERIOD_FACTORS = (0.85, 1.15)
"""Periods tried beside the gait's, as factors of it (at the gait's duty factor)."""

TIMINGS = ("gait", "search")
"""``codesign --timing``: the chosen gait's timing, or this module's search."""


@dataclass(frozen=True)
class Candidate:
    """One timing tried.

    Attributes:
        params: The gait at that timing.
        result: Its optimal cycle with the co-design's springs
            (:class:`~hexaleg.optimal.solve.OptimalResult`); None where its gait could not be
            made (:attr:`why`).
        predicted: Its cycle rebuilt in task space predicted with them, J/m; None where the
            analysis has no answer (:attr:`why`).
        why: Why there is no prediction, else ``""``.
    """

    params: GaitParams
    result: Any
    predicted: float | None
    why: str

    def data(self) -> dict[str, Any]:
        """codesign.json's entry."""
        return {"duty_factor": q(self.params.duty_factor, "1"),
                "period": q(self.params.period, "s"), "predicted": q(self.predicted, "J/m"),
                "solver": None if self.result is None else q(self.result.energy_per_metre,
                                                             "J/m"),
                **({"unpredicted": self.why} if self.why else {})}


@dataclass(frozen=True)
class TimingSearch:
    """The timing search's answer.

    Attributes:
        candidates: Every timing tried, in the lattice's order (:func:`candidates`).
        best: The index of the chosen one.
    """

    candidates: tuple[Candidate, ...]
    best: int

    @property
    def chosen(self) -> Candidate:
        """The timing chosen."""
        return self.candidates[self.best]

    def data(self) -> dict[str, Any]:
        """codesign.json's ``timing`` entry."""
        return {"candidates": [c.data() for c in self.candidates], "chosen": self.best}

    def line(self) -> str:
        """One line for the terminal: each timing's prediction, the chosen one marked."""
        def said(c: Candidate) -> str:
            value = "—" if c.predicted is None else f"{c.predicted:.3f}"
            return f"duty {c.params.duty_factor:.3g}, period {c.params.period:.4g} s: {value}"
        return ("    contact timing searched (J/m predicted rebuilt, the co-design's springs): "
                + "; ".join(("→ " if k == self.best else "") + said(c)
                            for k, c in enumerate(self.candidates)))


def candidates(chosen: GaitParams) -> list[GaitParams]:
    """The lattice about ``chosen`` (module docstring): itself first, then its duty factor plus
    each of :data:`DUTY_STEPS` that stays ≤ :data:`LATTICE_DUTY_HIGH`, then its period times each of
    :data:`PERIOD_FACTORS`."""
    out = [chosen]
    for step in DUTY_STEPS:
        duty = round(chosen.duty_factor + step, 12)  # 0.8 + 0.05 is 0.8500000000000001
        if duty <= LATTICE_DUTY_HIGH:
            out.append(dataclasses.replace(chosen, duty_factor=duty))
    out += [dataclasses.replace(chosen, period=chosen.period * f) for f in PERIOD_FACTORS]
    return out


def search_timing(robot: Robot, chosen: GaitParams, motor: Any, springs: SpringSet,
                  contact: ContactParams, params: Any, *,
                  say: Callable[[str], None] | None = None,
                  keep: Keep | None = None,
                  margin: float = Constraints.friction_margin) -> TimingSearch:
    """Each timing of :func:`candidates` solved with ``springs`` and predicted rebuilt, the
    solves side by side on the command's workers
    (:func:`~hexaleg.design.codesign.alternation.apart`); the least prediction chosen (module
    docstring).

    Args:
        robot: The robot. chosen: The co-design's gait. motor: Its motors.
        springs: The co-design's springs (in each candidate's dynamics and its prediction).
        contact: The floor of the prediction.
        params: :class:`~hexaleg.optimal.problem.OptimalParams`.
        say: Where progress lines go.
        keep: Runs each solve given what defines it (its gait, springs and settings).
        margin: The planners' friction margin: each cycle predicted inside ``margin · μ``
            (:func:`~hexaleg.design.codesign.alternation.judged`; one with no forces there has
            no prediction and is not chosen).

    Raises:
        BackendError: no usable Crocoddyl.
    """
    from hexaleg.optimal.problem import build_problem  # needs Crocoddyl
    from hexaleg.optimal.solve import solve

    tell = say or (lambda _line: None)
    lattice = candidates(chosen)

    def solved(g: GaitParams) -> Any:
        """The optimal cycle of the gait ``g`` with ``springs`` (its progress lines named by
        its timing: the lattice's solves run side by side)."""
        built = build_problem(robot, gait(robot, g), motor, springs, params)
        label = f"duty factor {g.duty_factor:.3g}, period {g.period:.4g} s"
        return solve(robot, built, say=lambda line: tell(f"{label}: {line}"), every=PROGRESS)

    motions: dict[int, Any] = {}
    unmade: dict[int, str] = {}
    for k, g in enumerate(lattice):
        try:
            motions[k] = gait(robot, g)
        except HexalegError as err:  # a longer stride the legs cannot reach
            unmade[k] = f"{type(err).__name__}: {err}"
    run = list(motions)

    def judge(index: int, result: Any) -> tuple[float | None, str]:
        said = judged(robot, result, motions[run[index]], motor, springs, contact, margin)
        return said.judged, said.why

    done = dict(zip(run, apart([(("timing", lattice[k], springs, params),
                                 functools.partial(solved, lattice[k])) for k in run],
                               robot, keep, judge), strict=True))
    tried = []
    for k, g in enumerate(lattice):
        if k in unmade:
            tried.append(Candidate(g, None, None, unmade[k]))
            tell(f"duty factor {g.duty_factor:.3g}, period {g.period:.4g} s: no gait "
                 f"({unmade[k]})")
            continue
        result, (value, why) = done[k]
        tried.append(Candidate(g, result, value, why))
        tell(f"duty factor {g.duty_factor:.3g}, period {g.period:.4g} s: "
             + (f"{shown(value)} J/m predicted rebuilt" if value is not None else
                f"no prediction ({why})") + f" (the solver's {shown(result.energy_per_metre)})")
    best = least([t.predicted for t in tried])
    return TimingSearch(tuple(tried), best)


__all__ = ["DUTY_STEPS", "LATTICE_DUTY_HIGH", "PERIOD_FACTORS", "TIMINGS", "Candidate",
           "TimingSearch", "candidates", "search_timing"]
