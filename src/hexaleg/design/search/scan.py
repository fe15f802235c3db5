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

Where the inequalities bind — a femur near its motor's torque limit over most of the cycle, a
friction cone — the condensed program is far below the exact value and prunes almost nothing
(a brushless hexapod's dead-zone search solved 1318 of its 1322 candidates exactly). A stronger
bound keeps those inequalities through their multipliers: the scan's state was solved exactly
before its scan, and its active set's multipliers (the torque limits', the friction cones',
the normal forces') price the inequalities in every candidate's Lagrangian, a lower bound of
that candidate's exact program whatever the multipliers (weak duality), equal to it at the
state and within round-off of it near the state (:class:`_Lagrangian`). It costs one more small
program per candidate, like the condensed one's; the search asks for it only of a candidate the
condensed bound cannot rule out (:attr:`RelaxedBounds.levels`).
"""

from __future__ import annotations

import dataclasses

import numpy as np

from hexaleg.design.search.program import DesignProblem, Multipliers, _solve_once, torque_gains
from hexaleg.design.search.setup import ENGAGED, DesignSetup
from hexaleg.dynamics.energy import quadrature_weights
from hexaleg.dynamics.reduction import RANK_TOL

State = dict[str, dict[str, float | str]]
"""Group → geometry (rad from each joint's centre of motion; ``side``)."""

BASIS = {"above": (0.0, -1.0), "below": (0.0, -1.0), "step_above": (-1.0, 0.0),
         "step_below": (1.0, 0.0)}
"""Term kind → (u, v): its torque on an engaged sample is u + v (r − θ) (terms module)."""
DUAL_MARGIN = 1e-9
"""The Lagrangian bound is lowered by this fraction of the baseline's value: the small program's
solve stops within Clarabel's tolerance (1e-11) of its minimum, and its sums of many terms carry
round-off; neither may lift it above the exact value."""
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
    """The lower bounds of :func:`relaxed_values` at ``thetas``, the strong ones on demand, and
    the Lagrangian bound of ``multipliers`` (the state's optimum's, :meth:`dual`).

    ``weak`` (shape (len(thetas),)) is the condensed program without its design rows and signs
    at every candidate (one batched pseudo-inverse); :meth:`tight` is candidate ``i``'s
    condensed program with them (one small Clarabel solve), never below ``weak[i]`` but for
    round-off. A scan that needs the bounds only in increasing order, up to the first that
    cannot win (:func:`hexaleg.design.search.geometry.search_geometry`), tightens only the
    candidates it reaches: the same bounds where it looks, the solves of the others saved.
    """

    def __init__(self, setup: DesignSetup, state: State, group: str, angle: str,
                 thetas: np.ndarray, side: str, multipliers: Multipliers | None = None
                 ) -> None:
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
        self._dual: dict[int, float] = {}
        self._lagrangian = None if multipliers is None else _Lagrangian(setup, multipliers)
        self.levels = (self.tight, self.dual)
        """The strong bounds in increasing strength, each a function of the candidate: the
        geometry search tightens a candidate to the next only when its turn comes."""

    def tight(self, i: int) -> float:
        """Candidate ``i``'s condensed program with its design rows and signs (J; ``inf`` where
        the rows admit no magnitudes; ``weak[i]`` where Clarabel stops short), solved once: a
        search that scans again from the same state asks again (a tenth of Solo-12's)."""
        if i not in self._tight:
            self._tight[i] = self._solve_tight(i)
        return self._tight[i]

    def dual(self, i: int) -> float:
        """Candidate ``i``'s strongest bound: the greater of :meth:`tight` and the Lagrangian
        bound of the multipliers given (:class:`_Lagrangian`; :meth:`tight` alone without them),
        solved once."""
        if i not in self._dual:
            tight = self.tight(i)
            self._dual[i] = tight if self._lagrangian is None or not np.isfinite(tight) else max(
                tight, self._solve_dual(i))
        return self._dual[i]

    def _solve_dual(self, i: int) -> float:
        """The Lagrangian bound of candidate ``i`` (−∞ where it is unbounded below)."""
        assert self._lagrangian is not None
        setup, state, group, geo, angle = self._args[:5]
        trial = {**state, group: {**geo, angle: float(self._thetas[i])}}
        return self._lagrangian.bound(setup.problem(trial))

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


class _Lagrangian:
    """The Lagrangian lower bound of a design program at fixed multipliers (those of another
    geometry's optimum: the scan's state).

    The bound. Let λ_t (:class:`~hexaleg.design.search.program.Multipliers`) be multipliers in
    the dual cones of sample t's friction, normal-force and torque-limit rows, so that
    ``μ_tᵀ τ + p_tᵀ f + κ_t ≤ 0`` wherever they hold. For any feasible (x, f) of a candidate's
    exact program, adding these terms lowers its value; minimising the sum over x within the
    design rows and over the forces within the base rows alone is therefore a lower bound of
    the exact value (weak duality; Boyd & Vandenberghe, *Convex Optimization*, 2004, §5.1.3),
    whatever the multipliers — the Lagrange dual function at λ, equal to the exact value at the
    candidate's own optimal multipliers (strong duality, §5.2.3) and close to it at a nearby
    geometry's. Given the spring torques s = B_t x, sample t's force part is
    ``min_f w_t ‖τ‖²_C + μᵀ τ + pᵀ f`` over A_t f = a_t, τ = b_t − D_t f − s. With f = f_c + Δ,
    f_c = f₀ − K s the condensed forces (the gains, :class:`~hexaleg.dynamics.solver.
    QuadraticGains`) and AΔ = 0, the cross term 2 w τ_cᵀ C D Δ vanishes (f_c's optimality), so
    the minimum is ``w ‖τ_c‖²_C + μᵀ τ_c + pᵀ f_c − ¼ g_Nᵀ H_N⁻¹ g_N / w`` with τ_c = τ₀ + G s,
    g = p − Dᵀ μ, N a basis of A_t's null space, g_N = Nᵀ g, H_N = Nᵀ Dᵀ C D N: the condensed
    cost plus terms affine in x, the last independent of the geometry. Summed over the samples,
    ``Σ_t w_t ‖τ₀_t + M_t x‖²_C + ℓᵀ x + c₀``, M_t = G_t B_t, with
    ``ℓ = Σ_t B_tᵀ (G_tᵀ μ_t − K_tᵀ p_t)`` (the sprung columns) and
    ``c₀ = Σ_t μ_tᵀ τ₀_t + p_tᵀ f₀_t + κ_t − ¼ g_Nᵀ H_N⁻¹ g_N / w_t``: one small program in x.
    A sample whose H_N is singular along g_N makes the bound −∞ (then the tight bound stands).

    Each candidate's program is built as the exact one's (:meth:`DesignSetup.problem`), its
    quadratic summed sample by sample, not by the scan's cumulative sums: those subtract
    running totals, and where a stop engages a few samples at a stiffness of ~10⁵ N·m/rad they
    lose ~10⁻⁷ of the value, more than this bound, equal to the exact value near the state, may
    spare. The minimiser's value is evaluated from its motor torques, sample by sample.
    """

    def __init__(self, setup: DesignSetup, multipliers: Multipliers) -> None:
        p = setup.prepared
        system = p.system
        S = multipliers.samples
        self.setup, self.m = setup, multipliers
        self.gains = p.gains(setup.objective)
        self.c = p.weights(setup.objective)
        mu, pf = multipliers.torque, multipliers.force
        constant = float(np.sum(mu * self.gains.tau0[S]) + np.sum(pf * self.gains.f0[S])
                         + np.sum(multipliers.constant))
        w = quadrature_weights(p.motion.n_samples, p.motion.dt, p.motion.periodic)
        for n, k in enumerate(S):
            st = np.flatnonzero(np.repeat(system.stance[k], 3))
            g = pf[n, st] - system.D[k][:, st].T @ mu[n]
            _, sv, vt = np.linalg.svd(system.A[k][:, st])
            rank = int(np.sum(sv > RANK_TOL * sv[0])) if sv.size else 0
            N = vt[rank:].T  # null space of the base rows
            if N.shape[1] == 0:
                continue
            DN = system.D[k][:, st] @ N
            ev, V = np.linalg.eigh(DN.T @ (self.c[:, None] * DN))
            proj = V.T @ (N.T @ g)
            flat = ev <= RANK_TOL * max(float(ev.max()), 0.0)
            if np.any(flat & (proj != 0.0)):
                constant = -np.inf
                break
            constant -= float(np.sum(proj**2 / ev)) / (4 * w[k])
        self.constant = constant

    def bound(self, problem: DesignProblem) -> float:
        """The bound for ``problem`` (J), lowered by :data:`DUAL_MARGIN` of the baseline's
        value; −∞ where it is unbounded or its small program is not solved."""
        if not np.isfinite(self.constant):
            return -np.inf
        gains, c, S = self.gains, self.c, self.m.samples
        w = problem.sample_weights
        M = np.einsum("tjs,tsx->tjx", gains.G[:, :, problem.cols], problem.B)
        Mw = M * (w[:, None, None] * c[None, :, None])
        Q = np.einsum("tjx,tjy->xy", Mw, M)
        r = np.einsum("tjx,tj->x", Mw, gains.tau0)
        a = (np.einsum("tis,ti->ts", gains.G[S][:, :, problem.cols], self.m.torque)
             - np.einsum("tfs,tf->ts", gains.K[S][:, :, problem.cols], self.m.force))
        linear = np.einsum("tsx,ts->x", problem.B[S], a)
        scale = float(np.sum(w[:, None] * c * gains.tau0**2)) or 1.0
        x, _, status = _solve_once(problem, np.zeros(0, dtype=int), Q, r + linear / 2, scale)
        if status != "Solved":
            return -np.inf
        tau = gains.tau0 + M @ x
        return (float(np.sum(w[:, None] * c * tau**2)) + float(linear @ x) + self.constant
                - DUAL_MARGIN * scale)


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
