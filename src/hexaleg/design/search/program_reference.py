"""The design program (:mod:`hexaleg.design.search.program`) in cvxpy: the reference, and the solver
of the non-quadratic objectives.

One program for the whole cycle, vectorised — no Python loop of per-sample expressions: the
forces of all stance feet at all samples are one variable, the base and joint rows are sparse
block-diagonal matrices, the friction cones one vectorised second-order cone, and the objective
``Σ_t w_t E(τ(t))`` one expression over the (T·nj) motor torques. The magnitudes x are shared by
all samples. Solved with Clarabel through cvxpy
(:func:`hexaleg.dynamics.reference.solve_clarabel`, the tolerance ladder of
:data:`hexaleg.dynamics.conic.CLARABEL_TOLERANCES`); for the quadratic objectives the tests
compare it with the condensed active-set path, which never calls cvxpy.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np

from hexaleg.design.search.program import DesignProblem, DesignSolution
from hexaleg.dynamics.conic import base_row_space
from hexaleg.dynamics.contact import QUADRATIC_OBJECTIVES, ContactParams
from hexaleg.dynamics.reference import solve_clarabel
from hexaleg.errors import InfeasibleForcesError


def stacked(problem: DesignProblem, samples: np.ndarray | None = None
            ) -> tuple[Any, Any, np.ndarray, np.ndarray]:
    """Sparse ``D`` (S·nj, N) and reduced base rows ``A`` (R, N) over the stance forces of the
    samples (all T, or ``samples``; N forces), the base right-hand side (R,), and the stance
    columns' global indices of the padded force vector (N,) (sample-major)."""
    import scipy.sparse as sp

    system = problem.prepared.system
    T, nj = system.n_samples, system.D.shape[1]
    d_blocks, a_blocks, b_rows, where = [], [], [], []
    for k in (range(T) if samples is None else (int(k) for k in samples)):
        st = np.flatnonzero(np.repeat(system.stance[k], 3))
        d_blocks.append(sp.csr_matrix(system.D[k][:, st]) if st.size else
                        sp.csr_matrix((nj, 0)))
        if st.size:
            rows, rhs = base_row_space(system, k, system.A[k][:, st])
            a_blocks.append(sp.csr_matrix(rows))
            b_rows.append(rhs)
        else:
            a_blocks.append(sp.csr_matrix((0, 0)))
        where.append(k * system.A.shape[2] + st)
    if not d_blocks:
        return (sp.csr_matrix((0, 0)), sp.csr_matrix((0, 0)), np.zeros(0),
                np.zeros(0, dtype=int))
    D = sp.block_diag(d_blocks, format="csr")
    A = sp.block_diag(a_blocks, format="csr")
    A.resize((A.shape[0], D.shape[1]))
    return D, A, np.concatenate(b_rows) if b_rows else np.zeros(0), np.concatenate(where)


def force_constraints(f: Any, A: Any, b_base: np.ndarray, contact: ContactParams) -> list:
    """cvxpy constraints on stacked stance forces ``f`` (x, y, z triples): the base rows
    ``A f = b_base``, normal forces ≥ the minimum, the friction cones (exact or pyramid)."""
    import cvxpy as cp

    fx, fy, fz = f[0::3], f[1::3], f[2::3]  # stance columns come in (x, y, z) triples
    cons = [fz >= contact.min_normal_force]
    if A.shape[0]:
        cons.append(A @ f == b_base)
    if contact.cone == "soc":
        cons.append(cp.SOC(contact.mu * fz, cp.vstack([fx, fy]), axis=0))
    else:
        s = contact.mu / math.sqrt(2)
        cons += [cp.abs(fx) <= s * fz, cp.abs(fy) <= s * fz]
    return cons


def solve_design_reference(problem: DesignProblem) -> DesignSolution:
    """The global optimum of ``problem`` for any objective, by one cvxpy program.

    Raises:
        InfeasibleForcesError: cvxpy/Clarabel reports no optimal solution (names the status and
            the design constraints).
    """
    import cvxpy as cp

    prepared = problem.prepared
    system, contact = prepared.system, prepared.contact
    T, nj = system.n_samples, system.D.shape[1]
    D, A, b_base, where = stacked(problem)
    N = D.shape[1]
    f = cp.Variable(N)
    x = cp.Variable(problem.nx)
    Bfull = np.zeros((T, nj, problem.nx))
    Bfull[:, problem.cols] = problem.B
    tau = system.b_joint.reshape(-1) - D @ f - Bfull.reshape(T * nj, -1) @ x  # (T·nj,)
    w = np.repeat(problem.sample_weights, nj)
    c = np.tile(prepared.weights(problem.objective), T)
    if problem.objective in QUADRATIC_OBJECTIVES:
        cost = cp.sum(cp.multiply(w * c, cp.square(tau)))
    else:
        qd = system.qdot.reshape(-1)
        if problem.objective == "electrical":
            eta = np.tile(np.broadcast_to(system.efficiency, (nj,)), T)  # per joint
            power = cp.maximum(cp.multiply(qd / eta, tau), cp.multiply(qd * eta, tau))
            per_joint = cp.maximum(0, power + cp.multiply(c, cp.square(tau)))
        else:
            per_joint = cp.maximum(0, cp.multiply(qd, tau))
        cost = (cp.sum(cp.multiply(w, per_joint))
                + contact.regularization * cp.sum(cp.multiply(w, cp.square(tau))))
    cons = force_constraints(f, A, b_base, contact)
    if contact.torque_limits:
        cons.append(cp.abs(tau) <= np.tile(system.tau_max, T))
    neg = np.flatnonzero(problem.nonnegative)
    if neg.size:
        cons.append(x[neg] >= 0)
    if problem.G.size:
        cons.append(problem.G @ x <= problem.h)
    program = cp.Problem(cp.Minimize(cost), cons)
    if solve_clarabel(program) != cp.OPTIMAL:
        raise InfeasibleForcesError(
            f"the spring design program has no solution (cvxpy: {program.status}); design "
            f"constraints: {', '.join(sorted(set(problem.labels))) or 'none'}")
    xv = np.asarray(x.value, dtype=float)
    tau_v = np.asarray(tau.value, dtype=float).reshape(T, nj)
    value = float(np.sum(problem.sample_weights[:, None] * prepared.weights(problem.objective)
                         * tau_v**2))
    forces = np.zeros(T * system.A.shape[2])
    forces[where] = f.value
    return DesignSolution(xv, value, np.arange(T), 1, forces.reshape(T, -1))


def solve_metric_reference(problem: DesignProblem, metric: str) -> tuple[np.ndarray, float]:
    """The magnitudes minimising ``metric`` (``"joule"`` or ``"electrical"``) per cycle of the
    Joule-optimal forces, by one cvxpy program that does not use the condensed gains: the forces
    of every sample are variables held at the Joule optimum by its optimality conditions —
    the base rows ``A f = b`` and stationarity ``Nᵀ Dᵀ C τ = 0`` with N a basis of the null
    space of A (the KKT conditions of ``min Σ c τ²`` s.t. ``A f = b``, the multiplier
    eliminated; no inequality, so valid where none binds) — and the
    objective is the metric of their motor torques (electrical:
    :meth:`hexaleg.robot.motor.Motor.electrical_power`). The reference of
    :func:`hexaleg.design.search.condensed.solve_condensed`; returns ``(x, value J)``.

    Raises:
        InfeasibleForcesError: cvxpy/Clarabel reports no optimal solution.
    """
    import cvxpy as cp
    import scipy.sparse as sp
    from scipy.linalg import null_space

    prepared = problem.prepared
    system = prepared.system
    T, nj = system.n_samples, system.D.shape[1]
    D, A, b_base, _ = stacked(problem)
    f, x = cp.Variable(D.shape[1]), cp.Variable(problem.nx)
    blocks = []  # per sample Nᵀ Dᵀ, N a basis of the null space of its base rows
    for k in range(T):
        st = np.flatnonzero(np.repeat(system.stance[k], 3))
        if not st.size:
            blocks.append(sp.csr_matrix((0, nj)))
            continue
        rows, _ = base_row_space(system, k, system.A[k][:, st])
        N = null_space(rows) if rows.size else np.eye(st.size)
        blocks.append(sp.csr_matrix(N.T @ system.D[k][:, st].T))
    Z = sp.block_diag(blocks, format="csr")
    Bfull = np.zeros((T, nj, problem.nx))
    Bfull[:, problem.cols] = problem.B
    tau = system.b_joint.reshape(-1) - D @ f - Bfull.reshape(T * nj, -1) @ x
    c = np.tile(prepared.weights("joule"), T)
    w = np.repeat(problem.sample_weights, nj)
    if metric == "joule":
        cost = cp.sum(cp.multiply(w * c, cp.square(tau)))
    else:
        qd = system.qdot.reshape(-1)
        eta = np.tile(np.broadcast_to(system.efficiency, (nj,)), T)
        power = cp.multiply(c, cp.square(tau)) + cp.maximum(cp.multiply(qd / eta, tau),
                                                            cp.multiply(qd * eta, tau))
        regen = np.tile(np.broadcast_to(np.asarray(prepared.motor.regeneration, dtype=bool),
                                        (nj,)), T)
        cost = w[regen] @ power[np.flatnonzero(regen)] if regen.any() else 0
        if (~regen).any():
            cost = cost + w[~regen] @ cp.pos(power[np.flatnonzero(~regen)])
    cons = [Z @ cp.multiply(c, tau) == 0, A @ f == b_base]
    neg = np.flatnonzero(problem.nonnegative)
    if neg.size:
        cons.append(x[neg] >= 0)
    if problem.G.size:
        cons.append(problem.G @ x <= problem.h)
    scale = float(prepared.baseline("joule")["total"][metric]) or 1.0  # O(1) for Clarabel
    program = cp.Problem(cp.Minimize(cost / scale), cons)
    if solve_clarabel(program) != cp.OPTIMAL:
        raise InfeasibleForcesError(f"the {metric} design program has no solution (cvxpy: "
                                    f"{program.status})")
    return np.asarray(x.value, dtype=float), float(program.value) * scale
