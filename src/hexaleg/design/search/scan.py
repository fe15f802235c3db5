"""Lower bounds on the design program at every candidate of one stop angle at once.

A scan of :mod:`hexaleg.design.search.geometry` moves one stop of one group over all its candidate
angles θ with every other angle fixed. Each candidate's exact value is a design program
(:func:`hexaleg.design.search.program.solve_design`: the magnitudes and the foot forces with their
friction, normal-force and torque-limit inequalities). Dropping those inequalities leaves the
*condensed* program of that module's first round — the forces at every sample the
equality-constrained optimum, the motor torque ``τ_t = τ₀_t + M_t x`` affine in the magnitudes —
whose value is a lower bound of the exact one (a relaxation). This module computes that bound for
all candidates together: the scan then solves exactly only the candidates whose bound is below
the best exact value found, in increasing order of bound, and stops there — the exact minimum
along the angle, at a fraction of the solves.

The algebra. The scanned stop's columns of ``M_t`` (its stiffness, and its preload where the
family has one) are ``Σ_j e_tj(θ) s_j G_t[:, j] (u + v (r_tj − θ))``: j the group's joints, r_tj
the sample's angle from the joint's centre of motion (reflected for a mirrored joint, s_j = −1),
e_tj(θ) whether the stop engages the sample, ``G`` the torque gains
(:class:`hexaleg.dynamics.solver.QuadraticGains`), and (u, v) the term's basis
(:mod:`hexaleg.robot.springs.terms`: a ramp u = 0, v = −1; a step u = ∓1, v = 0). With
``A_t = Σ_j e_tj s_j G_t[:, j]`` and ``R_t = Σ_j e_tj s_j r_tj G_t[:, j]`` every such column is
``(u − v θ) A_t + v R_t``, so the condensed quadratic's blocks are 2 × 2 and 2 × n sums over
samples of products of A and R with the fixed columns — sums over (sample, joint) pairs and
singles that a stop engages beyond a threshold (the lower or higher of the pair's angles), hence
cumulative sums over the thresholds sorted once. The design rows (bounds on torque and
deflection, terms that never engage) are built per candidate as :class:`DesignSetup` builds them.
"""

from __future__ import annotations

import dataclasses

import numpy as np

from hexaleg.design.search.program import DesignProblem, _solve_once, torque_gains
from hexaleg.design.search.setup import ENGAGED, DesignSetup

State = dict[str, dict[str, float | str]]
"""Group → geometry (rad from each joint's centre of motion; ``side``)."""

BASIS = {"above": (0.0, -1.0), "below": (0.0, -1.0), "step_above": (-1.0, 0.0),
         "step_below": (1.0, 0.0)}
"""Term kind → (u, v): its torque on an engaged sample is u + v (r − θ) (terms module)."""
WEAK_MARGIN = 1e-9
"""The unconstrained bound is lowered by this fraction of the baseline's value: the
pseudo-inverse's round-off must not lift it above the true minimum."""


def _sums(thresholds: np.ndarray, values: np.ndarray, thetas: np.ndarray, above: bool
          ) -> np.ndarray:
    """For each θ, the sum of ``values`` (n, ...) whose threshold is beyond θ (above: > θ;
    below: < θ); shape (len(thetas), ...)."""
    order = np.argsort(thresholds, kind="stable")
    t, v = thresholds[order], values[order]
    cum = np.concatenate([np.zeros((1, *v.shape[1:])), np.cumsum(v, axis=0)])
    if above:
        start = np.searchsorted(t, thetas, side="right")
        return cum[-1] - cum[start]
    return cum[np.searchsorted(t, thetas, side="left")]


def relaxed_values(setup: DesignSetup, state: State, group: str,
                   angle: str, thetas: np.ndarray, side: str, below: float = np.inf
                   ) -> np.ndarray:
    """The condensed program's value (a lower bound of the exact design program's, J) with the
    stop ``angle`` of ``group`` at each of ``thetas`` (rad from the centres of motion; a
    one-sided stop on ``side``), every other angle as in ``state``; shape (len(thetas),).
    ``inf`` where the design rows admit no magnitudes. Where the condensed program without its
    design rows and signs (one batched pseudo-inverse, a weaker bound) is already ≥ ``below``,
    that weaker bound is returned instead: such a candidate cannot go below ``below`` either.
    Where Clarabel stops short of the condensed program, the weaker bound stands."""
    bounds = RelaxedBounds(setup, state, group, angle, thetas, side)
    out = bounds.weak.copy()
    for i in np.flatnonzero(out < below):
        out[i] = bounds.tight(int(i))
    return out


class RelaxedBounds:
    """The lower bounds of :func:`relaxed_values` at ``thetas``, the strong ones on demand.

    ``weak`` (shape (len(thetas),)) is the condensed program without its design rows and signs
    at every candidate (one batched pseudo-inverse); :meth:`tight` is candidate ``i``'s
    condensed program with them (one small Clarabel solve), never below ``weak[i]`` but for
    round-off. A scan that needs the bounds only in increasing order, up to the first that
    cannot win (:func:`hexaleg.design.search.geometry.search_geometry`), tightens only the
    candidates it reaches: the same bounds where it looks, the solves of the others saved.
    """

    def __init__(self, setup: DesignSetup, state: State, group: str, angle: str,
                 thetas: np.ndarray, side: str) -> None:
        fam, p = setup.fam, setup.prepared
        groups = list(setup.groups)
        nm = len(fam.magnitudes)
        gi = groups.index(group)
        names = fam.stops[angle]
        local = [fam.magnitudes.index(n) for n in names]
        geo = {**state[group], angle: 0.0, **({"side": side} if angle == "contact" else {})}
        kinds = [fam.terms(geo, 0.0)[i].kind for i in local]
        uv = np.array([BASIS[k] for k in kinds])  # (|S|, 2)
        scanned = np.array([gi * nm + i for i in local])
        problem = setup.problem(state)
        nx = problem.nx
        rest = np.setdiff1d(np.arange(nx), scanned)
        gains = p.gains(setup.objective)
        wc = problem.sample_weights[:, None] * p.weights(setup.objective)[None, :]  # (T, nj)
        Mo = torque_gains(problem)[:, :, rest]  # (T, nj, n_o)
        tau0 = gains.tau0
        joints = setup.groups[group]
        Gj = np.stack([gains.G[:, :, p.robot.column(j)] for j in joints], axis=1)  # (T, J, nj)
        sign = np.array([-1.0 if j in setup.mirrored else 1.0 for j in joints])
        r = setup.relative(group)  # (T, J)
        SG = Gj * sign[None, :, None]
        above = (side if angle == "contact" else fam.side(angle, geo)) == "above"
        # singles (t, j): the scanned columns against the fixed ones and τ₀
        a_o = np.einsum("tji,ti,tio->tjo", SG, wc, Mo)  # (T, J, n_o)
        a_0 = np.einsum("tji,ti,ti->tj", SG, wc, tau0)  # (T, J)
        single = np.concatenate([np.stack([a_o, r[..., None] * a_o], axis=2).reshape(
            *r.shape, 2 * Mo.shape[2]), np.stack([a_0, r * a_0], axis=2)], axis=2)
        S = _sums(r.ravel(), single.reshape(r.size, -1), thetas, above)
        K = S[:, :2 * Mo.shape[2]].reshape(len(thetas), 2, Mo.shape[2])
        k = S[:, 2 * Mo.shape[2]:]  # (n, 2)
        # pairs (t, j, j'): the scanned columns against themselves
        haa = np.einsum("tji,ti,tki->tjk", SG, wc, SG)  # (T, J, J)
        rj, rk = r[:, :, None], r[:, None, :]
        pair = np.stack([haa, haa * rk, haa * rj, haa * rj * rk], axis=-1)  # AA, AR, RA, RR
        threshold = np.minimum(rj, rk) if above else np.maximum(rj, rk)
        H = _sums(threshold.ravel(), pair.reshape(-1, 4), thetas, above).reshape(-1, 2, 2)
        Qoo = np.einsum("tio,ti,tip->op", Mo, wc, Mo)
        ro = np.einsum("tio,ti,ti->o", Mo, wc, tau0)
        scale = float(np.sum(wc * tau0**2)) or 1.0
        fixed_rows = _fixed_rows(problem, gi * nm, (gi + 1) * nm, scanned)
        n = len(thetas)
        lam = np.empty((n, 2, len(local)))  # the scanned columns = (A, R) Λ(θ)
        lam[:, 0, :] = uv[:, 0] - uv[:, 1] * thetas[:, None]
        lam[:, 1, :] = uv[:, 1]
        Q = np.zeros((n, nx, nx))
        Q[:, rest[:, None], rest] = Qoo
        Q[:, scanned[:, None], scanned] = np.einsum("nas,nab,nbt->nst", lam, H, lam)
        cross = np.einsum("nas,nao->nso", lam, K)
        Q[:, scanned[:, None], rest] = cross
        Q[:, rest[:, None], scanned] = cross.transpose(0, 2, 1)
        rv = np.zeros((n, nx))
        rv[:, rest], rv[:, scanned] = ro, np.einsum("nas,na->ns", lam, k)
        # without the design rows and x ≥ 0: min xᵀQx + 2rᵀx = −rᵀQ⁺r, a weaker bound for all
        # at once
        self.weak = scale - np.einsum("ni,nij,nj->n", rv, np.linalg.pinv(Q, hermitian=True), rv)
        self.weak -= WEAK_MARGIN * scale
        self._args = (setup, state, group, geo, angle, gi * nm, nx, r, above, scanned, kinds)
        self._problem, self._fixed, self._Q, self._rv, self._scale = (
            problem, fixed_rows, Q, rv, scale)
        self._thetas = thetas
        self._tight: dict[int, float] = {}

    def tight(self, i: int) -> float:
        """Candidate ``i``'s condensed program with its design rows and signs (J; ``inf`` where
        the rows admit no magnitudes; ``weak[i]`` where Clarabel stops short), solved once: a
        search that scans again from the same state asks again (a tenth of Solo-12's)."""
        if i not in self._tight:
            self._tight[i] = self._solve_tight(i)
        return self._tight[i]

    def _solve_tight(self, i: int) -> float:
        setup, state, group, geo, angle, start, nx, r, above, scanned, kinds = self._args
        theta = float(self._thetas[i])
        trial = {**state, group: {**geo, angle: theta}}
        G, h = _group_rows(setup, trial, group, start, nx, r, theta, above, scanned, kinds)
        relaxed = dataclasses.replace(self._problem, G=np.vstack([self._fixed[0], G]),
                                      h=np.concatenate([self._fixed[1], h]))
        Q, rv, scale = self._Q[i], self._rv[i], self._scale
        x, _, status = _solve_once(relaxed, np.zeros(0, dtype=int), Q, rv, scale)
        if status == "Solved":
            return scale + float(x @ Q @ x + 2 * rv @ x)
        return np.inf if "Infeasible" in status else float(self.weak[i])


def _fixed_rows(problem: DesignProblem, start: int, stop: int, scanned: np.ndarray
                ) -> tuple[np.ndarray, np.ndarray]:
    """The current problem's design rows that do not move with the scanned stop: rows of the
    other groups, and the scanned group's "never engaged" rows of its other terms."""
    keep = []
    for i, (row, label) in enumerate(zip(problem.G, problem.labels, strict=True)):
        inside = np.flatnonzero(row[start:stop]).size > 0
        if not inside or (label == "never engaged" and not np.any(row[scanned])):
            keep.append(i)
    return problem.G[keep].reshape(-1, problem.nx), problem.h[keep]


def _group_rows(setup: DesignSetup, trial: State, group: str, start: int, nx: int, r: np.ndarray,
                theta: float, above: bool, scanned: np.ndarray, kinds: list[str]
                ) -> tuple[np.ndarray, np.ndarray]:
    """The scanned group's design rows at the trial geometry (as :meth:`DesignSetup.problem`
    builds them), and a row fixing each scanned term to 0 where it never engages."""
    rows, h = [], []
    nm = len(setup.fam.magnitudes)
    for j in setup.groups[group]:
        for row, rhs, _ in setup._rows(setup.fam.terms(trial[group], setup.centre[j]), j):
            full = np.zeros(nx)
            full[start:start + nm] = row
            rows.append(full)
            h.append(rhs)
    beyond = r[r > theta] - theta if above else theta - r[r < theta]
    for col, kind in zip(scanned, kinds, strict=True):
        engaged = beyond.size > 0 and (kind.startswith("step") or beyond.max() > ENGAGED)
        if not engaged:
            full = np.zeros(nx)
            full[col] = 1.0
            rows.append(full)
            h.append(0.0)
    return (np.array(rows).reshape(-1, nx), np.array(h))


__all__ = ["RelaxedBounds", "relaxed_values"]
