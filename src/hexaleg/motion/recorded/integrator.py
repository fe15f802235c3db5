"""Which integration a log's samples are the knots of, found from the samples themselves.

A log that gives its derivatives (``v_<name>``, ``a_<name>``) may be the knots of a
semi-implicit Euler integration, ``v_{k+1} = v_k + a_k dt``, ``q_{k+1} = q_k ⊕ v_{k+1} dt``: an
optimal motion written as a log (:data:`~hexaleg.motion.trajectory.SEMI_IMPLICIT`), whose
balance feedback closes the cycle by that step (:func:`hexaleg.simulation.balance.cycle_end`).
A motion log has no place to say so, and a marker written beside the data could be lost by
another tool or describe data it changed; so the data decide. Each sample is predicted from the
one before by the semi-implicit step ``q ⊕ (v + a dt) dt`` and by the explicit step ``q ⊕ v dt``
(Hairer, Lubich & Wanner, *Geometric Numerical Integration*, 2nd ed., §VI.3, the symplectic
Euler method against the explicit one): knots of a semi-implicit integration meet the first to
round-off and miss the second by about ``|a| dt²``, while samples of a smooth motion miss both
by about ``½ |a| dt²``. Measured: a co-design's optimal motion (32 ms knots) read back through
:func:`hexaleg.load_motion` misses them by 1.2e-6 and 0.13; the default tripod gait by 3.0e-5
and 3.0e-5 at 1000 samples a cycle, 0.012 and 0.012 at 50.
"""

from __future__ import annotations

import numpy as np
import pinocchio as pin

from hexaleg.motion.trajectory import SEMI_IMPLICIT

RATIO = 100.0
"""How many times better the semi-implicit step must predict the samples than the explicit one
(module docstring: 1e5 for an optimal motion's knots, 1.0 for a gait's samples)."""


def step_misses(model: pin.Model, q: np.ndarray, v: np.ndarray, a: np.ndarray, dt: float
                ) -> tuple[float, float]:
    """The largest miss of each sample predicted from the one before, by the semi-implicit and
    by the explicit Euler step (module docstring), in the tangent space (``pin.difference``:
    rad and m).

    Args:
        model: The robot's Pinocchio model (free flyer).
        q: Configurations, shape (T, nq). v, a: Velocities and accelerations, shape (T, nv)
            (the base's in its own frame, Pinocchio's convention). dt: The sample spacing, s.
    """
    def miss(k: int, step: np.ndarray) -> float:
        return float(np.abs(pin.difference(model, pin.integrate(model, q[k], step),
                                           q[k + 1])).max())

    ks = range(len(q) - 1)
    return (max((miss(k, (v[k] + a[k] * dt) * dt) for k in ks), default=0.0),
            max((miss(k, v[k] * dt) for k in ks), default=0.0))


def integrator_of(model: pin.Model, q: np.ndarray, v: np.ndarray, a: np.ndarray, dt: float
                  ) -> str | None:
    """:data:`~hexaleg.motion.trajectory.SEMI_IMPLICIT` when the samples are the knots of a
    semi-implicit Euler integration (:func:`step_misses`: its step predicts them :data:`RATIO`
    times better than the explicit step), else None (samples of a motion, or too few)."""
    if len(q) < 3 or not all(np.isfinite(x).all() for x in (q, v, a)):
        return None
    semi, explicit = step_misses(model, q, v, a, dt)
    return SEMI_IMPLICIT if semi * RATIO < explicit else None


__all__ = ["RATIO", "integrator_of", "step_misses"]
