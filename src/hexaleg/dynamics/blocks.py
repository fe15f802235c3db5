"""A group's force program in conic form, block by block, in local coordinates.

On a :class:`~hexaleg.dynamics.reduction.Group` the unknowns are the null-space coordinates ``z``
and, for the non-smooth objectives, one epigraph variable ``σ_j`` per stance-leg joint. Every
constraint is affine in *local* coordinates — a foot's force ``f_i = f_p + N_i z`` or a joint's
``(τ_j, σ_j)`` with ``τ_j = τ₀ − E_j z`` — or, for the electrical objective's pieces, concave
quadratic in τ_j, so each block of rows needs only its own few numbers:

===================  ===============================================  ==========================
block                slack ``s`` (in the cone)                         cone
===================  ===============================================  ==========================
:class:`FootCone`    ``(μ f_z, f_x, f_y)``                             second-order, one per foot
:class:`FootRows`    ``κ f_z ∓ f_x, κ f_z ∓ f_y`` (the pyramid,         nonnegative
                     κ = μ/√2) and ``f_z − f_min``
:class:`JointRows`   ``τ_max ∓ τ`` (the torque limits) and              nonnegative
                     ``σ − α_k τ − γ_k τ²`` (the pieces)
===================  ===============================================  ==========================

A piece with ``γ_k > 0`` makes its row nonlinear: it is linearised at the current point (as
CVXOPT's ``cp`` treats nonlinear constraints) and its curvature ``2 γ_k λ`` joins the Hessian of
the Lagrangian; a rotated second-order cone would be exact too, but its offset cancels digits
near the optimum. The objective is ``Σ_j ½ ρ_j τ_j² (+ Σ_j σ_j)``: ``ρ = 2 c`` for Joule, 2 for
torque², the regulariser ``2 ε`` for the others, whose per-joint cost ``max_k (α_k τ + γ_k τ²)``
is carried by ``σ_j`` (:mod:`hexaleg.dynamics.pieces`).

Each block gives its slack at a point (``value``), the linear part of that map at the point of
:meth:`Block.linearize` (``linear``), its transpose applied to row vectors (``add_transpose``)
and ``Aᵀ M A`` for the scaled Hessian (``add_hessian``); the interior-point method
(:mod:`hexaleg.dynamics.ipm`) combines them.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hexaleg.dynamics.contact import ContactParams
from hexaleg.dynamics.pieces import Pieces


@dataclass
class Local:
    """A point or direction in local coordinates: forces (3, n_f, T), torques and epigraph
    variables (J, T) (``sigma`` None for the quadratic objectives)."""

    f: np.ndarray
    tau: np.ndarray
    sigma: np.ndarray | None


@dataclass
class LocalHessian:
    """Local blocks of ``Aᵀ M A``: feet (3, 3, n_f, T); joints ττ, τσ, σσ (J, T)."""

    feet: np.ndarray
    tt: np.ndarray
    ts: np.ndarray
    ss: np.ndarray


class Block:
    """Rows of one cone type; ``s`` and ``lam`` are the slack and multiplier (interior-point
    state), ``soc`` whether the rows are 3-vectors of second-order cones (components first),
    ``nonlinear`` whether the slack is a nonlinear (concave) function of the point."""

    soc = False
    nonlinear = False
    s: np.ndarray
    lam: np.ndarray

    def linearize(self, x: Local) -> None:
        """Set the point where :meth:`linear` and :meth:`add_transpose` take the derivative."""

    def add_curvature(self, H: LocalHessian) -> None:
        """Add ``−Σ λ ∇² value`` (the rows' part of the Lagrangian's Hessian) to ``H``."""

    def value(self, x: Local) -> np.ndarray:
        raise NotImplementedError

    def linear(self, dx: Local) -> np.ndarray:
        raise NotImplementedError

    def add_transpose(self, u: np.ndarray, g: Local) -> None:
        raise NotImplementedError

    def add_hessian(self, M: np.ndarray, H: LocalHessian) -> None:
        raise NotImplementedError


class FootCone(Block):
    soc = True

    def __init__(self, mu: float) -> None:
        self.mu = mu

    def value(self, x: Local) -> np.ndarray:
        return np.stack([self.mu * x.f[2], x.f[0], x.f[1]])

    def linear(self, dx: Local) -> np.ndarray:
        return self.value(dx)

    def add_transpose(self, u: np.ndarray, g: Local) -> None:
        g.f[0] += u[1]
        g.f[1] += u[2]
        g.f[2] += self.mu * u[0]

    def add_hessian(self, M: np.ndarray, H: LocalHessian) -> None:
        mu, F = self.mu, H.feet
        F[0, 0] += M[1, 1]
        F[1, 1] += M[2, 2]
        F[2, 2] += mu * mu * M[0, 0]
        F[0, 1] += M[1, 2]
        F[0, 2] += mu * M[1, 0]
        F[1, 2] += mu * M[2, 0]


class FootRows(Block):
    """Linear rows ``A f + b`` on every foot's force: ``A`` (R, 3), ``b`` (R,); ``names`` say
    which rows they are (``"xm"``, ``"xp"``, ``"ym"``, ``"yp"`` of the pyramid, ``"bottom"``)."""

    def __init__(self, A: np.ndarray, b: np.ndarray, names: tuple[str, ...]) -> None:
        self.A, self.b, self.names = A, b, names
        self.AA = np.einsum("ra,rb->rab", A, A)

    def value(self, x: Local) -> np.ndarray:
        return self.linear(x) + self.b[:, None, None]

    def linear(self, dx: Local) -> np.ndarray:
        return np.einsum("rc,cft->rft", self.A, dx.f)

    def add_transpose(self, u: np.ndarray, g: Local) -> None:
        g.f += np.einsum("rc,rft->cft", self.A, u)

    def add_hessian(self, M: np.ndarray, H: LocalHessian) -> None:
        H.feet += np.einsum("rab,rft->abft", self.AA, M)


def linear_foot_rows(contact: ContactParams) -> FootRows | None:
    """The linear foot rows of ``contact`` (None for the cone without a minimum normal force)."""
    A, b, names = [], [], []
    if contact.cone == "pyramid":
        k = contact.mu / math.sqrt(2.0)
        A += [[-1.0, 0.0, k], [1.0, 0.0, k], [0.0, -1.0, k], [0.0, 1.0, k]]
        b += [0.0] * 4
        names += ["xm", "xp", "ym", "yp"]
    if contact.min_normal_force > 0:
        A.append([0.0, 0.0, 1.0])
        b.append(-contact.min_normal_force)
        names.append("bottom")
    return FootRows(np.array(A), np.array(b), tuple(names)) if A else None


class JointRows(Block):
    """Concave rows ``c₀ + c_τ τ + c_σ σ − c_q τ²`` per joint, coefficients (R, J, T) or
    broadcastable: the torque limits (``τ_max ∓ τ``, when ``limits``) first, then one row per
    piece (``σ − α_k τ − γ_k τ²``)."""

    nonlinear = True

    def __init__(self, c0: np.ndarray, ct: np.ndarray, cs: np.ndarray, cq: np.ndarray,
                 limits: bool) -> None:
        self.c0, self.ct, self.cs, self.cq, self.limits = c0, ct, cs, cq, limits
        self.curved = bool(np.any(cq != 0.0))
        self.slope = ct

    def linearize(self, x: Local) -> None:
        self.slope = self.ct - 2.0 * self.cq * x.tau if self.curved else self.ct

    def value(self, x: Local) -> np.ndarray:
        out = self.c0 + self.ct * x.tau
        if x.sigma is not None:
            out = out + self.cs * x.sigma
        return out - self.cq * x.tau**2 if self.curved else out

    def linear(self, dx: Local) -> np.ndarray:
        out = self.slope * dx.tau
        return out + self.cs * dx.sigma if dx.sigma is not None else out

    def add_transpose(self, u: np.ndarray, g: Local) -> None:
        g.tau += (self.slope * u).sum(0)
        if g.sigma is not None:
            g.sigma += (self.cs * u).sum(0)

    def add_hessian(self, M: np.ndarray, H: LocalHessian) -> None:
        Ms = M * self.slope
        H.tt += (Ms * self.slope).sum(0)
        H.ts += (Ms * self.cs).sum(0)
        H.ss += (M * self.cs * self.cs).sum(0)

    def add_curvature(self, H: LocalHessian) -> None:
        if self.curved:
            H.tt += 2.0 * (self.cq * self.lam).sum(0)


@dataclass(frozen=True, eq=False)
class Data:
    """The reduced programs of some samples of a group (samples on the last axis).

    Attributes:
        fp: Least-norm forces (3, n_f, T). N: Null-space basis (3, n_f, m, T).
        E: ``D N`` on the stance-leg joints (J, m, T). tau0: ``τ₀`` (J, T).
        pieces: The objective. tmax: Torque limits (J, T) or None. contact: Contact settings.
        const: The candidate rows' constant gradients
            (:func:`hexaleg.dynamics.active_set.constant_rows`), when computed.
        Z: The unconstrained optimum ``z = Z τ₀`` of a quadratic objective, (m, J, T), when
            computed: ``(Eᵀ diag(ρ) E)⁻¹ Eᵀ diag(ρ)``.
    """

    fp: np.ndarray
    N: np.ndarray
    E: np.ndarray
    tau0: np.ndarray
    pieces: Pieces
    tmax: np.ndarray | None
    contact: ContactParams
    const: np.ndarray | None = None
    Z: np.ndarray | None = None

    def local(self, z: np.ndarray, sigma: np.ndarray | None) -> Local:
        return Local(self.fp + np.einsum("cfmt,mt->cft", self.N, z),
                     self.tau0 - np.einsum("jmt,mt->jt", self.E, z), sigma)

    def take(self, idx: np.ndarray) -> Data:
        """The programs of samples ``idx`` (indices, increasing)."""
        if idx.size == self.tau0.shape[-1]:
            return self
        p = self.pieces
        return Data(self.fp[..., idx], self.N[..., idx], self.E[..., idx], self.tau0[..., idx],
                    Pieces(p.rho[..., idx], p.alpha[..., idx], p.gamma[..., idx]),
                    None if self.tmax is None else self.tmax[..., idx], self.contact,
                    None if self.const is None else self.const[..., idx],
                    None if self.Z is None else self.Z[..., idx])

    def direction(self, dz: np.ndarray, dsigma: np.ndarray | None) -> Local:
        return Local(np.einsum("cfmt,mt->cft", self.N, dz),
                     -np.einsum("jmt,mt->jt", self.E, dz), dsigma)


def make_blocks(data: Data) -> list[Block]:
    """The constraint blocks of ``data``'s programs (:mod:`hexaleg.dynamics.blocks`)."""
    c = data.contact
    blocks: list[Block] = [FootCone(c.mu)] if c.cone == "soc" else []
    rows = linear_foot_rows(c)
    if rows is not None:
        blocks.append(rows)
    p = data.pieces
    J, T = data.tau0.shape
    c0, ct, cs, cq = [], [], [], []
    if data.tmax is not None:
        c0 += [data.tmax, data.tmax]
        ct += [np.full((J, T), -1.0), np.full((J, T), 1.0)]
        cs += [np.zeros((J, T))] * 2
        cq += [np.zeros((J, T))] * 2
    for k in range(p.K):
        c0.append(np.zeros((J, T)))
        ct.append(-p.alpha[k])
        cs.append(np.ones((J, T)))
        cq.append(p.gamma[k])
    if c0:
        blocks.append(JointRows(np.stack(c0), np.stack(ct), np.stack(cs), np.stack(cq),
                                data.tmax is not None))
    return blocks
