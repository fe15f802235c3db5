"""The base wrench a measured motion's contacts can produce: the nearest to what the log implies.

A generated gait is the model's own motion: where no admissible foot forces give its base wrench,
the gait is wrong and the force program says so (``InfeasibleForcesError``). A logged motion is a
measurement: its base acceleration comes from a noisy, smoothed, sometimes inferred base pose, and
its stance from sensors or kinematics, so at some samples the contacts cannot produce exactly
the wrench ``M a + h`` of the base rows — a settle, a bump, a foot counted down a sample early.
There the forces are solved for the *nearest* wrench the contacts can produce, and the
difference — the residual — is reported, per sample and as a fraction of the robot's weight
(Newton–Euler: the residual is the external wrench the log's motion needs and no foot gives).

The nearest wrench of a sample is ``w* = A f*`` with ``f*`` minimising ``‖S (A f − b)‖²`` over
forces in the friction cones with at least the minimum normal force: each cone as the
inscribed pyramid of :data:`EDGES` edges (a cone's force is a non-negative combination of its
edges), the problem a non-negative least squares (Lawson & Hanson, *Solving Least Squares
Problems*, 1974, ch. 23: ``scipy.optimize.nnls``). ``S`` scales the moment rows by the stance
feet's lever arm so forces and moments weigh alike. Samples whose residual is below
:data:`TOLERANCE` of the weight keep their wrench as logged; a residual over :data:`BOUND` of
the weight anywhere is an error that names the samples and the likely causes.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from hexaleg.errors import InfeasibleForcesError

EDGES = 16
"""Edges of the inscribed friction pyramid (it holds cos(π/16) = 98 % of the cone's reach)."""
TOLERANCE = 1e-6
"""Fraction of the weight below which a sample's residual is round-off: its wrench is kept."""
BOUND = 0.5
"""Fraction of the weight a residual force may reach: beyond it the log's motion is not one the
contacts can carry (half the weight missing is not noise) and the result is an error."""


@dataclass(frozen=True)
class WrenchResidual:
    """What a measured motion's contacts could not produce.

    Attributes:
        residual: Logged minus produced base wrench, shape (T, 6): force (N), moment (N·m), in
            the base rows' frame (Pinocchio's free-flyer convention).
        weight: The robot's weight m g, N.
        t: Sample times, shape (T,), s.
    """

    residual: np.ndarray
    weight: float
    t: np.ndarray

    @property
    def fraction(self) -> np.ndarray:
        """The residual force per sample as a fraction of the weight, shape (T,)."""
        return np.linalg.norm(self.residual[:, :3], axis=1) / self.weight

    @property
    def samples(self) -> np.ndarray:
        """The samples whose wrench was replaced by the nearest one, indices."""
        return np.flatnonzero(np.abs(self.residual).max(axis=1) > 0.0)

    def line(self) -> str | None:
        """One line for the run's warnings, or None when every sample was produced as logged."""
        k = self.samples
        if k.size == 0:
            return None
        worst = int(k[np.argmax(self.fraction[k])])
        rms = 100 * math.sqrt(float(np.mean(self.fraction**2)))
        return (f"the contacts cannot produce the logged base motion at {k.size} of "
                f"{len(self.t)} samples: forces solved for the nearest motion they can produce, "
                f"the residual force at most {100 * self.fraction[worst]:.1f} % of the weight "
                f"(t = {self.t[worst]:.4f} s), rms {rms:.2f} %")


def _pyramid(mu: float) -> np.ndarray:
    """The inscribed friction pyramid's edges about z, shape (3, EDGES)."""
    angle = 2 * np.pi * np.arange(EDGES) / EDGES
    return np.stack([mu * np.cos(angle), mu * np.sin(angle), np.ones(EDGES)])


def nearest_wrench(A: np.ndarray, b: np.ndarray, stance: np.ndarray, mu: float,
                   min_normal_force: float, weight: float, t: np.ndarray
                   ) -> tuple[np.ndarray, WrenchResidual]:
    """The base wrench the contacts can produce nearest to the logged one (module docstring).

    Args:
        A: Base rows of the stance system, shape (T, 6, 3 n_legs) (forces in the contact frame).
        b: The logged base wrench ``M a + h``, shape (T, 6).
        stance: Stance flags, shape (T, n_legs).
        mu: Friction coefficient.
        min_normal_force: Smallest normal force of a stance foot, N.
        weight: The robot's weight, N.
        t: Sample times, shape (T,), s.

    Returns:
        The wrench to solve the forces for, shape (T, 6), and the residual.

    Raises:
        InfeasibleForcesError: a residual force beyond :data:`BOUND` of the weight; names the
            samples, the largest residual and what may cause it.
    """
    from scipy.optimize import nnls

    edges = _pyramid(mu)
    out = np.array(b, dtype=float, copy=True)
    residual = np.zeros_like(out)
    for k in range(len(b)):
        feet = np.flatnonzero(stance[k])
        blocks = [A[k][:, 3 * i:3 * i + 3] for i in feet]
        arm = max((float(np.linalg.norm(blk[3:])) / math.sqrt(2.0) for blk in blocks),
                  default=1.0)
        scale = np.r_[np.ones(3), np.full(3, 1.0 / max(arm, 1e-9))]
        target = b[k] - sum((blk[:, 2] * min_normal_force for blk in blocks), np.zeros(6))
        if blocks:
            basis = np.concatenate([blk @ edges for blk in blocks], axis=1)
            lam, _ = nnls(scale[:, None] * basis, scale * target, maxiter=50 * basis.shape[1])
            miss = target - basis @ lam
        else:
            miss = target
        if np.linalg.norm(scale * miss) > TOLERANCE * weight:
            residual[k] = miss
            out[k] = b[k] - miss
    found = WrenchResidual(residual=residual, weight=weight, t=np.asarray(t, dtype=float))
    far = np.flatnonzero(found.fraction > BOUND)
    if far.size:
        k = int(far[np.argmax(found.fraction[far])])
        raise InfeasibleForcesError(
            f"the contacts cannot carry the logged base motion at {far.size} samples (from "
            f"t = {t[far[0]]:.4f} s): at t = {t[k]:.4f} s (sample {k}) the nearest forces miss "
            f"{100 * found.fraction[k]:.0f} % of the weight (at most {100 * BOUND:.0f} % is taken "
            "as the log's noise). Likely causes: the log's base (a drop, a settle or a jump: cut "
            "a window of the steady gait, --cycle T0:T1), its stance (a foot counted down or up "
            "at the wrong time: check the contact columns) or the friction (raise [contact] mu)")
    return out, found


__all__ = ["BOUND", "EDGES", "TOLERANCE", "WrenchResidual", "nearest_wrench"]
