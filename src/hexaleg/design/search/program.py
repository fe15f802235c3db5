"""The design program: foot forces at every sample and spring magnitudes shared by all samples.

For a fixed spring geometry the spring torques are linear in the magnitudes x,
``τ_s(t) = B(t) x`` (:mod:`hexaleg.robot.springs.terms`), so the motor torque
``τ(t) = b_joint(t) − D(t) f(t) − B(t) x`` is affine in the forces *and* x, and the whole cycle's
objective ``Σ_t w_t E_t(τ(t))`` (w the quadrature weights of
:func:`hexaleg.dynamics.energy.metrics`) is one convex program over (x, f(1…T)) with the force
program's constraints at every sample (:mod:`hexaleg.dynamics.contact`) and the design's linear
constraints on x. Its optimum is global for that geometry.

Solving it fast (quadratic objectives, :func:`solve_design`)
-----------------------------------------------------------
Where no inequality of a sample binds, its optimal forces are affine in its spring torques through
the gains ``prepare`` already has (:class:`hexaleg.dynamics.solver.QuadraticGains`):
``f = f₀ − K B x`` and ``τ = τ₀ + G B x``, so the sample's cost is a quadratic in x alone. The
program keeps explicit forces only for an *active set* E of samples: the others are condensed
into one small quadratic ``xᵀ Q x + 2 rᵀ x``. Starting from E = ∅ (a least-squares problem in x
with the design constraints), every solve is checked at all condensed samples; those whose
condensed forces break a friction, normal-force or torque-limit inequality join E and the program
is solved again. The loop ends when no condensed sample breaks one: the solution of the relaxed
program (condensed samples without their inequalities) is then feasible for the full program,
hence its optimum — exact, not an approximation. Each solve is one Clarabel call
(:func:`hexaleg.dynamics.conic.clarabel_solve`). :mod:`hexaleg.design.search.program_reference`
writes the same program in cvxpy, for every objective, as the reference.
"""

from __future__ import annotations

import weakref
from collections.abc import Callable
from dataclasses import dataclass, field

import numpy as np

from hexaleg.design.search.bundle import csc
from hexaleg.dynamics.conic import base_row_space, clarabel_primal_dual, contact_rows
from hexaleg.dynamics.contact import (
    QUADRATIC_OBJECTIVES,
    ContactParams,
    StanceSystem,
    violations,
)
from hexaleg.dynamics.energy import quadrature_weights
from hexaleg.dynamics.prepare import Prepared
from hexaleg.errors import InfeasibleForcesError, InvalidParameterError

MAX_ROUNDS = 50
"""Active-set rounds before giving up (each adds every violating sample; a handful suffice)."""
ENGAGED = 1e-9
"""A term acts over the gait where its basis (a column of :attr:`DesignProblem.B`) exceeds this
somewhere (rad of compression, or the unit step); below it the term is fixed at 0 instead of left
to round-off (a ``"never engaged"`` row of the design)."""


@dataclass(frozen=True, eq=False)
class DesignProblem:
    """The data of one design program (module docstring).

    Attributes:
        prepared: The prepared gait.
        objective: The force program's objective (:data:`hexaleg.dynamics.contact.OBJECTIVES`).
        cols: Columns of the sprung joints, shape (n_s,).
        B: Spring torque per unit magnitude, shape (T, n_s, nx), N·m per unit.
        nonnegative: Which magnitudes must be ≥ 0, shape (nx,), bool.
        G: Design constraint rows on x (``G x ≤ h``), shape (m, nx).
        h: Their right-hand sides, shape (m,).
        labels: What each row of G is (for an infeasible set), length m.
    """

    prepared: Prepared
    objective: str
    cols: np.ndarray
    B: np.ndarray
    nonnegative: np.ndarray
    G: np.ndarray
    h: np.ndarray
    labels: tuple[str, ...] = field(default=())

    @property
    def nx(self) -> int:
        return int(self.B.shape[2])

    @property
    def sample_weights(self) -> np.ndarray:
        """Quadrature weights of the samples, (T,), s."""
        m = self.prepared.motion
        return quadrature_weights(m.n_samples, m.dt, m.periodic)

    def spring_torques(self, x: np.ndarray) -> np.ndarray:
        """Spring torques of magnitudes ``x`` on every joint, shape (T, nj), N·m."""
        out = np.zeros_like(self.prepared.q)
        out[:, self.cols] = self.B @ x
        return out


@dataclass(frozen=True)
class Multipliers:
    """The multipliers of the explicit samples' inequalities at a design program's optimum
    (Clarabel's dual variables of the active set's last round, in the objective's own units,
    each projected onto its dual cone): the Lagrangian term of sample ``samples[i]`` is
    ``torque[i] · τ + force[i] · f + constant[i]``, ≤ 0 wherever its forces and motor torques
    meet the friction cone, the normal-force bound and the torque limits (weak duality,
    Boyd & Vandenberghe, *Convex Optimization*, 2004, §5.1.3 and §5.9). A lower bound of another
    geometry's program is built on them (:class:`hexaleg.design.search.scan.RelaxedBounds`).

    Attributes:
        samples: The explicit samples, shape (S,).
        torque: The torque limits' multipliers y⁺ − y⁻ (of τ ≤ τ_max and −τ ≤ τ_max), (S, nj).
        force: The contact rows' multipliers on the forces, ``Rᵀ y``, (S, 3 n_legs) (padded).
        constant: ``−(y⁺ + y⁻) · τ_max − y · b`` of each sample, (S,).
    """

    samples: np.ndarray
    torque: np.ndarray
    force: np.ndarray
    constant: np.ndarray


@dataclass(frozen=True)
class DesignSolution:
    """The optimum of a :class:`DesignProblem`.

    Attributes:
        x: Magnitudes, shape (nx,), SI.
        value: ``Σ_t w_t Σ_j c_j τ_j²`` at the optimum (J for ``"joule"``).
        explicit: Samples the active set solved with explicit forces, shape (|E|,).
        rounds: Clarabel solves.
        forces: The optimal foot forces, shape (T, 3 n_legs), N (padded; in the stance
            system's frame: the world on level ground, the contact frame on a slope,
            ``prepared.system.to_world(forces)`` in the world).
        multipliers: The explicit samples' multipliers (:class:`Multipliers`; None where no
            sample is explicit or the solver gave none).
    """

    x: np.ndarray
    value: float
    explicit: np.ndarray
    rounds: int
    forces: np.ndarray
    multipliers: Multipliers | None = None


def _coo(block: np.ndarray, rows: np.ndarray, cols: np.ndarray
         ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    i, j = np.nonzero(block)
    return rows[i], cols[j], block[i, j]


_GAINS: weakref.WeakKeyDictionary[DesignProblem, np.ndarray] = weakref.WeakKeyDictionary()
"""Each problem's torque gains (:func:`torque_gains`): the electrical search solves a geometry's
Joule program (its start) and its condensed program on the same problem."""


def torque_gains(problem: DesignProblem) -> np.ndarray:
    """The motor torque per unit magnitude of the Joule-optimal forces, ``M = G B`` per sample
    (``τ = τ₀ + M x``, :class:`hexaleg.dynamics.solver.QuadraticGains`), shape (T, nj, nx);
    computed once per problem (einsum: the same bits every time, which the geometry searches'
    comparisons need)."""
    if problem not in _GAINS:
        G = problem.prepared.gains(problem.objective).G
        _GAINS[problem] = np.einsum("tjs,tsx->tjx", G[:, :, problem.cols], problem.B)
    return _GAINS[problem]



_ROWS: weakref.WeakKeyDictionary[StanceSystem, dict[tuple[int, ContactParams], list]] = \
    weakref.WeakKeyDictionary()
"""Each stance system's per-sample constraint blocks (:func:`_sample_rows`), computed once: an
active-set round, and every geometry of a search, asks for the same samples again."""


def _sample_rows(system: StanceSystem, k: int, contact: ContactParams
                 ) -> list[tuple[np.ndarray, np.ndarray, object]]:
    """Sample ``k``'s base rows (a zero cone) and contact rows on its stance forces, as
    ``(rows, rhs, cone)`` blocks (:func:`hexaleg.dynamics.conic.base_row_space`,
    :func:`~hexaleg.dynamics.conic.contact_rows`), cached per system."""
    import clarabel

    cache = _ROWS.setdefault(system, {})
    if (k, contact) not in cache:
        st = np.flatnonzero(np.repeat(system.stance[k], 3))
        rows, rhs = base_row_space(system, k, system.A[k][:, st])
        cache[(k, contact)] = [(rows, rhs, clarabel.ZeroConeT(rows.shape[0])),
                               *contact_rows(st.size, contact)]
    return cache[(k, contact)]


class _Assembler:
    """Rows ``b − A z ∈ cone`` of the stacked program on ``z = (x, f of the explicit samples)``."""

    def __init__(self) -> None:
        self.r: list[np.ndarray] = []
        self.c: list[np.ndarray] = []
        self.v: list[np.ndarray] = []
        self.b: list[np.ndarray] = []
        self.cones: list[object] = []
        self.m = 0

    def add(self, block: np.ndarray, cols: np.ndarray, b: np.ndarray, cone: object) -> None:
        r, c, v = _coo(block, self.m + np.arange(block.shape[0]), cols)
        self.r.append(r)
        self.c.append(c)
        self.v.append(v)
        self.b.append(b)
        self.cones.append(cone)
        self.m += block.shape[0]

    def dense(self, n: int) -> tuple[object, np.ndarray]:
        """As :meth:`matrices` when no entry is given twice, without scipy.sparse's checks."""
        A = np.zeros((self.m, n))
        if self.r:
            A[np.concatenate(self.r), np.concatenate(self.c)] = np.concatenate(self.v)
        return csc(A), np.concatenate(self.b) if self.b else np.zeros(0)

    def matrices(self, n: int) -> tuple[object, np.ndarray]:
        import scipy.sparse as sp

        A = sp.csc_matrix((np.concatenate(self.v), (np.concatenate(self.r),
                                                    np.concatenate(self.c))), shape=(self.m, n))
        return A, np.concatenate(self.b)


def _solve_once(problem: DesignProblem, explicit: np.ndarray, Q: np.ndarray, r: np.ndarray,
                scale: float) -> tuple[np.ndarray, dict[int, np.ndarray], str]:
    """One Clarabel solve with the condensed quadratic (Q, r) and explicit forces at the samples
    ``explicit``; returns (x, forces of the explicit samples padded to (3 n_legs,), status).

    The objective is divided by ``scale`` (the baseline's value): in joules with dt-sized weights
    its entries are ~1e-3 against O(1) constraint rows, and Clarabel then stalls."""
    x, forces, status, _ = _solve_round(problem, explicit, Q, r, scale)
    return x, forces, status


_Layout = list[tuple[int, list[tuple[int, np.ndarray, np.ndarray, bool]], int]]
"""Per explicit sample: (sample, its contact blocks as (first row, rows on its stance forces,
right-hand side, second-order cone?), first row of its torque-limit block or −1)."""


def _solve_round(problem: DesignProblem, explicit: np.ndarray, Q: np.ndarray, r: np.ndarray,
                 scale: float
                 ) -> tuple[np.ndarray, dict[int, np.ndarray], str, Callable[[], Multipliers]]:
    """:func:`_solve_once`, and how to read the explicit samples' :class:`Multipliers` from the
    solve's dual variables (asked only of the last round)."""
    import clarabel
    import scipy.sparse as sp

    prepared, nx = problem.prepared, problem.nx
    system = prepared.system
    c = prepared.weights(problem.objective)
    w = problem.sample_weights / scale
    nj = system.D.shape[1]
    Q, r = Q / scale, r / scale
    xcols = np.arange(nx)
    P_parts = [_coo(2 * Q, xcols, xcols)]
    q_parts = [2 * r]
    asm = _Assembler()
    neg = np.flatnonzero(problem.nonnegative)
    asm.add(-np.eye(nx)[neg], xcols, np.zeros(neg.size), clarabel.NonnegativeConeT(neg.size))
    if problem.G.size:
        asm.add(problem.G, xcols, problem.h, clarabel.NonnegativeConeT(problem.G.shape[0]))
    n = nx
    placed: dict[int, tuple[np.ndarray, np.ndarray]] = {}  # sample → (stance columns, z columns)
    layout: _Layout = []
    for k in (int(k) for k in explicit):
        st = np.flatnonzero(np.repeat(system.stance[k], 3))
        fcols = n + np.arange(st.size)
        placed[k] = (st, fcols)
        n += st.size
        Bk = np.zeros((nj, nx))
        Bk[problem.cols] = problem.B[k]
        Z = np.hstack([Bk, system.D[k][:, st]])  # τ = b_joint − Z (x, f)
        zcols = np.concatenate([xcols, fcols])
        P_parts.append(_coo(2 * w[k] * Z.T @ (c[:, None] * Z), zcols, zcols))
        qk = -2 * w[k] * Z.T @ (c * system.b_joint[k])
        q_parts[0][:nx] += qk[:nx]
        q_parts.append(qk[nx:])
        blocks = []
        if st.size:
            for i, (rows, rhs, cone) in enumerate(_sample_rows(system, k, prepared.contact)):
                if i:  # the base rows (an equality) are kept by the bound
                    blocks.append((asm.m, rows, rhs,
                                   isinstance(cone, clarabel.SecondOrderConeT)))
                asm.add(rows, fcols, rhs, cone)
        layout.append((k, blocks, asm.m if prepared.contact.torque_limits else -1))
        if prepared.contact.torque_limits:
            tmax, b = system.tau_max, system.b_joint[k]
            asm.add(np.vstack([-Z, Z]), zcols, np.concatenate([tmax - b, tmax + b]),
                    clarabel.NonnegativeConeT(2 * nj))
    rows_, cols_, vals = (np.concatenate(a) for a in zip(*P_parts, strict=True))
    if placed:
        P = sp.triu(sp.csc_matrix((vals, (rows_, cols_)), shape=(n, n)), format="csc")
        A, b = asm.matrices(n)
    else:  # no entry twice: the same CSC arrays built directly (scipy.sparse's checks cost more
        # than the solve of a program this small)
        dense = np.zeros((n, n))
        dense[rows_, cols_] = vals
        P = csc(np.triu(dense))
        A, b = asm.dense(n)
    z, duals, status = clarabel_primal_dual(P, np.concatenate(q_parts), A, b, asm.cones)
    forces = {}
    for k, (st, fcols) in placed.items():
        forces[k] = np.zeros(system.A.shape[2])
        forces[k][st] = z[fcols]
    return z[:nx], forces, status, lambda: _multipliers(system, layout, duals * scale)


def _multipliers(system: StanceSystem, layout: _Layout, y: np.ndarray) -> Multipliers:
    """The :class:`Multipliers` of the explicit samples in ``layout`` from the rows' dual
    variables ``y`` (the objective's own units), each block projected onto its dual cone (the
    nonnegative orthant, the second-order cone: both self-dual) so that the Lagrangian terms
    are ≤ 0 on every feasible point exactly, whatever the solver's round-off."""
    nj, nf = system.D.shape[1], system.A.shape[2]
    S = len(layout)
    torque, force, constant = np.zeros((S, nj)), np.zeros((S, nf)), np.zeros(S)
    for i, (k, blocks, at) in enumerate(layout):
        st = np.flatnonzero(np.repeat(system.stance[k], 3))
        for first, rows, rhs, second_order in blocks:
            yb = _dual_cone(y[first:first + rows.shape[0]], second_order)
            force[i, st] += rows.T @ yb  # yᵀ (R f − b): ≤ 0 where b − R f is in the cone
            constant[i] -= yb @ rhs
        if at >= 0:
            up = np.maximum(y[at:at + nj], 0.0)  # of τ_max − τ ≥ 0
            down = np.maximum(y[at + nj:at + 2 * nj], 0.0)  # of τ_max + τ ≥ 0
            torque[i] = up - down
            constant[i] -= (up + down) @ system.tau_max
    return Multipliers(np.array([k for k, _, _ in layout], dtype=int), torque, force, constant)


def _dual_cone(y: np.ndarray, second_order: bool) -> np.ndarray:
    """``y`` projected onto the nonnegative orthant, or onto the second-order cone
    {(t, u): ‖u‖ ≤ t} (Boyd & Vandenberghe, *Convex Optimization*, exercise 8.3)."""
    if not second_order:
        return np.maximum(y, 0.0)
    t, u = float(y[0]), y[1:]
    norm = float(np.linalg.norm(u))
    if norm <= t:
        return y.copy()
    if norm <= -t:
        return np.zeros_like(y)
    a = (t + norm) / 2
    return np.concatenate([[a], a * u / norm])


def solve_design(problem: DesignProblem) -> DesignSolution:
    """The global optimum of ``problem`` for a quadratic objective, by the condensed active-set
    method of the module docstring.

    Raises:
        InfeasibleForcesError: Clarabel finds the program infeasible (names the status and the
            design constraints; without design constraints x = 0, the baseline, is feasible).
    """
    if problem.objective not in QUADRATIC_OBJECTIVES:
        raise InvalidParameterError("objective", problem.objective,
                                    "a quadratic objective: " + ", ".join(QUADRATIC_OBJECTIVES))
    prepared = problem.prepared
    system = prepared.system
    gains = prepared.gains(problem.objective)
    c = prepared.weights(problem.objective)
    w = problem.sample_weights
    Kc = gains.K[:, :, problem.cols]
    M = torque_gains(problem)  # τ = τ₀ + M x
    Mw = M * (w[:, None, None] * c[None, :, None])
    Q_t = np.einsum("tjx,tjy->txy", Mw, M)
    r_t = np.einsum("tjx,tj->tx", Mw, gains.tau0)
    scale = float(np.sum(w[:, None] * c * gains.tau0**2)) or 1.0  # the baseline's value
    condensed = np.ones(system.n_samples, dtype=bool)
    for rounds in range(1, MAX_ROUNDS + 1):
        explicit = np.flatnonzero(~condensed)
        x, forces, status, multipliers = _solve_round(problem, explicit,
                                                      Q_t[condensed].sum(0),
                                                      r_t[condensed].sum(0), scale)
        if status != "Solved":
            raise InfeasibleForcesError(
                f"the spring design program has no solution (Clarabel: {status}); design "
                f"constraints: {', '.join(sorted(set(problem.labels))) or 'none'}")
        f = gains.f0 - np.matmul(Kc, (problem.B @ x)[:, :, None])[:, :, 0]  # f₀ − K B x
        tau = gains.tau0 + M @ x
        bad = violations(system, f, tau, prepared.contact) & condensed
        if not bad.any():
            for k, fk in forces.items():
                f[k] = fk
            tau[~condensed] = system.torques(f[~condensed], problem.spring_torques(x)[~condensed],
                                             ~condensed)
            value = float(np.sum(w[:, None] * c * tau**2))
            return DesignSolution(x, value, explicit, rounds, f,
                                  multipliers() if explicit.size else None)
        condensed &= ~bad
    raise InfeasibleForcesError(f"the spring design's active set did not settle in {MAX_ROUNDS} "
                                "rounds")
