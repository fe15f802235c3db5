"""The cvxpy reference of the force program (:mod:`hexaleg.dynamics.contact`), for tests and
benchmarks.

The cvxpy formulation (parametrised, compiled once, DPP), solved per sample: slow, kept as the
reference that the tests compare the fast path (:func:`hexaleg.dynamics.solver.solve_fast`)
against, and that ``analysis/bench_core.py`` times.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np

from hexaleg.dynamics.conic import CLARABEL_TOLERANCES, raise_infeasible
from hexaleg.dynamics.contact import QUADRATIC_OBJECTIVES, ContactParams, StanceSystem

if TYPE_CHECKING:
    import cvxpy as cp

REFERENCE_TOLERANCES: tuple[float, ...] = (1e-13, 1e-12, *CLARABEL_TOLERANCES)
"""The reference's tolerance ladder: :data:`~hexaleg.dynamics.conic.CLARABEL_TOLERANCES` with two
tighter rungs first (the reference is the yardstick of the exact solvers' tests)."""


@dataclass(frozen=True, eq=False)
class _ReferenceProblem:
    """The parametrised cvxpy program of one motion: the forces ``f`` (3 n_legs), and the
    per-sample parameters by name (``A``, ``D``, ``bb``, ``c``, ``qd``, ``qd_in``, ``qd_out``,
    ``mask``, ``fmin``)."""

    problem: cp.Problem
    f: cp.Variable
    params: dict[str, cp.Parameter]


def _build(system: StanceSystem, objective: str, weights: np.ndarray,
           contact: ContactParams) -> _ReferenceProblem:
    """The program for all legs — swing legs' forces are pinned to zero by the ``mask``
    parameter — built once, DPP."""
    import cvxpy as cp

    n_legs = system.stance.shape[1]
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
    assert problem.is_dcp(dpp=True)  # type: ignore[call-arg]  # cvxpy's signature hides dpp
    params = {"A": A, "D": D, "bb": bb, "c": c, "qd": qd, "qd_in": qd_in, "qd_out": qd_out,
              "mask": mask, "fmin": fmin}
    return _ReferenceProblem(problem, f, params)


def _load_sample(ref: _ReferenceProblem, system: StanceSystem, k: int, tau_spring: np.ndarray,
                 contact: ContactParams) -> np.ndarray:
    """Set the parameters to sample ``k``; returns its stance mask on the forces (3 n_legs,)."""
    p = ref.params
    m = np.repeat(system.stance[k], 3).astype(float)
    p["A"].value, p["D"].value, p["bb"].value = system.A[k], system.D[k], system.b_base[k]
    p["c"].value = system.b_joint[k] - tau_spring[k]
    p["qd"].value = system.qdot[k]
    p["qd_in"].value = system.qdot[k] / system.efficiency
    p["qd_out"].value = system.qdot[k] * system.efficiency
    p["mask"].value = m
    p["fmin"].value = contact.min_normal_force * system.stance[k].astype(float)
    return m


def solve_clarabel(problem: cp.Problem,
                   rungs: tuple[float, ...] = REFERENCE_TOLERANCES) -> str:
    """Solve with Clarabel: tight tolerances first (``rungs``, tightest first); where Clarabel
    stalls short of them, loosen step by step and keep the first solve that meets a tolerance.
    Returns the final status.

    Clarabel reports "almost solved" (cvxpy's "inaccurate") when it stops having met its
    *reduced* tolerances; these are set to the next, looser rung, so such an answer meets that
    rung's tolerances — from iterates that went further than a solve at that rung would, hence
    at least as accurate (on the weakly curved electrical objective, 1e-7 N against 4e-6 N
    from the looser solve). At the loosest rung only "solved" counts.
    """
    import cvxpy as cp

    for i, tol in enumerate(rungs):
        looser = rungs[i + 1] if i + 1 < len(rungs) else None
        reduced = {} if looser is None else {
            "reduced_tol_gap_abs": looser, "reduced_tol_gap_rel": looser,
            "reduced_tol_feas": looser, "reduced_tol_ktratio": 100 * looser}
        with warnings.catch_warnings():
            warnings.filterwarnings("ignore", message="Solution may be inaccurate")
            try:
                problem.solve(solver=cp.CLARABEL, tol_gap_abs=tol, tol_gap_rel=tol,
                              tol_feas=tol, tol_ktratio=100 * tol, max_iter=200, **reduced)
            except cp.error.SolverError:  # stalled short of even the reduced tolerances
                if looser is None:
                    raise
                continue
        if problem.status == cp.OPTIMAL_INACCURATE and looser is not None:
            return cp.OPTIMAL  # met the next rung's tolerances
        if problem.status != cp.OPTIMAL_INACCURATE:
            break
    return str(problem.status)


def solve_reference(system: StanceSystem, tau_spring: np.ndarray, objective: str,
                    weights: np.ndarray, contact: ContactParams,
                    samples: np.ndarray | None = None) -> np.ndarray:
    """Optimal foot forces by the cvxpy reference formulation, one solve per sample.

    The problem is built once with parameters (DPP) for all legs — swing legs' forces are pinned
    to zero by a mask parameter — and re-solved per sample with Clarabel at tight tolerances
    (:data:`hexaleg.dynamics.conic.CLARABEL_TOLERANCES`, the tightest one Clarabel reaches; an
    "inaccurate" status at the loosest one is an error, never a silent answer).

    Args:
        system: As for :func:`hexaleg.dynamics.solver.solve_fast`.
        tau_spring: As for :func:`hexaleg.dynamics.solver.solve_fast`.
        objective: As for :func:`hexaleg.dynamics.solver.solve_fast`.
        weights: As for :func:`hexaleg.dynamics.solver.solve_fast`.
        contact: As for :func:`hexaleg.dynamics.solver.solve_fast`.
        samples: Indices to solve (default all); other rows of the result are NaN.

    Returns:
        Forces, shape (T, 3 n_legs), N.

    Raises:
        InfeasibleForcesError, TorqueLimitError: as :func:`hexaleg.dynamics.solver.solve_fast`.
    """
    import cvxpy as cp

    ref = _build(system, objective, weights, contact)
    T = system.n_samples
    out = np.full((T, ref.f.size), np.nan)
    for k in range(T) if samples is None else samples:
        m = _load_sample(ref, system, int(k), tau_spring, contact)
        status = solve_clarabel(ref.problem)
        if status != cp.OPTIMAL:
            raise_infeasible(system, int(k), tau_spring, contact, status)
        out[k] = ref.f.value * m
    return out
