"""A stiffening spring: stages that engage one after another as the joint turns further.

Nested torsion springs (or one spring meeting a second) give a piecewise-linear, progressively
stiffer law: each stage adds its stiffness past its breakpoint (Hooke's law per stage, Shigley's
Mechanical Engineering Design, 10th ed., §10-12; the paper's eq. 8 is the one-stage case with a
dead zone). With stages (a_i, k_i) above and (b_i, κ_i) below::

    τ(q) = −Σ_i k_i (q − a_i)₊ + Σ_i κ_i (b_i − q)₊
    U(q) = Σ_i ½ k_i (q − a_i)₊² + Σ_i ½ κ_i (b_i − q)₊²

so the stiffness above a_n is k_1 + … + k_n.
"""

from __future__ import annotations

import itertools
from collections.abc import Sequence
from dataclasses import dataclass

import numpy as np

from hexaleg.checks import named_arguments, real
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.springs.law import TermSpring, magnitude
from hexaleg.robot.springs.terms import Term

Stages = tuple[tuple[float, float], ...]
"""Stages of one side: (breakpoint, rad absolute joint angle; added stiffness, N·m/rad ≥ 0)."""


def _stages(name: str, stages: Sequence[Sequence[float]], outward: int) -> Stages:
    """Checked stages, breakpoints strictly moving away from the dead zone (``outward`` = +1 for
    the stages above, −1 below)."""
    if isinstance(stages, (str, bytes)) or not isinstance(stages, Sequence):
        raise InvalidParameterError(name, stages, "a sequence of (breakpoint, stiffness) pairs")
    out = []
    for i, stage in enumerate(stages):
        if isinstance(stage, (str, bytes)) or not isinstance(stage, Sequence) or len(stage) != 2:
            raise InvalidParameterError(f"{name}[{i}]", stage, "a (breakpoint, stiffness) pair")
        out.append((real(f"{name}[{i}] breakpoint", stage[0]),
                    magnitude(f"{name}[{i}] stiffness", stage[1])))
    angles = [a for a, _ in out]
    if any(outward * (b - a) <= 0 for a, b in itertools.pairwise(angles)):
        raise InvalidParameterError(f"{name} breakpoints", angles, "strictly increasing"
                                    if outward > 0 else "strictly decreasing")
    return tuple(out)


@named_arguments
@dataclass(frozen=True)
class StiffeningSpring(TermSpring):
    """A piecewise-linear stiffening spring (module docstring).

    Attributes:
        above: Stages engaged for q above their breakpoints, breakpoints increasing.
        below: Stages engaged for q below their breakpoints, breakpoints decreasing.

    Raises:
        InvalidParameterError: no stage at all, a negative stiffness, breakpoints out of order,
            or a value that is not a finite number.
    """

    above: Stages = ()
    below: Stages = ()

    def __post_init__(self) -> None:
        object.__setattr__(self, "above", _stages("above", self.above, +1))
        object.__setattr__(self, "below", _stages("below", self.below, -1))
        if not self.above and not self.below:
            raise InvalidParameterError("stages", "none", "at least one stage above or below")

    def terms(self) -> tuple[Term, ...]:
        return (tuple(Term("above", a, f"k_above_{i + 1}") for i, (a, _) in enumerate(self.above))
                + tuple(Term("below", b, f"k_below_{i + 1}")
                        for i, (b, _) in enumerate(self.below)))

    def magnitudes(self) -> np.ndarray:
        return np.array([k for _, k in self.above] + [k for _, k in self.below])
