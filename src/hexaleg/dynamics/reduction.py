"""Each sample's force program on the null space of its base rows, batched by size.

A sample with ``n_st`` stance feet has ``n = 3 n_st`` force unknowns and 6 base rows ``A f = b``
of rank ``r`` (6 for three or more feet in general position, 5 for two point feet). Every force
that satisfies them is ``f = f_p + N z`` with ``f_p`` the least-norm solution, ``N`` an orthonormal
basis of the null space of ``A`` (from its SVD) and ``z`` free, ``m = n − r`` unknowns: 3 for a
tripod, 1 for two feet, 12 for six. Only the joints of the stance legs feel the forces; their
torques are ``τ = τ₀ − E z`` with ``E = D N`` and ``τ₀ = b_joint − D f_p − τ_spring``, the others'
are ``b_joint − τ_spring`` whatever the forces. None of this depends on the springs except
``τ_spring`` in ``τ₀``: it is computed once per motion (:func:`reduce`).

Samples with the same number of stance feet, null-space dimension and stance-leg joints form a
:class:`Group` (the default tripod gait is one group of 1000 samples): its arrays carry the
samples on the last axis, the layout of :mod:`hexaleg.dynamics.smallmat`.
"""

from __future__ import annotations

import weakref
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from hexaleg.dynamics.contact import StanceSystem

GROUP_SIZE = 1024
"""Most samples in one group (see :func:`reduce`)."""
RANK_TOL = 1e-9
"""Singular values of the base rows below this fraction of the largest are zero (here and in
:func:`hexaleg.dynamics.conic.base_row_space`)."""
REACH_TOL = 1e-8
"""A base wrench is reachable when the part of it outside the row space is below this, relative
to ``1 + max |b_base|`` (N, N·m)."""


@dataclass(frozen=True, eq=False)
class Group:
    """Samples whose reduced programs have the same sizes (the samples on the last axis).

    Attributes:
        rows: Sample indices, shape (T,).
        legs: The stance leg of each foot slot, shape (n_f, T).
        joints: The joints of the stance legs, shape (J, T).
        fp: Least-norm forces of the base rows, (3, n_f, T) — components (x, y, z) first, N.
        N: Orthonormal null-space basis of the base rows on those forces, (3, n_f, m, T).
        E: ``D N`` on the stance-leg joints, (J, m, T), N·m per N.
        tau_base: ``b_joint − D f_p`` on the stance-leg joints, (J, T), N·m.
        cache: What the solvers derive from the group and their settings, by key (computed
            once per motion).
    """

    rows: np.ndarray
    legs: np.ndarray
    joints: np.ndarray
    fp: np.ndarray
    N: np.ndarray
    E: np.ndarray
    tau_base: np.ndarray
    cache: dict[Any, Any] = field(default_factory=dict, repr=False)

    @property
    def m(self) -> int:
        """Null-space dimension (free unknowns per sample)."""
        return int(self.N.shape[2])

    @property
    def size(self) -> int:
        """Number of samples."""
        return int(self.rows.size)

    def tau0(self, tau_spring: np.ndarray) -> np.ndarray:
        """``τ₀ = b_joint − D f_p − τ_spring`` on the stance-leg joints, (J, T), N·m."""
        return self.tau_base - tau_spring[self.rows, self.joints]

    def forces(self, z: np.ndarray) -> np.ndarray:
        """Forces ``f_p + N z`` for null-space coordinates ``z`` (m, T): (3, n_f, T), N."""
        if self.m == 0:
            return self.fp.copy()
        return self.fp + np.einsum("cfmt,mt->cft", self.N, z)

    def torques(self, tau0: np.ndarray, z: np.ndarray) -> np.ndarray:
        """Stance-leg joint torques ``τ₀ − E z``: (J, T), N·m."""
        if self.m == 0:
            return tau0.copy()
        return tau0 - np.einsum("jmt,mt->jt", self.E, z)


@dataclass(frozen=True, eq=False)
class Reduction:
    """The reduced programs of one motion (:func:`reduce`).

    Attributes:
        groups: Samples with stance feet, by program size.
        residual: Part of each sample's base wrench its stance feet cannot produce (2-norm, N and
            N·m; all of it for a sample without stance feet), shape (T,).
        reachable: ``residual`` within rounding of zero, shape (T,), bool.
        free: Joints whose torque the forces do not change (swing legs), shape (T, nj), bool.
    """

    groups: tuple[Group, ...]
    residual: np.ndarray
    reachable: np.ndarray
    free: np.ndarray


_CACHE: weakref.WeakKeyDictionary[StanceSystem, Reduction] = weakref.WeakKeyDictionary()


def reduce(system: StanceSystem) -> Reduction:
    """The :class:`Reduction` of ``system``, computed once per system (cached while it lives)."""
    if system not in _CACHE:
        _CACHE[system] = _reduce(system)
    return _CACHE[system]


def _reduce(system: StanceSystem) -> Reduction:
    T = system.stance.shape[0]
    nj = system.D.shape[1]
    residual = np.linalg.norm(system.b_base, axis=1)  # samples without stance feet
    free = np.ones((T, nj), dtype=bool)
    parts: dict[tuple[int, int, int], list[dict[str, np.ndarray]]] = {}
    patterns, inverse = np.unique(system.stance, axis=0, return_inverse=True)
    inverse = inverse.reshape(-1)
    for p, pattern in enumerate(patterns):
        if not pattern.any():
            continue
        rows = np.flatnonzero(inverse == p)
        legs = np.flatnonzero(pattern)
        cols = (3 * legs[:, None] + np.arange(3)).reshape(-1)
        A = system.A[rows][:, :, cols]  # (Tp, 6, n)
        D = system.D[rows][:, :, cols]  # (Tp, nj, n)
        joints = np.flatnonzero(np.any(D != 0.0, axis=(0, 2)))
        free[np.ix_(rows, joints)] = False
        U, S, Vt = np.linalg.svd(A)  # U (Tp, 6, 6), S (Tp, min), Vt (Tp, n, n)
        rank = np.sum(S > RANK_TOL * S[:, :1], axis=1)
        b = system.b_base[rows]
        for r in np.unique(rank):
            sel = np.flatnonzero(rank == r)
            Ur, Sr, Vr = U[sel][:, :, :r], S[sel][:, :r], Vt[sel][:, :r, :]
            coef = np.einsum("tir,ti->tr", Ur, b[sel])
            residual[rows[sel]] = np.linalg.norm(b[sel] - np.einsum("tir,tr->ti", Ur, coef),
                                                 axis=1)
            fp = np.einsum("trn,tr->tn", Vr, coef / Sr)  # (Ts, n)
            N = np.transpose(Vt[sel][:, r:, :], (0, 2, 1))  # (Ts, n, m)
            Dj = D[sel][:, joints, :]  # (Ts, J, n)
            nf, m = legs.size, N.shape[2]
            parts.setdefault((nf, m, joints.size), []).append({
                "rows": rows[sel],
                "legs": np.broadcast_to(legs[:, None], (nf, sel.size)),
                "joints": np.broadcast_to(joints[:, None], (joints.size, sel.size)),
                "fp": np.transpose(fp.reshape(sel.size, nf, 3), (2, 1, 0)),
                # sizes spelled out: one stance foot leaves no null space (m = 0, N empty)
                "N": np.transpose(N.reshape(sel.size, nf, 3, m), (2, 1, 3, 0)),
                "E": np.transpose(Dj @ N, (1, 2, 0)),
                "tau_base": (system.b_joint[rows[sel]][:, joints]
                             - np.einsum("tjn,tn->tj", Dj, fp)).T,
            })
    groups = []
    axis = {"rows": 0, "legs": 1, "joints": 1, "fp": 2, "N": 3, "E": 2, "tau_base": 1}
    for chunks in parts.values():
        merged: dict[str, Any] = {k: np.concatenate([c[k] for c in chunks], axis=a)
                                  for k, a in axis.items()}
        # Long motions are cut into groups of at most GROUP_SIZE samples: each group's arrays
        # then stay in the processor's cache, and the cost per sample stays that of 1000 samples.
        n = merged["rows"].size
        for start in range(0, n, GROUP_SIZE):
            part = slice(start, min(n, start + GROUP_SIZE))
            cut: dict[str, Any] = {k: np.ascontiguousarray(np.moveaxis(
                np.moveaxis(v, axis[k], -1)[..., part], -1, axis[k]))
                for k, v in merged.items()}
            groups.append(Group(**cut))
    scale = 1.0 + np.abs(system.b_base).max(axis=1)
    return Reduction(tuple(groups), residual, residual <= REACH_TOL * scale, free)
