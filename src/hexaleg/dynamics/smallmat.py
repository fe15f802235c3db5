"""Dense linear algebra on many tiny matrices at once, the batch axis last.

The force programs of :mod:`hexaleg.dynamics.batched` are 1 to 12 unknowns each, thousands of them.
``numpy.linalg`` on a (T, n, n) stack calls LAPACK once per matrix (a tiny matrix's work is less
than the call's overhead), and batched ``matmul`` of such shapes is as slow. Here a matrix is an
array (n, n, T) and every step of the factorisation is one NumPy operation across all T matrices
(structure of arrays): a 3 × 3 Cholesky factorisation and solve cost ≈ 25 operations on arrays of
T numbers.

Only what the solvers need: Cholesky factorisation of symmetric positive definite matrices and the
two triangular solves, for one or several right-hand sides.
"""

from __future__ import annotations

import numpy as np

TINY = 1e-300
"""Floor of a Cholesky pivot: a matrix that is not numerically positive definite gives huge
(not NaN) entries; the caller's checks (residuals, verification) reject the result."""


def cholesky(H: np.ndarray, rcond: float = 0.0) -> np.ndarray:
    """Lower Cholesky factors of the symmetric positive definite matrices ``H`` (n, n, T).

    Only the lower triangle of ``H`` is read. Returns ``L`` (n, n, T) with ``L Lᵀ = H``. A pivot
    below ``rcond`` times its diagonal entry (a singular or indefinite matrix) is replaced by
    that floor; :func:`definite` tells which matrices had none.
    """
    n = H.shape[0]
    L = np.zeros_like(H)
    for j in range(n):
        d = H[j, j] - (L[j, :j] * L[j, :j]).sum(0) if j else H[j, j]
        ljj = np.sqrt(np.maximum(d, np.maximum(rcond * np.abs(H[j, j]), TINY)))
        L[j, j] = ljj
        if j + 1 < n:
            below = H[j + 1:, j]
            if j:
                below = below - (L[j + 1:, :j] * L[j, :j]).sum(1)
            L[j + 1:, j] = below / ljj
    return L


def cholesky_dropping(S: np.ndarray, rcond: float) -> tuple[np.ndarray, np.ndarray]:
    """Cholesky factors of the positive semidefinite Gram matrices ``S`` (n, n, T) of rows that
    may be dependent: a row whose pivot falls below ``rcond`` times its diagonal entry (it
    depends on the rows before it) is dropped — its row and column of ``L`` become those of
    the identity. Returns ``(L, kept)``, ``kept`` (n, T) bool; solving with ``L`` gives 0 for
    dropped rows if their right-hand side is zeroed."""
    n = S.shape[0]
    L = np.zeros_like(S)
    kept = np.ones(S.shape[::2], bool)
    for j in range(n):
        d = S[j, j] - (L[j, :j] * L[j, :j]).sum(0) if j else S[j, j]
        ok = d > rcond * np.abs(S[j, j])
        kept[j] = ok
        if j:
            L[j, :j] *= ok
        ljj = np.sqrt(np.where(ok, d, 1.0))
        L[j, j] = ljj
        if j + 1 < n:
            below = S[j + 1:, j]
            if j:
                below = below - (L[j + 1:, :j] * L[j, :j]).sum(1)
            L[j + 1:, j] = np.where(ok, below / ljj, 0.0)
    return L, kept


def definite(H: np.ndarray, L: np.ndarray, rcond: float) -> np.ndarray:
    """Which of :func:`cholesky`'s factorisations met no pivot floor: every pivot of ``L``
    above ``rcond`` times the diagonal entry of ``H`` (1e-12: numerically nonsingular), (T,)."""
    n = H.shape[0]
    diag = L[np.arange(n), np.arange(n)] ** 2
    return np.all(diag > rcond * np.abs(H[np.arange(n), np.arange(n)]), axis=0)


def forward(L: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Solve ``L y = b`` for lower triangular ``L`` (n, n, T); ``b`` is (n, T) or (n, k, T)."""
    n = L.shape[0]
    y = np.empty_like(b)
    multi = b.ndim == 3
    for i in range(n):
        r = b[i]
        if i:
            Li = L[i, :i]
            r = r - ((Li[:, None] * y[:i]).sum(0) if multi else (Li * y[:i]).sum(0))
        y[i] = r / L[i, i]
    return y


def backward(L: np.ndarray, y: np.ndarray) -> np.ndarray:
    """Solve ``Lᵀ x = y`` for lower triangular ``L`` (n, n, T); ``y`` is (n, T) or (n, k, T)."""
    n = L.shape[0]
    x = np.empty_like(y)
    multi = y.ndim == 3
    for i in range(n - 1, -1, -1):
        r = y[i]
        if i + 1 < n:
            Li = L[i + 1:, i]
            r = r - ((Li[:, None] * x[i + 1:]).sum(0) if multi else (Li * x[i + 1:]).sum(0))
        x[i] = r / L[i, i]
    return x


def solve_spd(H: np.ndarray, b: np.ndarray) -> np.ndarray:
    """Solve ``H x = b`` for symmetric positive definite ``H`` (n, n, T); ``b`` (n, T)/(n, k, T)."""
    L = cholesky(H)
    return backward(L, forward(L, b))


def gram(M: np.ndarray, weights: np.ndarray | None = None) -> np.ndarray:
    """``Mᵀ diag(weights) M`` for ``M`` (r, n, T) and ``weights`` (r, T): shape (n, n, T)."""
    Mw = M if weights is None else M * weights[:, None, :]
    return np.einsum("rpt,rqt->pqt", Mw, M)
