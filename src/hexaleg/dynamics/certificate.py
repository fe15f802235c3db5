"""The certificate of optimality: the KKT conditions of each sample's whole force program.

A solution of :func:`hexaleg.dynamics.active_set.solve_state` solves the program restricted to its
guess's active rows. It is the optimum of the whole (convex) program exactly when the KKT
conditions of the whole program hold (Nocedal & Wright, *Numerical Optimization*, 2nd ed.,
Theorem 12.1 and §12.3 for their sufficiency under convexity), which :func:`verify` checks:

- primal: every inactive row satisfied (friction, normal force, torque limits), every free joint
  on the piece of its cost that attains the maximum (:mod:`hexaleg.dynamics.pieces`), every
  active row and held joint where the guess puts it;
- dual: every active row's multiplier of the right sign, a foot at its cone's apex with its
  multiplier in the dual cone, every held joint's multiplier inside the subdifferential of its
  cost at the held torque (the interval between the slopes of the pieces that meet there, open
  on the side of a torque limit).

Tolerances are those of rounding (:data:`TOL_PRIMAL`, :data:`TOL_DUAL`): a certified solution is
exact, not within an interior-point tolerance.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hexaleg.dynamics.active_set import Solution, State, _model, foot_values
from hexaleg.dynamics.blocks import Data
from hexaleg.dynamics.pieces import pick

TOL_PRIMAL = 1e-9
"""Slack allowed on an inequality at a certified optimum, N or N·m (relative above 1)."""
TOL_DUAL = 1e-9
"""Slack allowed on a multiplier's sign, relative to the sample's largest multiplier."""


def feasible(data: Data, tau: np.ndarray, f: np.ndarray) -> np.ndarray:
    """Samples whose torques (J, T) and forces (3, n_f, T) are finite and meet every
    inequality (T,). (An infinite force would meet its own row's tolerance, scaled by the
    largest force.)"""
    ok = np.isfinite(f).all(axis=(0, 1)) & np.isfinite(tau).all(axis=0)
    with np.errstate(invalid="ignore"):
        ok &= np.all(foot_values(data, f)[:-3] >= -TOL_PRIMAL * (1.0 + np.abs(f).max(axis=0)),
                     axis=(0, 1))
    if data.tmax is not None:
        ok &= np.all(np.abs(tau) <= data.tmax + TOL_PRIMAL * (1.0 + np.abs(tau)), axis=0)
    return ok


@dataclass
class Check:
    """What :func:`verify` found, per sample (T,): ``ok`` (every KKT condition holds), and the
    quantities :func:`hexaleg.dynamics.guesses.repair` needs: piece values (K, J, T) and the
    held joints' subgradient ``g`` against its interval ``[lo, hi]`` (J, T), the foot rows'
    values (R, n_f, T) and the apex feet whose multipliers leave the dual cone (n_f, T)."""

    ok: np.ndarray
    values: np.ndarray
    g: np.ndarray
    lo: np.ndarray
    hi: np.ndarray
    rows: np.ndarray
    apex_bad: np.ndarray


def verify(data: Data, state: State, sol: Solution) -> Check:
    """Check the KKT conditions of every sample's whole program at ``sol`` (module docstring)."""
    p, c = data.pieces, data.contact
    J, T = sol.tau.shape
    tau, f, held = sol.tau, sol.f, state.held
    ok = sol.converged.copy()
    tol_t = TOL_PRIMAL * (1.0 + np.abs(tau))
    if data.tmax is not None:
        ok &= np.all(np.abs(tau) <= data.tmax + tol_t, axis=0)
    values = p.values(tau) if p.K else np.zeros((0, J, T))
    if p.K > 1:
        mine = pick(values, state.piece)
        tol_e = 1e-12 + 1e-10 * np.abs(mine)
        ok &= np.all(held | (values.max(axis=0) <= mine + tol_e), axis=0)
    rows = foot_values(data, f)
    n_ineq = rows.shape[0] - 3
    tol_f = TOL_PRIMAL * (1.0 + np.abs(f).max(axis=0))
    feet = state.feet
    g = lo = hi = np.zeros((J, T))
    apex_bad = np.zeros(feet.shape[1:], bool)
    if not (held.any() or feet.any()):  # nothing active: feasibility is optimality
        ok &= np.all(rows[:n_ineq] >= -tol_f, axis=(0, 1))
        return Check(ok, values, g, lo, hi, rows, apex_bad)
    ymax = 1.0 + np.maximum(np.abs(sol.y_joint).max(axis=0), np.abs(sol.y_feet).max(axis=(0, 1)))
    tol_g = TOL_DUAL * ymax
    if held.any():
        ok &= np.all(~held | (np.abs(tau - state.at) <= tol_t), axis=0)
        a, rho = _model(data, state)
        g = a + rho * state.at + sol.y_joint
        if p.K:
            at_vals = p.values(state.at)
            on = at_vals >= at_vals.max(axis=0) - (1e-12 + 1e-10 * np.abs(at_vals).max(axis=0))
            slopes = p.slopes(state.at)
            lo = p.rho * state.at + np.where(on, slopes, np.inf).min(axis=0)
            hi = p.rho * state.at + np.where(on, slopes, -np.inf).max(axis=0)
            if p.K > 1:
                ok &= np.all(~held | pick(on, state.piece), axis=0)
        else:
            lo = hi = p.rho * state.at
        if data.tmax is not None:
            hi = np.where(state.at >= data.tmax * (1 - 1e-12), np.inf, hi)
            lo = np.where(state.at <= -data.tmax * (1 - 1e-12), -np.inf, lo)
        ok &= np.all(~held | ((g >= lo - tol_g) & (g <= hi + tol_g)), axis=0)
    apex = feet[-1]
    ok &= np.all((rows[:n_ineq] >= -tol_f) | feet[:n_ineq] | apex, axis=(0, 1))
    ok &= np.all(~feet | (np.abs(rows) <= tol_f), axis=(0, 1))
    ok &= np.all(~feet[:n_ineq] | (sol.y_feet[:n_ineq] <= tol_g), axis=(0, 1))
    if apex.any():
        lam = -sol.y_feet[-3:]
        if c.cone == "soc":
            slack = lam[2] - c.mu * np.hypot(lam[0], lam[1])
        else:
            slack = lam[2] - c.mu / math.sqrt(2.0) * (np.abs(lam[0]) + np.abs(lam[1]))
        apex_bad = apex & (slack < -tol_g)
        ok &= ~apex_bad.any(axis=0)
    return Check(ok, values, g, lo, hi, rows, apex_bad)
