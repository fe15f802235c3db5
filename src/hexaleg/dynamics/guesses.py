"""Active-set guesses (:class:`hexaleg.dynamics.active_set.State`): read off an interior-point
solution, or repaired from a guess that failed its check.

From an interior-point solution (:func:`from_interior_point`): near the optimum every inequality
has either its slack ``s`` or its multiplier ``λ`` near zero (``s λ ≈ μ``, the interior-point
method stops at a duality gap ≈ 1e-9 of the objective), so an inequality is active when
``λ S² > s O`` with ``S`` the scale of its slack (the mean normal force for the foot rows, the
torque limit, the objective for a piece's epigraph row) and ``O`` that of the objective: the two
sides differ by ≈ 9 orders of magnitude either way, so rough scales suffice. This is the
classical "crossover" from an interior-point to an active-set solution (the identification
indicators of El-Bakry, Tapia & Zhang, J. Optim. Theory Appl. 89, 1996).

From a failed check (:func:`repair`): the moves of a primal active-set method, all at once —
violated rows join, rows with a multiplier of the wrong sign leave, a joint switches to the piece
that attains its maximum or is released from a kink to the side its multiplier points to.
"""

from __future__ import annotations

import numpy as np

from hexaleg.dynamics.active_set import Solution, State, foot_rows
from hexaleg.dynamics.blocks import Data, FootCone, FootRows, JointRows
from hexaleg.dynamics.certificate import Check
from hexaleg.dynamics.cones import soc_residual
from hexaleg.dynamics.ipm import Result
from hexaleg.dynamics.pieces import pick

KINK_TOL = 1e-6
"""A joint is at a kink only if the interior-point torque is this close to it, N·m (relative
above 1); the interior-point method stops ≈ 1e-9 from it."""


def _kink(data: Data, p: np.ndarray, q: np.ndarray, near: np.ndarray
          ) -> tuple[np.ndarray, np.ndarray]:
    """Where pieces ``p`` and ``q`` (J, T) meet nearest ``near``: ``(β, distinct)`` — 0 or
    ``−(α_p − α_q)/(γ_p − γ_q)``; ``distinct`` False where the two pieces are the same."""
    pc = data.pieces
    ap, aq = (pick(pc.alpha, i) for i in (p, q))
    gp, gq = (pick(pc.gamma, i) for i in (p, q))
    da, dg = ap - aq, gp - gq
    with np.errstate(divide="ignore", invalid="ignore"):
        other = np.where(dg != 0, -da / np.where(dg != 0, dg, 1.0), 0.0)
    beta = np.where(np.abs(other - near) < np.abs(near), other, 0.0)
    return beta, (da != 0) | (dg != 0)


def _best_piece(data: Data, tau: np.ndarray) -> np.ndarray:
    """The piece attaining each joint's maximum at ``tau`` (J, T)."""
    if not data.pieces.K:
        return np.zeros(tau.shape, np.intp)
    return np.argmax(data.pieces.values(tau), axis=0)


def from_interior_point(data: Data, result: Result) -> State:
    """The active set the interior-point solution ``result`` points to (module docstring)."""
    J, T = data.tau0.shape
    names = foot_rows(data)
    R, nf = len(names), data.fp.shape[1]
    x = data.local(result.z, result.sigma)
    cost = data.pieces.cost(x.tau).sum(axis=0)
    O_ = float(np.abs(cost).mean()) + 1e-12  # the objective's scale
    F = float(np.abs(data.fp[2]).mean()) + 1e-12
    feet = np.zeros((R, nf, T), bool)
    lam = np.zeros((R, nf, T))
    held = np.zeros((J, T), bool)
    at = np.zeros((J, T))
    K = data.pieces.K
    piece_lam, piece_s = np.zeros((K, J, T)), np.zeros((K, J, T))
    limit = np.zeros((J, T))
    g_limit = np.zeros((J, T))
    fmin0 = data.contact.min_normal_force == 0
    apex_lam = np.zeros((3, nf, T))  # the friction rows' multipliers on f (an apex's rows)
    for b in result.blocks:
        if isinstance(b, FootCone):
            free = b.lam[0] * F * F <= soc_residual(b.s) * O_
            apex = ~free & fmin0 & (b.s[0] * O_ < soc_residual(b.lam) * F * F)
            feet[0] = ~free & ~apex
            feet[-3:] |= apex
            lam[0] = b.lam[0]
            apex_lam += np.stack([b.lam[1], b.lam[2], b.mu * b.lam[0]])
        elif isinstance(b, FootRows):
            on = b.lam * F * F > b.s * O_
            where = [names.index(n) for n in b.names]
            if data.contact.cone == "pyramid":
                apex = fmin0 & (on[:4].sum(axis=0) >= 3)
                on[:4] &= ~apex
                feet[-3:] |= apex
            feet[where] = on
            lam[where] = b.lam
            apex_lam += np.einsum("rc,rft->cft", b.A, b.lam)
        elif isinstance(b, JointRows):
            rows = 0
            if b.limits:
                assert data.tmax is not None
                on = b.lam[:2] * data.tmax**2 > b.s[:2] * O_
                limit = np.where(on[0], 1.0, np.where(on[1], -1.0, 0.0))
                g_limit = b.lam[0] - b.lam[1]
                rows = 2
            piece_lam, piece_s = b.lam[rows:], b.s[rows:]
    if K:
        active = piece_lam * O_ > piece_s
        order = np.argsort(-piece_lam, axis=0)
        p, q = order[0], order[1] if K > 1 else order[0]
        beta, distinct = _kink(data, p, q, x.tau)
        # Two pieces active at a point far from where they meet are (nearly) the same piece.
        near = np.abs(x.tau - beta) <= KINK_TOL * (1.0 + np.abs(x.tau))
        kink = distinct & near & (active.sum(axis=0) >= 2)
        piece = p
        held |= kink
        at = np.where(kink, beta, at)
    else:
        piece = np.zeros((J, T), np.intp)
    if data.tmax is not None:
        bound = limit != 0
        held |= bound
        at = np.where(bound, limit * data.tmax, at)
        piece = np.where(bound, _best_piece(data, at), piece)
    lam[-3:] = apex_lam
    # The joints' subgradients in the interior-point solution, less their model pieces' slopes:
    # the held rows' multipliers (kept where rows depend on others).
    g = data.pieces.rho * at + g_limit
    if K:
        g = g + (piece_lam * data.pieces.slopes(at)).sum(axis=0)
    pa = pick(data.pieces.alpha, piece) if K else 0.0
    pg = pick(data.pieces.gamma, piece) if K else 0.0
    y = np.where(held, g - (pa + (data.pieces.rho + 2.0 * pg) * at), 0.0)
    return State(held, piece, at, feet, result.z.copy(), y, lam)


def repair(data: Data, state: State, sol: Solution, check: Check) -> State:
    """A new guess from a failed ``check`` of ``sol`` on ``state`` (module docstring).

    Where the solution breaks an inequality or leaves a piece, only rows are added (a joint
    held where it left its piece or at its torque limit, a violated foot row made active);
    only where it is feasible are rows with a wrong-signed multiplier released. Adding and
    releasing in the same round makes guesses cycle.
    """
    new = State(state.held.copy(), state.piece.copy(), state.at.copy(), state.feet.copy(),
                sol.z.copy(), sol.y_joint.copy(), -sol.y_feet)
    tau = sol.tau
    tol = 1e-9
    free = ~state.held
    added = np.zeros(tau.shape[1], bool)
    if data.pieces.K > 1:
        best = _best_piece(data, tau)
        values = check.values
        left = free & (pick(values, best)
                       > pick(values, state.piece)
                       + 1e-12 + 1e-10 * np.abs(values).max(axis=0))
        beta, distinct = _kink(data, state.piece, best, tau)
        new.held |= left & distinct
        new.at = np.where(left & distinct, beta, new.at)
        new.piece = np.where(left & ~distinct, best, new.piece)
        added |= left.any(axis=0)
    if data.tmax is not None:
        over = free & (np.abs(tau) > data.tmax)
        new.held |= over
        new.at = np.where(over, np.sign(tau) * data.tmax, new.at)
        new.piece = np.where(over, _best_piece(data, new.at), new.piece)
        added |= over.any(axis=0)
    names = foot_rows(data)
    n_ineq = len(names) - 3
    tol_f = tol * (1.0 + np.abs(sol.f).max(axis=0))
    apex = state.feet[-1]
    joins = ~state.feet[:n_ineq] & (check.rows[:n_ineq] < -tol_f) & ~apex
    new.feet[:n_ineq] |= joins
    added |= joins.any(axis=(0, 1))
    # Releases, where nothing was added: a held joint whose multiplier leaves the
    # subdifferential moves to the piece on that side, a foot row with a wrong-signed multiplier
    # leaves, an apex foot whose multiplier leaves the dual cone is freed.
    scale = tol * (1.0 + np.abs(check.g))
    up = state.held & (check.g > check.hi + scale) & ~added
    down = state.held & (check.g < check.lo - scale) & ~added
    if data.pieces.K:
        slopes = data.pieces.slopes(state.at)
        at_values = data.pieces.values(state.at)
        on = at_values >= at_values.max(axis=0) - 1e-12
        right = np.argmax(np.where(on, slopes, -np.inf), axis=0)
        left_piece = np.argmin(np.where(on, slopes, np.inf), axis=0)
        new.piece = np.where(up, right, np.where(down, left_piece, new.piece))
    new.held &= ~(up | down)
    # An active row that does not hold (it depends on others that fix it elsewhere: three coxa
    # joints whose torques sum to the body's yaw moment cannot all be held at zero) is released.
    broken = state.held & (np.abs(tau - state.at) > tol * (1.0 + np.abs(tau)))
    new.held &= ~broken
    new.piece = np.where(broken, _best_piece(data, tau), new.piece)
    ymax = 1.0 + np.abs(sol.y_feet).max(axis=(0, 1))
    leaves = state.feet[:n_ineq] & (sol.y_feet[:n_ineq] > tol * ymax) & ~added
    new.feet[:n_ineq] &= ~leaves & ~(state.feet[:n_ineq] & (np.abs(check.rows[:n_ineq]) > tol_f))
    new.feet[-3:] &= ~(check.apex_bad & ~added)
    if data.contact.min_normal_force == 0:  # a foot unloading onto the apex of its cone
        size = np.abs(sol.f).max(axis=0)
        unloaded = ((size <= 1e-9 * (1.0 + np.abs(sol.f).max(axis=(0, 1))))
                    & new.feet[:n_ineq].any(axis=0))
        new.feet[:n_ineq] &= ~unloaded
        new.feet[-3:] |= unloaded
    if data.contact.cone == "pyramid" and data.contact.min_normal_force == 0:
        crowded = new.feet[:4].sum(axis=0) >= 3
        new.feet[:4] &= ~crowded
        new.feet[-3:] |= crowded
    return new
