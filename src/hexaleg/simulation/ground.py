"""The ground contact in physical units, and how it maps onto MuJoCo's soft constraints.

A contact is a spring–damper normal to the ground with Coulomb friction:
``f_n = K δ + B δ̇`` (δ the penetration, m) and ``|f_t| ≤ μ f_n``; the analysis' feet are the
limit K → ∞ with sticking friction. MuJoCo computes contact forces from a soft-constraint model
instead (MuJoCo documentation, "Computation → Soft constraints" and "Modeling → Solver
parameters"): for one scalar constraint with impedance d, reference acceleration
``a_ref = −b v − k r`` and regulariser ``R = (1 − d)/d · Â`` (Â MuJoCo's approximation of the
constraint-space inverse inertia, frozen at ``qpos0``), the force is
``f = (A + R)⁻¹ (a_ref − a_u)``. With the "direct" ``solref = (−k₀, −b₀)`` and a constant
impedance ``solimp = (d, d, …)``, MuJoCo uses ``k = k₀ / d`` and ``b = b₀ / d``
(``engine_core_constraint.c``, ``mj_makeImpedance``). Choosing

    k₀ = K (1 − d) Â,        b₀ = B (1 − d) Â

gives, with ε = d A / ((1 − d) Â),

    (1 + ε) m a_c = −K δ − B δ̇ + m a_u       (m = 1/A the effective mass),

i.e. the physical spring–damper up to an added mass ε ≈ d/(1 − d) (1 % at the default
:data:`IMPEDANCE` d = 0.01), and the static deflection exactly ``f/K`` for any d. ``Â`` is
``body_invweight0`` of the contacting body (the ground is the world: 0), read from the compiled
model. Friction rows have no stiffness; with ``impratio`` ρ their regulariser is ``R/ρ``
(MuJoCo: "ratio of frictional-to-normal constraint impedance") and their damping
``b_t = −solreffriction[1] / d``; while the force is inside the cone a slip velocity decays with
rate b_t and a steady tangential load f_t creeps at ``v = (R/ρ) f_t / b_t`` — with the defaults
(ρ = :data:`IMPRATIO`, 1/b_t = :data:`FRICTION_TIMECONST`) a fraction of a millimetre per second
per newton. ``noslip`` adds MuJoCo's no-slip pass (``noslip_iterations``), which re-solves the
friction forces as hard constraints and removes that creep.

The foot is a sphere of radius :data:`FOOT_RADIUS` centred on the foot frame, with contact margin
−r: the constraint acts on the foot *point*'s height (MuJoCo "margin and gap"), as in the
analysis, and the force's lever arm about the foot point (r) is negligible.
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from hexaleg.checks import nonnegative, positive, real
from hexaleg.errors import InvalidParameterError

IMPEDANCE = 0.01
"""MuJoCo constraint impedance d of every ground contact (small: the soft, penalty-like regime
in which ``solref`` maps exactly onto a physical spring–damper; module docstring)."""
IMPRATIO = 1e4
"""MuJoCo ``impratio``: friction rows 10⁴ times harder than the normal ones (sticking feet)."""
FRICTION_TIMECONST = 2e-3
"""s: 1/b_t, the decay time of a foot's slip velocity inside the friction cone."""
FOOT_RADIUS = 1e-4
"""m: radius of a foot's contact sphere (a point foot for the contact geometry)."""


@dataclass(frozen=True)
class Ground:
    """The ground: contact stiffness, damping and friction in physical units, and its slope.

    Attributes:
        stiffness: K, N/m per contact, > 0 (default 2·10⁴: a rubber-tipped foot on a hard
            floor, 0.2 mm under the 4.5 N of a tripod foot of the built-in robot).
        damping: B, N·s/m per contact, ≥ 0 (default 100: damping ratio ≈ 0.5 for the third of
            the built-in robot's mass a tripod foot carries).
        mu: Coulomb friction coefficient, > 0 (default 0.6, the analysis' default
            :class:`~hexaleg.dynamics.contact.ContactParams`).
        noslip: Run MuJoCo's no-slip pass (feet do not creep inside the friction cone).
        incline: Slope of the ground, rad, in (−π/2, π/2): positive walks uphill along the
            robot's heading (gravity tilted in the ground frame).

    Raises:
        InvalidParameterError: a value out of its range (named).
    """

    stiffness: float = 2e4
    damping: float = 100.0
    mu: float = 0.6
    noslip: bool = False
    incline: float = 0.0

    def __post_init__(self) -> None:
        positive("ground.stiffness (N/m)", self.stiffness)
        nonnegative("ground.damping (N·s/m)", self.damping)
        positive("ground.mu", self.mu)
        real("ground.incline (rad)", self.incline, low=-np.pi / 2, high=np.pi / 2,
             low_open=True, high_open=True)
        if not isinstance(self.noslip, bool):
            raise InvalidParameterError("ground.noslip", self.noslip, "true or false")

    def solref(self, inverse_weight: float) -> tuple[float, float]:
        """MuJoCo ``solref`` (direct form) of a contact with a body of ``body_invweight0``
        ``inverse_weight`` (1/kg): ``(−K (1−d) Â, −B (1−d) Â)``."""
        scale = (1.0 - IMPEDANCE) * inverse_weight
        return -self.stiffness * scale, -self.damping * scale

    @staticmethod
    def solreffriction() -> tuple[float, float]:
        """MuJoCo ``solreffriction`` (direct form): no stiffness, damping b_t d."""
        return 0.0, -IMPEDANCE / FRICTION_TIMECONST

    @staticmethod
    def solimp() -> tuple[float, float, float, float, float]:
        """MuJoCo ``solimp``: the constant impedance :data:`IMPEDANCE`."""
        return IMPEDANCE, IMPEDANCE, 0.001, 0.5, 2.0

    def gravity(self, heading: np.ndarray, g: float) -> np.ndarray:
        """Gravity in the ground frame, (3,), m/s²: ``−g (cos α ẑ + sin α h)``."""
        h = np.asarray(heading, dtype=float)
        return -g * (np.cos(self.incline) * np.array([0.0, 0.0, 1.0]) + np.sin(self.incline) * h)

    def explicit_rate(self, mass: float) -> tuple[float, float]:
        """``(K/m, B/m)``: the contact's stiffness and damping per unit of the ``mass`` (kg) its
        foot point moves (1/s², 1/s; :mod:`~hexaleg.simulation.foot_mass`), for the
        explicit-integration check of :func:`hexaleg.simulation.model.check_timestep`. The
        physical K and B act on the true mass whatever ``Â`` sized ``solref`` (module
        docstring: the force is ``−K δ − B δ̇`` up to the added mass ε)."""
        return self.stiffness / mass, self.damping / mass
