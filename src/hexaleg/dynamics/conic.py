"""The exact per-sample solve of the force program (:mod:`hexaleg.dynamics.contact`) with Clarabel.

One sample's program on its stance columns is written in Clarabel's conic form (an interior-point
conic solver): the base rows as a zero cone, the normal forces and the friction pyramid as
nonnegative cones, the friction cone as a second-order cone, and the non-smooth objectives in
epigraph form (the electrical one with one rotated cone per joint for the Joule term, shared by
the two gearbox branches). :func:`hexaleg.dynamics.solver.solve_fast` calls :func:`solve_sample`
on a sample the batched solver does not certify (the last resort); the errors raised here name
the time, the feet and (for torque limits) the joint.
"""

from __future__ import annotations

import dataclasses
import math
from dataclasses import dataclass, field
from typing import NoReturn

import numpy as np

from hexaleg.dynamics.contact import QUADRATIC_OBJECTIVES, ContactParams, StanceSystem
from hexaleg.dynamics.reduction import RANK_TOL, REACH_TOL
from hexaleg.errors import InfeasibleForcesError, TorqueLimitError

CLARABEL_TOLERANCES: tuple[float, ...] = (1e-11, 1e-10, 1e-9, 1e-8, 1e-7)
"""Clarabel gap and feasibility tolerances (absolute and relative) tried in turn, by the exact
per-sample solves and by the cvxpy reference, until one is met: an "almost solved" answer at the
loosest is an error, never a silent result."""


UNLIMITED_FRICTION = 100.0
"""A friction coefficient that stands for "no friction limit" when an infeasible sample is
diagnosed (larger ones scale the cone too badly for Clarabel)."""


@dataclass(eq=False)
class _ConicProgram:
    """One sample's program in Clarabel's form: minimise ½ xᵀ P x + qᵀ x subject to
    ``b − A x`` in ``cones``, with ``x = (f on the stance columns (n_f), epigraph variables)``;
    ``A`` and ``b`` are stacked from ``rows`` and ``rhs``, one block per cone."""

    P: np.ndarray
    q: np.ndarray
    n_f: int
    rows: list[np.ndarray] = field(default_factory=list)
    rhs: list[np.ndarray] = field(default_factory=list)
    cones: list[object] = field(default_factory=list)

    @property
    def n_epi(self) -> int:
        """Number of epigraph variables after ``f``."""
        return int(self.q.size) - self.n_f

    def add(self, rows: np.ndarray, b: np.ndarray, cone: object) -> None:
        """Constrain ``b − rows x`` to ``cone`` (``rows`` on all of ``x``)."""
        self.rows.append(rows)
        self.rhs.append(b)
        self.cones.append(cone)

    def add_on_f(self, rows: np.ndarray, b: np.ndarray, cone: object) -> None:
        """Constrain ``b − rows f`` to ``cone`` (``rows`` on ``f`` only)."""
        self.add(np.hstack([rows, np.zeros((rows.shape[0], self.n_epi))]), b, cone)


def _objective(D: np.ndarray, c: np.ndarray, objective: str, weights: np.ndarray,
               contact: ContactParams) -> _ConicProgram:
    """The cost of a sample with joint rows ``D`` (nj, n) and ``τ = c − D f``: Σ w τ² (the
    quadratic objectives, or the regulariser ε Σ τ² of the others) plus, for ``"positive_work"``
    and ``"electrical"``, the sum of the per-joint epigraph variables ``s`` (nj); ``"electrical"``
    also has ``u`` (nj), an upper bound of the Joule loss ``c_w τ²`` (one rotated cone per joint,
    shared by both gearbox branches)."""
    nj, n = D.shape
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
    return _ConicProgram(P, q, n)


def base_row_space(system: StanceSystem, k: int, A: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Base rows ``A f = b_base`` of sample ``k`` reduced to their row space, ``(rows, rhs)``:
    two point feet give only 5 independent rows, and an interior-point solver stalls on redundant
    equalities. The part of the base wrench outside that space is what no forces can produce.

    Raises:
        InfeasibleForcesError: that part is not zero (:func:`raise_unreachable`).
    """
    u, sv, _ = np.linalg.svd(A, full_matrices=False)
    rank = int(np.sum(sv > RANK_TOL * sv[0]))
    b_in = u[:, :rank].T @ system.b_base[k]
    missing = float(np.linalg.norm(system.b_base[k] - u[:, :rank] @ b_in))
    if missing > REACH_TOL * (1.0 + np.abs(system.b_base[k]).max()):
        raise_unreachable(system, k, missing)
    return u[:, :rank].T @ A, b_in


def _add_base_rows(program: _ConicProgram, system: StanceSystem, k: int, A: np.ndarray) -> None:
    """Base rows of sample ``k`` as a zero cone (:func:`base_row_space`)."""
    import clarabel

    rows, rhs = base_row_space(system, k, A)
    program.add_on_f(rows, rhs, clarabel.ZeroConeT(rows.shape[0]))


def contact_rows(n_f: int, contact: ContactParams) -> list[tuple[np.ndarray, np.ndarray, object]]:
    """Minimum normal force and friction cone (or inscribed pyramid) of ``n_f // 3`` stance feet
    whose forces are ``f`` (n_f,) in (x, y, z) triples: blocks ``(rows (m, n_f), b, cone)`` with
    ``b − rows f`` in the Clarabel cone."""
    import clarabel

    n_st = n_f // 3
    ez = np.zeros((n_st, n_f))
    ez[np.arange(n_st), 3 * np.arange(n_st) + 2] = 1.0
    out: list[tuple[np.ndarray, np.ndarray, object]] = [
        (-ez, np.full(n_st, -contact.min_normal_force), clarabel.NonnegativeConeT(n_st))]
    for i in range(n_st):
        e = np.zeros((3, n_f))
        e[0, 3 * i + 2], e[1, 3 * i], e[2, 3 * i + 1] = 1.0, 1.0, 1.0
        if contact.cone == "soc":  # (μ f_z, f_x, f_y) in the second-order cone
            m = e.copy()
            m[0] *= contact.mu
            out.append((-m, np.zeros(3), clarabel.SecondOrderConeT(3)))
        else:
            s = contact.mu / math.sqrt(2)
            m = np.array([s * e[0] - e[1], s * e[0] + e[1], s * e[0] - e[2], s * e[0] + e[2]])
            out.append((-m, np.zeros(4), clarabel.NonnegativeConeT(4)))
    return out


def _add_contact_rows(program: _ConicProgram, contact: ContactParams) -> None:
    """:func:`contact_rows` of one sample's program."""
    for rows, b, cone in contact_rows(program.n_f, contact):
        program.add_on_f(rows, b, cone)


def _add_torque_limits(program: _ConicProgram, D: np.ndarray, c: np.ndarray,
                       tau_max: np.ndarray) -> None:
    """|τ| ≤ τ_max with ``τ = c − D f``."""
    import clarabel

    # τ ≤ τmax:  −D f ≤ τmax − c ;  −τ ≤ τmax:  D f ≤ τmax + c
    program.add_on_f(np.vstack([-D, D]), np.concatenate([tau_max - c, tau_max + c]),
                     clarabel.NonnegativeConeT(2 * D.shape[0]))


def _add_positive_work(program: _ConicProgram, D: np.ndarray, c: np.ndarray,
                       qd: np.ndarray) -> None:
    """Epigraph of Σ_j max(0, q̇_j τ_j): ``s ≥ 0`` and ``s ≥ q̇ τ``."""
    import clarabel

    nj, n = D.shape
    eye = np.eye(nj)
    program.add(np.hstack([np.zeros((nj, n)), -eye]), np.zeros(nj),
                clarabel.NonnegativeConeT(nj))  # s ≥ 0
    # s ≥ q̇ τ = q̇ (c − D f)  ⇔  −q̇ D f − s ≤ −q̇ c
    program.add(np.hstack([-qd[:, None] * D, -eye]), -qd * c, clarabel.NonnegativeConeT(nj))


def _add_electrical(program: _ConicProgram, D: np.ndarray, c: np.ndarray, qd: np.ndarray,
                    weights: np.ndarray, efficiency: float | np.ndarray) -> None:
    """Epigraph of Σ_j max(0, max(q̇_j τ_j / η_j, η_j q̇_j τ_j) + c_j τ_j²): ``s ≥ 0``,
    ``s ≥ κ q̇ τ + u`` for κ = 1/η and κ = η (per joint), and ``u ≥ c_w τ²``."""
    import clarabel

    nj, n = D.shape
    nx = program.q.size
    eye, zero = np.eye(nj), np.zeros((nj, nj))
    program.add(np.hstack([np.zeros((nj, n)), -eye, zero]), np.zeros(nj),
                clarabel.NonnegativeConeT(nj))  # s ≥ 0
    # s ≥ κ q̇ τ + u for κ = 1/η and κ = η  ⇔  −κ q̇ D f − s + u ≤ −κ q̇ c
    eta = np.broadcast_to(np.asarray(efficiency, dtype=float), (nj,))
    for kappa in (eta,) if np.all(eta == 1.0) else (eta, 1.0 / eta):
        kq = kappa * qd
        program.add(np.hstack([-kq[:, None] * D, -eye, eye]), -kq * c,
                    clarabel.NonnegativeConeT(nj))
    # u ≥ c_w τ² ⇔ ‖(2√c_w τ, u − 1)‖ ≤ u + 1 (a rotated cone as a second-order cone);
    # Clarabel form: b − A x = (u + 1, 2√c_w τ, u − 1) with τ = c − D f.
    for j in range(nj):
        e_u = np.zeros(nx)
        e_u[n + nj + j] = 1.0
        row_f = np.zeros(nx)
        row_f[:n] = D[j]
        sw = 2 * math.sqrt(weights[j])
        program.add(np.vstack([-e_u, sw * row_f, -e_u]), np.array([1.0, sw * c[j], -1.0]),
                    clarabel.SecondOrderConeT(3))


def _conic_program(system: StanceSystem, k: int, tau_spring: np.ndarray, objective: str,
                   weights: np.ndarray, contact: ContactParams) -> _ConicProgram:
    """Sample ``k``'s program on its stance columns, for ``objective``."""
    cols = np.flatnonzero(np.repeat(system.stance[k], 3))
    D = system.D[k][:, cols]
    A = system.A[k][:, cols]
    c = system.b_joint[k] - tau_spring[k]  # τ = c − D f
    program = _objective(D, c, objective, weights, contact)
    _add_base_rows(program, system, k, A)
    _add_contact_rows(program, contact)
    if contact.torque_limits:
        _add_torque_limits(program, D, c, system.tau_max)
    if objective == "positive_work":
        _add_positive_work(program, D, c, system.qdot[k])
    elif objective == "electrical":
        _add_electrical(program, D, c, system.qdot[k], weights, system.efficiency)
    return program


def clarabel_solve(P: object, q: np.ndarray, A: object, b: np.ndarray, cones: list[object]
                   ) -> tuple[np.ndarray, str]:
    """Minimise ½ xᵀ P x + qᵀ x subject to ``b − A x`` in ``cones`` with Clarabel, at the tightest
    of :data:`CLARABEL_TOLERANCES` it meets (never "almost solved" while a looser one remains; a
    stall short of the tolerances, "insufficient progress", also moves on to the next one).

    Args:
        P: The upper triangle of P (scipy.sparse CSC). q: (n,).
        A: Constraint rows (scipy.sparse CSC, (m, n)). b: (m,). cones: Clarabel cones, in row order.

    Returns:
        ``(x, status)``.
    """
    x, _, status = clarabel_primal_dual(P, q, A, b, cones)
    return x, status


def clarabel_primal_dual(P: object, q: np.ndarray, A: object, b: np.ndarray,
                         cones: list[object]) -> tuple[np.ndarray, np.ndarray, str]:
    """:func:`clarabel_solve` with Clarabel's dual variables: ``(x, z, status)``, z (m,) the
    multipliers of the rows, in the dual cones, with ``P x + q + Aᵀ z = 0`` at the optimum
    (Clarabel's convention: the Lagrangian is ½ xᵀ P x + qᵀ x + zᵀ (A x − b))."""
    import clarabel

    settings = clarabel.DefaultSettings()
    settings.verbose = False
    settings.max_iter = 200
    for tol in CLARABEL_TOLERANCES:
        settings.tol_gap_abs = settings.tol_gap_rel = settings.tol_feas = tol
        settings.tol_ktratio = 100 * tol
        solution = clarabel.DefaultSolver(P, q, A, b, cones, settings).solve()
        status = str(solution.status)
        if status not in ("AlmostSolved", "InsufficientProgress"):
            break
    return np.asarray(solution.x), np.asarray(solution.z), status


def _clarabel_solve(program: _ConicProgram) -> tuple[np.ndarray, str]:
    """Solve one sample's ``program`` (:func:`clarabel_solve`); returns ``(x, status)``."""
    import scipy.sparse as sp

    return clarabel_solve(sp.csc_matrix(np.triu(program.P)), program.q,
                          sp.csc_matrix(np.vstack(program.rows)), np.concatenate(program.rhs),
                          program.cones)


def solve_sample(system: StanceSystem, k: int, tau_spring: np.ndarray, objective: str,
                 weights: np.ndarray, contact: ContactParams) -> np.ndarray:
    """Solve sample ``k``'s program exactly with Clarabel; returns f padded to (3 n_legs,), N.

    Raises:
        InfeasibleForcesError, TorqueLimitError: see :func:`raise_infeasible` and
            :func:`raise_unreachable`.
    """
    program = _conic_program(system, k, tau_spring, objective, weights, contact)
    x, status = _clarabel_solve(program)
    if status != "Solved":
        raise_infeasible(system, k, tau_spring, contact, status)
    pattern = system.stance[k]
    f = np.zeros(3 * pattern.size)
    f[np.flatnonzero(np.repeat(pattern, 3))] = x[:program.n_f]
    return f


def raise_infeasible(system: StanceSystem, k: int, tau_spring: np.ndarray,
                     contact: ContactParams, status: str) -> NoReturn:
    """Raise the error of sample ``k`` whose program a solver found infeasible (``status``).

    Raises:
        TorqueLimitError: forces exist without the torque limits; names the joint that needs
            the most beyond its limit, the time and the torque.
        InfeasibleForcesError: otherwise; names the time and the stance feet.
    """
    feet = [system.leg_names[i] for i in np.flatnonzero(system.stance[k])]
    where = f"t = {system.t[k]:.4f} s (sample {k}), stance feet {', '.join(feet) or '(none)'}"
    if contact.torque_limits:
        # Without the torque limits: if forces exist then, the limits are what failed.
        relaxed = dataclasses.replace(contact, torque_limits=False)
        try:
            f = solve_sample(system, k, tau_spring, "torque_squared",
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
        f"({contact.cone}) and normal force ≥ {contact.min_normal_force} N: "
        f"{_binding_constraint(system, k, tau_spring, contact)}; solver status {status}")


def _feasible(system: StanceSystem, k: int, tau_spring: np.ndarray,
              contact: ContactParams) -> np.ndarray | None:
    """Forces of sample ``k`` under ``contact`` (least Σ τ², no torque limits), or None."""
    relaxed = dataclasses.replace(contact, torque_limits=False)
    program = _conic_program(system, k, tau_spring, "torque_squared", np.ones(system.D.shape[1]),
                             relaxed)
    x, status = _clarabel_solve(program)
    if status != "Solved":
        return None
    f = np.zeros((system.stance.shape[1], 3))
    f[system.stance[k]] = x[:program.n_f].reshape(-1, 3)
    return f


def _binding_constraint(system: StanceSystem, k: int, tau_spring: np.ndarray,
                        contact: ContactParams) -> str:
    """Which constraint makes sample ``k`` infeasible, in words: the friction cone (with the
    least friction coefficient that would do, and the foot that needs it) or the normal forces
    (some foot would have to pull even on a frictionless-limit floor)."""
    loose = dataclasses.replace(contact, mu=UNLIMITED_FRICTION)
    if _feasible(system, k, tau_spring, loose) is None:
        return (f"the normal forces — even with unlimited friction some stance foot would have "
                f"to push less than {contact.min_normal_force} N (pull on the ground)")
    lo, hi = contact.mu, UNLIMITED_FRICTION
    while hi / lo > 1.001:  # the least μ with forces, by bisection on a log scale
        mid = math.sqrt(lo * hi)
        if _feasible(system, k, tau_spring, dataclasses.replace(contact, mu=mid)) is None:
            lo = mid
        else:
            hi = mid
    f = _feasible(system, k, tau_spring, dataclasses.replace(contact, mu=hi))
    feet = np.flatnonzero(system.stance[k])
    worst = ""
    if f is not None:
        load = np.hypot(f[feet, 0], f[feet, 1]) / np.maximum(f[feet, 2], 1e-300)
        worst = f", foot {system.leg_names[feet[int(np.argmax(load))]]} at its cone's edge"
    single = ""
    if len(feet) == 1:  # the force of one point foot points at the centre of mass
        single = (" (one point foot's force points from the foot at the centre of mass, so its "
                  "friction ratio is the centre of mass's horizontal distance from the foot "
                  "over its height: a gait on one foot needs the body over the foot, longer "
                  "two-foot phases that carry it from one foot to the next — a higher "
                  "duty_factor — or a higher body_height)")
    return (f"the friction cone — the least friction that admits forces here is "
            f"μ = {hi:.3g}{worst}{single}")


def raise_unreachable(system: StanceSystem, k: int, residual: float) -> NoReturn:
    """Raise InfeasibleForcesError: sample ``k``'s base wrench is out of its feet's reach by
    ``residual`` (N, N·m)."""
    feet = [system.leg_names[i] for i in np.flatnonzero(system.stance[k])]
    if not feet:  # a flight phase: named as such, not as a want of sway
        flying = float(np.mean(~system.stance.any(axis=1)))
        raise InfeasibleForcesError(
            f"no foot is on the ground at t = {system.t[k]:.4f} s (sample {k}): every leg is in "
            f"swing together for {flying:.0%} of the samples (a flight phase), and nothing "
            "carries the body's weight there (hexaleg's gaits plan no ballistic phase); raise "
            "duty_factor or stagger the legs' phases (pattern, phases or groups) so that a foot "
            "is always down")
    if len(feet) == 1 and len(system.leg_names) < 3:  # a biped: single support is inevitable
        why = (f"one point foot ({feet[0]}) pushes no moment about itself, and a robot of "
               f"{len(system.leg_names)} legs stands on one foot whenever the other swings: it "
               "balances only dynamically, its centre of mass falling about the stance foot "
               "by a walking pattern that puts the zero-moment point on it: hexaleg's gaits "
               "plan one ([gait] balance = 'auto' or 'zmp', hexaleg.motion.zmp); this motion "
               "does not put it there at this sample (balance = 'none', or a recorded or "
               "optimal motion whose body is not balanced exactly over its foot)")
    elif len(feet) == 1:  # one point foot: its force must pass through the centre of mass
        why = (f"one point foot ({feet[0]}) pushes no moment about itself, so the body's "
               "weight and inertia must act through it — raise duty_factor so that more feet "
               "share the support, or give the gait the centre of mass over that foot")
    else:
        why = ("e.g. two point feet cannot push a moment about the line through them — the "
               "motion needs a body sway that balances it")
    raise InfeasibleForcesError(
        f"the stance feet {', '.join(feet)} cannot produce the base wrench at "
        f"t = {system.t[k]:.4f} s (sample {k}) with any forces: the best forces miss the "
        f"base rows by {residual:.3g} (N, N·m); {why}")
