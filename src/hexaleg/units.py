"""Conversions between the paper's units and SI — the only place where paper units appear.

hexaleg computes in SI (m, kg, s, rad, N·m, J). The paper (Tables 4–6, Section 4) states lengths
in mm, angles in deg, masses in kg, inertias in kg·mm², stiffness in N·mm/deg and damping in
N·mm·s/deg. Convert at the edges, with these functions, and nowhere else.
"""

from __future__ import annotations

import math

import numpy as np
from numpy.typing import ArrayLike

DEG = math.pi / 180.0
"""One degree in radians."""
MM = 1e-3
"""One millimetre in metres."""
G = 9.81
"""Standard gravity used by hexaleg, m/s² (Pinocchio's default model gravity)."""


def _f(x: ArrayLike) -> float | np.ndarray:
    a = np.asarray(x, dtype=float)
    return float(a) if a.ndim == 0 else a


def deg_to_rad(x: ArrayLike) -> float | np.ndarray:
    """Degrees → radians."""
    return _f(np.asarray(x, dtype=float) * DEG)


def rad_to_deg(x: ArrayLike) -> float | np.ndarray:
    """Radians → degrees."""
    return _f(np.asarray(x, dtype=float) / DEG)


def mm_to_m(x: ArrayLike) -> float | np.ndarray:
    """Millimetres → metres."""
    return _f(np.asarray(x, dtype=float) * MM)


def m_to_mm(x: ArrayLike) -> float | np.ndarray:
    """Metres → millimetres."""
    return _f(np.asarray(x, dtype=float) / MM)


def kgmm2_to_kgm2(x: ArrayLike) -> float | np.ndarray:
    """Moment of inertia kg·mm² → kg·m²."""
    return _f(np.asarray(x, dtype=float) * MM**2)


def kgm2_to_kgmm2(x: ArrayLike) -> float | np.ndarray:
    """Moment of inertia kg·m² → kg·mm²."""
    return _f(np.asarray(x, dtype=float) / MM**2)


def nmm_per_deg_to_nm_per_rad(x: ArrayLike) -> float | np.ndarray:
    """Torsional stiffness N·mm/deg → N·m/rad (1 N·mm/deg = 0.0572958 N·m/rad)."""
    return _f(np.asarray(x, dtype=float) * MM / DEG)


def nm_per_rad_to_nmm_per_deg(x: ArrayLike) -> float | np.ndarray:
    """Torsional stiffness N·m/rad → N·mm/deg."""
    return _f(np.asarray(x, dtype=float) * DEG / MM)


def nmms_per_deg_to_nms_per_rad(x: ArrayLike) -> float | np.ndarray:
    """Rotational damping N·mm·s/deg → N·m·s/rad."""
    return _f(np.asarray(x, dtype=float) * MM / DEG)


def nms_per_rad_to_nmms_per_deg(x: ArrayLike) -> float | np.ndarray:
    """Rotational damping N·m·s/rad → N·mm·s/deg."""
    return _f(np.asarray(x, dtype=float) * DEG / MM)


def nmm_to_nm(x: ArrayLike) -> float | np.ndarray:
    """Torque N·mm → N·m."""
    return _f(np.asarray(x, dtype=float) * MM)


def nm_to_nmm(x: ArrayLike) -> float | np.ndarray:
    """Torque N·m → N·mm."""
    return _f(np.asarray(x, dtype=float) / MM)


ASCII_SPELLINGS: dict[str, str] = {
    "·": "*", "−": "-", "–": "-", "—": "--", "²": "^2", "³": "^3", "⁻": "^-", "¹": "^1",
    "→": "->", "←": "<-", "≥": ">=", "≤": "<=", "≈": "~", "×": "x", "±": "+/-", "∓": "-/+",
    "°": " deg", "…": "...", "µ": "u", "μ": "mu", "θ": "theta", "τ": "tau", "ω": "omega",
    "α": "alpha", "β": "beta", "γ": "gamma", "δ": "delta", "Δ": "Delta", "ε": "eps",
    "η": "eta", "κ": "kappa", "λ": "lambda", "π": "pi", "ρ": "rho", "σ": "sigma",
    "Σ": "Sum", "φ": "phi", "ψ": "psi", "Ω": "Ohm", "½": "1/2", "‖": "||", "√": "sqrt",
    "∞": "inf", "§": "S", "₀": "0", "₁": "1", "₂": "2", "“": '"', "”": '"', "‘": "'",
    "’": "'",
}
"""ASCII spellings of the symbols hexaleg prints (units such as N·m and m/s², Greek letters,
arrows), for a console that cannot show them (:func:`ascii_spelling`)."""


def ascii_spelling(error: UnicodeError) -> tuple[str, int]:
    """A codec error handler (:func:`codecs.register_error`) for output to an ASCII console
    (``PYTHONIOENCODING=ascii``, the C locale): each character the console cannot show is
    spelt in ASCII (:data:`ASCII_SPELLINGS`: ``N·m`` → ``N*m``, ``θ`` → ``theta``), any other
    as a ``\\u`` escape, so output never fails on a symbol."""
    if not isinstance(error, UnicodeEncodeError):
        raise error
    text = error.object[error.start:error.end]
    return "".join(ASCII_SPELLINGS.get(c, c.encode("ascii", "backslashreplace").decode())
                   for c in text), error.end
