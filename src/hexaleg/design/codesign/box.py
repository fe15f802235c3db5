"""The co-design's search box from its options: the searches' highest duty factor and body
height (``[codesign] duty_high`` and ``body_high``, ``--duty-high`` and ``--body-high``), their
defaults and allowed ranges, the checks that refuse a value outside them, and the box about the
default gait they bound (:func:`default_space`), which both of ``hexaleg codesign``'s searches
(:func:`~hexaleg.design.codesign.gait_search.search`: with springs and without) get, and the
box's edges a chosen gait lies on (:func:`edges`: where it does, the answer is the box's optimum
and a cheaper gait may lie past that edge)."""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from hexaleg.checks import real
from hexaleg.design.codesign.gait_evaluation import PARAMETERS
from hexaleg.design.codesign.gait_search import Space
from hexaleg.motion.params import GaitParams

DUTY_HIGH = 0.8
"""The searches' highest duty factor by default (``[codesign] duty_high``, ``--duty-high``).
It stays at 0.8, though the default robot's co-design sits on it and a bound of 0.9 finds a
cheaper gait (docs/optimal.md: 9.10 against 9.99 J/m predicted): every co-design figure the
docs and tests pin was searched to 0.8, and a tripod past it swings each leg in a tenth of the
cycle or less, which the servo check has only partly simulated."""
DUTY_CEILING = 0.95
"""The highest ``duty_high`` allowed (the search box's own ceiling: a swing of a twentieth of
the cycle)."""
BODY_HIGH = 1.3
"""The searches' highest body height by default, × the default gait's (``[codesign]
body_high``, ``--body-high``). It stays at 1.3, though the default robot's co-design sits on it
and a top of 1.5 × finds a cheaper gait (docs/optimal.md, "Starts of the optimal motion": 8.545
against 9.093 J/m predicted at duty factor ≤ 0.9): every co-design figure the docs and tests
pin was searched to 1.3 ×."""
BODY_FLOOR = 1.0
"""The lowest ``body_high`` allowed: the box keeps the default gait, the search's first start."""
BODY_CEILING = 2.0
"""The highest ``body_high`` allowed: past the legs' reach of every registered robot (the
default gait's body height × 1.7 still walks on the hexapod, × 2 does not; Solo-12's × 1.5 does
not); a body the legs cannot reach is a gait the generator refuses, which the search
penalises."""


def duty_bound(value: Any, lowest: float) -> float:
    """``duty_high`` checked against the default gait's duty factor ``lowest`` (the search
    box's low end): in [``lowest`` + 0.05, :data:`DUTY_CEILING`]; None: :data:`DUTY_HIGH`, or
    ``lowest`` + 0.05 where that is higher.

    Raises:
        InvalidParameterError: not a number, or outside that range (both named).
    """
    low = round(lowest + 0.05, 12)
    if value is None:
        return max(DUTY_HIGH, low)
    return real("[codesign] duty_high", value, low=low, high=DUTY_CEILING,
                allowed=f"a duty factor in [{low:g}, {DUTY_CEILING:g}] (the default gait's "
                        f"{lowest:g} plus 0.05, up to {DUTY_CEILING:g})")


def body_bound(value: Any) -> float:
    """``body_high``, the search box's highest body height as a factor of the default gait's,
    checked: in [:data:`BODY_FLOOR`, :data:`BODY_CEILING`]; None: :data:`BODY_HIGH`.

    Raises:
        InvalidParameterError: not a number, or outside that range (both named).
    """
    if value is None:
        return BODY_HIGH
    return real("[codesign] body_high", value, low=BODY_FLOOR, high=BODY_CEILING,
                allowed=f"a factor of the default gait's body height in [{BODY_FLOOR:g}, "
                        f"{BODY_CEILING:g}] (the box keeps the default gait; past "
                        f"{BODY_CEILING:g} × the legs reach no robot's ground)")


def default_space(gait: GaitParams, min_step: float, free: Sequence[str] = PARAMETERS,
                  duty_high: float = DUTY_HIGH, body_high: float = BODY_HIGH) -> Space:
    """The default box about a robot's gait ``gait`` (its resolved values): body height
    ×[0.7, ``body_high``], foot radius ×[0.7, 1.3], step height [``min_step``, 1.5 × default],
    duty factor [the pattern's β₀, max(β₀ + 0.05, ``duty_high``)] (β₀ is the least that keeps
    the pattern's support: 0.5 for a tripod or trot, 0.75 for a crawl; ``duty_high`` held to
    :data:`DUTY_CEILING`), period ×[0.5, 2]."""
    assert gait.body_height is not None and gait.foot_radius is not None
    beta = gait.duty_factor
    box = {"body_height": (0.7 * gait.body_height, body_high * gait.body_height),
           "foot_radius": (0.7 * gait.foot_radius, 1.3 * gait.foot_radius),
           "step_height": (min_step, max(1.5 * gait.step_height, 2 * min_step)),
           "duty_factor": (beta, max(beta + 0.05, min(duty_high, DUTY_CEILING))),
           "period": (0.5 * gait.period, 2.0 * gait.period)}
    return Space({n: box[n] for n in PARAMETERS if n in free})


EDGE = 1e-6
"""How near its bound, as a fraction of its range, a parameter lies on it (:func:`edges`): the
search's finest step is 1/32 of a range and it clips a point to the box, so a parameter the
search left at its bound is there to rounding, and one a step inside is 0.03 of the range
away."""


@dataclass(frozen=True)
class Edge:
    """A parameter of a gait on its search box's edge.

    Attributes:
        parameter: One of :data:`~hexaleg.design.codesign.gait_evaluation.PARAMETERS`.
        side: ``"top"`` or ``"floor"`` of its range.
        value: The gait's value there, SI (:data:`~hexaleg.design.codesign.gait_evaluation.
            UNITS`).
        moved_by: The option that moves this bound and how far it may go, or None where the
            bound is fixed (the box's own factor of the default gait, the pattern's least duty
            factor, or an option already at its ceiling).
    """

    parameter: str
    side: str
    value: float
    moved_by: str | None


def edges(space: Space, params: GaitParams, duty_high: float = DUTY_HIGH,
          body_high: float = BODY_HIGH) -> tuple[Edge, ...]:
    """The edges of ``space`` (:func:`default_space` with ``duty_high`` and ``body_high``)
    that the gait ``params`` lies on, within :data:`EDGE` of a range, in ``space``'s order.

    The printed optimum of a search is the box's: where a parameter lies on an edge the box
    binds it, and the gap to a gait past that edge is unknown; this says which edges, and which
    option widens each (``--body-high`` to :data:`BODY_CEILING`, ``--duty-high`` to
    :data:`DUTY_CEILING`, the step height's floor ``[codesign.constraints]
    min_foot_clearance``)."""
    moved = {("body_height", "top"): None if body_high >= BODY_CEILING else
             f"--body-high, up to {BODY_CEILING:g} × the default gait's",
             ("duty_factor", "top"): None if duty_high >= DUTY_CEILING else
             f"--duty-high, up to {DUTY_CEILING:g}",
             ("step_height", "floor"): "[codesign.constraints] min_foot_clearance"}
    out = []
    for name in space.names:
        low, high = space.bounds[name]
        value = float(getattr(params, name))
        for side, bound in (("floor", low), ("top", high)):
            if abs(value - bound) <= EDGE * (high - low):
                out.append(Edge(name, side, value, moved.get((name, side))))
    return tuple(out)


__all__ = ["BODY_CEILING", "BODY_FLOOR", "BODY_HIGH", "DUTY_CEILING", "DUTY_HIGH", "EDGE", "Edge",
           "body_bound", "default_space", "duty_bound", "edges"]
