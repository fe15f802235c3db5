"""How to simulate: :class:`Settings`, the ``[simulate]`` table of a config file, and the ground
it sizes to the robot (:data:`GROUND_STIFFNESS`, :data:`GROUND_DAMPING` at the built-in robot's
:data:`GROUND_MASS`) — what :func:`hexaleg.simulation.run.simulate` runs with."""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

from hexaleg.checks import integer, one_of, real
from hexaleg.config import from_mapping
from hexaleg.dynamics.contact import ContactParams
from hexaleg.simulation import balance
from hexaleg.simulation.controllers import COMPLIANCE, Servo
from hexaleg.simulation.ground import Ground

GROUND_MASS = 1.36366
"""kg: the built-in robot's mass, whose ground :data:`GROUND_STIFFNESS` and
:data:`GROUND_DAMPING` are (:meth:`Settings.sized` scales them to another robot's)."""
GROUND_STIFFNESS = 2e4
"""N/m per contact: a rubber-tipped foot on a hard floor, 0.2 mm under the 4.5 N of a tripod foot
of the built-in robot (:class:`~hexaleg.simulation.ground.Ground`)."""
GROUND_DAMPING = 100.0
"""N·s/m per contact: damping ratio ≈ 0.5 for the third of the built-in robot's mass a tripod
foot carries."""



@dataclass(frozen=True)
class Settings:
    """How to simulate (the ``[simulate]`` table of a config file; SI).

    Attributes:
        controller: ``"feedforward"`` or ``"position"``
            (:data:`hexaleg.simulation.controllers.CONTROLLERS`).
        timestep: s, > 0, below the gait's sample spacing; None (default): automatic, the least
            of :data:`~hexaleg.simulation.model.TIMESTEP`, half the gait's sample spacing
            and 80 % of the explicit-stability limit
            (:func:`hexaleg.simulation.timestep.automatic_timestep`). Rounded down so that a
            cycle is a whole number of steps.
        cycles: Cycles simulated, ≥ 2.
        evaluate: The last cycles evaluated, in [1, cycles − 1] (the others settle).
        stiffness: Ground contact stiffness K, N/m, > 0; None (default): sized to the robot,
            ``K₀ m / m₀`` (:meth:`sized`: the built-in robot's 2·10⁴ N/m scaled by the mass, so
            a foot sinks as far under its share of any robot's weight).
        damping: Ground contact damping B, N·s/m, ≥ 0; None (default): ``B₀ m / m₀`` (100
            N·s/m scaled: B ∝ √(K m) keeps the contact's damping ratio).
        mu: Friction coefficient, > 0; None: the analysis' (``ContactParams.mu``).
        noslip: MuJoCo's no-slip pass (no creep inside the friction cone).
        incline: Ground slope, rad (uphill along the heading > 0).
        feedback: Balance feedback (:mod:`hexaleg.simulation.balance`): ``"auto"`` (default)
            where the gait needs it — fewer than three planned stance feet at some instant, or
            an open-loop run that fell (both runs are then simulated again with it) —
            ``"on"`` or ``"off"`` (open loop: the servos track the plan alone).
        compliance: Servo compliance angle θ_c (kp = τ_s/θ_c), rad, > 0.
        kp_scale: Factor on kp, > 0.
        kd_scale: Factor on kd, > 0.
        force_samples: Steps at which the foot forces are compared with the analysis' (0: none).

    Raises:
        InvalidParameterError: a value out of range (named).
        UnknownNameError: an unknown controller (lists them).
    """

    controller: str = "feedforward"
    timestep: float | None = None
    cycles: int = 4
    evaluate: int = 2
    stiffness: float | None = None
    damping: float | None = None
    mu: float | None = None
    noslip: bool = False
    incline: float = 0.0
    feedback: str = "auto"
    compliance: float = COMPLIANCE
    kp_scale: float = 1.0
    kd_scale: float = 1.0
    force_samples: int = 200

    def __post_init__(self) -> None:
        if self.timestep is not None:
            real("timestep", self.timestep, low=0.0, low_open=True,
                 allowed="a finite timestep > 0 s (e.g. 0.0005), or none for the automatic one")
        self.servo()
        one_of("feedback", self.feedback, balance.MODES)
        self.ground(ContactParams().mu)
        integer("cycles", self.cycles, low=2, high=10_000)
        integer("evaluate", self.evaluate, low=1, high=self.cycles - 1)
        integer("force_samples", self.force_samples, low=0)

    def servo(self) -> Servo:
        """The servo of these settings."""
        return Servo(self.controller, self.compliance, self.kp_scale, self.kd_scale)

    def sized(self, mass: float) -> Settings:
        """These settings with the ground sized to a robot of ``mass`` kg where they leave it
        unset: ``K = K₀ m / m₀``, ``B = B₀ m / m₀`` with :data:`GROUND_STIFFNESS`,
        :data:`GROUND_DAMPING` for the built-in robot's :data:`GROUND_MASS` (the same sink
        ``m g / (n K)`` under the same feet, the same damping ratio ``B / (2 √(K m / n))``:
        Hunt–Crossley's linear limit, the spring-damper ground of MuJoCo's ``solref``)."""
        ratio = mass / GROUND_MASS
        return dataclasses.replace(
            self, stiffness=GROUND_STIFFNESS * ratio if self.stiffness is None else self.stiffness,
            damping=GROUND_DAMPING * ratio if self.damping is None else self.damping)

    def ground(self, mu: float) -> Ground:
        """The ground of these settings (``mu`` unless :attr:`mu` is set; an unsized stiffness
        or damping the built-in robot's, :meth:`sized` first for another robot)."""
        return Ground(GROUND_STIFFNESS if self.stiffness is None else self.stiffness,
                      GROUND_DAMPING if self.damping is None else self.damping,
                      mu if self.mu is None else self.mu, self.noslip, self.incline)

    @classmethod
    def from_mapping(cls, table: Any, where: str = "simulate") -> Settings:
        """From a TOML table (unknown keys are an error listing the valid ones)."""
        return from_mapping(cls, table, where)
