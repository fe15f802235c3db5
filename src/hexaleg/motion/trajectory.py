"""``Motion``: sampled whole-robot trajectories — the input of the dynamics and energy analysis.

A motion is one period of a periodic (or any) trajectory sampled at ``T`` instants
``t[k] = k · dt``; for a periodic motion the endpoint ``t = period`` is *not* stored (it equals
sample 0 up to a base displacement), so a cycle integral of a periodic signal ``x`` is exactly
``x.sum(axis=0) * dt`` (the trapezoidal rule on a periodic grid).
"""

from __future__ import annotations

import math
from dataclasses import dataclass, field
from typing import Any

import numpy as np

from hexaleg.checks import named_arguments, real
from hexaleg.errors import InvalidParameterError

PERIOD_TOLERANCE = 1e-6
"""Relative tolerance of ``T · dt == period`` for a periodic :class:`Motion`."""
SEMI_IMPLICIT = "semi-implicit Euler"
"""``info["integrator"]`` of a motion whose samples are the knots of a semi-implicit Euler
integration, ``v_{k+1} = v_k + a_k dt``, ``q_{k+1} = q_k ⊕ v_{k+1} dt`` (Crocoddyl's
``IntegratedActionModelEuler``; an optimal motion, :mod:`hexaleg.optimal.solve`): the sample
after its last is that step, exactly."""


@named_arguments
@dataclass(frozen=True, eq=False)
class Motion:
    """Sampled configuration, velocity and acceleration of the floating base and all joints.

    Arrays are time-major and follow Pinocchio's conventions: the base velocity and acceleration
    are expressed in the base (LOCAL) frame, ``a`` is the time derivative of ``v``.

    Attributes:
        t: Sample times, shape (T,), s, uniformly spaced by ``dt``.
        q: Configurations, shape (T, nq) (base position, base quaternion xyzw, joint angles rad).
        v: Generalised velocities, shape (T, nv).
        a: Generalised accelerations, shape (T, nv).
        stance: Which feet are on the ground, shape (T, n_legs), bool, legs in the robot's order
            (LF LM LH RF RM RH for the hexapod).
        feet: World foot positions, shape (T, n_legs, 3), m.
        period: Duration of one cycle, s; for a periodic motion ``T * dt == period``.
        distance: Distance the body travels per cycle, m (0 for motions in place).
        periodic: Whether the motion repeats with ``period`` (up to a base displacement).
        fixed_base: Whether the base is held by a fixture (no base equations; e.g. the paper's
            single-joint case) rather than carried by the feet.
        supported: Samples at which the base rests on a support that supplies whatever wrench
            the base equations need — the body lying on the ground while the legs fold — shape
            (T,), bool. No foot may be in stance at such a sample (the support carries the
            robot; feet touching it too would make the load sharing indeterminate). ``None``
            (the default) means every sample when ``fixed_base`` and none otherwise.
        info: Free-form description of how the motion was made (e.g. gait parameters;
            ``integrator``: :data:`SEMI_IMPLICIT` for the knots of such an integration).
        normal: The ground's unit normal in the world frame, shape (3,): the axis of the feet's
            friction cones (:mod:`hexaleg.dynamics.contact`). None (the default): level ground,
            ``[0, 0, 1]``.
    """

    t: np.ndarray
    q: np.ndarray
    v: np.ndarray
    a: np.ndarray
    stance: np.ndarray
    feet: np.ndarray
    period: float
    distance: float = 0.0
    periodic: bool = True
    fixed_base: bool = False
    info: dict[str, Any] = field(default_factory=dict)
    supported: np.ndarray = None  # type: ignore[assignment]  # None → set in __post_init__
    normal: np.ndarray | None = None

    def __post_init__(self) -> None:
        n = self.t.shape[0]
        for name in ("q", "v", "a", "stance", "feet"):
            arr = getattr(self, name)
            if arr.shape[0] != n:
                raise InvalidParameterError(f"Motion.{name}", f"array of shape {arr.shape}",
                                            f"first dimension T = {n} (the length of t)")
        for name in ("t", "q", "v", "a", "feet"):
            arr = getattr(self, name)
            if not np.all(np.isfinite(arr)):
                k = int(np.argwhere(~np.isfinite(arr.reshape(n, -1)))[0, 0])
                raise InvalidParameterError(f"Motion.{name}", f"NaN/inf at sample {k} "
                                            f"(t = {self.t[k] if k < len(self.t) else '?'})",
                                            "finite values")
        if np.any(np.diff(self.t) <= 0):
            raise InvalidParameterError("Motion.t", "not increasing", "sample times that "
                                        "increase from one sample to the next")
        real("Motion.period", self.period, low=0.0, low_open=True,
             allowed="a finite duration > 0 (s)")
        if self.periodic and n > 1 and not math.isclose(n * self.dt, self.period,
                                                         rel_tol=PERIOD_TOLERANCE):
            raise InvalidParameterError("Motion.period", self.period,
                                        f"T × dt = {n * self.dt!r} s for a periodic motion of "
                                        f"{n} samples {self.dt!r} s apart (or periodic=False)")
        real("Motion.distance", self.distance, low=0.0, allowed="a finite distance ≥ 0 (m)")
        stance = np.asarray(self.stance)
        if stance.dtype != bool and not np.all((stance == 0) | (stance == 1)):
            values = sorted(set(np.unique(stance)[:4].tolist()))
            raise InvalidParameterError("Motion.stance", f"values {values}",
                                        "booleans, or 0 (swing) and 1 (stance)")
        if self.supported is None:
            object.__setattr__(self, "supported", np.full(n, bool(self.fixed_base)))
        supported = np.asarray(self.supported)
        if supported.shape != (n,) or supported.dtype != bool:
            raise InvalidParameterError("Motion.supported", f"array of shape {supported.shape}, "
                                        f"dtype {supported.dtype}",
                                        f"a bool array of shape ({n},)")
        if self.fixed_base and not supported.all():
            raise InvalidParameterError("Motion.supported", "False at some samples of a "
                                        "fixed-base motion", "all True (a fixture holds the base "
                                        "throughout) or fixed_base=False")
        if self.normal is not None:
            normal = np.asarray(self.normal, dtype=float)
            if normal.shape != (3,) or not np.all(np.isfinite(normal)) \
                    or abs(np.linalg.norm(normal) - 1.0) > 1e-9 or normal[2] <= 0.0:
                raise InvalidParameterError("Motion.normal", self.normal, "None or a unit "
                                            "3-vector pointing up (z > 0): the ground's normal")
            object.__setattr__(self, "normal", normal)
        both = supported & np.asarray(self.stance).any(axis=1)
        if both.any():
            k = int(np.flatnonzero(both)[0])
            raise InvalidParameterError("Motion.supported", f"True at sample {k} "
                                        f"(t = {self.t[k]:.4f} s) where feet are in stance",
                                        "a supported base with every foot in the air")

    @property
    def n_samples(self) -> int:
        """Number of samples T."""
        return int(self.t.shape[0])

    @property
    def dt(self) -> float:
        """Sample spacing, s."""
        return float(self.t[1] - self.t[0]) if self.n_samples > 1 else float(self.period)
