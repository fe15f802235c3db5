"""Minimise the worst (or the mean) of a few convex functions of a few variables: a proximal
bundle method.

The robust spring program (:mod:`hexaleg.design.robust.box`) has a handful of magnitudes x (2–12)
and one convex, piecewise-quadratic function per condition, each a sum over thousands of
samples; written out as one conic program it has a cone per sample and joint, which makes the
solver, not the physics, the cost. Here each function is only *evaluated* (value and a
subgradient, vectorised NumPy), and the program in x is built from cutting planes:

    minimise  F(x) = max_c f_c(x)   (or  Σ_c f_c(x) / n)   subject to  G x ≤ h,  x_i ≥ 0 (i ∈ N)

Each iteration minimises the cutting-plane model ``max_c max_j f_c(x_j) + g_cj·(x − x_j)`` plus
a proximal term ``(u/2)‖x − x̂‖²`` about the best point x̂ (one small QP, Clarabel); a point
that lowers F by a tenth of the predicted decrease becomes x̂ (a serious step), otherwise its
cuts refine the model (a null step); a cut that has not made the model at the last
:data:`CUT_AGE` model steps is dropped, so that each QP stays small (bundle compression: the
active cuts are kept, and with them the convergence). It stops when the predicted decrease is
below the tolerance — x̂ is then optimal to that tolerance (Kiwiel's proximal bundle method; e.g.
Bonnans, Gilbert, Lemaréchal & Sagastizábal, *Numerical Optimization*, 2006, ch. 10). F never
increases from the start: started at a feasible x₀, the result is never worse than x₀. A model
step the QP solver cannot solve once x̂ is feasible (its program always has a solution then: the
model's epigraph variables are free) is a numerical failure: the method stops there with x̂ and
says so (:attr:`BundleResult.stopped`), as it does at :data:`MAX_ITERATIONS`.

**A working set of functions** (mode ``"worst"``). Of many functions (the stop-tolerance
program's 17–21 shifted conditions) a few set the worst at the optimum; each one held in the
model costs an evaluation and its cuts at every step. The model starts with those within
:data:`WORKING_SET` of the worst at x₀; when it has converged on them, the others are evaluated
at x̂, and any above the model's worst joins (its cut at x̂ added) and the method goes on. It ends
when none is: then ``max over the held ≤ min F ≤ F(x̂) = max over the held at x̂``, so x̂ is
optimal for every function to the same tolerance (the minimum over a subset of the functions is
a lower bound; an outer-approximation / constraint-generation argument, e.g. Bonnans et al.
§10 on bundle compression, Kelley's cutting planes). Functions only join, so it ends.
"""

from __future__ import annotations

from collections.abc import Callable, Sequence
from dataclasses import dataclass
from typing import Any

import numpy as np

from hexaleg.checks import one_of
from hexaleg.errors import InfeasibleForcesError

Oracle = Callable[[np.ndarray], tuple[float, np.ndarray]]
"""x → (f(x), a subgradient of f at x, shape (nx,))."""
MODES: tuple[str, ...] = ("worst", "mean")
"""Minimise the largest function or their mean."""
MAX_ITERATIONS = 400
"""Model steps (QPs) before it stops with the gap it reached (:attr:`BundleResult.gap`)."""
TOLERANCE = 1e-10
"""Predicted decrease (in the units of F) at which the method stops."""
CUT_AGE = 10
"""Model steps a cutting plane may stay below its condition's model before it is dropped."""
WORKING_SET = 0.01
"""Mode ``"worst"``: the functions the model starts with are those within this fraction of the
largest at the start (of its magnitude, at least 1); the others join when the model's optimum
leaves one of them above its worst."""


@dataclass(frozen=True)
class BundleResult:
    """The minimiser, its value per function, and the work done; ``stopped`` says why it ended
    before the tolerance ("" when it met it or used its :data:`MAX_ITERATIONS`); ``held``: how
    many functions the model held when it ended (the working set, module docstring)."""

    x: np.ndarray
    values: np.ndarray
    iterations: int
    serious_steps: int
    gap: float
    stopped: str = ""
    held: int = 0


@dataclass
class _Cuts:
    """Cutting planes ``f + g·(y − y_j) ≤ t_c``: condition, value, subgradient, point, and how
    many model steps each has been off its condition's model (its age)."""

    c: np.ndarray
    f: np.ndarray
    g: np.ndarray
    y: np.ndarray
    age: np.ndarray

    @classmethod
    def empty(cls, nx: int) -> _Cuts:
        return cls(np.zeros(0, int), np.zeros(0), np.zeros((0, nx)), np.zeros((0, nx)),
                   np.zeros(0, int))

    def add(self, values: np.ndarray, grads: list[np.ndarray], y: np.ndarray,
            first: int = 0) -> None:
        """Cuts at ``y`` of the functions ``first, first + 1, …`` (their places in the model)."""
        n = values.size
        self.c = np.r_[self.c, first + np.arange(n)]
        self.f = np.r_[self.f, values]
        self.g = np.vstack([self.g, np.array(grads)])
        self.y = np.vstack([self.y, np.tile(y, (n, 1))])
        self.age = np.r_[self.age, np.zeros(n, int)]

    def prune(self, y: np.ndarray, n: int) -> None:
        """Age the cuts below their condition's model at the model step ``y`` (the active ones,
        those that make the model there, become 0) and drop those older than
        :data:`CUT_AGE`."""
        v = self.f + np.sum(self.g * (y - self.y), axis=1)
        top = np.full(n, -np.inf)
        np.maximum.at(top, self.c, v)
        active = v >= top[self.c] - 1e-9 * np.maximum(1.0, np.abs(top[self.c]))
        self.age = np.where(active, 0, self.age + 1)
        keep = self.age <= CUT_AGE
        self.c, self.f, self.g, self.y, self.age = (self.c[keep], self.f[keep], self.g[keep],
                                                    self.y[keep], self.age[keep])

    def model(self, y: np.ndarray, n: int) -> np.ndarray:
        """The model of each function at y, shape (n,)."""
        v = self.f + np.sum(self.g * (y - self.y), axis=1)
        out = np.full(n, -np.inf)
        np.maximum.at(out, self.c, v)
        return out


def csc(dense: np.ndarray) -> Any:
    """``scipy.sparse.csc_matrix(dense)`` (its nonzeros, column-major, rows sorted) without the
    checks of the sparse constructors — the same arrays, so the same Clarabel solve."""
    import scipy.sparse as sp

    cols, rows = np.nonzero(dense.T)
    indptr = np.zeros(dense.shape[1] + 1, dtype=np.int32)
    np.cumsum(np.bincount(cols, minlength=dense.shape[1]), out=indptr[1:])
    return sp.csc_matrix((dense.T[cols, rows], rows.astype(np.int32), indptr), shape=dense.shape)


def _qp(cuts: _Cuts, n: int, mode: str, centre: np.ndarray, u: float, G: np.ndarray,
        h: np.ndarray, nonneg: np.ndarray, fixed: np.ndarray) -> np.ndarray:
    """The proximal model step: z = (x, t_1…t_n[, s]) minimising the model + (u/2)‖x − x̂‖²
    (without cuts: the point nearest x̂ that meets the constraints). One dense block of rows
    ``A z ≤ b`` (cuts, t_c ≤ s, G, −z_i ≤ 0) then the fixed z_i = 0, handed to Clarabel."""
    import clarabel

    from hexaleg.dynamics.conic import clarabel_solve

    nx = centre.size
    worst = mode == "worst" and n > 0
    nz = nx + n + (1 if worst else 0)
    P = np.zeros((nz, nz))
    P[np.arange(nx), np.arange(nx)] = u
    q = np.zeros(nz)
    q[:nx] = -u * centre
    if worst:
        q[-1] = 1.0
    elif n:
        q[nx:nx + n] = 1.0 / n
    k = cuts.c.size
    neg, eq = np.flatnonzero(nonneg), np.flatnonzero(fixed)
    m = k + (n if worst else 0) + G.shape[0] + neg.size
    A = np.zeros((m + eq.size, nz))
    b = np.zeros(m + eq.size)
    if k:  # f + g·(y − y_j) − t_c ≤ 0
        A[:k, :nx] = cuts.g
        A[np.arange(k), nx + cuts.c] = -1.0
        b[:k] = np.sum(cuts.g * cuts.y, axis=1) - cuts.f
    r = k
    if worst:  # t_c − s ≤ 0
        A[r + np.arange(n), nx + np.arange(n)] = 1.0
        A[r:r + n, -1] = -1.0
        r += n
    if G.size:
        A[r:r + G.shape[0], :nx] = G
        b[r:r + G.shape[0]] = h
    r += G.shape[0]
    A[r + np.arange(neg.size), neg] = -1.0
    A[m + np.arange(eq.size), eq] = 1.0
    cones = [clarabel.NonnegativeConeT(m)]
    if eq.size:
        cones.append(clarabel.ZeroConeT(eq.size))
    z, status = clarabel_solve(csc(P), q, csc(A), b, cones)
    if status != "Solved":
        raise InfeasibleForcesError(f"the robust program's model step has no solution "
                                    f"(Clarabel: {status}); design limits no spring meets")
    return z[:nx]


def minimise(oracles: Sequence[Oracle], x0: np.ndarray, mode: str = "worst", *,
             G: np.ndarray | None = None, h: np.ndarray | None = None,
             nonneg: np.ndarray | None = None, fixed: np.ndarray | None = None,
             tolerance: float = TOLERANCE) -> BundleResult:
    """Minimise ``max_c f_c`` (mode ``"worst"``) or their mean (``"mean"``) over x (module
    docstring).

    Args:
        oracles: One per function: x → (value, subgradient).
        x0: The start, shape (nx,); projected onto the constraints when it breaks them.
        mode: One of :data:`MODES`.
        G: Constraint rows ``G x ≤ h``, shape (m, nx).
        h: Their right-hand sides, shape (m,).
        nonneg: Which x must be ≥ 0, shape (nx,), bool.
        fixed: Which x are 0, shape (nx,), bool.
        tolerance: The predicted decrease at which it stops.

    Raises:
        UnknownNameError: an unknown mode (lists them).
        InfeasibleForcesError: the constraints have no solution.
    """
    one_of("mode", mode, MODES)
    x0 = np.asarray(x0, dtype=float)
    nx, n = x0.size, len(oracles)
    G = np.zeros((0, nx)) if G is None else np.asarray(G, dtype=float)
    h = np.zeros(0) if h is None else np.asarray(h, dtype=float)
    nonneg = np.zeros(nx, bool) if nonneg is None else np.asarray(nonneg, bool)
    fixed = np.zeros(nx, bool) if fixed is None else np.asarray(fixed, bool)
    scale = np.maximum(np.abs(x0), 1e-2)  # work in x / scale: magnitudes of unlike units

    def evaluate(y: np.ndarray, which: Sequence[int]) -> tuple[np.ndarray, list[np.ndarray]]:
        out = [oracles[c](y * scale) for c in which]
        return np.array([v for v, _ in out]), [g * scale for _, g in out]

    def total(v: np.ndarray) -> float:
        return float(v.max() if mode == "worst" else v.mean())

    Gs = G * scale
    y = x0 / scale
    ok = (Gs @ y <= h + 1e-12).all() and (y[nonneg] >= 0).all() and not y[fixed].any()
    if not ok:  # the closest feasible start
        y = _qp(_Cuts.empty(nx), 0, mode, y, 1.0, Gs, h, nonneg, fixed)
    values, grads = evaluate(y, range(n))
    if mode == "worst" and n > 1:  # the working set: those near the worst at the start
        near = values.max() - WORKING_SET * max(1.0, abs(values.max()))
        held = [int(c) for c in np.flatnonzero(values >= near)]
    else:
        held = list(range(n))
    cuts = _Cuts.empty(nx)
    cuts.add(values[held], [grads[c] for c in held], y)
    best, best_values = y, values[held]
    u, serious, gap, it, stopped = 1.0, 0, np.inf, 0, ""
    checked: tuple[list[int], np.ndarray] | None = None  # the left-out ones' values at x̂
    for it in range(1, MAX_ITERATIONS + 1):
        try:
            trial = _qp(cuts, len(held), mode, best, u, Gs, h, nonneg, fixed)
        except InfeasibleForcesError as e:  # x̂ meets the constraints: a numerical failure
            stopped = f"model step {it} failed ({e}); the best point so far is kept"
            break
        gap = total(best_values) - total(cuts.model(trial, len(held)))
        if gap <= tolerance * max(1.0, abs(total(best_values))):
            rest = [c for c in range(n) if c not in held]
            out, out_grads = evaluate(best, rest)
            joins = np.flatnonzero(out > total(best_values))
            if not joins.size:  # no function left out is above the model's worst: optimal
                checked = (rest, out)
                break
            cuts.add(out[joins], [out_grads[i] for i in joins], best, first=len(held))
            held += [rest[i] for i in joins]
            best_values = np.r_[best_values, out[joins]]
            continue
        cuts.prune(trial, len(held))
        values, grads = evaluate(trial, held)
        cuts.add(values, grads, trial)
        if total(values) <= total(best_values) - 0.1 * gap:
            best, best_values = trial, values
            serious += 1
            u = max(u / 2, 1e-6)
        else:
            u = min(u * 1.5, 1e6)
    every = np.empty(n)
    every[held] = best_values
    if len(held) < n:
        if checked is None:  # stopped before the check: the left-out ones evaluated here
            rest = [c for c in range(n) if c not in held]
            checked = (rest, evaluate(best, rest)[0])
        every[checked[0]] = checked[1]
    return BundleResult(x=best * scale, values=every, iterations=it,
                        serious_steps=serious, gap=float(gap), stopped=stopped,
                        held=len(held))
