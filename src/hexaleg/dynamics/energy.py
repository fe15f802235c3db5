"""Energy metrics over a motion cycle: work, Joule loss, electrical energy, torques, CoT, ε.

Integrals use the trapezoidal rule: on a periodic grid ``t[k] = k dt`` that excludes the
endpoint a cycle integral is ``x.sum(0) * dt`` (see :mod:`hexaleg.motion.trajectory`); a motion that
stores both ends (``periodic=False``) weighs the end samples ``dt / 2``. The electrical model is
:class:`hexaleg.robot.motor.Motor`; the paper's energy is the signed joint work of eq. 20, its
energy consumption ratio is eq. 23 (cost of transport) and eq. 24 (the single-joint variant,
:func:`epsilon`, and per joint in :func:`metrics`). ``docs/energy.md`` lists every key.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any, overload

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.checks import positive, real, typed
from hexaleg.errors import InvalidParameterError
from hexaleg.robot.actuator import Actuator
from hexaleg.robot.motor import as_torque_speed
from hexaleg.units import G

ENERGY_KEYS = ("net_work", "positive_work", "absolute_work", "joule", "electrical",
               "electrical_regen", "electrical_noregen")
"""Per-joint and total energies in :func:`metrics`, J."""
TORQUE_KEYS = ("peak_torque", "rms_torque", "mean_abs_torque")
"""Per-joint and total torque statistics in :func:`metrics`, N·m."""
NO_SAVING_KEYS = ("net_work",)
"""Keys :func:`savings` leaves out: the signed net work is ≈ 0 over a conservative periodic cycle,
so a fraction of it is rounding noise."""
IN_PLACE = 1e-9
"""m a cycle up to which a motion walks in place: no cost of transport (a stride of a few
float64 subnormals made ``E / (m g d)`` overflow to inf, and its saving inf − inf a NaN)."""
COT_KEYS = ("positive_work", "absolute_work", "electrical", "electrical_regen",
            "electrical_noregen", "electrical_bus")
"""Energies whose cost of transport :func:`metrics` reports."""


@typed
def cost_of_transport(energy: float, mass: float, distance: float, g: float = G) -> float:
    """Dimensionless cost of transport ``E / (m g d)`` (paper eq. 23, ``ε = E / (m_c g S)``).

    Args:
        energy: Energy spent over the distance, J.
        mass: Total robot mass, kg, > 0.
        distance: Distance travelled, m, > 0.
        g: Gravitational acceleration, m/s², > 0.

    Returns:
        The cost of transport (1).

    Raises:
        InvalidParameterError: energy not finite, or mass, distance or g not > 0.
    """
    return real("energy", energy) / (
        positive("mass", mass) * positive("g", g) * positive("distance", distance))


@typed
def epsilon(energy: float, inertia: float, angle: float) -> float:
    """The paper's single-joint energy consumption ratio, eq. 24: ``ε = ∫ M_k θ̇ dt / (I θ)``.

    Eq. 23 with the distance replaced by the joint angle travelled and the weight by the moment of
    inertia about the joint axis.

    Args:
        energy: Energy over the motion, J (eq. 20 uses the signed work ``∫ M_k θ̇ dt``; pass
            another entry of :func:`metrics` to rate e.g. positive work).
        inertia: Moment of inertia about the joint axis, kg·m², > 0.
        angle: Angle travelled, rad, > 0.

    Returns:
        ε in J/(kg·m²·rad) = 1/(rad·s²).

    Raises:
        InvalidParameterError: energy not finite, or inertia or angle not > 0.
    """
    return real("energy", energy) / (positive("inertia", inertia) * positive("angle", angle))


@typed
def metrics(tau: ArrayLike, qdot: ArrayLike, dt: float, motor: Actuator, *,
            mass: float | None = None, distance: float | None = None,
            joint_names: Sequence[str] | None = None, periodic: bool = True,
            inertia: ArrayLike | None = None) -> dict[str, Any]:
    """Energy and torque metrics of one cycle, per joint and in total.

    Integrals use the trapezoidal rule: on a periodic grid (the endpoint not stored) that is
    ``Σ x dt``; on a motion that stores both ends (``periodic=False``, e.g. stand → sphere) the
    two end samples weigh ``dt / 2``. Means (RMS, mean |τ|) are the integrals over the duration.

    Args:
        tau: Motor (joint) torques, shape (T, n) or (T,) for one joint, N·m.
        qdot: Joint speeds, the shape of ``tau``, rad/s.
        dt: Sample spacing, s, > 0.
        motor: The actuators (:class:`~hexaleg.robot.actuator.Actuator`): one model on every
            joint, or a :class:`~hexaleg.robot.motor_set.MotorSet` (one per joint class).
        mass: Robot mass, kg, > 0; with ``distance`` > 0 adds the cost of transport.
        distance: Distance travelled in the cycle, m, ≥ 0 (up to :data:`IN_PLACE`: in place,
            no cost of transport).
        joint_names: n names; default ``j0 … j{n-1}``.
        periodic: Whether the samples are one period without its endpoint (duration ``T dt``)
            or a motion with both ends stored (duration ``(T − 1) dt``, T ≥ 2).
        inertia: Moment of inertia about each joint's axis, shape (n,), kg·m², > 0; adds the
            paper's ε per joint.

    Returns:
        A dict with

        * ``joint_names`` (tuple of n str), ``motor`` (str), ``duration`` (T dt, s);
        * ``joint``: dict of (n,) arrays, ``total``: dict of floats, keyed by
          ``net_work`` ∫ τ q̇ (eq. 20, signed), ``positive_work`` ∫ max(0, τ q̇),
          ``absolute_work`` ∫ |τ q̇|, ``joule`` ∫ c τ², ``electrical_regen`` ∫ P_e,
          ``electrical_noregen`` ∫ max(0, P_e), ``electrical`` (one of the two, by
          each motor's ``regeneration``) — all J — and ``peak_torque`` max |τ|, ``rms_torque``
          √(mean τ²), ``mean_abs_torque`` mean |τ| — N·m (totals over all joints and samples);
          ``total`` also has ``electrical_bus`` ∫ max(0, Σ_j P_e,j), J: joints share a supply
          that takes nothing back;
        * ``cost_of_transport``: dict of floats E/(m g d) for the energies in :data:`COT_KEYS`
          (only with ``mass`` and ``distance`` > :data:`IN_PLACE`);
        * ``epsilon`` (only with ``inertia``): dict of (n,) arrays ``angle`` θ = ∫ |q̇| dt (rad,
          the angle travelled), ``inertia`` (kg·m²) and ``positive_work`` — the paper's eq. 24
          per joint, ε = E / (I θ) with E the positive work (as
          :func:`hexaleg.paper.metrics.energy_ratio`: eq. 20's signed work vanishes
          over a conservative cycle), 1/s²; 0 for a joint that does not move (it does no work
          either).

    Raises:
        InvalidParameterError: shapes differ or are not (T, n), NaN/inf values, ``dt`` not > 0,
            wrong number of joint names, ``mass`` not > 0 or ``distance`` < 0.
    """
    t, w = _columns(tau, qdot)
    dt = positive("dt", dt)
    n = t.shape[1]
    names = tuple(f"j{j}" for j in range(n)) if joint_names is None else tuple(joint_names)
    if len(names) != n:
        raise InvalidParameterError("joint_names", names, f"{n} names, one per column of tau")
    weight = quadrature_weights(t.shape[0], dt, periodic)
    joint, total = _cycle_integrals(t, w, weight, motor)
    result: dict[str, Any] = {
        "joint_names": names, "motor": motor.name, "duration": float(weight.sum()),
        "joint": {key: joint[key] for key in (*ENERGY_KEYS, *TORQUE_KEYS)}, "total": total,
    }
    if mass is not None:
        positive("mass", mass)
    if distance is not None and (real("distance", distance) < 0):
        raise InvalidParameterError("distance", distance, "≥ 0 (0 for a motion in place)")
    if mass is not None and distance is not None and distance > IN_PLACE:
        result["cost_of_transport"] = {
            key: cost_of_transport(total[key], mass, distance) for key in COT_KEYS}
    if inertia is not None:
        result["epsilon"] = _epsilon(inertia, w, weight, joint["positive_work"])
    return result


def _columns(tau: ArrayLike, qdot: ArrayLike) -> tuple[np.ndarray, np.ndarray]:
    """Torques and speeds as (T, n) arrays (a (T,) pair is one joint), checked finite and alike."""
    t, w = as_torque_speed(tau, qdot)
    if t.ndim == 1:
        t, w = t[:, None], w[:, None]
    if t.ndim != 2 or t.shape[0] == 0 or t.shape[1] == 0:
        raise InvalidParameterError("tau", f"array of shape {t.shape}",
                                    "shape (T, n) or (T,) with T, n ≥ 1")
    return t, w


def quadrature_weights(n_samples: int, dt: float, periodic: bool) -> np.ndarray:
    """Trapezoidal-rule weights (T,), s: ``dt`` on a periodic grid without its endpoint; the two
    end samples ``dt / 2`` on a motion with both ends stored."""
    weight = np.full(n_samples, dt)
    if not periodic:
        if n_samples < 2:
            raise InvalidParameterError("tau", f"{n_samples} sample",
                                        "T ≥ 2 samples for a motion with both ends stored")
        weight[[0, -1]] = dt / 2
    return weight


def _cycle_integrals(t: np.ndarray, w: np.ndarray, weight: np.ndarray,
                     motor: Actuator
                     ) -> tuple[dict[str, np.ndarray], dict[str, float]]:
    """The per-joint ``(n,)`` and total energies and torque statistics of :func:`metrics`, for
    torques ``t`` and speeds ``w`` (T, n) and quadrature weights ``weight`` (T,)."""

    def integral(x: np.ndarray) -> np.ndarray:
        return weight @ x

    duration = float(weight.sum())
    n = t.shape[1]
    p = t * w
    pe_regen = motor.electrical_power(t, w, regeneration=True)
    pe_noregen = np.maximum(pe_regen, 0.0)
    joint = {
        "net_work": integral(p),
        "positive_work": integral(np.maximum(p, 0.0)),
        "absolute_work": integral(np.abs(p)),
        "joule": integral(motor.joule_power(t)),
        "electrical_regen": integral(pe_regen),
        "electrical_noregen": integral(pe_noregen),
        "peak_torque": np.abs(t).max(0),
        "rms_torque": np.sqrt(integral(t**2) / duration),
        "mean_abs_torque": integral(np.abs(t)) / duration,
    }
    # Each joint's motor takes back power or not (a MotorSet: per joint).
    joint["electrical"] = np.where(motor.regeneration, joint["electrical_regen"],
                                   joint["electrical_noregen"])
    total = {key: float(joint[key].sum()) for key in ENERGY_KEYS}
    total["electrical_bus"] = float(integral(np.maximum(pe_regen.sum(1), 0.0)))
    total["peak_torque"] = float(np.abs(t).max())
    total["rms_torque"] = float(np.sqrt(integral(t**2).sum() / (duration * n)))
    total["mean_abs_torque"] = float(integral(np.abs(t)).sum() / (duration * n))
    return joint, total


def _epsilon(inertia: ArrayLike, w: np.ndarray, weight: np.ndarray,
             positive_work: np.ndarray) -> dict[str, np.ndarray]:
    """The paper's eq. 24 per joint, ε = E / (I θ), for :func:`metrics` (see there)."""
    n = w.shape[1]
    inert = np.asarray(inertia, dtype=float)
    if inert.shape != (n,) or not np.all(np.isfinite(inert)) or not np.all(inert > 0):
        raise InvalidParameterError("inertia", inertia, f"{n} finite numbers > 0 (kg·m²)")
    angle = weight @ np.abs(w)
    moved = angle > 0
    eps = np.zeros(n)
    eps[moved] = positive_work[moved] / (inert[moved] * angle[moved])
    return {"angle": angle, "inertia": inert, "positive_work": eps}


@overload
def saving(with_: float, without: float) -> float: ...
@overload
def saving(with_: ArrayLike, without: ArrayLike) -> np.ndarray: ...
def saving(with_: ArrayLike, without: ArrayLike) -> np.ndarray | float:
    """Fraction of a cost saved: ``(without − with) / |without|``, elementwise (broadcast).

    Positive means less energy (or torque) with the springs, 1 means all of it saved, negative
    means more. Where ``without`` is 0 the fraction has no finite value, and the rule is:

    * 0 where ``with`` is 0 too — nothing was spent either way, nothing was saved;
    * otherwise ±inf with the sign of ``without − with``: −inf when the springs make a joint (or
      the robot) pay for something that cost nothing without them — an unbounded relative loss,
      which ranks below every finite saving — and +inf for a saving against a zero reference
      (only possible for a signed quantity).

    Never NaN from a zero reference (a NaN compares false with everything and would silently drop
    out of rankings); a NaN input gives NaN.

    Args:
        with_: The cost with springs, any shape.
        without: The same cost without springs (the baseline), broadcastable with ``with_``.

    Returns:
        The fraction (1), a float for scalar inputs, else an array of the broadcast shape.
    """
    diff = np.asarray(without, dtype=float) - np.asarray(with_, dtype=float)
    den = np.abs(np.broadcast_to(np.asarray(without, dtype=float), diff.shape))
    out = np.where(diff == 0, 0.0, np.copysign(np.inf, diff))
    np.divide(diff, den, out=out, where=den > 0)
    out = np.where(np.isnan(diff), np.nan, out)
    return float(out) if out.ndim == 0 else out


@typed
def savings(metrics_with: Mapping[str, Any], metrics_without: Mapping[str, Any]
            ) -> dict[str, Any]:
    """Fraction of each metric saved by the springs against the same gait without them.

    Each entry is :func:`saving` ``= (without − with) / |without|``: positive means less energy
    (or torque) with the springs, 1 means all of it saved, negative means more. Where the
    reference is 0 the saving is 0 if both are 0 and ±inf otherwise (never NaN). The keys in
    :data:`NO_SAVING_KEYS` are left out.

    Args:
        metrics_with: :func:`metrics` of the gait with springs.
        metrics_without: :func:`metrics` of the same gait without springs (the baseline).

    Returns:
        ``{"joint": {key: (n,) array}, "total": {key: float}}`` for the keys of both, plus
        ``"cost_of_transport"`` when both have it.

    Raises:
        InvalidParameterError: the two results have different joints or keys.
    """
    if tuple(metrics_with["joint_names"]) != tuple(metrics_without["joint_names"]):
        raise InvalidParameterError("metrics_with joint_names", metrics_with["joint_names"],
                                    f"the joints of metrics_without, "
                                    f"{tuple(metrics_without['joint_names'])}")
    out: dict[str, Any] = {}
    for group in ("joint", "total", "cost_of_transport"):
        if group not in metrics_with or group not in metrics_without:
            continue
        a, b = metrics_with[group], metrics_without[group]
        if set(a) != set(b):
            raise InvalidParameterError(f"metrics_with[{group!r}] keys", sorted(a),
                                        f"the keys of metrics_without, {sorted(b)}")
        keys = [key for key in a if key not in NO_SAVING_KEYS]
        saved = saving(np.array([a[k] for k in keys], dtype=float),
                       np.array([b[k] for k in keys], dtype=float))  # one call: a sweep's hot path
        out[group] = (dict(zip(keys, saved, strict=True)) if group == "joint" else
                      {k: float(v) for k, v in zip(keys, saved, strict=True)})
    return out


def metric_unit(metric: str) -> str:
    """Unit of a metric of :func:`hexaleg.dynamics.energy.metrics`: ``"N·m"`` or ``"J"``."""
    return "N·m" if metric in TORQUE_KEYS else "J"
