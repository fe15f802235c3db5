"""The force programs solved exactly on a guessed active set, and the check that proves it right.

An *active set* (:class:`State`) says, for every sample, which inequalities hold with equality at
the optimum and which piece of each joint's cost (:mod:`hexaleg.dynamics.pieces`) the joint lies
on: a joint is either *free* on one piece or *held* at a torque ``β`` (a kink where two pieces
meet, or a torque limit); a foot's rows (:data:`SOC_ROWS` or :data:`PYRAMID_ROWS`) are active or
not. On that guess the program is an equality-constrained one — a strictly convex quadratic in
the null-space coordinates ``z`` with linear rows, plus ``μ f_z = ‖f_t‖`` for a foot on its
friction cone's surface — whose KKT system :func:`solve_state` solves by Newton's method
(Nocedal & Wright, *Numerical Optimization*, 2nd ed., §16.1–16.2 for the equality-constrained
KKT system and its range-space solution, §18.1 for Newton's method on the KKT conditions):
one step where every row is linear, a few where a foot is on its cone's surface. Rows that
depend on the others (a degenerate vertex: three coxa torques whose sum the body's yaw fixes)
are dropped from the solve and keep the multipliers of the guess.

:mod:`hexaleg.dynamics.certificate` then checks the KKT conditions of the *whole* program;
where they fail, :mod:`hexaleg.dynamics.guesses` moves the guess or reads one off the
interior-point method (:mod:`hexaleg.dynamics.ipm`).

The guess of one stiffness choice is the natural guess of the next: that is the warm start of a
sweep (:mod:`hexaleg.dynamics.batched`).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, fields

import numpy as np

from hexaleg.dynamics import smallmat
from hexaleg.dynamics.blocks import Data
from hexaleg.dynamics.pieces import pick

SOC_ROWS = ("surface", "bottom", "apex_x", "apex_y", "apex_z")
"""A foot's rows with the friction cone: ``μ f_z − ‖f_t‖ ≥ 0``, ``f_z − f_min ≥ 0``, and the
three rows ``f = 0`` of a foot at the cone's apex (unloaded, ``f_min = 0``)."""
PYRAMID_ROWS = ("xm", "xp", "ym", "yp", "bottom", "apex_x", "apex_y", "apex_z")
"""A foot's rows with the friction pyramid: ``κ f_z ∓ f_x ≥ 0``, ``κ f_z ∓ f_y ≥ 0``, the
minimum normal force and the apex rows."""
MAX_NEWTON = 12
"""Newton steps on a guess with feet on their cones' surfaces (it converges quadratically)."""
RCOND = 1e-12
"""A pivot below this fraction of its diagonal entry makes the active rows dependent."""
NEWTON_TOL = 1e-7
"""Newton's method has converged when the step it has just taken is below this (relative
above 1): converging quadratically, it is then within ≈ 1e-14 of the solution."""


@dataclass
class State:
    """An active-set guess for some samples of a group (samples on the last axis).

    Attributes:
        held: Joints held at ``at``, (J, T), bool.
        piece: The piece each joint lies on (held joints: one piece active at ``at``), (J, T).
        at: Torque of a held joint, (J, T), N·m.
        feet: Active foot rows, (R, n_f, T), bool (:data:`SOC_ROWS` / :data:`PYRAMID_ROWS`).
        z: Null-space coordinates: the solution, or where Newton's method starts, (m, T).
        y: Multipliers of the held joints' rows, (J, T), and
        lam: of the foot rows, (R, n_f, T), ``λ = −y``: the curvature of a cone's surface row,
            and the multipliers given to rows that depend on others (a degenerate vertex, where
            the multipliers are not unique: :func:`solve_state` keeps these).
    """

    held: np.ndarray
    piece: np.ndarray
    at: np.ndarray
    feet: np.ndarray
    z: np.ndarray
    y: np.ndarray
    lam: np.ndarray

    def take(self, idx: np.ndarray) -> State:
        """The guess of samples ``idx`` (indices, increasing)."""
        if idx.size == self.z.shape[-1]:
            return self
        return State(**{f.name: getattr(self, f.name)[..., idx] for f in fields(self)})

    def put(self, idx: np.ndarray, other: State) -> None:
        """Overwrite samples ``idx`` with ``other``."""
        for f in fields(self):
            getattr(self, f.name)[..., idx] = getattr(other, f.name)


def foot_rows(data: Data) -> tuple[str, ...]:
    return SOC_ROWS if data.contact.cone == "soc" else PYRAMID_ROWS


def empty_state(data: Data) -> State:
    """Nothing active, every joint on its first piece, ``z = 0``."""
    J, T = data.tau0.shape
    R, nf, m = len(foot_rows(data)), data.fp.shape[1], data.N.shape[2]
    return State(np.zeros((J, T), bool), np.zeros((J, T), np.intp), np.zeros((J, T)),
                 np.zeros((R, nf, T), bool), np.zeros((m, T)), np.zeros((J, T)),
                 np.zeros((R, nf, T)))


@dataclass
class Solution:
    """A guess's KKT solution: ``z`` (m, T), joint torques (J, T), forces (3, n_f, T), the
    multipliers of the held joints (J, T) and of the foot rows (R, n_f, T), and whether Newton's
    method converged (T,)."""

    z: np.ndarray
    tau: np.ndarray
    f: np.ndarray
    y_joint: np.ndarray
    y_feet: np.ndarray
    converged: np.ndarray


def _model(data: Data, state: State) -> tuple[np.ndarray, np.ndarray]:
    """Each joint's smooth model ``a τ + ½ ρ' τ²`` (its piece plus the regulariser): ``(a, ρ')``."""
    p = data.pieces
    if not p.K:
        return np.zeros_like(p.rho), p.rho
    if p.K == 1:
        return p.alpha[0], p.rho + 2.0 * p.gamma[0]
    a = pick(p.alpha, state.piece)
    g = pick(p.gamma, state.piece)
    return a, p.rho + 2.0 * g


def foot_values(data: Data, f: np.ndarray) -> np.ndarray:
    """Each foot row's value at forces ``f`` (3, n_f, T): (R, n_f, T), N."""
    c = data.contact
    fz = f[2] - c.min_normal_force
    if c.cone == "soc":
        return np.stack([c.mu * f[2] - np.hypot(f[0], f[1]), fz, f[0], f[1], fz])
    kz = c.mu / math.sqrt(2.0) * f[2]
    return np.stack([kz - f[0], kz + f[0], kz - f[1], kz + f[1], fz, f[0], f[1], fz])


def unconstrained_gains(data: Data) -> np.ndarray:
    """``Z = (Eᵀ diag(ρ) E)⁻¹ Eᵀ diag(ρ)``, (m, J, T): the unconstrained optimum ``z = Z τ₀`` of
    the quadratic objectives (``data.Z`` once computed)."""
    if data.Z is not None:
        return data.Z
    rho = data.pieces.rho
    rhs = np.transpose(data.E * rho[:, None, :], (1, 0, 2))  # (m, J, T)
    # a singular Gram matrix (a two-joint leg's codesign candidates reach some) gives gains
    # that are not finite at its samples; their forces are then never feasible
    # (certificate.feasible), so those samples go to the certified paths
    with np.errstate(over="ignore", divide="ignore", invalid="ignore"):
        return smallmat.solve_spd(smallmat.gram(data.E, rho), rhs)


def constant_rows(data: Data) -> np.ndarray:
    """Gradients in ``z`` of every candidate row — the joints' ``τ − β`` (J), then each foot
    row (R × n_f, zero for the cone's surface, which :func:`newton` computes): (C, m, T)."""
    if data.const is not None:
        return data.const
    Nx, Ny, Nz = data.N
    if data.contact.cone == "soc":
        feet = [np.zeros_like(Nz), Nz, Nx, Ny, Nz]
    else:
        k = data.contact.mu / math.sqrt(2.0)
        feet = [k * Nz - Nx, k * Nz + Nx, k * Nz - Ny, k * Nz + Ny, Nz, Nx, Ny, Nz]
    _, m, T = data.E.shape
    return np.concatenate([-data.E, np.stack(feet).reshape(-1, m, T)])


@dataclass
class Rows:
    """The active rows of each sample's guess, packed into slots (P the most of any sample).

    Entry ``k`` of the flat lists is candidate row ``cand[k]`` (:func:`constant_rows`' order:
    joints, then foot rows) of sample ``t[k]``, in the slot ``s`` that follows its sample's
    earlier entries; ``dst[k] = s T + t[k]`` is its place in a (P, T) array raveled. ``index``
    holds, per kind of entry (a held joint, a cone's surface row, a linear foot row),
    ``(dst, src)``: the entries' places in the (P, T) arrays and in the raveled (J, T) joint,
    (n_f, T) foot or (R n_f, T) foot-row arrays their values come from (flat indices: one gather
    per kind). ``used`` (P, T) marks the slots in
    use, ``G`` their constant gradients (m, P, T) (zero for a surface row, whose gradient
    :func:`newton` sets at each point), ``given`` their multipliers in the guess (P, T), ``at``
    the held joints' torques (per held-joint entry) and ``foot`` (n_f, T) the feet on their
    cone's surface.
    """

    t: np.ndarray
    cand: np.ndarray
    dst: np.ndarray
    index: tuple[tuple[np.ndarray, np.ndarray], ...]
    used: np.ndarray
    G: np.ndarray
    given: np.ndarray
    at: np.ndarray
    foot: np.ndarray

    @property
    def P(self) -> int:
        return int(self.used.shape[0])

    @property
    def curved(self) -> np.ndarray:
        """Samples with a foot on its cone's surface, (T,)."""
        return np.asarray(self.foot.any(axis=0))


def pack(data: Data, state: State, const: np.ndarray) -> Rows:
    """The :class:`Rows` of ``state`` with the candidate gradients ``const``
    (:func:`constant_rows`)."""
    J, T = state.held.shape
    R, nf = state.feet.shape[:2]
    active = np.concatenate([state.held, state.feet.reshape(R * nf, T)])
    count = active.sum(axis=0)
    P = int(count.max()) if active.size else 0
    t, cand = np.nonzero(active.T)  # by sample, then candidate
    slot = np.arange(t.size) - (np.cumsum(count) - count)[t]
    dst = slot * T + t
    used = np.zeros((P, T), bool)
    used.ravel()[dst] = True
    G = np.zeros((const.shape[1], P, T))
    G[:, slot, t] = const[cand, :, t].T
    given = np.zeros((P, T))
    given.ravel()[dst] = np.concatenate([state.y, -state.lam.reshape(R * nf, T)]).ravel()[
        cand * T + t]
    joint = cand < J
    surface = (~joint & (cand < J + nf)) if data.contact.cone == "soc" else np.zeros_like(joint)
    src = (cand - np.where(joint, 0, J)) * T + t
    index = tuple((dst[k], src[k]) for k in (joint, surface, ~joint & ~surface))
    foot = np.zeros((nf, T), bool)
    foot.ravel()[index[1][1]] = True
    return Rows(t, cand, dst, index, used, G, given, state.at.ravel()[src[joint]], foot)


def newton(data: Data, rows: Rows, z: np.ndarray, lam: np.ndarray, HJ: np.ndarray,
           a: np.ndarray, rho: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """One Newton step on the KKT system of each sample's guess, from ``z`` (m, T).

    Minimise ``Σ_j a_j τ_j + ½ ρ'_j τ_j²`` (``HJ = Eᵀ diag(ρ') E``) subject to the active rows
    (:class:`Rows`); ``lam`` (n_f, T) are the surface rows' multipliers for the curvature of
    ``‖f_t‖``. The range-space method: ``H = L Lᵀ``, ``V = L⁻¹ Gᵀ``, ``(VᵀV) y = e − Vᵀ L⁻¹ ∇F``,
    ``Δz = −L⁻ᵀ L⁻¹ (∇F + Gᵀ y)``; rows that depend on earlier ones keep their given multipliers
    (a degenerate vertex). Returns ``(z + Δz, y (P, T), |Δz|)``.
    """
    T = data.tau0.shape[1]
    x = data.local(z, None)
    H, G = HJ, rows.G
    m, P = G.shape[:2]
    e = np.zeros(P * T)
    (d0, r0), (d1, r1), (d2, r2) = rows.index
    if r1.size:
        f, N, mu = x.f, data.N, data.contact.mu
        ft = np.hypot(f[0], f[1])
        safe = np.where(ft > 0, ft, 1.0)
        ux, uy = f[0] / safe, f[1] / safe
        Nt = np.transpose(N, (0, 2, 1, 3))  # (3, m, n_f, T)
        G = G.copy()
        # The surface rows' gradients μ N_zᵀ − u_x N_xᵀ − u_y N_yᵀ, every foot (m, n_f, T).
        G.reshape(m, P * T)[:, d1] = (mu * Nt[2] - ux * Nt[0] - uy * Nt[1]).reshape(m, -1)[:, r1]
        e[d1] = (mu * f[2] - ft).ravel()[r1]
        r = ux * Nt[1] - uy * Nt[0]  # N_iᵀ t, t = (−u_y, u_x, 0): (m, n_f, T)
        H = HJ + np.einsum("pft,qft->pqt", r * np.where(rows.foot, lam / safe, 0.0), r)
    dF = -np.einsum("jmt,jt->mt", data.E, a + rho * x.tau)
    L = smallmat.cholesky(H)
    u = smallmat.forward(L, dF)
    if not P:
        dz = -smallmat.backward(L, u)
        return z + dz, np.zeros((0, T)), np.abs(dz).max(axis=0)
    if r0.size:
        e[d0] = x.tau.ravel()[r0] - rows.at
    if r2.size:
        e[d2] = foot_values(data, x.f).ravel()[r2]
    e = e.reshape(P, T)
    V = smallmat.forward(L, G)
    S = np.einsum("mpt,mqt->pqt", V, V)
    S[np.arange(P), np.arange(P)] += ~rows.used
    # Rows that depend on earlier ones (a degenerate vertex) are dropped from the solve: they
    # keep their given multipliers (the interior point's, or the last certified ones) and
    # verify() checks that they still hold.
    Ls, kept = smallmat.cholesky_dropping(S, RCOND)
    rhs = e - np.einsum("mpt,mt->pt", V, u)
    if kept.all():
        y = smallmat.backward(Ls, smallmat.forward(Ls, rhs))
    else:
        fixed = np.where(kept, 0.0, rows.given)
        rhs = rhs - np.einsum("pqt,qt->pt", S, fixed)
        y = smallmat.backward(Ls, smallmat.forward(Ls, rhs * kept)) * kept + fixed
    dz = -smallmat.backward(L, u + np.einsum("mpt,pt->mt", V, y))
    return z + dz, y, np.abs(dz).max(axis=0)


def surface_multipliers(rows: Rows, y: np.ndarray) -> np.ndarray:
    """The surface rows' multipliers ``λ = max(0, −y)`` per foot (n_f, T), from packed ``y``."""
    lam = np.zeros(rows.foot.shape)
    dst, src = rows.index[1]
    lam.ravel()[src] = np.maximum(-y.ravel()[dst], 0.0)
    return lam


def solution(data: Data, state: State, rows: Rows, z: np.ndarray, y: np.ndarray,
             converged: np.ndarray) -> Solution:
    """The :class:`Solution` at ``z`` with the packed multipliers ``y`` (P, T) unpacked."""
    J, T = state.held.shape
    R, nf = state.feet.shape[:2]
    y_all = np.zeros((J + R * nf, T))
    if rows.P:
        y_all.ravel()[rows.cand * T + rows.t] = y.ravel()[rows.dst]
    x = data.local(z, None)
    return Solution(z, x.tau, x.f, y_all[:J], y_all[J:].reshape(R, nf, T), converged)


def solve_state(data: Data, state: State, grow: bool = False) -> tuple[State, Solution]:
    """Solve the KKT system of each sample's program on its guess ``state``: one Newton step
    from ``z = 0`` where every row is linear (exact), up to :data:`MAX_NEWTON` from ``state.z``
    where a foot is on its cone's surface.

    With ``grow``, the foot rows that the first step's forces break join the guess at once
    (a sweep's next stiffness pushes feet onto their cones: they bind), and Newton's method
    continues on the grown guess — a repair round saved where the guess was stale.

    Returns:
        ``(state, solution)``: the guess solved (grown) and its solution.
    """
    T = state.held.shape[1]
    const = constant_rows(data)
    rows = pack(data, state, const)
    a, rho = _model(data, state)
    HJ = smallmat.gram(data.E, rho)
    curved = rows.curved
    z = np.where(curved, state.z, 0.0)
    lam = np.maximum(state.lam[0], 0.0)
    y = rows.given
    converged = np.zeros(T, bool)
    for it in range(MAX_NEWTON):
        z_new, y_new, step = newton(data, rows, z, lam, HJ, a, rho)
        todo = ~converged
        z = np.where(todo, z_new, z)
        y = np.where(todo, y_new, y)
        lam = surface_multipliers(rows, y)
        finite = np.isfinite(z).all(axis=0)
        converged |= finite & (~curved | (step <= NEWTON_TOL * (1.0 + np.abs(z).max(axis=0))))
        if grow and it == 0:
            f = data.local(z, None).f
            values = foot_values(data, f)[:-3]
            broken = ~state.feet[:-3] & (values < -1e-6 * (1.0 + np.abs(f).max(axis=(0, 1))))
            broken &= ~state.feet[-1]  # not a foot at its apex
            if broken.any():
                hit = broken.any(axis=(0, 1))
                state = State(state.held, state.piece, state.at,
                              np.concatenate([state.feet[:-3] | broken, state.feet[-3:]]),
                              np.where(hit, z, state.z), state.y, state.lam.copy())
                sol_y = solution(data, state, rows, z, y, converged)  # multipliers so far
                state.lam[:-3] = np.where(state.feet[:-3] & ~broken, -sol_y.y_feet[:-3], 0.0)
                rows = pack(data, state, const)  # the same slots for the samples not hit
                curved = rows.curved
                z = np.where(hit & ~curved, 0.0, z)
                lam = np.where(hit, np.maximum(state.lam[0], 0.0), lam)
                y_old, y = y, rows.given.copy()
                y[:y_old.shape[0], ~hit] = y_old[:, ~hit]
                converged &= ~hit
        if converged.all() or not finite.all():
            break
    z = np.where(np.isfinite(z), z, 0.0)
    return state, solution(data, state, rows, z, y, converged)
