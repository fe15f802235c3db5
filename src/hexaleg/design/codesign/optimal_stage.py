"""The optimal motion's stage of ``hexaleg codesign --motion optimal`` and its keeping.

The parametric co-design (:func:`hexaleg.design.codesign.build.codesign`: its searches, rules
and simulations, minutes) is kept as the stage file :data:`PARAMETRIC`
(:class:`~hexaleg.design.chain.checkpoint.StageFiles`, keyed by the caller on the run and its
settings) before the optimal motion's minutes begin (:func:`with_optimal`: the four rows of
:mod:`hexaleg.design.codesign.optimal_rows`): a run killed in the optimal stage reads the kept
co-design back (:func:`kept_parametric`) and goes straight to the optimal stage. The robots the
kept co-design refers to — the run's, and the copy the spring rules' forked child sent back — are
read back as this run's robot, by the stage files' robot references.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Callable
from typing import Any

from hexaleg.design.chain.checkpoint import StageFiles
from hexaleg.design.codesign.result import CodesignResult
from hexaleg.design.search.optimal import Groups
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


def with_optimal(result: CodesignResult, model: Robot, motor: Any, groups: Groups,
                 servo: str, say: Callable[[str], None]) -> CodesignResult:
    """``result`` with the optimal motion's rows (:mod:`hexaleg.design.codesign.optimal_rows`)
    from its chosen gait and springs; its wall time the two stages' together."""
    from hexaleg.design.codesign.optimal_rows import optimal_rows  # the optimal extra's rows

    optimal = optimal_rows(model, motor, result.constraints.contact(), result.default,
                           result.chosen, result.springs,
                           (result.rows[0].per_metre, result.rows[3].per_metre),
                           family=result.family, groups=groups, servo=servo,
                           say=lambda line: say(f"optimal motion: {line}"))
    return dataclasses.replace(result, optimal=optimal, wall=result.wall + optimal.wall)


__all__ = ["PARAMETRIC", "keep_parametric", "kept_parametric", "with_optimal"]
