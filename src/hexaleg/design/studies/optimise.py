"""The optimal dead-zone spring of one joint group on one gait: a grid start, then Nelder–Mead.

The paper picks k_E by minimising the energy of eq. 21 for one joint; here the stiffness k, the
symmetric contact angle θ_k of the dead zone (eq. 8) and optionally the neutral offset are chosen
together for a group of joints, minimising any metric of :data:`hexaleg.design.evaluator.METRICS`
(by default the electrical energy per cycle, the paper's energy criterion eq. 20–24 with a motor
model) through an :class:`~hexaleg.design.evaluator.Evaluator`.
"""

from __future__ import annotations

import itertools
import math
from collections.abc import Callable, Sequence
from dataclasses import dataclass

import numpy as np

from hexaleg.checks import is_integer, real, typed
from hexaleg.design.evaluator import DEFAULT_METRIC, METRICS, Evaluator
from hexaleg.dynamics.energy import saving
from hexaleg.errors import InvalidParameterError, UnknownNameError


@dataclass(frozen=True)
class Optimum:
    """The optimal (k, θ_k[, offset]) of one spring group for one metric on one gait.

    Attributes:
        group: Group name. joints: Its joints. metric: The metric minimised.
        k: Stiffness, N·m/rad. theta_k: Symmetric contact angle, rad. offset: Neutral offset
            from the centre of each joint's range of motion, rad (fixed or optimised).
        value: The metric at the optimum (J or N·m). baseline: The metric without springs.
        saving: ``(baseline − value) / |baseline|``.
        grid_value: The best value of the starting grid. evaluations: Designs evaluated.
    """

    group: str
    joints: tuple[str, ...]
    metric: str
    k: float
    theta_k: float
    offset: float
    value: float
    baseline: float
    saving: float
    grid_value: float
    evaluations: int

    def design(self) -> dict[str, float]:
        """The group's design parameters (``k``, ``theta_k``, ``offset``)."""
        return {"k": self.k, "theta_k": self.theta_k, "offset": self.offset}


@dataclass(frozen=True)
class _Box:
    """The search variables (log k, θ_k[, offset]) scaled to the unit box.

    Attributes:
        bounds: (low, high) of k (N·m/rad), θ_k (rad) and, when optimised, the offset (rad).
        offset: The neutral offset when it is held fixed, rad.
    """

    bounds: Sequence[Sequence[float]]
    offset: float

    @property
    def dims(self) -> int:
        """Number of search variables: 2, or 3 with the offset."""
        return len(self.bounds)

    def design(self, x: np.ndarray) -> dict[str, float]:
        """The design (``k``, ``theta_k``, ``offset``) at scaled point ``x``, clipped to the box."""
        (lo_k, hi_k), (lo_t, hi_t) = self.bounds[0], self.bounds[1]
        x = np.clip(x, 0.0, 1.0)
        design = {"k": float(lo_k * (hi_k / lo_k) ** x[0]),
                  "theta_k": float(lo_t + (hi_t - lo_t) * x[1]), "offset": self.offset}
        if self.dims == 3:
            lo_o, hi_o = self.bounds[2]
            design["offset"] = float(lo_o + (hi_o - lo_o) * x[2])
        return design

    def scaled(self, values: Sequence[float]) -> np.ndarray:
        """(k, θ_k[, offset]) → the scaled point, clipped to the box."""
        (lo_k, hi_k), (lo_t, hi_t) = self.bounds[0], self.bounds[1]
        x = [math.log(values[0] / lo_k) / math.log(hi_k / lo_k), (values[1] - lo_t) / (hi_t - lo_t)]
        if self.dims == 3:
            x.append((values[2] - self.bounds[2][0]) / (self.bounds[2][1] - self.bounds[2][0]))
        return np.clip(np.array(x), 0.0, 1.0)


def _check_bounds(bounds: Sequence[Sequence[float]]) -> None:
    """Each (low, high): finite, low < high, and low > 0 for k and θ_k.

    Raises:
        InvalidParameterError: bad bounds (named ``k_bounds``, ``theta_bounds``,
            ``offset_bounds``).
    """
    for name, (lo, hi) in zip(("k_bounds", "theta_bounds", "offset_bounds"), bounds,
                              strict=False):
        lo, hi = real(name, lo), real(name, hi)
        if not lo < hi or (name != "offset_bounds" and lo <= 0):
            raise InvalidParameterError(name, (lo, hi), "low < high" + (
                "" if name == "offset_bounds" else ", low > 0"))


def _starts(box: _Box, grid: tuple[int, ...], start: Sequence[float] | None
            ) -> tuple[list[np.ndarray], np.ndarray]:
    """Candidate starting points (scaled) and the initial simplex step per variable.

    Raises:
        InvalidParameterError: a grid without ``dims`` integers ≥ 2, or a bad ``start``.
    """
    dims = box.dims
    if start is None:
        n = tuple(grid[:dims])
        if len(n) != dims or any(not is_integer(m) or m < 2 for m in n):
            raise InvalidParameterError("grid", grid, f"{dims} integers ≥ 2")
        cands = [np.array(x) for x in itertools.product(*(np.linspace(0, 1, m) for m in n))]
        return cands, 1.0 / (np.array(n) - 1)
    if len(start) != dims or not all(v > 0 for v in start[:2]):
        raise InvalidParameterError("start", start, f"{dims} values, k > 0 and θ_k > 0")
    return [box.scaled(start)], np.full(dims, 0.1)


def _nelder_mead(f: Callable[[np.ndarray], float], x0: np.ndarray, step: np.ndarray,
                 tol: float) -> tuple[np.ndarray, float]:
    """Bounded Nelder–Mead on the unit box from ``x0`` (:func:`scipy.optimize.minimize`)."""
    from scipy.optimize import minimize

    dims = len(x0)
    # initial simplex: one grid step along each variable, pointing into the box
    simplex = [x0] + [x0 + np.eye(dims)[d] * step[d] * (-1 if x0[d] > 0.5 else 1)
                      for d in range(dims)]
    res = minimize(f, x0, method="Nelder-Mead", bounds=[(0.0, 1.0)] * dims,
                   options={"initial_simplex": np.array(simplex), "xatol": tol, "fatol": 1e-12,
                            "maxiter": 200 * dims})
    return res.x, float(res.fun)


@typed
def optimise(ev: Evaluator, group: str, joints: Sequence[str], metric: str = DEFAULT_METRIC, *,
             k_bounds: tuple[float, float] = (1e-3, 3.0),
             theta_bounds: tuple[float, float] | None = None, offset: float = 0.0,
             offset_bounds: tuple[float, float] | None = None,
             grid: tuple[int, ...] = (12, 6, 5), start: Sequence[float] | None = None,
             tol: float = 1e-4) -> Optimum:
    """The (k, θ_k) — and optionally the neutral offset — minimising ``metric`` for one group.

    A symmetric dead-zone spring with the same design goes on every joint of the group. The
    objective is piecewise smooth in θ_k and the offset (samples enter and leave the engaged
    region) and k spans decades, so the search runs on (log k, θ_k[, offset]) scaled to the unit
    box: a grid start (or ``start``), then bounded Nelder–Mead (:func:`scipy.optimize.minimize`,
    derivative-free, tolerant of the kinks; scipy ≥ 1.7 supports bounds for it). Designs without
    admissible forces count as +inf.

    Args:
        ev: Evaluator of the gait.
        group: Group name (for the result). joints: The joints sprung with the same design.
        metric: A key of :data:`~hexaleg.design.evaluator.METRICS`.
        k_bounds: Stiffness bounds, N·m/rad, 0 < low < high.
        theta_bounds: θ_k bounds, rad, 0 < low < high; default (0.01, 0.95) × the largest half
            range of motion of ``joints`` in the gait.
        offset: Neutral offset from each joint's centre of motion, rad, when it is held fixed.
        offset_bounds: (low, high) rad to optimise the offset too (a preloaded spring that
            carries part of a steady load such as gravity); None holds it at ``offset``.
        grid: Starting grid points per variable (k log-spaced, θ_k and offset linear), each ≥ 2;
            the third entry is used only with ``offset_bounds``; ignored with ``start``.
        start: (k, θ_k[, offset]) to start from instead of the grid.
        tol: Convergence tolerance on the scaled variables.

    Returns:
        The optimum (never worse than the start).

    Raises:
        UnknownNameError: unknown metric. InvalidParameterError: bad bounds, grid or start.
    """
    if metric not in METRICS:
        raise UnknownNameError("metric", metric, METRICS)
    if theta_bounds is None:
        half = max(ev.half_range[j] for j in joints)
        theta_bounds = (0.01 * half, 0.95 * half)
    bounds = [k_bounds, theta_bounds] + ([offset_bounds] if offset_bounds is not None else [])
    _check_bounds(bounds)
    box = _Box(bounds, offset)
    groups = {group: tuple(joints)}
    count0 = ev.evaluations

    def f(x: np.ndarray) -> float:
        return ev.value(groups, {group: box.design(x)}, metric)

    cands, step = _starts(box, grid, start)
    values = [f(x) for x in cands]
    x0, f0 = cands[int(np.argmin(values))], min(values)
    x, value = _nelder_mead(f, x0, step, tol)
    if not value <= f0:
        x, value = x0, f0
    design = box.design(x)
    base = float(ev.baseline["total"][metric])
    return Optimum(group=group, joints=tuple(joints), metric=metric, k=design["k"],
                   theta_k=design["theta_k"], offset=design["offset"], value=value,
                   baseline=base, saving=saving(value, base),
                   grid_value=f0, evaluations=ev.evaluations - count0)
