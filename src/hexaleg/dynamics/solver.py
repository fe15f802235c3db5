"""The exact solver of the force program (:mod:`hexaleg.dynamics.contact`), batched per motion.

:func:`solve_fast` is the path every analysis, sweep and optimiser uses. Each sample's program is
reduced to the null space of its base rows (:mod:`hexaleg.dynamics.reduction`) and solved, all
samples of a stance size at once, by :mod:`hexaleg.dynamics.batched`: a guess of the active set
(the last stiffness choice's, in a sweep) is solved and *certified* by the KKT conditions of the
whole program (:mod:`hexaleg.dynamics.active_set`), repaired where it fails, and the batched
interior-point method (:mod:`hexaleg.dynamics.ipm`) finds the active set where no guess does.
Certified forces are the optimum to rounding, for every objective, friction model and torque
limit: the same solution as Clarabel through cvxpy (:mod:`hexaleg.dynamics.reference`, the tests'
reference), without its per-sample calls. A sample nothing certifies is solved by Clarabel
(:mod:`hexaleg.dynamics.conic`), which also raises the error that names an infeasible sample.

:class:`QuadraticGains` — the unconstrained optimum of the quadratic objectives as an affine map
of the spring torques — serves the design program (:mod:`hexaleg.design.search.program`), which
needs it as a matrix.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass

import numpy as np

from hexaleg.dynamics.active_set import constant_rows, unconstrained_gains
from hexaleg.dynamics.batched import Stats, WarmStart, solve_group
from hexaleg.dynamics.blocks import Data
from hexaleg.dynamics.conic import raise_infeasible, raise_unreachable, solve_sample
from hexaleg.dynamics.contact import (
    QUADRATIC_OBJECTIVES,
    ContactParams,
    StanceSystem,
    violations,
)
from hexaleg.dynamics.pieces import pieces
from hexaleg.dynamics.reduction import Group, reduce


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
        sd = np.linalg.svd(D, compute_uv=False)
        if (n >= 6 and np.all(sv[:, -1] > 1e-9 * sv[:, 0])
                and n <= nj and np.all(sd[:, -1] > 1e-9 * sd[:, 0])):
            sol = np.linalg.solve(kkt, rhs)
        else:
            # Rank-deficient base rows (e.g. two point feet cannot push any moment about the line
            # through them, one foot's three forces meet six rows): f is still unique where the
            # base wrench is reachable; the pseudo-inverse gives it, and solve_fast rejects
            # samples whose base rows then fail. Rank-deficient joint rows (a two-joint leg's
            # foot force along its joint axes loads no joint): that force costs nothing, and
            # the pseudo-inverse takes the least of it (no internal push across the legs'
            # planes).
            sol = np.linalg.pinv(kkt, rcond=1e-10) @ rhs
        K[np.ix_(rows, cols, np.arange(nj))] = sol[:, :n, :nj]
        L[np.ix_(rows, cols, np.arange(6))] = sol[:, :n, nj:]
    f0 = np.einsum("tkj,tj->tk", K, system.b_joint) + np.einsum("tki,ti->tk", L, system.b_base)
    G = system.D @ K - np.eye(nj)
    return QuadraticGains(np.asarray(weights, dtype=float).copy(), K, f0,
                          system.torques(f0, np.zeros_like(system.b_joint)), G)


def _efficiency(system: StanceSystem, weights: np.ndarray) -> np.ndarray:
    return np.broadcast_to(np.asarray(system.efficiency, dtype=float), weights.shape)


def group_program(system: StanceSystem, group: Group, objective: str, weights: np.ndarray,
                  contact: ContactParams) -> Data:
    """``group``'s programs for an objective, joint weights (nj,) and contact settings, with
    ``τ₀`` that of no springs (``tau_base``; :meth:`Group.tau0` gives it for spring torques),
    the candidate rows' gradients and, for the quadratic objectives, the unconstrained gains."""
    J = group.joints
    base = Data(group.fp, group.N, group.E, group.tau_base,
                pieces(objective, weights[J], system.qdot[group.rows, J],
                       _efficiency(system, weights)[J], contact.regularization),
                system.tau_max[J] if contact.torque_limits else None, contact)
    return dataclasses.replace(base, const=constant_rows(base),
                               Z=None if base.pieces.K else unconstrained_gains(base))


def solve_fast(system: StanceSystem, tau_spring: np.ndarray, objective: str,
               weights: np.ndarray, contact: ContactParams, *,
               warm: WarmStart | None = None) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Optimal foot forces for every sample (module docstring).

    Args:
        system: The motion's stance system.
        tau_spring: Spring torques on the joints, shape (T, nj), N·m.
        objective: One of :data:`hexaleg.dynamics.contact.OBJECTIVES`.
        weights: Joule coefficients ``c_j`` (``"joule"``, ``"electrical"``) or ones
            (``"torque_squared"``), shape (nj,), W/(N·m)².
        contact: Contact settings.
        warm: The last solve's active sets for this motion and objective: the guess to start
            from, replaced by this solve's (a sweep passes the same object every time).

    Returns:
        ``(f, tau, resolved)``: forces (T, 3 n_legs), N, in the program's frame (the world's on
        level ground, else the contact frame: ``system.to_world``); motor torques (T, nj), N·m;
        and the mask (T,) of samples where an inequality binds (the quadratic objectives) or that
        have stance feet (the others): those whose forces are not the unconstrained optimum.

    Raises:
        InfeasibleForcesError: no forces satisfy a sample's constraints (names time and feet).
        TorqueLimitError: the torque limits cannot be met (names joint, time, torque).
    """
    red = reduce(system)
    T, n_legs = system.stance.shape
    if not red.reachable.all():
        k = int(np.flatnonzero(~red.reachable)[0])
        raise_unreachable(system, k, float(red.residual[k]))
    tau = system.b_joint - tau_spring
    if contact.torque_limits:
        over = red.free & (np.abs(tau) > system.tau_max * (1.0 + 1e-12))
        if over.any():  # a swing-leg joint beyond its limit, whatever the forces
            k = int(np.flatnonzero(over.any(axis=1))[0])
            raise_infeasible(system, k, tau_spring, contact, "swing-leg joint beyond its limit")
    f3 = np.zeros((T, n_legs, 3))
    quadratic = objective in QUADRATIC_OBJECTIVES
    resolved = np.zeros(T, bool) if quadratic else np.asarray(system.stance.any(axis=1))
    eff = _efficiency(system, weights)
    key = (objective, weights.tobytes(), eff.tobytes(), float(contact.regularization), contact)
    if warm is not None and (warm.key != key or len(warm.states) != len(red.groups)):
        warm.key, warm.states = key, [None] * len(red.groups)
    stats = warm.stats if warm is not None else Stats()
    uncertified: list[np.ndarray] = []
    fixed: list[np.ndarray] = []
    for i, g in enumerate(red.groups):
        J = g.joints
        if g.m == 0:  # one point foot: the base rows fix its force, there is nothing to choose
            f3[g.rows[None, :], g.legs] = np.transpose(g.fp, (1, 2, 0))
            tau[g.rows[None, :], J] = g.tau0(tau_spring)
            fixed.append(g.rows)
            continue
        if key not in g.cache:  # the group's program for these settings, once per motion
            g.cache[key] = group_program(system, g, objective, weights, contact)
        data = dataclasses.replace(g.cache[key], tau0=g.tau0(tau_spring))
        guess = warm.states[i] if warm is not None else None
        state, ok = solve_group(data, guess, stats)
        if warm is not None:
            warm.states[i] = state
        f3[g.rows[None, :], g.legs] = np.transpose(g.forces(state.z), (1, 2, 0))
        tau[g.rows[None, :], J] = g.torques(data.tau0, state.z)
        if quadratic:
            resolved[g.rows] = state.held.any(axis=0) | state.feet.any(axis=(0, 1))
        uncertified.append(g.rows[~ok])
    f = f3.reshape(T, 3 * n_legs)
    if fixed:  # a fixed force outside its cone or a torque beyond its limit: the sample's
        # own program names why (it has no other forces to offer)
        rows = np.concatenate(fixed)
        bad = rows[violations(system, f, tau, contact)[rows]]
        uncertified.append(bad)
        if not quadratic:
            resolved[rows] = True
    for k in np.sort(np.concatenate(uncertified or [np.zeros(0, int)])):
        f[k] = solve_sample(system, int(k), tau_spring, objective, weights, contact)
        tau[k] = system.torques(f[k:k + 1], tau_spring[k:k + 1], slice(k, k + 1))[0]
        resolved[k] = True
    return f, tau, resolved
