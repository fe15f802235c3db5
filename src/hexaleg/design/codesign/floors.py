"""The springs to buy on floors of other friction (issue #41): the saving over a range of μ.

The co-design plans its foot forces inside ``friction_margin · μ`` of the floor it was given
(:class:`~hexaleg.design.codesign.gait_evaluation.Constraints`), and the springs are sized for the
internal forces that floor lets the force program choose. On another floor the program chooses
other forces: a grippier one frees them (the springs were sized for forces the floor no longer
dictates), a slipperier one narrows them, or admits none. So the springs to buy are evaluated on
the chosen gait at each μ of :data:`FLOORS` — a fresh analysis each (:func:`hexaleg.dynamics.
prepare.prepare`, forces of minimum Joule loss, the robot's motor and torque limits) — and the
saving at the worst μ is stated beside the nominal one, in the terminal, ``codesign.json``
``floors`` and the page.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass
from typing import Any

from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.prepare import prepare
from hexaleg.errors import HexalegError
from hexaleg.motion.legged import gait
from hexaleg.motion.params import GaitParams
from hexaleg.quantities import quantity
from hexaleg.robot.model import Robot
from hexaleg.robot.springs import SpringSet

FLOORS: tuple[float, ...] = (0.4, 0.6, 0.8, 1.0)
"""The friction coefficients the springs to buy are evaluated on: a slippery floor (0.4) to
rubber on concrete (1.0)."""


@dataclass(frozen=True)
class Floor:
    """The springs' predicted electrical saving on one floor.

    Attributes:
        mu: The floor's friction coefficient.
        saving: The electrical saving, fraction; None when the gait has no admissible forces
            there (``error`` says why).
        error: The analysis' error, or None.
    """

    mu: float
    saving: float | None
    error: str | None = None

    def data(self) -> dict[str, Any]:
        """codesign.json's row."""
        return {"mu": quantity(self.mu, "1"),
                "saving": None if self.saving is None else quantity(100 * self.saving, "%"),
                **({"error": self.error} if self.error else {})}


def over_floors(robot: Robot, params: GaitParams, motor: Any, springs: SpringSet,
                torque_limits: bool = True, floors: Sequence[float] = FLOORS
                ) -> tuple[Floor, ...]:
    """``springs`` on the gait ``params`` at each floor's μ (module docstring)."""
    motion = gait(robot, params)
    out = []
    for mu in floors:
        try:
            prepared = prepare(robot, motion, motor=motor,
                               contact=ContactParams(mu=mu, torque_limits=torque_limits))
            saving = float(prepared.evaluate(springs, "joule").savings["total"]["electrical"])
        except HexalegError as err:
            out.append(Floor(mu, None, f"{type(err).__name__}: {err}"))
            continue
        out.append(Floor(mu, saving))
    return tuple(out)


def worst(floors: Sequence[Floor]) -> Floor | None:
    """The floor of least saving among those with forces (the first of equals), or None."""
    rated = [(f.saving, i, f) for i, f in enumerate(floors) if f.saving is not None]
    return min(rated)[2] if rated else None


__all__ = ["FLOORS", "Floor", "over_floors", "worst"]
