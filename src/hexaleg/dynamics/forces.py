"""Ground reaction forces of the stance feet, chosen by a convex program minimising motor energy.

The motion fixes ``b = M(q) a + h(q, v)`` (RNEA) at every sample, but not how the stance feet share
the load: with 3 feet there are 9 force components against the 6 base equations. For each sample
hexaleg picks the world-frame foot forces ``f`` (3 per stance foot) that solve::

    minimise   E(τ)                                   (the motor-energy objective below)
    subject to J_baseᵀ f = b_base                     (6 base rows: Newton–Euler of the robot)
               τ = b_joint − J_jointᵀ f − τ_spring    (joint rows: the motor torques)
               ‖(f_x, f_y)‖ ≤ μ f_z                    (Coulomb friction cone; or the inscribed
                                                        pyramid |f_x|, |f_y| ≤ μ f_z / √2)
               f_z ≥ f_min                            (unilateral contact, minimum normal force)
               |τ| ≤ τ_max                             (optional motor torque limits)

The samples are independent (the objective is a sum over time), so the program separates into one
small problem per sample. Objectives, all convex in ``f`` because ``τ`` is affine in ``f``:

- ``"joule"`` (default): Joule losses Σ_j c_j τ_j², ``c_j = R/(k_t G)²`` of joint j's motor. It is
  what a servo robot mostly spends (Seok et al., IEEE/ASME T-Mech 2013: 76 % of the MIT Cheetah's
  energy is motor heat), it is strictly convex (a unique answer) and it admits the exact fast path.
- ``"torque_squared"``: Σ_j τ_j² (identical forces to ``"joule"`` when every joint has the same
  motor).
- ``"electrical"``: electrical energy without regeneration
  Σ_j max(0, max(τ_j q̇_j / η, η τ_j q̇_j) + c_j τ_j²) + ε Σ_j τ_j² — the servo model of
  :meth:`hexaleg.robot.motor.Motor.electrical_power` (gearbox efficiency η by power-flow direction,
  Verstraten et al., RA-L 1(1) 2016; "positive electrical work" of Yesilevskiy & Remy, J.
  Mechanisms Robotics 10(3) 031008); the max is flat while a joint regenerates, so the same small
  regulariser ε makes the answer unique.
- ``"positive_work"``: positive mechanical work Σ_j max(0, τ_j q̇_j) + ε Σ_j τ_j²; the small
  regulariser ε makes the answer unique (same source).

Two solvers share these definitions:

- :func:`solve_fast` — the path sweeps use. For the quadratic objectives the equality-constrained
  least-squares solution is linear in the spring torques, ``f = f₀ − K τ_spring``, with per-sample
  gains ``K`` computed once per motion (:class:`QuadraticGains`); samples where that solution
  violates a friction, normal-force or torque-limit inequality are re-solved exactly with Clarabel
  (an interior-point conic solver), as are all samples of the non-quadratic objectives. Where no
  inequality binds, the unconstrained optimum is feasible and hence the optimum of the convex
  program: the fast path is exact, not an approximation.
- :func:`solve_reference` — the cvxpy formulation (parametrised, compiled once, DPP), solved per
  sample; slow, kept as the reference that the tests compare the fast path against.
"""

from __future__ import annotations

import dataclasses
import math
import warnings
from dataclasses import dataclass

import numpy as np

from hexaleg.errors import InfeasibleForcesError, InvalidParameterError, TorqueLimitError

OBJECTIVES: tuple[str, ...] = ("joule", "torque_squared", "electrical", "positive_work")
"""Names of the motor-energy objectives, default first."""
QUADRATIC_OBJECTIVES = ("joule", "torque_squared")
CONES: tuple[str, ...] = ("soc", "pyramid")
"""Friction models: the exact second-order cone, or the inscribed (inner) linear pyramid."""


@dataclass(frozen=True)
class ContactParams:
    """Contact and force-distribution settings.

    Attributes:
        mu: Coulomb friction coefficient, > 0 (default 0.6: rubber foot on a hard floor, assumed).
        cone: ``"soc"`` (exact cone) or ``"pyramid"`` (inscribed pyramid, an inner approximation).
        min_normal_force: Smallest normal force of a stance foot, N, ≥ 0.
        torque_limits: Constrain |τ_motor| to the URDF effort limits.
        regularization: ε of the ``"positive_work"`` objective, W/(N·m)², > 0.
    """

    mu: float = 0.6
    cone: str = "soc"
    min_normal_force: float = 0.0
    torque_limits: bool = True
    regularization: float = 1e-4

    def __post_init__(self) -> None:
        for name in ("mu", "min_normal_force", "regularization"):
            value = getattr(self, name)
            if not isinstance(value, (int, float)) or not math.isfinite(value):
                raise InvalidParameterError(f"ContactParams.{name}", value, "a finite number")
        if self.mu <= 0:
            raise InvalidParameterError("ContactParams.mu", self.mu, "> 0")
        if self.min_normal_force < 0:
            raise InvalidParameterError("ContactParams.min_normal_force", self.min_normal_force,
                                        ">= 0 N")
        if self.regularization <= 0:
            raise InvalidParameterError("ContactParams.regularization", self.regularization, "> 0")
        if self.cone not in CONES:
            raise InvalidParameterError("ContactParams.cone", self.cone, " or ".join(CONES))


def check_objective(objective: str) -> str:
    """Return ``objective`` if it is one of :data:`OBJECTIVES`.

    Raises:
        InvalidParameterError: otherwise; the message lists the objectives.
    """
    if objective not in OBJECTIVES:
        raise InvalidParameterError("objective", objective, "one of " + ", ".join(OBJECTIVES))
    return objective


@dataclass(frozen=True, eq=False)
class StanceSystem:
    """The spring-independent linear algebra of one motion, for the force program.

    Force vectors are padded to all legs: ``f`` has shape (T, 3 n_legs) with leg ``i``'s world
    force at ``f[:, 3i:3i+3]``; swing legs' columns of ``A`` and ``D`` are zero and their forces are
    zero.

    Attributes:
        stance: Stance mask, shape (T, n_legs), bool.
        A: Base rows ``J_baseᵀ``, shape (T, 6, 3 n_legs).
        D: Joint rows ``J_jointᵀ``, shape (T, nj, 3 n_legs).
        b_base: Base rows of ``M a + h``, shape (T, 6).
        b_joint: Joint rows of ``M a + h``, shape (T, nj), N·m.
        qdot: Joint velocities, shape (T, nj), rad/s.
        tau_max: Motor torque limits, shape (nj,), N·m.
        t: Sample times, shape (T,), s (for error messages).
        leg_names: Leg names, for error messages.
        joint_names: Joint names, for error messages.
        efficiency: Gearbox efficiency η of the motors, in (0, 1] (``"electrical"`` objective).
    """

    stance: np.ndarray
    A: np.ndarray
    D: np.ndarray
    b_base: np.ndarray
    b_joint: np.ndarray
    qdot: np.ndarray
    tau_max: np.ndarray
    t: np.ndarray
    leg_names: tuple[str, ...]
    joint_names: tuple[str, ...]
    efficiency: float = 1.0

    @property
    def n_samples(self) -> int:
        return int(self.stance.shape[0])

    def torques(self, f: np.ndarray, tau_spring: np.ndarray,
                rows: np.ndarray | slice = slice(None)) -> np.ndarray:
        """Motor torques ``b_joint − D f − τ_spring`` of samples ``rows``, for their forces ``f``
        (T', 3 n_legs) and spring torques (T', nj); shape (T', nj), N·m."""
        return self.b_joint[rows] - (self.D[rows] @ f[..., None])[..., 0] - tau_spring


@dataclass(frozen=True, eq=False)
class QuadraticGains:
    """Exact solution of the equality-constrained quadratic program, linear in the spring torques.

    For weights ``w`` (nj,) the minimiser of Σ_j w_j τ_j² subject to the base rows is
    ``f = K (b_joint − τ_spring) + L b_base``; this holds the per-sample ``K`` (T, 3 n_legs, nj),
    the rigid forces ``f₀ = K b_joint + L b_base`` (T, 3 n_legs), the rigid motor torques
    ``τ₀ = b_joint − D f₀`` (T, nj) and ``G = D K − I`` (T, nj, nj), so that with springs
    ``f = f₀ − K τ_s`` and ``τ = τ₀ + G τ_s`` — only the spring columns of ``K`` and ``G`` are
    touched. Derived from the KKT system ``[H Aᵀ; A 0] [f; λ] = [DᵀW c; b_base]`` with
    ``H = Dᵀ W D`` on the stance columns.
    """

    weights: np.ndarray
    K: np.ndarray
    f0: np.ndarray
    tau0: np.ndarray
    G: np.ndarray


def quadratic_gains(system: StanceSystem, weights: np.ndarray) -> QuadraticGains:
    """Compute :class:`QuadraticGains` for ``system`` and joint weights ``weights`` (nj,), > 0.

    Samples with the same stance pattern are solved as one batch (``numpy.linalg.solve`` on
    stacked KKT matrices).
    """
    T, n_legs = system.stance.shape
    nj = system.D.shape[1]
    K = np.zeros((T, 3 * n_legs, nj))
    L = np.zeros((T, 3 * n_legs, 6))
    patterns, inverse = np.unique(system.stance, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    for p, pattern in enumerate(patterns):
        rows = np.flatnonzero(inverse == p)
        if not pattern.any():
            continue
        cols = np.flatnonzero(np.repeat(pattern, 3))
        n = cols.size
        D = system.D[rows][:, :, cols]  # (Tg, nj, n)
        A = system.A[rows][:, :, cols]  # (Tg, 6, n)
        H = np.einsum("tjk,j,tjl->tkl", D, weights, D)
        kkt = np.zeros((rows.size, n + 6, n + 6))
        kkt[:, :n, :n] = H
        kkt[:, :n, n:] = np.transpose(A, (0, 2, 1))
        kkt[:, n:, :n] = A
        rhs = np.zeros((rows.size, n + 6, nj + 6))
        rhs[:, :n, :nj] = np.transpose(D, (0, 2, 1)) * weights  # DᵀW
        rhs[:, n:, nj:] = np.eye(6)
        sv = np.linalg.svd(A, compute_uv=False)
        if np.all(sv[:, -1] > 1e-9 * sv[:, 0]):
            sol = np.linalg.solve(kkt, rhs)
        else:
            # Rank-deficient base rows (e.g. two point feet cannot push any moment about the line
            # through them): f is still unique where the base wrench is reachable; the
            # pseudo-inverse gives it, and solve_fast rejects samples whose base rows then fail.
            sol = np.linalg.pinv(kkt, rcond=1e-10) @ rhs
        K[np.ix_(rows, cols, np.arange(nj))] = sol[:, :n, :nj]
        L[np.ix_(rows, cols, np.arange(6))] = sol[:, :n, nj:]
    f0 = np.einsum("tkj,tj->tk", K, system.b_joint) + np.einsum("tki,ti->tk", L, system.b_base)
    G = system.D @ K - np.eye(nj)
    return QuadraticGains(np.asarray(weights, dtype=float).copy(), K, f0,
                          system.torques(f0, np.zeros_like(system.b_joint)), G)


def violations(system: StanceSystem, f: np.ndarray, tau: np.ndarray, contact: ContactParams,
               tol: float = 1e-9) -> np.ndarray:
    """Which samples' forces/torques break an inequality of the program, shape (T,), bool."""
    T, n_legs = system.stance.shape
    f3 = f.reshape(T, n_legs, 3)
    fz = f3[..., 2]
    st = system.stance
    bad = np.any(st & (fz < contact.min_normal_force - tol), axis=1)
    if contact.cone == "soc":
        slack = contact.mu * fz - np.hypot(f3[..., 0], f3[..., 1])
    else:
        slack = contact.mu / math.sqrt(2) * fz - np.maximum(np.abs(f3[..., 0]), np.abs(f3[..., 1]))
    bad |= np.any(st & (slack < -tol), axis=1)
    if contact.torque_limits:
        bad |= np.any(np.abs(tau) > system.tau_max + tol, axis=1)
    return bad


CLARABEL_TOLERANCES = (1e-11, 1e-10, 1e-9, 1e-8, 1e-7)
"""Clarabel gap and feasibility tolerances (absolute and relative) tried in turn, by the exact
per-sample solves and by the cvxpy reference, until one is met: an "almost solved" answer at the
loosest is an error, never a silent result."""


def _solve_sample(system: StanceSystem, k: int, tau_spring: np.ndarray, objective: str,
                  weights: np.ndarray, contact: ContactParams) -> np.ndarray:
    """Solve sample ``k``'s program exactly with Clarabel; returns f padded to (3 n_legs,)."""
    import clarabel
    import scipy.sparse as sp

    pattern = system.stance[k]
    cols = np.flatnonzero(np.repeat(pattern, 3))
    n = cols.size
    nj = system.D.shape[1]
    D = system.D[k][:, cols]
    A = system.A[k][:, cols]
    c = system.b_joint[k] - tau_spring[k]  # τ = c − D f
    qd = system.qdot[k]
    # Epigraph variables after f: s (nj), the per-joint cost; and for "electrical" u (nj), an
    # upper bound of the Joule loss c_w τ² (one rotated cone per joint, shared by both gearbox
    # branches).
    n_epi = {"positive_work": nj, "electrical": 2 * nj}.get(objective, 0)
    nx = n + n_epi
    P = np.zeros((nx, nx))
    q = np.zeros(nx)
    if objective in QUADRATIC_OBJECTIVES:
        w = weights
    else:  # the non-smooth objectives' regulariser ε Σ τ²
        w = np.full(nj, contact.regularization)
    P[:n, :n] = 2 * D.T @ (w[:, None] * D)
    q[:n] = -2 * D.T @ (w * c)
    q[n:n + nj] = 1.0 if n_epi else 0.0
    rows: list[np.ndarray] = []
    rhs: list[np.ndarray] = []
    cones: list = []

    def add(Arows: np.ndarray, b: np.ndarray, cone) -> None:
        rows.append(Arows)
        rhs.append(b)
        cones.append(cone)

    def pad(m: np.ndarray) -> np.ndarray:  # rows on f → rows on x
        return np.hstack([m, np.zeros((m.shape[0], n_epi))])

    # Base rows, reduced to their row space: two point feet give only 5 independent rows, and
    # an interior-point solver stalls on redundant equalities. The part of the base wrench
    # outside that space is what no forces can produce.
    u, sv, _ = np.linalg.svd(A, full_matrices=False)
    rank = int(np.sum(sv > 1e-9 * sv[0]))
    b_in = u[:, :rank].T @ system.b_base[k]
    missing = float(np.linalg.norm(system.b_base[k] - u[:, :rank] @ b_in))
    if missing > 1e-8 * (1.0 + np.abs(system.b_base[k]).max()):
        _raise_unreachable(system, k, missing)
    add(pad(u[:, :rank].T @ A), b_in, clarabel.ZeroConeT(rank))
    n_st = n // 3
    ez = np.zeros((n_st, n))
    ez[np.arange(n_st), 3 * np.arange(n_st) + 2] = 1.0
    add(pad(-ez), np.full(n_st, -contact.min_normal_force), clarabel.NonnegativeConeT(n_st))
    for i in range(n_st):
        e = np.zeros((3, n))
        e[0, 3 * i + 2], e[1, 3 * i], e[2, 3 * i + 1] = 1.0, 1.0, 1.0
        if contact.cone == "soc":
            m = e.copy()
            m[0] *= contact.mu
            add(pad(-m), np.zeros(3), clarabel.SecondOrderConeT(3))
        else:
            s = contact.mu / math.sqrt(2)
            m = np.array([s * e[0] - e[1], s * e[0] + e[1], s * e[0] - e[2], s * e[0] + e[2]])
            add(pad(-m), np.zeros(4), clarabel.NonnegativeConeT(4))
    if contact.torque_limits:
        # τ ≤ τmax:  −D f ≤ τmax − c ;  −τ ≤ τmax:  D f ≤ τmax + c
        add(pad(np.vstack([-D, D])), np.concatenate([system.tau_max - c, system.tau_max + c]),
            clarabel.NonnegativeConeT(2 * nj))
    if n_epi:
        eye, zero = np.eye(nj), np.zeros((nj, nj))
        u_cols = [zero] if objective == "electrical" else []
        # s ≥ 0
        add(np.hstack([np.zeros((nj, n)), -eye, *u_cols]), np.zeros(nj),
            clarabel.NonnegativeConeT(nj))
        if objective == "positive_work":
            # s ≥ q̇ τ = q̇ (c − D f)  ⇔  −q̇ D f − s ≤ −q̇ c
            add(np.hstack([-qd[:, None] * D, -eye]), -qd * c, clarabel.NonnegativeConeT(nj))
        else:
            # s ≥ κ q̇ τ + u for κ = 1/η and κ = η  ⇔  −κ q̇ D f − s + u ≤ −κ q̇ c
            for kappa in sorted({1.0 / system.efficiency, system.efficiency}):
                add(np.hstack([-kappa * qd[:, None] * D, -eye, eye]), -kappa * qd * c,
                    clarabel.NonnegativeConeT(nj))
            # u ≥ c_w τ² ⇔ ‖(2√c_w τ, u − 1)‖ ≤ u + 1 (a rotated cone as a second-order cone);
            # Clarabel form: b − A x = (u + 1, 2√c_w τ, u − 1) with τ = c − D f.
            for j in range(nj):
                e_u = np.zeros(nx)
                e_u[n + nj + j] = 1.0
                row_f = np.zeros(nx)
                row_f[:n] = D[j]
                sw = 2 * math.sqrt(weights[j])
                add(np.vstack([-e_u, sw * row_f, -e_u]), np.array([1.0, sw * c[j], -1.0]),
                    clarabel.SecondOrderConeT(3))
    Amat = sp.csc_matrix(np.vstack(rows))
    bvec = np.concatenate(rhs)
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    settings.max_iter = 200
    for tol in CLARABEL_TOLERANCES:  # the tightest tolerances Clarabel meets; never "almost"
        settings.tol_gap_abs = settings.tol_gap_rel = settings.tol_feas = tol
        settings.tol_ktratio = 100 * tol
        solution = clarabel.DefaultSolver(sp.csc_matrix(np.triu(P)), q, Amat, bvec, cones,
                                          settings).solve()
        status = str(solution.status)
        if status != "AlmostSolved":
            break
    if status != "Solved":
        _raise_infeasible(system, k, tau_spring, contact, status)
    f = np.zeros(3 * pattern.size)
    f[cols] = np.asarray(solution.x)[:n]
    return f


def _raise_infeasible(system: StanceSystem, k: int, tau_spring: np.ndarray,
                      contact: ContactParams, status: str) -> None:
    feet = [system.leg_names[i] for i in np.flatnonzero(system.stance[k])]
    where = f"t = {system.t[k]:.4f} s (sample {k}), stance feet {', '.join(feet) or '(none)'}"
    if contact.torque_limits:
        # Without the torque limits: if forces exist then, the limits are what failed.
        relaxed = dataclasses.replace(contact, torque_limits=False)
        try:
            f = _solve_sample(system, k, tau_spring, "torque_squared",
                              np.ones(system.D.shape[1]), relaxed)
        except InfeasibleForcesError:
            f = None
        if f is not None:
            tau = system.b_joint[k] - system.D[k] @ f - tau_spring[k]
            j = int(np.argmax(np.abs(tau) - system.tau_max))
            if abs(tau[j]) > system.tau_max[j]:
                raise TorqueLimitError(
                    f"motor torque limit exceeded at {where}: joint {system.joint_names[j]} "
                    f"needs |τ| = {abs(tau[j]):.4f} N·m (limit {system.tau_max[j]:.4f} N·m) "
                    f"with the friction-feasible forces of least Σ τ², and no forces keep every "
                    f"joint within its limit; solver status {status}")
    raise InfeasibleForcesError(
        f"no contact forces satisfy the dynamics at {where} with friction μ = {contact.mu} "
        f"({contact.cone}) and normal force ≥ {contact.min_normal_force} N; solver status {status}")


def _check_base_rows(system: StanceSystem, f: np.ndarray) -> None:
    """Raise InfeasibleForcesError at the first sample whose stance feet cannot produce the base
    wrench at all (the equality-constrained solution ``f`` (T, 3 n_legs) misses the base rows)."""
    residual = np.abs((system.A @ f[..., None])[..., 0] - system.b_base).max(axis=1)
    scale = 1.0 + np.abs(system.b_base).max(axis=1)
    bad = np.flatnonzero(residual > 1e-8 * scale)
    if bad.size:
        _raise_unreachable(system, int(bad[0]), float(residual[bad[0]]))


def _raise_unreachable(system: StanceSystem, k: int, residual: float) -> None:
    """Raise InfeasibleForcesError: sample ``k``'s base wrench is out of its feet's reach."""
    feet = [system.leg_names[i] for i in np.flatnonzero(system.stance[k])]
    raise InfeasibleForcesError(
        f"the stance feet {', '.join(feet) or '(none)'} cannot produce the base wrench at "
        f"t = {system.t[k]:.4f} s (sample {k}) with any forces: the best forces miss the "
        f"base rows by {residual:.3g} (N, N·m); e.g. two point feet cannot push a moment about "
        "the line through them — the motion needs a body sway that balances it")


def solve_fast(system: StanceSystem, tau_spring: np.ndarray, objective: str,
               weights: np.ndarray, contact: ContactParams,
               gains: QuadraticGains | None = None) -> tuple[np.ndarray, np.ndarray]:
    """Optimal foot forces for every sample (fast exact path).

    Args:
        system: The motion's stance system.
        tau_spring: Spring torques on the joints, shape (T, nj), N·m.
        objective: One of :data:`OBJECTIVES`.
        weights: Joule coefficients ``c_j`` (``"joule"``, ``"electrical"``) or ones
            (``"torque_squared"``), shape (nj,), W/(N·m)².
        contact: Contact settings.
        gains: Precomputed :func:`quadratic_gains` for these weights (quadratic objectives).

    Returns:
        ``(f, tau, resolved)``: forces (T, 3 n_legs), N, world frame; motor torques (T, nj), N·m;
        and the mask (T,) of samples that needed the exact conic solve.

    Raises:
        InfeasibleForcesError: no forces satisfy a sample's constraints (names time and feet).
        TorqueLimitError: the torque limits cannot be met (names joint, time, torque).
    """
    T = system.n_samples
    if objective in QUADRATIC_OBJECTIVES:
        if gains is None:
            gains = quadratic_gains(system, weights)
        cols = np.flatnonzero(np.any(tau_spring != 0.0, axis=0))  # joints with a spring
        ts = tau_spring[:, cols, None]
        f = gains.f0 - (gains.K[:, :, cols] @ ts)[..., 0]
        tau = gains.tau0 + (gains.G[:, :, cols] @ ts)[..., 0]
        _check_base_rows(system, f)
        bad = violations(system, f, tau, contact)
    else:
        f = np.zeros((T, system.A.shape[2]))
        bad = system.stance.any(axis=1)
    for k in np.flatnonzero(bad):
        f[k] = _solve_sample(system, int(k), tau_spring, objective, weights, contact)
    if objective not in QUADRATIC_OBJECTIVES:
        tau = system.torques(f, tau_spring)
    elif bad.any():
        tau[bad] = system.torques(f[bad], tau_spring[bad], bad)
    return f, tau, bad


def solve_reference(system: StanceSystem, tau_spring: np.ndarray, objective: str,
                    weights: np.ndarray, contact: ContactParams,
                    samples: np.ndarray | None = None) -> np.ndarray:
    """Optimal foot forces by the cvxpy reference formulation, one solve per sample.

    The problem is built once with parameters (DPP) for all legs — swing legs' forces are pinned
    to zero by a mask parameter — and re-solved per sample with Clarabel at tight tolerances
    (:data:`CLARABEL_TOLERANCES`, the tightest one Clarabel reaches; an "inaccurate" status at
    the loosest one is an error, never a silent answer).

    Args:
        system, tau_spring, objective, weights, contact: As for :func:`solve_fast`.
        samples: Indices to solve (default all); other rows of the result are NaN.

    Returns:
        Forces, shape (T, 3 n_legs), N.
    """
    import cvxpy as cp

    T, n_legs = system.stance.shape
    nj, nf = system.D.shape[1], 3 * n_legs
    f = cp.Variable(nf)
    A = cp.Parameter((6, nf))
    D = cp.Parameter((nj, nf))
    bb = cp.Parameter(6)
    c = cp.Parameter(nj)
    qd = cp.Parameter(nj)
    qd_in, qd_out = cp.Parameter(nj), cp.Parameter(nj)  # q̇/η and η q̇ (electrical)
    mask = cp.Parameter(nf, nonneg=True)
    fmin = cp.Parameter(n_legs, nonneg=True)
    tau = cp.Variable(nj)  # a variable pinned to c − D f keeps q̇ ⊙ τ parameter-affine (DPP)
    w = np.asarray(weights, dtype=float)
    if objective in QUADRATIC_OBJECTIVES:
        cost = cp.sum(cp.multiply(w, cp.square(tau)))
    elif objective == "electrical":
        gearbox = cp.maximum(cp.multiply(qd_in, tau), cp.multiply(qd_out, tau))
        cost = (cp.sum(cp.maximum(0, gearbox + cp.multiply(w, cp.square(tau))))
                + contact.regularization * cp.sum_squares(tau))
    else:
        cost = (cp.sum(cp.maximum(0, cp.multiply(qd, tau)))
                + contact.regularization * cp.sum_squares(tau))
    fx, fy, fz = f[0::3], f[1::3], f[2::3]
    cons = [tau == c - D @ f, A @ f == bb, cp.multiply(1 - mask, f) == 0, fz >= fmin]
    if contact.cone == "soc":
        cons += [cp.norm(cp.vstack([fx[i], fy[i]])) <= contact.mu * fz[i] for i in range(n_legs)]
    else:
        s = contact.mu / math.sqrt(2)
        cons += [cp.abs(fx) <= s * fz, cp.abs(fy) <= s * fz]
    if contact.torque_limits:
        cons += [cp.abs(tau) <= system.tau_max]
    problem = cp.Problem(cp.Minimize(cost), cons)
    assert problem.is_dcp(dpp=True)
    out = np.full((T, nf), np.nan)
    for k in range(T) if samples is None else samples:
        m = np.repeat(system.stance[k], 3).astype(float)
        A.value, D.value, bb.value = system.A[k], system.D[k], system.b_base[k]
        c.value = system.b_joint[k] - tau_spring[k]
        qd.value = system.qdot[k]
        qd_in.value = system.qdot[k] / system.efficiency
        qd_out.value = system.qdot[k] * system.efficiency
        mask.value = m
        fmin.value = contact.min_normal_force * system.stance[k].astype(float)
        # Tight tolerances first; where Clarabel stalls short of them ("inaccurate"), loosen
        # step by step and keep the first solve that meets its own tolerances.
        for tol in CLARABEL_TOLERANCES:
            with warnings.catch_warnings():
                warnings.filterwarnings("ignore", message="Solution may be inaccurate")
                problem.solve(solver=cp.CLARABEL, tol_gap_abs=tol, tol_gap_rel=tol, tol_feas=tol,
                              tol_ktratio=100 * tol, max_iter=200)
            if problem.status != cp.OPTIMAL_INACCURATE:
                break
        if problem.status != cp.OPTIMAL:
            _raise_infeasible(system, int(k), tau_spring, contact, str(problem.status))
        out[k] = f.value * m
    return out
