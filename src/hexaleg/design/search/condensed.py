"""Spring design programs in any metric, with every sample's forces condensed to the Joule optimum.

Where no inequality of a sample binds, its Joule-optimal foot forces and motor torques are affine
in the spring magnitudes x (:class:`hexaleg.dynamics.solver.QuadraticGains`):
``f = f₀ − K B x``, ``τ = τ₀ + G B x`` — the forces every evaluation uses
(``Prepared.evaluate(springs, "joule")``). A metric convex in τ is then convex in x: the Joule
loss ``Σ w c τ²`` and the electrical energy ``Σ w max(0, c τ² + max(q̇τ/η, q̇τη))``
(:meth:`hexaleg.robot.motor.Motor.electrical_power`; without the clip at 0 where the motor
regenerates). Each problem ``c`` (a condition, a stop shift) is one such function ``E_c(x)``,
divided here by its baseline ``E_c(0)``; :func:`solve_condensed` minimises their maximum
(``"worst"``) or their mean over the design rows ``G x ≤ h`` and ``x ≥ 0``.

Exactness. The condensed function equals the evaluation's metric on the convex set R of magnitudes
at which no sample's condensed forces break a friction, normal-force or torque-limit inequality.
When the minimiser x* of the condensed program lies in R (checked at every sample), it is the
global minimiser over R of the metric as evaluated — the program is convex and equals the true
function there. When a sample binds at x*, that sample gets forces of its own in the program
(explicit variables with its constraints, cvxpy + Clarabel), grown until no condensed sample
binds: for the Joule metric this is the exact joint program over (x, f); for the electrical
metric those samples' forces minimise the electrical energy rather than the Joule loss, so the
optimum is then that of a slightly different (more favourable) force convention — the savings
reported come from the exact evaluation either way.

Solver: the proximal bundle method (:func:`hexaleg.design.search.bundle.minimise`), which stops when
its cutting-plane model proves the optimum to its tolerance. The electrical energy is dominated
by its kinks (the gearbox's loss switching with the sign of the power, the clip at 0), not its
curvature, so Newton steps on its pieces were tried and were slower: most were cut back by the
line search.
"""

from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from hexaleg.design.search.bundle import MODES, minimise
from hexaleg.design.search.bundle import TOLERANCE as CERTIFIED
from hexaleg.design.search.program import ENGAGED, MAX_ROUNDS, DesignProblem, torque_gains
from hexaleg.design.search.program_reference import force_constraints, stacked
from hexaleg.dynamics.contact import violations
from hexaleg.dynamics.reference import REFERENCE_TOLERANCES, solve_clarabel
from hexaleg.errors import InfeasibleForcesError, InvalidParameterError

METRICS: tuple[str, ...] = ("joule", "electrical")
"""The metrics a condensed program can minimise."""
TOLERANCE = 1e-8
"""Clarabel's gap and feasibility tolerance for the explicit program (savings to ~1e-8)."""
LOOSER: tuple[float, ...] = (1e-6, 1e-5)
"""Rungs below Clarabel's own ladder an explicit program's solve is accepted at, where it stalls
at every tighter one: the program's value, a ratio ``E_c(x)/E_c(0)`` of order 1, to ~1e-5 at
worst — a saving to 1e-3 points, a tenth of what is printed. (A co-design candidate of the
default robot, duty factor 0.8 and period 1.5625 s at 200 samples, stalls at a gap of 1.8e-6
relative with residuals of 4e-10: its program failed outright before.)"""
NEAR = 1e-3
"""How close to the worst ``E_c(x) / E_c(0)`` at the condensed optimum a problem without
explicit samples must be to enter the explicit program first (:func:`explicit_program`); the
others join only if they turn out to set the worst case."""
PENALTY = 1e4
"""M of :func:`preferred`'s exact penalty: the preferred problem's value traded against a
constraint's excess (both values ≈ 1, savings' complements)."""
SEARCH_TOLERANCE = 1e-6
"""The bundle's predicted decrease at which a geometry search's comparisons stop (of a value
≈ 1, the metric over its baseline)."""


class Condensed:
    """One problem's condensed data: gains along x, baseline, the current explicit set."""

    def __init__(self, problem: DesignProblem, metric: str) -> None:
        if metric not in METRICS:
            raise InvalidParameterError("metric", metric, " or ".join(METRICS))
        self.problem, self.metric = problem, metric
        p = problem.prepared
        self.system = p.system
        gains = p.gains("joule")
        self.c = p.weights("joule")
        self.w = problem.sample_weights
        self.M = (torque_gains(problem) if problem.objective == "joule" else  # (T, nj, nx)
                  np.einsum("tjs,tsx->tjx", gains.G[:, :, problem.cols], problem.B))
        self._K = gains.K[:, :, problem.cols]
        self.f0, self.tau0 = gains.f0, gains.tau0
        qd = self.system.qdot
        eta = np.broadcast_to(self.system.efficiency, qd.shape)
        self._out, self._in = qd / eta, qd * eta  # slopes of motoring and of braking power
        self._c = np.broadcast_to(self.c, qd.shape)
        self._regen = np.broadcast_to(np.asarray(p.motor.regeneration, dtype=bool), qd.shape)
        self.root = np.sqrt(self.w[:, None] * self.c[None, :])  # (T, nj)
        self.base = float(p.baseline("joule")["total"][metric])  # E_c(0), exact
        if not self.base > 0:
            raise InvalidParameterError(f"the baseline's {metric} energy", self.base,
                                        "> 0 (a gait that costs energy without springs)")
        self.condensed = np.ones(self.system.n_samples, dtype=bool)

    def pieces(self, tau: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
        """Per sample and joint: the power, its derivative in τ (a subgradient at the kinks) and
        its second derivative, shape (T, nj) each."""
        c = self._c
        if self.metric == "joule":
            return c * tau**2, 2 * c * tau, 2 * c
        slope = np.where(self.system.qdot * tau >= 0, self._out, self._in)
        phi = c * tau**2 + slope * tau
        dphi = 2 * c * tau + slope
        drop = ~self._regen & (phi < 0)
        return (np.where(drop, 0.0, phi), np.where(drop, 0.0, dphi), np.where(drop, 0.0, 2 * c))

    def oracle(self, x: np.ndarray) -> tuple[float, np.ndarray]:
        """The metric over the baseline at magnitudes x with every sample condensed, and its
        gradient (a subgradient at the kinks), shape (nx,)."""
        phi, dphi, _ = self.pieces(self.tau0 + self.M @ x)
        value = float(np.sum(self.w[:, None] * phi)) / self.base
        grad = np.einsum("tj,tjx->x", self.w[:, None] * dphi, self.M) / self.base
        return value, grad

    def _electrical(self, tau: Any, samples: np.ndarray) -> Any:
        """cvxpy electrical energy of motor torques ``tau`` (S·nj, sample-major) at ``samples``:
        ``Σ w (c τ² + max(q̇τ/η, q̇τη))``, clipped at 0 per joint without regeneration
        (:meth:`hexaleg.robot.motor.Motor.electrical_power`)."""
        import cvxpy as cp

        nj = self.system.D.shape[1]
        qd = self.system.qdot[samples].reshape(-1)
        eta = np.tile(np.broadcast_to(self.system.efficiency, (nj,)), samples.size)
        c = np.tile(self.c, samples.size)
        w = np.repeat(self.w[samples], nj)
        power = cp.multiply(c, cp.square(tau)) + cp.maximum(cp.multiply(qd / eta, tau),
                                                            cp.multiply(qd * eta, tau))
        regen = np.tile(np.broadcast_to(np.asarray(self.problem.prepared.motor.regeneration,
                                                   dtype=bool), (nj,)), samples.size)
        cost = 0
        if regen.any():
            cost = cost + w[regen] @ power[np.flatnonzero(regen)]
        if (~regen).any():
            cost = cost + w[~regen] @ cp.pos(power[np.flatnonzero(~regen)])
        return cost

    def cost(self, x: Any, cons: list) -> Any:
        """cvxpy energy of the problem in the metric at magnitudes x; appends the explicit
        samples' force constraints to ``cons``."""
        import cvxpy as cp

        k = self.condensed
        nx = self.problem.nx
        if self.metric == "joule":
            rows = (self.root[k][:, :, None] * self.M[k]).reshape(-1, nx)
            cost = cp.sum_squares(rows @ x + (self.root[k] * self.tau0[k]).reshape(-1))
        else:
            cost = self._electrical(self.M[k].reshape(-1, nx) @ x + self.tau0[k].reshape(-1),
                                    np.flatnonzero(k))
        explicit = np.flatnonzero(~k)
        if explicit.size:
            D, A, b_base, _ = stacked(self.problem, explicit)
            f = cp.Variable(D.shape[1])
            nj = self.system.D.shape[1]
            Bfull = np.zeros((explicit.size, nj, nx))
            Bfull[:, self.problem.cols] = self.problem.B[explicit]
            tau = (self.system.b_joint[explicit].reshape(-1) - D @ f
                   - Bfull.reshape(-1, nx) @ x)
            cost = cost + (cp.sum_squares(cp.multiply(self.root[explicit].reshape(-1), tau))
                           if self.metric == "joule" else self._electrical(tau, explicit))
            cons += force_constraints(f, A, b_base, self.problem.prepared.contact)
            if self.problem.prepared.contact.torque_limits:
                cons.append(cp.abs(tau) <= np.tile(self.system.tau_max, explicit.size))
        return cost

    @property
    def F(self) -> np.ndarray:
        """Condensed forces per unit magnitude, ``f = f₀ − F x``, shape (T, 3 n_legs, nx)."""
        return np.einsum("tfs,tsx->tfx", self._K, self.problem.B)

    def update(self, x: np.ndarray) -> bool:
        """Add the condensed samples whose forces at x break an inequality; True if any."""
        f = self.forces(x)
        tau = self.tau0 + self.M @ x
        bad = violations(self.system, f, tau, self.problem.prepared.contact) & self.condensed
        self.condensed &= ~bad
        return bool(bad.any())

    def forces(self, x: np.ndarray) -> np.ndarray:
        """The condensed foot forces at x, shape (T, 3 n_legs), N."""
        return self.f0 - np.einsum("tfs,ts->tf", self._K, self.problem.B @ x)


@dataclass(frozen=True)
class CondensedSolution:
    """The optimum of :func:`solve_condensed`.

    Attributes:
        x: Magnitudes, shape (nx,), SI. values: ``E_c(x) / E_c(0)`` per problem, shape (n,).
        explicit: Explicit samples per problem. solver: Path, iterations, gap.
    """

    x: np.ndarray
    values: np.ndarray
    explicit: tuple[int, ...]
    solver: dict[str, Any] = field(default_factory=dict)


def rows(problems: Sequence[DesignProblem], distinct: bool = False
         ) -> tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """The shared design rows of stacked problems: ``(G, h, nonneg, fixed)`` — every problem's
    rows but its "never engaged" ones; a magnitude is fixed at 0 only when its term acts in no
    problem. Repeated rows are kept (ANYmal's 21 shifts stack 336 rows, 70 distinct): stacking
    each once is the same program, but its QP solutions move by rounding, and when it was tried
    the co-design's gait search of the time (a Nelder–Mead path, since replaced by a compass
    search with ties: :mod:`hexaleg.design.codesign.gait_search`) ended at another gait.
    ``distinct``: each repeated row once (first occurrences, in order) — for the comparisons of a
    stop-tolerance search alone (:func:`solve_condensed` of stacked problems with
    ``exact=False``), whose values are compared within the tie of
    :data:`hexaleg.design.search.geometry.TIE`; the certified solve keeps every row. Solo-12's 21
    shifted programs stack 336 rows, 73 distinct, and each of the bundle's model steps (a
    Clarabel QP over them) costs 40 % less. The same program, another rounding: its values moved
    by up to 4e-5 of themselves (the bundle stops at a predicted decrease of
    :data:`SEARCH_TOLERANCE`, not at the optimum), and Solo-12's fine stage then took a stop
    place 7e-5 rad (0.004°) from the one it took before, its worst saving 7e-7 higher."""
    nx = problems[0].nx
    engaged = np.zeros(nx, dtype=bool)
    G, h = [np.zeros((0, nx))], [np.zeros(0)]
    for p in problems:
        engaged |= np.any(np.abs(p.B) > ENGAGED, axis=(0, 1))
        keep = np.array([label != "never engaged" for label in p.labels], dtype=bool)
        if p.G.size and keep.any():
            G.append(p.G[keep])
            h.append(p.h[keep])
    G_all, h_all = np.vstack(G), np.concatenate(h)
    if distinct and h_all.size:
        _, first = np.unique(np.c_[G_all, h_all], axis=0, return_index=True)
        kept = np.sort(first)
        G_all, h_all = G_all[kept], h_all[kept]
    return G_all, h_all, problems[0].nonnegative, ~engaged


def solve_condensed(problems: Sequence[DesignProblem], metric: str, mode: str = "worst",
                    x0: np.ndarray | None = None, *, exact: bool = True,
                    data: Sequence[Condensed] | None = None,
                    prefer: int | None = None) -> CondensedSolution:
    """Minimise the worst (or mean) ``E_c(x) / E_c(0)`` over ``problems`` (module docstring).

    Args:
        problems: Design programs sharing the magnitudes x (same family and groups).
        metric: One of :data:`METRICS`.
        mode: One of :data:`hexaleg.design.search.bundle.MODES`.
        x0: Start (feasible or projected), shape (nx,); default 0, the baseline.
        exact: Certify the optimum (bundle tolerance, explicit forces where samples bind);
            False for a geometry search's comparisons (a looser bundle, every sample condensed).
        data: The problems' :class:`Condensed` data when the caller made them.
        prefer: With ``exact`` in mode ``"worst"``: the problem whose value decides between
            the magnitudes of equal worst (:func:`preferred`; the unshifted stops' of a
            stop-tolerance program), index into ``problems``; None: no preference.

    Raises:
        InvalidParameterError: an unknown mode or metric, no problems.
        InfeasibleForcesError: design rows no magnitudes meet, or no admissible forces.
    """
    if mode not in MODES:
        raise InvalidParameterError("mode", mode, " or ".join(MODES))
    if not problems:
        raise InvalidParameterError("problems", [], "at least one design program")
    data = list(data) if data is not None else [Condensed(p, metric) for p in problems]
    G, h, nonneg, fixed = rows(problems, distinct=not exact and len(problems) > 1)
    nx = problems[0].nx
    x = np.zeros(nx) if x0 is None else np.where(fixed, 0.0, np.asarray(x0, dtype=float))
    result = minimise([c.oracle for c in data], x, mode, G=G, h=h, nonneg=nonneg, fixed=fixed,
                      tolerance=CERTIFIED if exact else SEARCH_TOLERANCE)
    solver: dict[str, Any] = {"path": "proximal bundle, every sample condensed",
                              "iterations": result.iterations,
                              "serious_steps": result.serious_steps, "gap": result.gap}
    x = np.where(nonneg, np.maximum(result.x, 0.0), result.x)
    if exact and mode == "worst" and prefer is not None and len(data) > 1:
        x, solver["preferred"] = preferred(data, prefer, x, G, h, nonneg, fixed)
    if exact and any([c.update(x) for c in data]):  # some sample binds: explicit forces there
        x, explicit = explicit_program(data, mode, nonneg, ~fixed, G, h, start=x)
        solver.update(explicit)
    values = np.array([c.oracle(x)[0] for c in data])
    solver["program_value"] = float(values.max() if mode == "worst" else values.mean())
    return CondensedSolution(x=x, values=values,
                             explicit=tuple(int((~c.condensed).sum()) for c in data),
                             solver=solver)


def preferred(data: Sequence[Condensed], prefer: int, x: np.ndarray, G: np.ndarray,
               h: np.ndarray, nonneg: np.ndarray, fixed: np.ndarray
               ) -> tuple[np.ndarray, dict[str, Any]]:
    """Of the magnitudes with the worst value ``F* = max_c E_c(x)/E_c(0)`` at x (a minimiser),
    those best for problem ``prefer``: ``min E_p(x)`` subject to ``E_c(x) ≤ F*`` for every c.

    The worst case's minimiser need not be unique — the conditions that do not set the worst
    leave directions free — and the bundle method stops anywhere in that set, where its
    floating-point path takes it: on ANYmal two paths to one tolerant geometry gave nominal
    savings 0.1 point apart. The lexicographic second stage picks one point of the set by a
    stated rule (the preferred problem's value least). It is solved by the same bundle method
    as the exact penalty ``E_p + M max(0, max_c E_c − F*)``, written as the worst of
    ``E_p`` and ``E_p + M (E_c − F*)`` (exact for M above the constraints' multipliers:
    Nocedal & Wright, *Numerical Optimization*, 2nd ed., 2006, Thm 17.3). Kept only when its
    worst is F* to the bundle's tolerance (a too small M shows as a larger worst); else x.

    Returns:
        The magnitudes, shape (nx,), and what the stage did (for the solver's record).
    """
    oracles = [c.oracle for c in data]
    worst = max(o(x)[0] for o in oracles)
    own = oracles[prefer]

    def penalised(o: Any) -> Any:
        def g(y: np.ndarray) -> tuple[float, np.ndarray]:
            (vp, gp), (vc, gc) = own(y), o(y)
            return vp + PENALTY * (vc - worst), gp + PENALTY * gc
        return g

    result = minimise([own, *(penalised(o) for o in oracles)], x, "worst", G=G, h=h,
                      nonneg=nonneg, fixed=fixed, tolerance=CERTIFIED)
    y = np.where(nonneg, np.maximum(result.x, 0.0), result.x)
    after = max(o(y)[0] for o in oracles)
    kept = after <= worst + 10 * CERTIFIED * max(1.0, abs(worst))
    return (y if kept else x), {"kept": bool(kept), "iterations": result.iterations,
                                "excess": float(after - worst),
                                "before": float(own(x)[0]), "after": float(own(y)[0])}


def _solve(program: Any) -> str:
    """Clarabel by the tolerance ladder of :func:`hexaleg.dynamics.reference.solve_clarabel`
    from :data:`TOLERANCE` down to the last of :data:`LOOSER`: a solve that meets
    :data:`TOLERANCE` is that of a plain solve at it (the reduced tolerances count only where
    Clarabel stalls); one that stalls is solved at the next looser rung. The ladder's rungs
    tighter than :data:`TOLERANCE` are skipped: a program that stalls at it fails them too (each
    failure ~0.1 s on the default robot's explicit program, a stall spent six, and a plain solve
    at :data:`TOLERANCE` before them: 60 % of a co-design candidate's time)."""
    import cvxpy as cp

    rungs = tuple(t for t in REFERENCE_TOLERANCES if t >= TOLERANCE)
    try:
        return solve_clarabel(program, (*rungs, *(t for t in LOOSER if t > rungs[-1])))
    except cp.error.SolverError as e:  # failed at every rung: the caller names it
        return f"failed ({e})"


def explicit_program(data: Sequence[Condensed], mode: str, nonneg: np.ndarray,
                     engaged: np.ndarray, G: np.ndarray, h: np.ndarray,
                     start: np.ndarray | None = None) -> tuple[np.ndarray, dict[str, Any]]:
    """The stacked program with explicit forces at the samples that bind (cvxpy, Clarabel),
    their set grown until no condensed sample breaks an inequality (module docstring).

    With ``start`` (the condensed optimum) in ``"worst"`` mode the program holds only the
    problems that can set the worst case: those with explicit samples and those within
    :data:`NEAR` of the worst at ``start``. A left-out problem — every sample condensed, so its
    value is the oracle's — whose value at the solution exceeds the program's worst (by more
    than :data:`TOLERANCE`) joins and the program is solved again; the explicit sets grow only
    at a solution every problem meets. That solution is the whole program's optimum: the
    smaller program is a relaxation of it (fewer constraints ``r_c ≤ t``), and a relaxation's
    optimum that meets the left-out constraints is optimal for the whole. Measured on the
    co-designed gait's 17 stop-shift scenarios: 5 of 17 in the program, the same magnitudes to
    the solver's tolerance, in a fifth of the time (tests/design/search/test_tolerance.py)."""
    import cvxpy as cp

    nx = data[0].problem.nx
    every = set(range(len(data)))
    if mode == "worst" and start is not None:
        values = np.array([d.oracle(start)[0] for d in data])
        held = {i for i, d in enumerate(data)
                if not d.condensed.all() or values[i] >= values.max() - NEAR}
    else:
        held = every
    for rounds in range(1, MAX_ROUNDS + 1):
        x = cp.Variable(nx)
        cons: list = []
        kept = sorted(held)
        ratios = [data[i].cost(x, cons) / data[i].base for i in kept]
        if nonneg.any():
            cons.append(x[np.flatnonzero(nonneg)] >= 0)
        if (~engaged).any():
            cons.append(x[np.flatnonzero(~engaged)] == 0)
        if G.size:
            cons.append(G @ x <= h)
        if mode == "worst":
            t = cp.Variable()
            program = cp.Problem(cp.Minimize(t), cons + [r <= t for r in ratios])
        else:
            program = cp.Problem(cp.Minimize(sum(ratios) / len(ratios)), cons)
        status = _solve(program)
        if status.startswith("failed"):
            raise InfeasibleForcesError(
                f"Clarabel could not solve the condensed spring program at any tolerance down "
                f"to {LOOSER[-1]:g} ({status}): the solver failed; that is no proof that "
                "no springs exist")
        if status != cp.OPTIMAL:
            raise InfeasibleForcesError(
                f"the condensed spring program has no solution (Clarabel: {status}); "
                "conditions without admissible forces, or design limits no spring meets")
        xv = np.asarray(x.value, dtype=float)
        xv = np.where(nonneg, np.maximum(xv, 0.0), xv)
        above = {i for i in every - held
                 if data[i].oracle(xv)[0] > float(program.value) + TOLERANCE}
        if above:  # a left-out problem sets the worst case: solve again with it
            held |= above
            continue
        if not any([d.update(xv) for d in data]):  # every problem checked
            info = {"path": "cvxpy with explicit forces where samples bind",
                    "rounds": rounds, "program_value": float(program.value)}
            if held != every:
                info["problems_in_program"] = len(held)
            return xv, info
        held |= {i for i, d in enumerate(data) if not d.condensed.all()}
    raise InfeasibleForcesError(f"the condensed program's active set did not settle in "
                                f"{MAX_ROUNDS} rounds")
