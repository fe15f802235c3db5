"""Statically stable gaits: the body shift that keeps the centre of mass inside the support
polygon with a margin (crawls, slow waves; ``GaitParams.balance``, ``min_static_margin``).

A gait on three or more feet is statically stable while the centre of mass's ground projection
stays inside the stance feet's support polygon (McGhee & Frank, "On the stability properties of
quadruped creeping gaits", Math. Biosci. 3, 1968); its static margin is that projection's
distance from the nearest edge (:mod:`hexaleg.motion.support`). A crawl moved with a constant
twist carries the CoM across the diagonal where one support triangle hands over to the next,
so its margin is ≤ 0 there. The body is therefore shifted by a periodic displacement ``s(t)``
in the base frame's horizontal plane (parallel to the ground on a slope), a trigonometric
polynomial of :data:`HARMONICS` harmonics per axis::

    s(t) = a₀ + Σₙ aₙ cos nωt + bₙ sin nωt        (ω = 2π / period, for x and y)

— smooth, periodic, with exact derivatives (two :class:`hexaleg.motion.balance.Sway` along the
base's x and y). Its coefficients θ minimise the mean squared body acceleration
``(1/T)∫|s̈|² = ½ Σₙ (nω)⁴ (aₙ² + bₙ²)`` (plus :data:`REGULARISATION` ω⁴ times the mean squared
shift, so the solution is unique) subject to, at every sample k and every edge of every support
polygon it must be in (its own and, across a change of stance, the neighbour's:
:meth:`hexaleg.motion.support.SupportCycle.polygons`; inward unit normal ν, offset b)::

    ν · (c_k + ρ P_k (s_k − s_k⁰)) ≥ m + b                               (the CoM)
    ν · (z_k + ρ P_k ((s_k − s_k⁰) − (h/g)(s̈_k − s̈_k⁰))) ≥ m_z + b       (the ZMP)
    |s_x(t_k)|, |s_y(t_k)| ≤ s_max

with c_k the CoM's ground projection of the gait as last sampled (shift s⁰), P_k the horizontal
rows of the base orientation (base-frame shift → world), ρ the fraction of the shift the CoM
follows (the legs reach back to the feet), m the required margin and s_max (:data:`MAX_SHIFT`
of the nearest foothold's distance) what the legs can follow. The second row keeps the
zero-moment point of the linear inverted pendulum, ``z = c − (h/g) c̈`` (Kajita et al., ICRA
2003; h the CoM's mean height above the stance feet), :data:`ZMP_FRACTION` m inside the same
polygons: a shift fast enough to push the ZMP out would leave the force program without forces,
however well the CoM itself stays inside. This convex quadratic program (Boyd & Vandenberghe,
*Convex Optimization*, 2004, §4.4) is solved with Clarabel; the gait is sampled again with the
shift (leg IK), ρ is fitted to how far the CoM really moved, and the loop stops when the
sampled CoM margin is ≥ m — typically in two or three rounds. When the program is infeasible,
the linear program that maximises m over the same shifts gives the largest margin the gait
allows, and :class:`hexaleg.errors.StaticMarginError` says so before any force program runs.
"""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any

import numpy as np
import pinocchio as pin

from hexaleg.errors import StaticMarginError
from hexaleg.motion.balance import Sway
from hexaleg.motion.params import MARGIN_FRACTION, GaitParams
from hexaleg.motion.support import Edges, SupportCycle, edge_margin
from hexaleg.motion.trajectory import Motion
from hexaleg.robot.model import Robot

HARMONICS = 10
"""Harmonics per axis of the body shift (fewer when the cycle has fewer than 2·HARMONICS + 2
samples)."""
REGULARISATION = 1e-2
"""Weight of the mean squared shift against the mean squared acceleration, in units of ω⁴."""
ZMP_FRACTION = 1.0
"""The zero-moment point is kept this fraction of the required margin inside the polygons."""
MAX_ROUNDS = 12
"""Shift-and-resample rounds before the body shift gives up."""
OVERSHOOT = 1e-3
"""The program asks for (1 + OVERSHOOT) m (plus 1 µm) so that the resampled gait keeps m."""
MAX_SHIFT = 0.5
"""Largest shift along each base axis, as a fraction of the nearest nominal foothold's
horizontal distance from the base."""
AXES = (np.array([1.0, 0.0, 0.0]), np.array([0.0, 1.0, 0.0]))
"""The shift's axes, base frame."""


def required_margin(robot: Robot, gait: GaitParams, nominal: np.ndarray) -> float:
    """The static margin a shifted gait keeps, m: ``gait.min_static_margin``, or
    :data:`hexaleg.motion.params.MARGIN_FRACTION` of the nearest nominal foothold's horizontal
    distance from the base.

    Args:
        robot: The robot.
        gait: The gait.
        nominal: Nominal footholds, base frame, shape (n_legs, 3), m.
    """
    if gait.min_static_margin is not None:
        return gait.min_static_margin
    return MARGIN_FRACTION * float(np.linalg.norm(nominal[:, :2], axis=1).min())


def _basis(t: np.ndarray, period: float, harmonics: int
           ) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """Φ (T, 2H+1) = [1, cos nωt, sin nωt], its second time derivative Φ̈ and the weights
    ``(nω)⁴ / 2`` plus the regulariser (2H+1,)."""
    omega = 2.0 * math.pi / period
    n = np.arange(1, harmonics + 1)
    phase = np.outer(t, n * omega)
    basis = np.hstack([np.ones((len(t), 1)), np.cos(phase), np.sin(phase)])
    second = basis * -np.concatenate([[0.0], (n * omega) ** 2, (n * omega) ** 2])
    reg = REGULARISATION * omega**4
    weights = np.concatenate([[reg], np.tile(0.5 * (n * omega) ** 4 + 0.5 * reg, 2)])
    return basis, second, weights


class _Program:
    """The data of the shift's program at one round: the linearisation point and its maps."""

    def __init__(self, robot: Robot, motion: Motion, grid: SupportCycle, basis: np.ndarray,
                 second: np.ndarray) -> None:
        data = robot.model.createData()
        com, acc = np.empty((motion.n_samples, 3)), np.empty((motion.n_samples, 3))
        for k in range(motion.n_samples):
            pin.centerOfMass(robot.model, data, motion.q[k], motion.v[k], motion.a[k])
            com[k], acc[k] = data.com[0], data.acom[0]
        feet_z = np.array([f[s, 2].mean() for f, s in zip(motion.feet, motion.stance,
                                                           strict=True)])
        gravity = float(np.linalg.norm(robot.model.gravity.linear))
        self.lever = float(np.mean(com[:, 2] - feet_z)) / gravity  # h / g, s²
        self.com = grid.points(com)[:, :2]
        self.zmp = self.com - self.lever * grid.points(acc, vectors=True)[:, :2]
        rot = np.array([pin.Quaternion(q[3:7]).toRotationMatrix() for q in motion.q])
        rot = np.concatenate([rot, grid.cycle[None, :3, :3] @ rot[:1]])
        self.proj = rot[:, :2, :2]  # base-frame (x, y) shift → world (x, y)
        width = basis.shape[1]
        self.maps = (_blocks(basis, width), _blocks(basis - self.lever * second, width))


def _blocks(basis: np.ndarray, width: int) -> np.ndarray:
    """(N+1, 2, 2·width): θ (x's then y's) → the two components at each sample."""
    out = np.zeros((len(basis), 2, 2 * width))
    out[:, 0, :width], out[:, 1, width:] = basis, basis
    return out


def _constraints(edges: Edges, program: _Program, theta: np.ndarray, rho: float,
                 margin: float, limit: float) -> tuple[np.ndarray, np.ndarray, int]:
    """Rows G and right-hand sides h of ``G θ' ≥ h`` (module docstring): the CoM and ZMP rows of
    every sample and edge (a sample without a polygon: the impossible ``0 ≥ 1``), then the
    bounds; and the number of margin rows (the first ones)."""
    rows, rhs = [], []
    for points, m, fraction in ((program.com, program.maps[0], 1.0),
                                (program.zmp, program.maps[1], ZMP_FRACTION)):
        for k, nu, b in edges:
            if not len(b):
                rows.append(np.zeros((1, len(theta))))
                rhs.append(np.ones(1))
                continue
            gain = rho * nu @ program.proj[k] @ m[k]  # (E, 2·width)
            rows.append(gain)
            rhs.append(fraction * margin + b - nu @ points[k] + gain @ theta)
    bounds = program.maps[0].reshape(-1, len(theta))
    n_margin = sum(len(r) for r in rows)
    return (np.vstack([*rows, -bounds, bounds]),
            np.concatenate([*rhs, np.full(2 * len(bounds), -limit)]), n_margin)


def static_shift(robot: Robot, gait: GaitParams, motion: Motion, target: float,
                 sample: Callable[[tuple[Sway, ...] | None, dict[str, Any]], Motion]
                 ) -> tuple[Motion, tuple[Sway, ...], dict[str, Any]]:
    """The body shift that keeps the static margin ≥ ``target`` at every sample and across
    every switch (module docstring; :func:`hexaleg.motion.support.switch_margin`).

    Args:
        robot: The robot.
        gait: The gait (period, samples, for the messages).
        motion: The gait without a shift, on its cycle grid (every sample on ≥ 3 feet), with
            ``info["cycle"]``, the rigid motion of one cycle (4 × 4, world).
        target: The margin to keep, m (≥ 0).
        sample: The gait on the cycle grid with a shift (two sways, base x and y) and the
            ``info["balance"]`` report to store.

    Returns:
        The shifted motion, the shift and the report (``mode`` ``"shift"``, ``target`` m,
        ``margin`` m (:func:`~hexaleg.motion.support.switch_margin`), ``amplitude`` m (largest
        |s|), ``iterations``, ``harmonics``).

    Raises:
        StaticMarginError: no shift keeps ``target`` (names the largest margin possible), or
            the rounds do not reach it.
    """
    harmonics = max(1, min(HARMONICS, (motion.n_samples - 2) // 2))
    basis, second, weights = _basis(motion.t, gait.period, harmonics)
    basis, second = np.vstack([basis, basis[:1]]), np.vstack([second, second[:1]])
    grid = SupportCycle(motion)
    edges = grid.polygons()
    limit = MAX_SHIFT * float(np.linalg.norm(motion.feet[0, :, :2] - motion.q[0, None, :2],
                                             axis=1).min())
    theta, rho = np.zeros(2 * basis.shape[1]), 1.0
    program = _Program(robot, motion, grid, basis, second)
    margins: list[float] = []
    for rounds in range(1, MAX_ROUNDS + 1):
        rows, rhs, _ = _constraints(edges, program, theta, rho,
                                    target * (1 + OVERSHOOT) + 1e-6, limit)
        solution = _solve(np.tile(weights, 2), rows, rhs)
        if solution is None:
            largest = _largest_margin(edges, program, theta, rho, limit)
            raise StaticMarginError(
                "min_static_margin", target,
                f"≤ {largest:.4g} m, the largest static margin a smooth body shift of this gait "
                f"keeps across its switches with its zero-moment point {ZMP_FRACTION:g} of that "
                f"inside ({motion.n_samples} samples, {harmonics} harmonics, shifts up to "
                f"±{limit:.3g} m): lower min_static_margin, raise duty_factor (longer four-foot "
                "phases to shift the body in), lengthen the period, shorten stride_length or "
                f"widen foot_radius{_slope_hint(gait)}", largest=largest)
        planned = basis @ solution.reshape(2, -1).T  # (N+1, 2)
        sways = tuple(Sway.from_samples(e, gait.period, planned[:-1, i])
                      for i, e in enumerate(AXES))
        report: dict[str, Any] = {"mode": "shift", "target": target, "iterations": rounds,
                                  "harmonics": harmonics,
                                  "amplitude": float(np.linalg.norm(planned, axis=1).max())}
        moved = sample(sways, report)
        new = _Program(robot, moved, grid, basis, second)
        margins.append(edge_margin(edges, new.com))
        report["margin"] = margins[-1]
        step = np.einsum("tij,tj->ti", program.proj, planned - basis @ theta.reshape(2, -1).T)
        rho = _fit_rho(new.com - program.com, step, rho)
        theta, program = solution, new
        if margins[-1] >= target:
            return moved, sways, report
    raise StaticMarginError(
        "min_static_margin", target, f"a margin the body shift reaches: after {MAX_ROUNDS} "
        f"rounds the gait keeps {margins[-1]:.4g} m; lower min_static_margin or raise "
        f"duty_factor{_slope_hint(gait)}", largest=margins[-1])


def _slope_hint(gait: GaitParams) -> str:
    """The ground's part in a margin the shift cannot keep: on a slope the body's weight
    leans downhill over the support polygon (named, with its angle), or ''."""
    tilted = {k: float(getattr(gait, k)) for k in ("slope", "cross_slope")
              if getattr(gait, k, 0.0)}
    if not tilted:
        return ""
    angles = ", ".join(f"{k} = {v:.4g} rad ({np.degrees(v):.3g}°)" for k, v in tilted.items())
    return (f"; the ground is inclined ({angles}): the weight leans downhill over the feet, so "
            "a gentler slope keeps a wider margin (angles are in radians)")


def _solve(weights: np.ndarray, rows: np.ndarray, rhs: np.ndarray) -> np.ndarray | None:
    """argmin θᵀ diag(w) θ subject to rows θ ≥ rhs (Clarabel), or None if infeasible."""
    import clarabel
    import scipy.sparse as sp

    settings = clarabel.DefaultSettings()
    settings.verbose = False
    solver = clarabel.DefaultSolver(sp.csc_matrix(np.diag(2 * weights)), np.zeros(len(weights)),
                                    sp.csc_matrix(-rows), -rhs,
                                    [clarabel.NonnegativeConeT(len(rhs))], settings)
    solution = solver.solve()
    if str(solution.status) not in ("Solved", "AlmostSolved"):
        return None
    return np.asarray(solution.x)


def _largest_margin(edges: Edges, program: _Program, theta: np.ndarray, rho: float,
                    limit: float) -> float:
    """The largest m for which the constraints hold: a linear program in (θ, m); −inf when
    some sample has no support polygon or Clarabel finds no solution (no margin is reachable
    then either — the caller's error says so rather than quoting a failed solve's iterate)."""
    import clarabel
    import scipy.sparse as sp

    if any(not len(b) for _, _, b in edges):
        return -math.inf
    rows, rhs, n_margin = _constraints(edges, program, theta, rho, 0.0, limit)
    n = rows.shape[1]
    a = np.hstack([-rows, np.zeros((len(rhs), 1))])  # −G θ + f m ≤ −h on the margin rows
    a[:n_margin // 2, -1], a[n_margin // 2:n_margin, -1] = 1.0, ZMP_FRACTION
    settings = clarabel.DefaultSettings()
    settings.verbose = False
    cost = np.zeros(n + 1)
    cost[-1] = -1.0
    solution = clarabel.DefaultSolver(
        sp.csc_matrix((n + 1, n + 1)), cost, sp.csc_matrix(a), -rhs,
        [clarabel.NonnegativeConeT(len(rhs))], settings).solve()
    if str(solution.status) not in ("Solved", "AlmostSolved"):
        return -math.inf
    return float(np.asarray(solution.x)[-1])


def _fit_rho(moved: np.ndarray, planned: np.ndarray, rho: float) -> float:
    """The fraction of the planned world shift (T, 2) the CoM followed (T, 2), least squares;
    the previous ``rho`` when the shift did not change."""
    scale = float(np.sum(planned * planned))
    if scale < 1e-18:
        return rho
    return float(np.clip(np.sum(moved * planned) / scale, 0.05, 1.0))
