"""A small fixed multi-start of the optimal motion (issue #56, ``codesign --motion optimal
--starts lattice``).

Box-FDDP is a local method: the optimal cycle it reaches depends on the gait it starts from,
whose swing path and body height it is also pulled towards (the swing feet near the gait's
path, every state near the warm start: :class:`~hexaleg.optimal.problem.OptimalParams`). The
contact timing search (:mod:`hexaleg.design.codesign.timing`) moves the duty factor and period;
this module moves what that lattice does not: the gait's step height, its body height, and how
strongly the swing feet are held to the gait's path (their shape). A fixed lattice of starts
(:func:`starts`: the gait itself, then its step height × :data:`STEP_FACTORS` — none below the
co-design's least foot clearance —, its body height × :data:`BODY_FACTORS`, then the gait with
the swing weight × :data:`SWING_FACTORS`), each solved with the springs given in its
dynamics and judged by hexaleg's prediction of its cycle rebuilt in task space
(:func:`~hexaleg.design.codesign.alternation.judged`, the figure the alternation judges); the
least prediction wins, a tie or no prediction keeps the earlier start (the gait first). The
optimal rows (:mod:`~hexaleg.design.codesign.optimal_rows`) solve the lattice twice: with the
co-design's springs, whose start the alternation runs from, and without springs, whose start
the optimal motion without springs runs from. An enumeration, not a descent: the same inputs
give the same starts and the same choice on any machine, and its answer is the best of the
lattice.

A start that moves the step or body height is another parametric gait (above the foot
clearance, and its body height possibly above the co-design's search box: the optimal problem
is bounded by the legs' reach and joint limits, not by that box); the alternation then starts
from that gait, and it is that gait with the co-design's springs that the optimal cycle must
beat. A start above the box, either lattice's, is said under the optimal table
(:meth:`~hexaleg.design.codesign.result.CodesignResult.bound_lines`), with the ``--body-high``
that would search the parametric co-design in one box with it.
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

STEP_FACTORS = (0.7, 1.3)
"""Step heights tried beside the gait's, as factors of it (docs/optimal.md: × 0.7 was the
best other start probed, 0.864× the co-design by the solver's figure)."""

BODY_FACTORS = (0.95, 1.05, 1.15, 1.25)
"""Body heights tried beside the gait's, as factors of it. The optimal problem's body height is
a state, bounded by the legs' reach, not by the parametric search's box; box-FDDP stays near
its start, so the lattice reaches up towards the legs' reach. On the default robot the
co-design's gait stands at the box's top (1.3 × the default gait's body height), and × 1.25 of
it (1.63 ×) is the cheapest start (docs/optimal.md, "Starts of the optimal motion"); × 1.3 of
it (1.69 ×) stands within 1 % of the legs' reach, where the answer moved with a start moved by
1e-9 m by 0.16 J/m, at 100 iterations and at 200 (0.016 at × 1.25). A start the legs cannot
reach is reported and not solved."""

SWING_FACTORS = (0.01,)
"""Swing weights tried beside :class:`~hexaleg.optimal.problem.OptimalParams`' own, as factors
of it: the swing feet freer of the gait's path (its shape left to the cost)."""

STARTS = ("gait", "lattice")
"""``codesign --starts``: the gait alone, or this module's lattice."""


@dataclass(frozen=True)
class Start:
    """One start of the lattice.

    Attributes:
        label: What it moves (``"the gait"``, ``"step height × 0.7"``, …).
        params: The gait it starts from (and whose path its problem takes).
        settings: Its :class:`~hexaleg.optimal.problem.OptimalParams`.
        result: Its optimal cycle with the co-design's springs
            (:class:`~hexaleg.optimal.solve.OptimalResult`); None where its gait could not be
            made (:attr:`why`).
        predicted: Its cycle rebuilt in task space predicted with them, J/m; None where there
            is no answer (:attr:`why`).
        why: Why there is no prediction, else ``""``.
    """

    label: str
    params: GaitParams
    settings: Any
    result: Any
    predicted: float | None
    why: str

    def data(self) -> dict[str, Any]:
        """codesign.json's entry."""
        return {"start": self.label, "step_height": q(self.params.step_height, "m"),
                "body_height": q(self.params.body_height, "m"),
                "swing_weight": q(self.settings.swing_weight, "1/m²"),
                "predicted": q(self.predicted, "J/m"),
                "solver": None if self.result is None else q(self.result.energy_per_metre,
                                                             "J/m"),
                **({"unpredicted": self.why} if self.why else {})}


@dataclass(frozen=True)
class StartSearch:
    """The multi-start's answer.

    Attributes:
        starts: Every start tried, in the lattice's order (:func:`starts`).
        best: The index of the chosen one.
        springs: The springs each start was solved with, as the table names them.
    """

    starts: tuple[Start, ...]
    best: int
    springs: str = "the co-design's springs"

    @property
    def chosen(self) -> Start:
        """The start chosen."""
        return self.starts[self.best]

    def data(self) -> dict[str, Any]:
        """codesign.json's ``starts`` entry."""
        return {"starts": [s.data() for s in self.starts], "chosen": self.best,
                "springs": self.springs}

    def line(self) -> str:
        """One line for the terminal: each start's prediction, the chosen one marked."""
        def said(s: Start) -> str:
            return f"{s.label}: {'—' if s.predicted is None else f'{s.predicted:.3f}'}"
        return (f"    starts of the optimal motion (J/m predicted rebuilt, {self.springs}): "
                + "; ".join(("→ " if k == self.best else "") + said(s)
                                        for k, s in enumerate(self.starts)))


def starts(chosen: GaitParams, params: Any, min_step: float
           ) -> list[tuple[str, GaitParams, Any]]:
    """The lattice about ``chosen`` and the solver's ``params`` (module docstring): ``(label,
    gait, params)`` of the gait itself first, then its step height × :data:`STEP_FACTORS`
    (a height below ``min_step``, the least foot clearance, is raised to it, and a start equal
    to one before is left out), its body height × :data:`BODY_FACTORS`, then the gait with
    the swing weight × :data:`SWING_FACTORS`."""
    assert chosen.body_height is not None
    out = [("the gait", chosen, params)]
    for f in STEP_FACTORS:
        h = max(chosen.step_height * f, min_step)
        if all(abs(h - g.step_height) > 1e-12 for _, g, _ in out):
            out.append((f"step height × {h / chosen.step_height:.3g}",
                        dataclasses.replace(chosen, step_height=h), params))
    out += [(f"body height × {f:g}",
             dataclasses.replace(chosen, body_height=chosen.body_height * f), params)
            for f in BODY_FACTORS]
    out += [(f"swing weight × {f:g}", chosen,
             dataclasses.replace(params, swing_weight=params.swing_weight * f))
            for f in SWING_FACTORS]
    return out


def search_starts(robot: Robot, chosen: GaitParams, motor: Any, springs: SpringSet,
                  contact: ContactParams, params: Any, min_step: float, *,
                  first: Any = None, say: Callable[[str], None] | None = None,
                  keep: Keep | None = None,
                  margin: float = Constraints.friction_margin,
                  springs_named: str = "the co-design's springs") -> StartSearch:
    """Each start of :func:`starts` solved with ``springs`` and predicted rebuilt, the solves
    side by side on the command's workers (:func:`~hexaleg.design.codesign.alternation.apart`);
    the least prediction chosen (module docstring).

    Args:
        robot: The robot. chosen: The gait (at the contact timing chosen). motor: Its motors.
        springs: The springs in each start's dynamics and its prediction: the co-design's, or
            none for the optimal motion without springs (its own starts).
        contact: The floor of the prediction.
        params: :class:`~hexaleg.optimal.problem.OptimalParams`.
        min_step: The least step height, m (the co-design's least foot clearance).
        first: The optimal cycle of ``chosen`` with ``springs`` and ``params`` when it is
            solved already (the timing search's); None: solved here.
        say: Where progress lines go.
        keep: Runs each solve given what defines it (its gait, springs and settings).
        margin: The planners' friction margin: each cycle predicted inside ``margin · μ``
            (:func:`~hexaleg.design.codesign.alternation.judged`; one with no forces there has
            no prediction and is not chosen).
        springs_named: How the table names ``springs`` (:attr:`StartSearch.springs`).

    Raises:
        BackendError: no usable Crocoddyl.
    """
    from hexaleg.optimal.problem import build_problem  # needs Crocoddyl
    from hexaleg.optimal.solve import solve

    tell = say or (lambda _line: None)

    def solved(label: str, g: GaitParams, settings: Any) -> Any:
        """The optimal cycle of the gait ``g`` with ``springs`` and ``settings`` (its progress
        lines named by its start: the lattice's solves run side by side)."""
        built = build_problem(robot, gait(robot, g), motor, springs, settings)
        return solve(robot, built, say=lambda line: tell(f"{label}: {line}"), every=PROGRESS)

    lattice = starts(chosen, params, min_step)
    motions: dict[int, Any] = {}
    unmade: dict[int, str] = {}
    for k, (_, g, _) in enumerate(lattice):
        try:
            motions[k] = gait(robot, g)
        except HexalegError as err:  # a body height the legs cannot reach
            unmade[k] = f"{type(err).__name__}: {err}"
    given = 0 in motions and first is not None
    run = [k for k in motions if not (k == 0 and given)]

    def judge(index: int, result: Any) -> tuple[float | None, str]:
        return figure(run[index], result)

    def figure(k: int, result: Any) -> tuple[float | None, str]:
        said = judged(robot, result, motions[k], motor, springs, contact, margin)
        return said.judged, said.why

    done = dict(zip(run, apart(
        [(("start", lattice[k][1], springs, lattice[k][2]),
          functools.partial(solved, *lattice[k])) for k in run], robot, keep, judge),
        strict=True))
    if given:
        done[0] = (first, figure(0, first))
    tried = []
    for k, (label, g, settings) in enumerate(lattice):
        if k in unmade:
            tried.append(Start(label, g, settings, None, None, unmade[k]))
            tell(f"{label}: no gait ({unmade[k]})")
            continue
        result, (value, why) = done[k]
        tried.append(Start(label, g, settings, result, value, why))
        tell(f"{label}: " + (f"{shown(value)} J/m predicted rebuilt" if value is not None else
                             f"no prediction ({why})")
             + f" (the solver's {shown(result.energy_per_metre)})")
    best = least([t.predicted for t in tried])
    return StartSearch(tuple(tried), best, springs_named)


__all__ = ["BODY_FACTORS", "STARTS", "STEP_FACTORS", "SWING_FACTORS", "Start", "StartSearch",
           "search_starts", "starts"]
