"""Energy metrics over a motion cycle: work, Joule loss, electrical energy, torques, CoT, ε.

Integrals use the trapezoidal rule: on a periodic grid ``t[k] = k dt`` that excludes the
endpoint a cycle integral is ``x.sum(0) * dt`` (see :mod:`hexaleg.motion.trajectory`); a motion that
stores both ends (``periodic=False``) weighs the end samples ``dt / 2``. The electrical model is
:class:`hexaleg.robot.motor.Motor`; the paper's energy is the signed joint work of eq. 20, its
energy consumption ratio is eq. 23 (cost of transport) and eq. 24 (the single-joint variant,
:func:`epsilon`, and per joint in :func:`metrics`). ``docs/energy.md`` lists every key.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from hexaleg.errors import InvalidParameterError
from hexaleg.robot.motor import Motor, as_torque_speed
from hexaleg.units import G

ENERGY_KEYS = ("net_work", "positive_work", "absolute_work", "joule", "electrical",
               "electrical_regen", "electrical_noregen")
"""Per-joint and total energies in :func:`metrics`, J."""
TORQUE_KEYS = ("peak_torque", "rms_torque", "mean_abs_torque")
"""Per-joint and total torque statistics in :func:`metrics`, N·m."""
NO_SAVING_KEYS = ("net_work",)
"""Keys :func:`savings` leaves out: the signed net work is ≈ 0 over a conservative periodic cycle,
so a fraction of it is rounding noise."""
COT_KEYS = ("positive_work", "absolute_work", "electrical", "electrical_regen",
            "electrical_noregen", "electrical_bus")
"""Energies whose cost of transport :func:`metrics` reports."""


def _positive(name: str, value: Any) -> float:
    if (isinstance(value, bool) or not isinstance(value, (int, float, np.floating))
            or not math.isfinite(value) or value <= 0):
        raise InvalidParameterError(name, value, "a finite number > 0")
    return float(value)


def _finite(name: str, value: Any) -> float:
    if (isinstance(value, bool) or not isinstance(value, (int, float, np.floating))
            or not math.isfinite(value)):
        raise InvalidParameterError(name, value, "a finite number")
    return float(value)


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
    return _finite("energy", energy) / (
        _positive("mass", mass) * _positive("g", g) * _positive("distance", distance))


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
    return _finite("energy", energy) / (_positive("inertia", inertia) * _positive("angle", angle))


def metrics(tau: ArrayLike, qdot: ArrayLike, dt: float, motor: Motor, *,
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
        motor: The servo model of every joint.
        mass: Robot mass, kg, > 0; with ``distance`` > 0 adds the cost of transport.
        distance: Distance travelled in the cycle, m, ≥ 0 (0: in place, no cost of transport).
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
          ``motor.regeneration``) — all J — and ``peak_torque`` max |τ|, ``rms_torque``
          √(mean τ²), ``mean_abs_torque`` mean |τ| — N·m (totals over all joints and samples);
          ``total`` also has ``electrical_bus`` ∫ max(0, Σ_j P_e,j), J: joints share a supply
          that takes nothing back;
        * ``cost_of_transport``: dict of floats E/(m g d) for the energies in :data:`COT_KEYS`
          (only with ``mass`` and ``distance`` > 0);
        * ``epsilon`` (only with ``inertia``): dict of (n,) arrays ``angle`` θ = ∫ |q̇| dt (rad,
          the angle travelled), ``inertia`` (kg·m²) and ``positive_work`` — the paper's eq. 24
          per joint, ε = E / (I θ) with E the positive work (as
          :meth:`hexaleg.studies.paper.model.PaperJoint. epsilon`: eq. 20's signed work vanishes
          over a conservative cycle), 1/s²; 0 for a joint that does not move (it does no work
          either).

    Raises:
        InvalidParameterError: shapes differ or are not (T, n), NaN/inf values, ``dt`` not > 0,
            wrong number of joint names, ``mass`` not > 0 or ``distance`` < 0.
    """
    t, w = as_torque_speed(tau, qdot)
    if t.ndim == 1:
        t, w = t[:, None], w[:, None]
    if t.ndim != 2 or t.shape[0] == 0 or t.shape[1] == 0:
        raise InvalidParameterError("tau", f"array of shape {t.shape}",
                                    "shape (T, n) or (T,) with T, n ≥ 1")
    dt = _positive("dt", dt)
    n = t.shape[1]
    names = tuple(f"j{j}" for j in range(n)) if joint_names is None else tuple(joint_names)
    if len(names) != n:
        raise InvalidParameterError("joint_names", names, f"{n} names, one per column of tau")

    weight = np.full(t.shape[0], dt)  # quadrature weights (T,), s
    if not periodic:
        if t.shape[0] < 2:
            raise InvalidParameterError("tau", f"{t.shape[0]} sample",
                                        "T ≥ 2 samples for a motion with both ends stored")
        weight[[0, -1]] = dt / 2

    def integral(x: np.ndarray) -> np.ndarray:
        return weight @ x

    duration = float(weight.sum())
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
    joint["electrical"] = joint["electrical_regen" if motor.regeneration else "electrical_noregen"]
    total = {key: float(joint[key].sum()) for key in ENERGY_KEYS}
    total["electrical_bus"] = float(integral(np.maximum(pe_regen.sum(1), 0.0)))
    total["peak_torque"] = float(np.abs(t).max())
    total["rms_torque"] = float(np.sqrt(integral(t**2).sum() / (duration * n)))
    total["mean_abs_torque"] = float(integral(np.abs(t)).sum() / (duration * n))

    result: dict[str, Any] = {
        "joint_names": names, "motor": motor.name, "duration": duration,
        "joint": {key: joint[key] for key in (*ENERGY_KEYS, *TORQUE_KEYS)}, "total": total,
    }
    if mass is not None:
        _positive("mass", mass)
    if distance is not None and (_finite("distance", distance) < 0):
        raise InvalidParameterError("distance", distance, "≥ 0 (0 for a motion in place)")
    if mass is not None and distance is not None and distance > 0:
        result["cost_of_transport"] = {
            key: cost_of_transport(total[key], mass, distance) for key in COT_KEYS}
    if inertia is not None:
        inert = np.asarray(inertia, dtype=float)
        if inert.shape != (n,) or not np.all(np.isfinite(inert)) or not np.all(inert > 0):
            raise InvalidParameterError("inertia", inertia, f"{n} finite numbers > 0 (kg·m²)")
        angle = integral(np.abs(w))
        moved = angle > 0
        eps = np.zeros(n)
        eps[moved] = joint["positive_work"][moved] / (inert[moved] * angle[moved])
        result["epsilon"] = {"angle": angle, "inertia": inert, "positive_work": eps}
    return result


def _fraction_saved(with_: np.ndarray, without: np.ndarray) -> np.ndarray:
    """``(without − with) / |without|``; 0 where both are 0, ±inf where only ``without`` is 0."""
    diff = without - with_
    den = np.abs(without)
    out = np.where(diff == 0, 0.0, np.copysign(np.inf, diff))
    np.divide(diff, den, out=out, where=den > 0)
    return out


def savings(metrics_with: Mapping[str, Any], metrics_without: Mapping[str, Any]
            ) -> dict[str, Any]:
    """Fraction of each metric saved by the springs against the same gait without them.

    ``saving = (without − with) / |without|``: positive means less energy (or torque) with the
    springs, 1 means all of it saved, negative means more. Where the reference is 0 the saving is
    0 if both are 0 and ±inf otherwise (never NaN). The keys in :data:`NO_SAVING_KEYS` are left
    out.

    Args:
        metrics_with: :func:`metrics` of the gait with springs.
        metrics_without: :func:`metrics` of the same gait without springs.

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
        saved = {key: _fraction_saved(np.asarray(a[key], float), np.asarray(b[key], float))
                 for key in a if key not in NO_SAVING_KEYS}
        out[group] = saved if group == "joint" else {k: float(v) for k, v in saved.items()}
    return out
