"""Costs of the paper's joint's motor torque over one period and the stiffness that minimises one.

:func:`metric` evaluates a cost (mean, RMS and peak torque, ∫M², positive and absolute work of
eq. 20–21, Joule loss) vectorised over stiffness; :func:`energy_ratio` is the paper's ε (eq. 24);
:func:`optimal_stiffness` finds the stiffness minimising a cost numerically (compared with the
closed forms of :class:`~hexaleg.paper.joint.PaperJoint` in the tests).
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike
from scipy.optimize import minimize_scalar

from hexaleg.checks import count
from hexaleg.dynamics.energy import saving
from hexaleg.errors import InvalidParameterError
from hexaleg.motion.limits import SAMPLE_BYTES
from hexaleg.paper.joint import PaperJoint
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.catalogue import motor as default_motor

JOINT_METRICS: tuple[str, ...] = ("mean_abs", "rms", "peak", "int_sq", "positive_work",
                                  "absolute_work", "joule")
"""Cost functions of the paper's joint's motor torque over one period (see :func:`metric`)."""


def paper_samples(n: object) -> int:
    """The samples per period of the paper study, checked: an integer in [8, the memory bound
    :data:`hexaleg.motion.limits.MAX_SAMPLES`].

    Raises:
        InvalidParameterError: names the value and the bound.
    """
    return count("samples", n, item_bytes=SAMPLE_BYTES, item="one sample", low=8,
                 fix="use fewer samples per period (8192 reproduces every number)")


def metric(joint: PaperJoint, name: str, k: ArrayLike, gravity: bool = True, n: int = 2048,
           motor: Actuator | None = None) -> np.ndarray:
    """A cost of the motor torque over one period, vectorised over stiffness.

    Args:
        joint: The joint.
        name: One of :data:`JOINT_METRICS`: ``mean_abs`` (mean |M|, N·m), ``rms`` (N·m), ``peak``
            (max |M|, N·m), ``int_sq`` (∫M² dt, N²·m²·s), ``positive_work`` (∫max(Mθ̇, 0) dt, J),
            ``absolute_work`` (∫|Mθ̇| dt, J), ``joule`` (∫ c M² dt, J, c = R/(k_t G)² of
            ``motor``).
        k: Stiffness(es), N·m/rad, scalar or (K,).
        gravity: Include gravity.
        n: Samples per period (uniform, endpoint excluded: integrals are sums × dt).
        motor: Servo for ``joule`` (default :data:`hexaleg.robot.catalogue.DEFAULT_MOTOR`, the
            robot's AX-18A).

    Returns:
        Scalar array or shape (K,).
    """
    if name not in JOINT_METRICS:
        raise InvalidParameterError("metric", name, f"one of {', '.join(JOINT_METRICS)}")
    t = joint.times(n)
    dt = joint.period / n
    tau = joint.motor_torque(t, k, gravity)
    _, thd, _ = joint.trajectory(t)
    if name == "mean_abs":
        return np.abs(tau).mean(-1)
    if name == "rms":
        return np.sqrt((tau**2).mean(-1))
    if name == "peak":
        extra = joint.motor_torque(joint.critical_times(), k, gravity)
        return np.maximum(np.abs(tau).max(-1), np.abs(extra).max(-1))
    if name == "int_sq":
        return (tau**2).sum(-1) * dt
    if name == "positive_work":
        return np.maximum(tau * thd, 0.0).sum(-1) * dt
    if name == "absolute_work":
        return np.abs(tau * thd).sum(-1) * dt
    return (motor or default_motor()).joule_power(tau).sum(-1) * dt


def energy_ratio(joint: PaperJoint, k: ArrayLike, gravity: bool = True,
                 n: int = 2048) -> np.ndarray:
    """Eq. 24 energy consumption ratio ε of the joint over one period, 1/s².

    ``ε = E / (J θ_path)`` with E the positive motor work per period (a motor that cannot
    recover energy; the net eq. 20 work of this friction-free model is zero), J = m l² + I
    (eq. 24's "moment of inertia about the rotation axis") and θ_path = 4A, the angle swept.

    Args:
        joint: The joint.
        k: Stiffness(es), N·m/rad, scalar or (K,).
        gravity: Include gravity.
        n: Samples per period.

    Returns:
        Scalar array or shape (K,).
    """
    return metric(joint, "positive_work", k, gravity, n) / (joint.J * 4 * joint.amplitude)


@dataclass(frozen=True)
class StiffnessOptimum:
    """Result of :func:`optimal_stiffness`.

    Attributes:
        metric: Metric name.
        gravity: Whether gravity was included.
        k: Optimal stiffness, N·m/rad, in the joint's convention.
        flat: (low, high) stiffness interval, N·m/rad, where the metric is within 1e-9 relative of
            its minimum on the search grid (a single point unless the optimum is flat).
        value: Metric at k.
        baseline: Metric without spring (k = 0).
        saving: Fraction saved, :func:`hexaleg.dynamics.energy.saving` of ``value`` against
            ``baseline``.
        on_bound: The optimum is at the upper search bound (widen ``bounds``).
    """

    metric: str
    gravity: bool
    k: float
    flat: tuple[float, float]
    value: float
    baseline: float
    saving: float
    on_bound: bool


def optimal_stiffness(joint: PaperJoint, name: str, gravity: bool = True,
                      bounds: tuple[float, float] | None = None, n: int = 2048, grid: int = 801,
                      motor: Actuator | None = None) -> StiffnessOptimum:
    """Numerically optimal stiffness for one metric: grid search, then a bounded Brent refinement.

    Args:
        joint: The joint.
        name: One of :data:`JOINT_METRICS`.
        gravity: Include gravity.
        bounds: Search interval of k, N·m/rad (default 0 to 10 (J ω² + m g l)/α, ten times the
            inertial plus gravity stiffness scale).
        n: Samples per period.
        grid: Grid points over ``bounds``.
        motor: The actuator of the joint for ``joule`` (a single model).

    Returns:
        The optimum.
    """
    if bounds is None:
        scale = joint.J * joint.omega**2 + joint.mass * joint.gravity * joint.com * gravity
        bounds = (0.0, 10.0 * scale / joint.transmission)
    lo, hi = bounds
    if not (math.isfinite(lo) and math.isfinite(hi) and 0 <= lo < hi):
        raise InvalidParameterError("bounds", bounds, "finite (low, high) with 0 <= low < high")
    ks = np.linspace(lo, hi, grid)
    values = metric(joint, name, ks, gravity, n, motor)
    i = int(np.argmin(values))
    best = values[i]
    near = ks[values <= best * (1 + 1e-9) + 1e-300]

    def f(k: float) -> float:
        return float(metric(joint, name, k, gravity, n, motor))

    a, b = ks[max(i - 1, 0)], ks[min(i + 1, grid - 1)]
    res = minimize_scalar(f, bounds=(a, b), method="bounded",
                          options={"xatol": 1e-12 * max(hi, 1e-300)})
    k_opt, v_opt = (float(res.x), float(res.fun)) if res.fun <= best else (float(ks[i]),
                                                                           float(best))
    if near.size > 1:  # a flat optimum: report its middle, not an arbitrary point of it
        k_opt = float(0.5 * (near[0] + near[-1]))
        v_opt = f(k_opt)
    baseline = float(metric(joint, name, 0.0, gravity, n, motor))
    return StiffnessOptimum(name, gravity, k_opt, (float(near[0]), float(near[-1])), v_opt,
                            baseline, float(saving(v_opt, baseline)),
                            bool(near[-1] >= hi))
