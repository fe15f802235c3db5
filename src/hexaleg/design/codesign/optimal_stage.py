"""The optimal motion's stage of ``hexaleg codesign --motion optimal`` and its keeping.

The parametric co-design (:func:`hexaleg.design.codesign.build.codesign`: its searches, rules
and simulations, minutes) is kept as the stage file :data:`PARAMETRIC`
(:class:`~hexaleg.design.chain.checkpoint.StageFiles`, keyed by the caller on the run and its
settings) before the optimal motion's minutes begin (:func:`with_optimal`: the four rows of
:mod:`hexaleg.design.codesign.optimal_rows`): a run killed in the optimal stage reads the kept
co-design back (:func:`kept_parametric`) and goes straight to the optimal stage. The robots the
kept co-design refers to — the run's, and the copy the spring rules' forked child sent back — are
read back as this run's robot, by the stage files' robot references.

Inside the optimal stage, each optimal-control solve (minutes each: the motion without springs,
the alternation's start and each of its rounds) is kept as it ends (:class:`KeptSolves`), as a
stage file named by a digest of its inputs (its label, springs, solver settings and the cycle
its warm start comes from): a run killed in a round reads back the solves before it, which
give the same inputs to the next, and solves only from there. The full spring rules on the
optimal motion (the springs to buy for it, a minute or two) are kept the same way, defined by the
motion they run on, and so are the rules on each repeat of that motion from its start moved by
its spread's moves (:mod:`~hexaleg.design.codesign.rules_spread`: how far the springs to buy move
with the motion).
"""

from __future__ import annotations

import dataclasses
import functools
import hashlib
import pickle
import time
from collections.abc import Callable
from typing import Any

from hexaleg.design.chain.checkpoint import StageFiles
from hexaleg.design.chain.result import DesignResult
from hexaleg.design.codesign.alternation import MOVES
from hexaleg.design.codesign.result import CodesignResult
from hexaleg.design.codesign.rules_spread import rules_spread
from hexaleg.design.search.optimal import Groups
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot

PARAMETRIC = "parametric"
"""The stage file of the finished parametric co-design, kept before the optimal motion's stage."""


def keep_parametric(stages: StageFiles | None, result: CodesignResult, robot: Robot) -> None:
    """Keep the finished parametric co-design ``result`` of the run's ``robot`` in ``stages``
    (None: nothing kept)."""
    if stages is not None:
        stages.save(PARAMETRIC, result, {"robot": robot})


def kept_parametric(stages: StageFiles | None, robot: Robot) -> CodesignResult | None:
    """The parametric co-design this run kept in ``stages`` before it was killed, referring to
    the run's ``robot``; None when there is none (no stages, another run's, another robot's)."""
    if stages is None:
        return None
    kept = stages.load(PARAMETRIC, {"robot": robot})
    return kept if isinstance(kept, CodesignResult) else None


RULES = "full spring rules on the optimal motion"
"""The label of the springs to buy for the optimal motion among the kept results
(:class:`KeptSolves`: defined by the motion they run on)."""

SOLVE = "optimal-solve-"
"""The start of a kept solve's stage name (:class:`KeptSolves`), the rest its inputs' digest."""


class KeptSolves:
    """Each solve of the optimal stage kept in ``stages`` as it ends and read back from there
    by a later process of the same run (module docstring; an
    :data:`~hexaleg.design.codesign.alternation.Keep`).

    Args:
        stages: The run's stage files (None: every solve computed, nothing kept).
        robot: The run's robot (a solve's motion is read back referring to it).
        say: Where the line of a solve read back goes.
    """

    def __init__(self, stages: StageFiles | None, robot: Robot,
                 say: Callable[[str], None]) -> None:
        self._stages = stages
        self._robot = robot
        self._say = say

    @staticmethod
    def name(inputs: tuple[Any, ...]) -> str:
        """The stage name of the solve defined by ``inputs``: :data:`SOLVE` and the SHA-256 of
        their pickle (springs, settings and arrays written exactly: the same inputs in another
        process give the same name)."""
        digest = hashlib.sha256(pickle.dumps(inputs, protocol=pickle.HIGHEST_PROTOCOL))
        return SOLVE + digest.hexdigest()[:32]

    def __call__(self, inputs: tuple[Any, ...], compute: Callable[[], Any]) -> Any:
        """The solve's result: read back when this run kept it, else computed and kept."""
        if self._stages is None:
            return compute()
        name = self.name(inputs)
        shared = {"robot": self._robot}
        kept = self._stages.load(name, shared)
        if kept is not None:
            self._say(f"{inputs[0]}: solve read back from the kept stage of this run")
            return kept
        value = compute()
        self._stages.save(name, value, shared)
        return value


def with_optimal(result: CodesignResult, model: Robot, motor: Any, groups: Groups,
                 servo: str, say: Callable[[str], None],
                 stages: StageFiles | None = None, feedback: str = "auto",
                 timing: str = "gait", starts: str = "lattice",
                 rules: Callable[[Motion], DesignResult | str] | None = None,
                 params: Any = None) -> CodesignResult:
    """``result`` with the optimal motion's rows (:mod:`hexaleg.design.codesign.optimal_rows`)
    from its chosen gait and springs (at its contact timing, or the one ``timing="search"``
    chooses; from that gait, or from the best start of ``starts="lattice"``), each row
    simulated with the balance ``feedback`` setting, then the springs to buy for the optimal
    motion by ``rules`` (:func:`~hexaleg.design.codesign.full_rules.motion_rules` with the
    run's settings; None: none) where the alternation did not keep the gait, the optimal problem
    set by ``params`` (:class:`~hexaleg.optimal.problem.OptimalParams`; None: its defaults), each
    optimal row solved without and with the landing cost and kept by the worse servo
    (:func:`~hexaleg.design.codesign.landing_choice.by_worse_servo`; the rules run on the motion
    kept, then, where they buy springs, on each repeat of it that measured its spread: how far
    the springs to buy move, :func:`~hexaleg.design.codesign.rules_spread.rules_spread`); each
    solve and each rules' result kept in ``stages`` (:class:`KeptSolves`); its wall time the two
    stages' together."""
    from hexaleg.design.codesign.optimal_rows import optimal_rows  # the optimal extra's rows

    def tell(line: str) -> None:
        say(f"optimal motion: {line}")

    keep = KeptSolves(stages, model, tell)
    optimal = optimal_rows(model, motor, result.constraints.contact(), result.default,
                           result.chosen, result.springs,
                           margin=result.constraints.friction_margin, family=result.family,
                           groups=groups, servo=servo,
                           feedback=feedback, timing=timing, starts=starts,
                           min_step=result.constraints.min_foot_clearance, say=tell,
                           keep=keep, params=params)
    if rules is not None and not optimal.alternation.kept_gait:
        began = time.perf_counter()
        motion = optimal.alternation.motion
        bought = keep((RULES, motion), lambda: rules(motion))
        again: list[DesignResult | str | None] = []
        compared = optimal.repeats if isinstance(bought, DesignResult) and bought.pays else ()
        for k, repeat in enumerate(compared):
            if repeat is None:
                again.append(None)
                continue
            tell(f"springs to buy on the row's repeat {k + 1} of {len(compared)}")
            again.append(keep((RULES, repeat), functools.partial(rules, repeat)))
        spread = rules_spread(bought, again, MOVES, motion.distance) if again else None
        optimal = dataclasses.replace(optimal, rules=bought, rules_spread=spread,
                                      wall=optimal.wall + time.perf_counter() - began)
    return dataclasses.replace(result, optimal=optimal, wall=result.wall + optimal.wall)


__all__ = ["PARAMETRIC", "RULES", "SOLVE", "KeptSolves", "keep_parametric", "kept_parametric",
           "with_optimal"]
