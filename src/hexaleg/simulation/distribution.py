"""The balance controller's force distribution: the change of the stance feet's forces that best
makes a change of the body's wrench, inside the friction cones.

Given the planned forces ``f⁰_i`` (world, N) of the n stance feet, the wrench map ``A`` (6, 3n)
(``[I … I; [r₁]× … [r_n]×]``, ``r_i`` the foot from the centre of mass, m) and the wrench change
``ΔW`` (6,) (force N, moment N·m) the body's feedback asks for, the correction ``Δf`` (3n,) is

    minimise   ‖S (A Δf − ΔW)‖² + α ‖Δf‖²
    subject to ‖(f⁰_i + Δf_i)_t‖ ≤ μ (f⁰_i + Δf_i)_z        (each stance foot's friction cone)
               τ_low ≤ T Δf ≤ τ_high                          (the actuators' torques)

— the balance controller's quadratic program of Di Carlo et al. (Cheetah 3 / Mini Cheetah,
"Dynamic locomotion in the MIT Cheetah 3 through convex model-predictive control", IROS 2018,
§III, the single-step "balance controller" it builds on: Focchi et al., "High-slope terrain
locomotion for torque-controlled quadruped robots", Auton. Robots 41, 2017, eq. 5), written
for the change from the plan: with ``ΔW = 0`` the answer is ``Δf = 0``, the plan's forces.
``S = diag(1, 1, 1, 1/L, 1/L, 1/L)`` puts the moment rows in newtons (L the feet's spread, m)
and ``α`` (dimensionless) makes the program strictly convex where two feet leave a moment
about the line through them uncontrollable (the least-norm correction then). ``T`` maps the
force correction to the joint torques' (``Δτ = −J_cᵀ Δf``), and ``τ_low, τ_high`` are the
stall torques less the plan's (``±τ_s − τ⁰``): the torque limits of a whole-body controller
(Kim et al. 2019, WBIC's QP, eq. 20; Del Prete's TSID), so the correction never asks a servo
for more than it has.

The cones are elliptic, as MuJoCo's ground (``cone="elliptic"``) and the analysis' ``"soc"``
cone. The program is solved exactly in two ways: its unconstrained minimiser
``Δf = (AᵀS²A + αI)⁻¹ AᵀS² ΔW`` (the normal equations) is the constrained one whenever it lies
inside every cone (a convex program's unconstrained minimiser that is feasible is optimal), which
is the common case; otherwise Clarabel solves the second-order cone program (Goulart & Chen,
"Clarabel: an interior-point solver for conic programs with quadratic objectives", 2024).
The plan is within its cones and the actuators' limits, so ``Δf = 0`` is feasible and the
program has its unique solution; where the simulated ground's μ is below the plan's (``[simulate]
mu``) a plan's force may lie outside its cone, and if the torque rows then leave no feasible
point the program is solved without them (zero force, ``Δf = −f⁰``, is in every cone).
``tests/simulation/test_distribution.py`` checks it against cvxpy.

**Units of the solve.** Clarabel is given the program in units of the plan's largest foot
force F (N): ``Δf = F y``, the cones' and the torque rows' offsets divided by F and the
objective by F² — the same program (the cones are homogeneous, the rows linear, the objective's
minimiser unchanged), with offsets and an optimum of order one. In newtons it need not
converge: Clarabel's equilibration (Ruiz's, on the constraint matrix and the quadratic term)
leaves the offsets and the linear term unscaled, and on an 80-kg robot (HyQ from
example-robot-data, offsets ~500 N, linear term ~3000 N, objective ~2e6 N²) its iterates cycled
between two points at a relative gap of 4e-2 until the iteration limit (200) — at a stand of
two feet where a cone and the torque rows bind, and cvxpy's and SCS's answers agree to 1e-3 N.
In units of F (tolerances :data:`TOLERANCE` there) it solves that program in 9 iterations.
"""

from __future__ import annotations

import functools
from dataclasses import dataclass

import numpy as np

from hexaleg.errors import InvalidParameterError

REGULARISATION = 1e-3
"""α: the weight of ‖Δf‖² against the wrench error (both in N²)."""
TOLERANCE = 1e-11
"""Clarabel's gap and feasibility tolerances, in units of the plan's largest foot force (module
docstring): at 1e-9 there the captured instants' corrections were 2e-5 N from cvxpy's, their
cones 3e-5 N short of tight; at 1e-11, 1.4e-7 N."""


def wrench_map(feet: np.ndarray, com: np.ndarray) -> np.ndarray:
    """``A`` (6, 3n): the total force and the moment about ``com`` of forces at ``feet``.

    Args:
        feet: Foot positions (world), shape (n, 3), m.
        com: Centre of mass (world), shape (3,), m.
    """
    r = np.asarray(feet, dtype=float) - np.asarray(com, dtype=float)
    n = len(r)
    a = np.zeros((6, n, 3))
    a[0, :, 0] = a[1, :, 1] = a[2, :, 2] = 1.0
    a[3, :, 1], a[3, :, 2] = -r[:, 2], r[:, 1]  # [r]×: the moment r × f
    a[4, :, 0], a[4, :, 2] = r[:, 2], -r[:, 0]
    a[5, :, 0], a[5, :, 1] = -r[:, 1], r[:, 0]
    return a.reshape(6, 3 * n)


def inside_cones(f: np.ndarray, mu: float, slack: float = 0.0) -> bool:
    """Whether every foot force of ``f`` (n, 3) is inside its friction cone ``‖f_t‖ ≤ μ f_z``
    (up to ``slack`` N)."""
    f = np.asarray(f).reshape(-1, 3)
    return bool((np.hypot(f[:, 0], f[:, 1]) <= mu * f[:, 2] + slack).all())


@dataclass(frozen=True)
class TorqueBounds:
    """The actuators' rows of the program: ``low ≤ T Δf ≤ high``.

    Attributes:
        t: T, shape (m, 3n): the joint torques' change per force change, N·m/N.
        low: Shape (m,), N·m, ≤ 0 where the plan is feasible. high: Shape (m,), N·m, ≥ 0.
    """

    t: np.ndarray
    low: np.ndarray
    high: np.ndarray

    def holds(self, df: np.ndarray, slack: float = 0.0) -> bool:
        """Whether ``Δf`` (3n,) keeps every torque within its bounds (up to ``slack`` N·m)."""
        tau = self.t @ np.ravel(df)
        return bool((tau <= self.high + slack).all() and (tau >= self.low - slack).all())


def distribute(a: np.ndarray, dw: np.ndarray, f0: np.ndarray, mu: float, spread: float,
               bounds: TorqueBounds | None = None, alpha: float = REGULARISATION
               ) -> tuple[np.ndarray, bool]:
    """The force correction of the module's program.

    Args:
        a: Wrench map (6, 3n) (:func:`wrench_map`).
        dw: Wrench change (6,): force N, moment about the centre of mass N·m.
        f0: Planned forces of the stance feet (n, 3), N, world.
        mu: Friction coefficient, > 0.
        spread: L, m, > 0: the moment rows' scale.
        bounds: The actuators' rows, or None (none).
        alpha: α, > 0.

    Returns:
        ``(Δf (n, 3), constrained)``: the correction, and whether a cone or a torque bound it
        (Clarabel solved it) rather than the normal equations.

    Raises:
        InvalidParameterError: μ, L or α not > 0, or shapes that do not match.
        SimulationError: Clarabel failed (it cannot on this program: it is always feasible).
    """
    f0 = np.asarray(f0, dtype=float).reshape(-1, 3)
    n = len(f0)
    if a.shape != (6, 3 * n) or np.shape(dw) != (6,):
        raise InvalidParameterError("force distribution shapes", (a.shape, np.shape(dw)),
                                    f"(6, {3 * n}) and (6,) for {n} stance feet")
    for name, value in (("mu", mu), ("spread", spread), ("alpha", alpha)):
        if not value > 0:
            raise InvalidParameterError(f"force distribution {name}", value, "> 0")
    if n == 0:
        return np.zeros((0, 3)), False
    s = np.ones(6)
    s[3:] = 1.0 / spread
    sa = a * s[:, None]
    h = sa.T @ sa + _ridge(alpha, 3 * n)
    g = sa.T @ (s * dw)
    df = np.linalg.solve(h, g).reshape(n, 3)
    if inside_cones(f0 + df, mu) and (bounds is None or bounds.holds(df)):
        return df, False
    return _conic(h, g, f0, mu, bounds), True


@functools.lru_cache(maxsize=64)
def _ridge(alpha: float, size: int) -> np.ndarray:
    """``α I`` (size, size), read-only: the same matrix at every update of a controller."""
    out = alpha * np.eye(size)
    out.flags.writeable = False
    return out


def _conic(h: np.ndarray, g: np.ndarray, f0: np.ndarray, mu: float,
           bounds: TorqueBounds | None) -> np.ndarray:
    """``min ½ xᵀ H x − gᵀ x`` over the cones of ``f0 + x`` and the torque bounds with Clarabel
    (its form: ``b − A x`` in the cones: ``(μ (f0_z + x_z), f0_x + x_x, f0_y + x_y)`` in a
    second-order cone, ``high − T x`` and ``T x − low`` non-negative)."""
    import clarabel
    import scipy.sparse as sp

    from hexaleg.errors import SimulationError

    n = len(f0)
    scale = max(float(np.max(np.linalg.norm(f0, axis=1), initial=0.0)), 1.0)  # F, N (docstring)
    rows = np.zeros((3 * n, 3 * n))
    b = np.zeros(3 * n)
    for i, f in enumerate(f0):
        rows[3 * i, 3 * i + 2] = -mu
        rows[3 * i + 1, 3 * i] = -1.0
        rows[3 * i + 2, 3 * i + 1] = -1.0
        b[3 * i:3 * i + 3] = (mu * f[2], f[0], f[1])
    cones = [clarabel.SecondOrderConeT(3)] * n
    if bounds is not None and len(bounds.t):
        rows = np.vstack([rows, bounds.t, -bounds.t])
        b = np.r_[b, bounds.high, -bounds.low]
        cones.append(clarabel.NonnegativeConeT(2 * len(bounds.t)))
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    settings.tol_gap_abs = settings.tol_gap_rel = settings.tol_feas = TOLERANCE
    solver = clarabel.DefaultSolver(sp.csc_matrix(np.triu(h)), -g / scale,
                                    sp.csc_matrix(rows), b / scale, cones, settings)
    solution = solver.solve()
    if "Infeasible" in str(solution.status) and bounds is not None:
        return _conic(h, g, f0, mu, None)
    if str(solution.status) not in ("Solved", "AlmostSolved"):
        rows_said = ("with the servos' torque rows" if bounds is not None
                     else "without torque rows, where it is always feasible")
        raise SimulationError(f"the balance controller's force program: Clarabel {solution.status}"
                              f" on {n} contact points {rows_said} (report this)")
    return scale * np.asarray(solution.x).reshape(n, 3)
